// The glTF/GLB reader on arbitrary bytes: GLB container checks, JSON depth, the schema, URI
// resolution (against an empty directory, so only data: URIs resolve) and image headers.

#include <filesystem>

#include "fuzz/fuzz_target.h"
#include "scenes/gltf_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path emptyDir = [] {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / "aasim-fuzz-gltf-empty";
    std::filesystem::create_directories(dir);
    return dir;
  }();
  // The container decides the reader, as the file extension does for a file.
  const bool binary = fuzz::Text(data, size).starts_with("glTF");
  try {
    scenes::LoadGltfFromMemory(fuzz::Bytes(data, size), binary, emptyDir, "fuzz.gltf", 16.0f / 9.0f);
  } catch (const scenes::SceneError&) {
  }
  return 0;
}
