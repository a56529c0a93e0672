// oneTBB behind sim/parallel.h.

#include "sim/parallel.h"

#include <tbb/parallel_for.h>

namespace sim {

void ParallelFor(std::size_t count, FunctionRef<void(std::size_t)> body) {
  tbb::parallel_for(std::size_t{0}, count, [body](std::size_t i) { body(i); });
}

}  // namespace sim
