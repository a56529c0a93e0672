// sim::KeepFreedHostMemory: a frame-sized buffer comes from the heap and its pages stay with the
// process once freed.

#include <gtest/gtest.h>

#include <cstddef>
#include <memory>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "sanitized.h"
#include "sim/host_memory.h"

namespace {

#if defined(__GLIBC__) && !AASIM_TEST_SANITIZED
// An RGBA float texture at 1920x1080, the size of a pass's decoded output: above glibc's largest
// dynamic mmap threshold (32 MB), so by default it gets a mapping of its own.
constexpr std::size_t kFrameBytes = std::size_t{1920} * 1080 * 16;

TEST(SimHostMemory, AFrameSizedBufferComesFromTheHeapAndStaysAfterItIsFreed) {
  ASSERT_TRUE(sim::KeepFreedHostMemory());
  const std::size_t mappedBlocks = mallinfo2().hblks;
  auto buffer = std::make_unique_for_overwrite<std::byte[]>(kFrameBytes);
  buffer[kFrameBytes - 1] = std::byte{1};
  EXPECT_EQ(mallinfo2().hblks, mappedBlocks) << "the buffer got a mapping of its own";
  buffer.reset();
  EXPECT_GE(mallinfo2().arena, kFrameBytes) << "the freed buffer went back to the kernel";
}
#else
TEST(SimHostMemory, AFrameSizedBufferComesFromTheHeapAndStaysAfterItIsFreed) {
  GTEST_SKIP() << "glibc's allocator only (a sanitizer replaces it)";
}
#endif

}  // namespace
