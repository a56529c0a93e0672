#pragma once
// AASIM_TEST_SANITIZED: 1 when the tests are built with AddressSanitizer or ThreadSanitizer, whose
// allocators replace the C library's (shadow memory, quarantine, no mallopt).
// GCC announces a sanitizer with __SANITIZE_*__; clang 14 answers __has_feature instead.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define AASIM_TEST_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define AASIM_TEST_SANITIZED 1
#endif
#endif
#ifndef AASIM_TEST_SANITIZED
#define AASIM_TEST_SANITIZED 0
#endif
