#pragma once
// How the host keeps the memory of frame-sized buffers between passes.

namespace sim {

// Keeps freed blocks in the process for the next allocation instead of returning them to the
// kernel. Every pass allocates and frees frame-sized buffers every frame (its decoded output and
// its layers: 8-33 MB each at 1080p), and glibc serves blocks above its mmap threshold (128 KB,
// raised at most to 32 MB) with fresh mappings, whose every page the kernel faults in and zeroes
// again: about a quarter of an SMAA pass's host time on the benchmark machine (docs/PERFORMANCE.md,
// "Host memory"). Peak resident memory stays the same; memory freed late in a run is kept until
// exit. Call at the start of main, before any other thread exists. Returns false, changing
// nothing, where the C library has no such setting (anything but glibc).
bool KeepFreedHostMemory();

}  // namespace sim
