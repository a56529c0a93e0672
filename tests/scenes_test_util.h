#pragma once
// Helpers the scene tests share: writing glTF documents in code, a scratch directory per test,
// the test models, and readable glm vectors in failure output.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

// Readable failure output for vectors compared with EXPECT_EQ (found by argument lookup).
namespace glm {
inline void PrintTo(const vec3& v, std::ostream* out) { *out << '(' << v.x << ", " << v.y << ", " << v.z << ')'; }
}  // namespace glm

#ifndef AASIM_TESTMODELS_DIR
#define AASIM_TESTMODELS_DIR "/usr/share/assimp/models"
#endif

namespace scenes_test {

inline constexpr float kAspect = 16.0f / 9.0f;

inline const std::filesystem::path& Gltf2Models() {
  static const std::filesystem::path models = std::filesystem::path(AASIM_TESTMODELS_DIR) / "glTF2";
  return models;
}

// A fresh directory per test, so tests can run in parallel processes.
inline std::filesystem::path TestDir() {
  const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "aasim_scenes_test" /
                                    (std::string(info->test_suite_name()) + "." + info->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline std::filesystem::path WriteText(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// RFC 4648 base64 with padding, for data: URIs.
inline std::string Base64(const std::vector<std::uint8_t>& bytes) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string text;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t left = std::min<std::size_t>(3, bytes.size() - i);
    std::uint32_t group = static_cast<std::uint32_t>(bytes[i]) << 16;
    if (left > 1) group |= static_cast<std::uint32_t>(bytes[i + 1]) << 8;
    if (left > 2) group |= bytes[i + 2];
    for (std::size_t k = 0; k < 4; ++k) {
      text += k <= left ? kAlphabet[(group >> (18 - 6 * k)) & 63u] : '=';
    }
  }
  return text;
}

template <typename T>
void AppendBytes(std::vector<std::uint8_t>& bytes, const std::vector<T>& values) {
  const std::size_t offset = bytes.size();
  bytes.resize(offset + values.size() * sizeof(T));
  std::memcpy(bytes.data() + offset, values.data(), values.size() * sizeof(T));
}

// One mesh, one triangle-list primitive: float VEC3 positions and uint32 indices, in a base64
// data URI.
inline std::string TriangleGltf(const std::vector<float>& positions, const std::vector<std::uint32_t>& indices) {
  std::vector<std::uint8_t> buffer;
  AppendBytes(buffer, positions);
  const std::size_t positionBytes = buffer.size();
  AppendBytes(buffer, indices);
  const nlohmann::json gltf = {
      {"asset", {{"version", "2.0"}}},
      {"buffers", {{{"byteLength", buffer.size()}, {"uri", "data:application/octet-stream;base64," + Base64(buffer)}}}},
      {"bufferViews",
       {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", positionBytes}},
        {{"buffer", 0}, {"byteOffset", positionBytes}, {"byteLength", buffer.size() - positionBytes}}}},
      {"accessors",
       {{{"bufferView", 0}, {"componentType", 5126}, {"count", positions.size() / 3}, {"type", "VEC3"}},
        {{"bufferView", 1}, {"componentType", 5125}, {"count", indices.size()}, {"type", "SCALAR"}}}},
      {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}}}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"scenes", {{{"nodes", {0}}}}},
      {"scene", 0}};
  return gltf.dump();
}

}  // namespace scenes_test
