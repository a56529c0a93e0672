#pragma once
// Runtime errors of the command line's own outputs (directories, image and JSON files). Like
// raster::RasterError and scenes::SceneError the message is one line naming the path.

#include <stdexcept>
#include <string>

namespace cli {

class OutputError : public std::runtime_error {
 public:
  explicit OutputError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace cli
