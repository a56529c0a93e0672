// The texture image reader (PNG/JPEG through stb_image, dimensions checked from the header).

#include "fuzz/fuzz_target.h"
#include "scenes/texture.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    scenes::DecodeImage(fuzz::Bytes(data, size), "fuzz.png", scenes::ColourEncoding::Srgb);
  } catch (const scenes::SceneError&) {
  }
  return 0;
}
