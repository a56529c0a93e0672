#include "raster/json_input.h"

#include <fstream>

namespace raster {

std::string ReadJsonFile(const std::filesystem::path& path) {
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(path, error);
  if (error) throw JsonTextError("cannot be opened: " + error.message());
  if (std::filesystem::is_directory(status)) throw JsonTextError("is a directory, not a file");
  if (!std::filesystem::is_regular_file(status)) {
    throw JsonTextError("is not a regular file (a FIFO, device or socket is never read)");
  }
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  if (error) throw JsonTextError("cannot be read: " + error.message());
  if (size > kMaxJsonFileBytes) {
    throw JsonTextError("is " + std::to_string(size) + " bytes, more than the " +
                        std::to_string(kMaxJsonFileBytes) + " a JSON input may hold");
  }
  std::ifstream file(path, std::ios::binary);
  std::string text(static_cast<std::size_t>(size), '\0');
  if (!file.read(text.data(), static_cast<std::streamsize>(text.size()))) {
    throw JsonTextError("cannot be read");
  }
  return text;
}

}  // namespace raster
