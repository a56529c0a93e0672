// `aasim post`'s input reader (cli/image_input.h): PNG through the texture reader, OpenEXR
// through OpenEXR, then the depth and velocity readers on the same bytes. It reads by path, so each input is
// written to a file of this process first.

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "cli/image_input.h"
#include "fuzz/fuzz_target.h"

namespace {

const std::filesystem::path& InputFile() {
  static const std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("aasim_input_image_fuzz_" + std::to_string(::getpid()));
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  {
    std::ofstream file(InputFile(), std::ios::binary | std::ios::trunc);
    file.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    cli::ReadInputImage(InputFile(), [](int, int) {});
  } catch (const cli::InputImageError&) {
  }
  try {
    cli::ReadDepthExr(InputFile(), 4, 4, "colour.png");
  } catch (const cli::InputImageError&) {
  }
  try {
    cli::ReadVelocityExr(InputFile(), 4, 4, "colour.png");
  } catch (const cli::InputImageError&) {
  }
  return 0;
}
