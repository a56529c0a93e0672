#pragma once
// Input errors of the raster layer. The message is one line that names the offending input and
// the problem; callers print it as is.

#include <stdexcept>
#include <string>

namespace raster {

class RasterError : public std::runtime_error {
 public:
  explicit RasterError(const std::string& message) : std::runtime_error(message) {}
};

// A draw whose quad stream would pass kMaxQuadStreamBytes (raster/limits.h). The rasterizer
// knows the draw, not where it came from, so a caller that knows the scene puts its name first.
class QuadStreamError : public RasterError {
 public:
  using RasterError::RasterError;
};

}  // namespace raster
