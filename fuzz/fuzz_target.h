#pragma once
// What every aasim fuzz target shares: each reader is called on the fuzzer's bytes and may
// throw only its documented error type; anything else (another exception, a crash, a sanitizer
// report, a hang) is a finding.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

namespace fuzz {

inline std::span<const std::uint8_t> Bytes(const std::uint8_t* data, std::size_t size) {
  return {data, size};
}

inline std::string_view Text(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

}  // namespace fuzz
