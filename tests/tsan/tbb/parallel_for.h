#pragma once
// ThreadSanitizer builds only: <tbb/parallel_for.h> is the std::thread loop of
// tests/tsan/oneapi/tbb/parallel_for.h (see there).
#include <oneapi/tbb/parallel_for.h>
