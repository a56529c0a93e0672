// The host allocator's policy (see host_memory.h).

#include "sim/host_memory.h"

#include <cstdlib>  // defines __GLIBC__ where the C library is glibc

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace sim {

bool KeepFreedHostMemory() {
#if defined(__GLIBC__)
  // Every block comes from the heap, none from a mapping of its own (glibc refuses an mmap
  // threshold above 32 MB, less than one RGBA float texture at 1080p, so mappings are switched
  // off instead), and the heap's top is never trimmed, so a freed buffer's pages serve the next
  // one already faulted in.
  return mallopt(M_MMAP_MAX, 0) == 1 && mallopt(M_TRIM_THRESHOLD, -1) == 1;
#else
  return false;
#endif
}

}  // namespace sim
