// Tests of scenes/: glTF flattening, texture coordinates, materials, textures and cameras, and
// validation, on files written here and on the assimp test models; the original built-in scenes'
// claimed properties; camera framing. The stress scenes and motion have their own files.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "scenes/scene.h"
#include "scenes/texture.h"
#include "scenes_test_util.h"

namespace {

namespace fs = std::filesystem;

constexpr int kUnsignedByte = 5121;
constexpr int kUnsignedShort = 5123;
constexpr int kUnsignedInt = 5125;
constexpr int kFloat = 5126;

using scenes_test::Base64;
using scenes_test::kAspect;
using scenes_test::TestDir;
using scenes_test::WriteText;

// Built with append: GCC 12 warns falsely (-Wrestrict) on "literal" + temporary string.
std::string JoinJson(const std::vector<std::string>& items) {
  std::string joined = "[";
  for (const std::string& item : items) joined.append(joined.size() > 1 ? "," : "").append(item);
  return joined.append("]");
}

// Assembles a small glTF: one buffer (embedded as a data URI unless `bufferUri` is set), one
// bufferView per accessor unless a test adds its own JSON entries.
class GltfWriter {
 public:
  std::vector<std::string> accessors;
  std::vector<std::string> bufferViews;
  std::vector<std::string> meshes;
  std::vector<std::string> nodes;
  std::vector<std::string> materials;
  std::vector<std::string> textures;
  std::vector<std::string> images;
  std::vector<std::string> samplers;
  std::vector<std::string> cameras;
  std::vector<std::string> extensionsUsed;
  std::vector<int> sceneNodes{0};
  std::string bufferUri;

  // TEXCOORD_0 data: float, or the values encoded as normalized unsigned byte or short.
  int AddTexcoords(const std::vector<glm::vec2>& values, int componentType,
                   bool normalized = true) {
    std::vector<unsigned char> bytes;
    for (const glm::vec2& uv : values) {
      for (float value : {uv.x, uv.y}) {
        if (componentType == kFloat) {
          Append(bytes, Bytes(&value, sizeof(value)));
          continue;
        }
        const bool isByte = componentType == kUnsignedByte;
        const float scale = isByte ? 255.0f : 65535.0f;
        const auto code = static_cast<std::uint32_t>(std::lround(value * scale));
        for (std::size_t b = 0; b < (isByte ? 1u : 2u); ++b) {
          bytes.push_back(static_cast<unsigned char>(code >> (8 * b)));
        }
      }
    }
    const int accessor = AddAccessor(AddBufferView(bytes, 0), componentType, values.size(), "VEC2");
    if (normalized && componentType != kFloat) {
      accessors.back().insert(accessors.back().size() - 1, R"(,"normalized":true)");
    }
    return accessor;
  }

  int AddVec3(const std::vector<glm::vec3>& values) {
    const int view = AddBufferView(Bytes(values.data(), values.size() * sizeof(glm::vec3)), 0);
    return AddAccessor(view, kFloat, values.size(), "VEC3");
  }

  int AddIndices(const std::vector<std::uint32_t>& values, int componentType) {
    std::vector<unsigned char> bytes;
    for (std::uint32_t v : values) {
      const std::size_t size =
          componentType == kUnsignedByte ? 1 : componentType == kUnsignedShort ? 2 : 4;
      for (std::size_t b = 0; b < size; ++b) {
        bytes.push_back(static_cast<unsigned char>(v >> (8 * b)));
      }
    }
    return AddAccessor(AddBufferView(bytes, 0), componentType, values.size(), "SCALAR");
  }

  // Positions and normals interleaved in one bufferView with a 24-byte stride.
  std::pair<int, int> AddInterleaved(const std::vector<glm::vec3>& positions,
                                     const std::vector<glm::vec3>& normals) {
    std::vector<unsigned char> bytes;
    for (std::size_t i = 0; i < positions.size(); ++i) {
      Append(bytes, Bytes(&positions[i], sizeof(glm::vec3)));
      Append(bytes, Bytes(&normals[i], sizeof(glm::vec3)));
    }
    const int view = AddBufferView(bytes, 24);
    const int position = AddAccessor(view, kFloat, positions.size(), "VEC3");
    accessors.push_back(R"({"bufferView":)" + std::to_string(view) +
                        R"(,"byteOffset":12,"componentType":5126,"count":)" +
                        std::to_string(normals.size()) + R"(,"type":"VEC3"})");
    return {position, static_cast<int>(accessors.size()) - 1};
  }

  int AddMesh(const std::string& primitives) {
    meshes.push_back(R"({"primitives":)" + primitives + "}");
    return static_cast<int>(meshes.size()) - 1;
  }

  std::string Json() const {
    std::vector<std::string> roots;
    for (int node : sceneNodes) roots.push_back(std::to_string(node));
    std::string document = R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":)";
    document.append(JoinJson(roots)).append(R"(}],"nodes":)").append(JoinJson(nodes));
    document.append(R"(,"meshes":)").append(JoinJson(meshes));
    document.append(R"(,"accessors":)").append(JoinJson(accessors));
    document.append(R"(,"bufferViews":)").append(JoinJson(bufferViews));
    // glTF forbids empty arrays, so optional ones appear only when used.
    const std::pair<const char*, const std::vector<std::string>*> optional[] = {
        {"materials", &materials}, {"textures", &textures}, {"images", &images},
        {"samplers", &samplers},   {"cameras", &cameras},   {"extensionsUsed", &extensionsUsed}};
    for (const auto& [key, items] : optional) {
      if (!items->empty()) document.append(",\"").append(key).append("\":").append(JoinJson(*items));
    }
    document.append(R"(,"buffers":[{"byteLength":)").append(std::to_string(buffer_.size()));
    document.append(R"(,"uri":")");
    if (bufferUri.empty()) {
      document.append("data:application/octet-stream;base64,").append(Base64(buffer_));
    } else {
      document.append(bufferUri);
    }
    return document.append(R"("}]})");
  }

 private:
  static std::vector<unsigned char> Bytes(const void* data, std::size_t size) {
    std::vector<unsigned char> bytes(size);
    std::memcpy(bytes.data(), data, size);
    return bytes;
  }

  static void Append(std::vector<unsigned char>& to, const std::vector<unsigned char>& bytes) {
    to.insert(to.end(), bytes.begin(), bytes.end());
  }

  int AddBufferView(const std::vector<unsigned char>& bytes, int stride) {
    while (buffer_.size() % 4 != 0) buffer_.push_back(0);
    const std::size_t offset = buffer_.size();
    Append(buffer_, bytes);
    bufferViews.push_back(R"({"buffer":0,"byteOffset":)" + std::to_string(offset) +
                          R"(,"byteLength":)" + std::to_string(bytes.size()) +
                          (stride > 0 ? R"(,"byteStride":)" + std::to_string(stride) : "") +
                          "}");
    return static_cast<int>(bufferViews.size()) - 1;
  }

  int AddAccessor(int view, int componentType, std::size_t count, const std::string& type) {
    accessors.push_back(R"({"bufferView":)" + std::to_string(view) + R"(,"componentType":)" +
                        std::to_string(componentType) + R"(,"count":)" +
                        std::to_string(count) + R"(,"type":")" + type + R"("})");
    return static_cast<int>(accessors.size()) - 1;
  }

  std::vector<unsigned char> buffer_;
};

fs::path WriteGltf(const GltfWriter& writer, const std::string& name) {
  return WriteText(TestDir() / name, writer.Json());
}

// The SceneError message of loading `path`, or a test failure if it loads.
std::string LoadError(const fs::path& path) {
  try {
    scenes::LoadGltf(path, kAspect);
  } catch (const scenes::SceneError& e) {
    return e.what();
  }
  ADD_FAILURE() << path << " loaded, expected a SceneError";
  return {};
}

std::string Primitive(int position, int indices, int mode = 4, int normal = -1,
                      int texcoord = -1, int material = -1) {
  std::string attributes = R"("POSITION":)" + std::to_string(position);
  if (normal >= 0) attributes += R"(,"NORMAL":)" + std::to_string(normal);
  if (texcoord >= 0) attributes += R"(,"TEXCOORD_0":)" + std::to_string(texcoord);
  std::string text = R"({"attributes":{)" + attributes + "}";
  if (indices >= 0) text += R"(,"indices":)" + std::to_string(indices);
  if (material >= 0) text += R"(,"material":)" + std::to_string(material);
  return text + R"(,"mode":)" + std::to_string(mode) + "}";
}

const std::vector<glm::vec3> kSquare = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
const std::vector<std::uint32_t> kSquareIndices = {0, 1, 2, 0, 2, 3};

glm::vec3 FaceNormal(const scenes::Mesh& mesh, std::size_t triangle) {
  const glm::vec3 a = mesh.positions[mesh.indices[3 * triangle]];
  const glm::vec3 b = mesh.positions[mesh.indices[3 * triangle + 1]];
  const glm::vec3 c = mesh.positions[mesh.indices[3 * triangle + 2]];
  return glm::cross(b - a, c - a);
}

// --- A minimal PNG encoder (stored deflate blocks), so tests control every byte of an image:
// bit depth 8 or 16, colour type 0 (grey), 4 (grey + alpha), 2 (RGB) or 6 (RGBA).

std::uint32_t Crc32(const unsigned char* data, std::size_t size, std::uint32_t crc = 0) {
  crc = ~crc;
  for (std::size_t i = 0; i < size; ++i) {
    crc ^= data[i];
    for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

void PutBigEndian(std::vector<unsigned char>& out, std::uint32_t value, int bytes) {
  for (int b = bytes - 1; b >= 0; --b) out.push_back(static_cast<unsigned char>(value >> (8 * b)));
}

void PutChunk(std::vector<unsigned char>& png, const char* type,
              const std::vector<unsigned char>& data) {
  PutBigEndian(png, static_cast<std::uint32_t>(data.size()), 4);
  std::vector<unsigned char> typed(type, type + 4);
  typed.insert(typed.end(), data.begin(), data.end());
  png.insert(png.end(), typed.begin(), typed.end());
  PutBigEndian(png, Crc32(typed.data(), typed.size()), 4);
}

// `samples` holds width * height * channels values, rows top first.
std::vector<unsigned char> EncodePng(int width, int height, int channels, int bits,
                                     const std::vector<std::uint16_t>& samples) {
  const int colourType = channels == 1 ? 0 : channels == 2 ? 4 : channels == 3 ? 2 : 6;
  std::vector<unsigned char> raw;
  const std::size_t rowValues = static_cast<std::size_t>(width * channels);
  for (std::size_t row = 0; row < static_cast<std::size_t>(height); ++row) {
    raw.push_back(0);  // filter: none
    for (std::size_t i = 0; i < rowValues; ++i) {
      PutBigEndian(raw, samples[row * rowValues + i], bits / 8);
    }
  }
  std::vector<unsigned char> zlib = {0x78, 0x01};
  for (std::size_t start = 0; start < raw.size() || start == 0; start += 65535) {
    const std::size_t length = std::min<std::size_t>(65535, raw.size() - start);
    zlib.push_back(start + length >= raw.size() ? 1 : 0);
    zlib.push_back(static_cast<unsigned char>(length));
    zlib.push_back(static_cast<unsigned char>(length >> 8));
    zlib.push_back(static_cast<unsigned char>(~length));
    zlib.push_back(static_cast<unsigned char>(~length >> 8));
    zlib.insert(zlib.end(), raw.begin() + static_cast<std::ptrdiff_t>(start),
                raw.begin() + static_cast<std::ptrdiff_t>(start + length));
    if (start + length >= raw.size()) break;
  }
  std::uint32_t a = 1;
  std::uint32_t b = 0;
  for (unsigned char byte : raw) {
    a = (a + byte) % 65521u;
    b = (b + a) % 65521u;
  }
  PutBigEndian(zlib, (b << 16) | a, 4);
  std::vector<unsigned char> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  std::vector<unsigned char> header;
  PutBigEndian(header, static_cast<std::uint32_t>(width), 4);
  PutBigEndian(header, static_cast<std::uint32_t>(height), 4);
  header.insert(header.end(), {static_cast<unsigned char>(bits),
                               static_cast<unsigned char>(colourType), 0, 0, 0});
  PutChunk(png, "IHDR", header);
  PutChunk(png, "IDAT", zlib);
  PutChunk(png, "IEND", {});
  return png;
}

std::string PngDataUri(const std::vector<unsigned char>& png) {
  return "data:image/png;base64," + Base64(png);
}

// A unit square with texture coordinates at its corners and one material whose base colour
// texture is image 0; tests add the image.
GltfWriter TexturedSquare(const std::string& material) {
  GltfWriter writer;
  const int position = writer.AddVec3(kSquare);
  const int texcoord = writer.AddTexcoords({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, kFloat);
  const int indices = writer.AddIndices(kSquareIndices, kUnsignedShort);
  writer.AddMesh("[" + Primitive(position, indices, 4, -1, texcoord, 0) + "]");
  writer.nodes = {R"({"mesh":0})"};
  writer.materials = {material};
  writer.textures = {R"({"source":0})"};
  return writer;
}

std::size_t LineCount(const std::string& text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

// ---------------------------------------------------------------------------------------------
// glTF flattening

TEST(SceneGltf, FlattensTwoLevelHierarchyExactly) {
  GltfWriter writer;
  const std::vector<glm::vec3> positions = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const glm::vec3 normal = glm::normalize(glm::vec3{1, 1, 1});
  const int position = writer.AddVec3(positions);
  const int normals = writer.AddVec3({normal, normal, normal});
  writer.AddMesh("[" + Primitive(position, -1, 4, normals) + "]");
  // Parent: translate (10, 20, 30) after a non-uniform scale; child: 90 degrees about z, then
  // up by one. Every world coordinate is far from zero, so rounding vanishes in the float cast.
  writer.nodes = {R"({"children":[1],"translation":[10,20,30],"scale":[2,1,1]})",
                  R"({"mesh":0,"translation":[0,1,0],)"
                  R"("rotation":[0,0,0.7071067811865476,0.7071067811865476]})"};
  const scenes::Scene scene = scenes::LoadGltf(WriteGltf(writer, "hierarchy.gltf"), kAspect);
  ASSERT_EQ(scene.meshes.size(), 1u);
  const scenes::Mesh& mesh = scene.meshes[0];
  ASSERT_EQ(mesh.positions.size(), 3u);
  EXPECT_EQ(mesh.positions[0], glm::vec3(10, 22, 30));
  EXPECT_EQ(mesh.positions[1], glm::vec3(8, 21, 30));
  EXPECT_EQ(mesh.positions[2], glm::vec3(10, 21, 31));
  // Normals follow the inverse-transpose: (1,1,1) -> rotated (-1,1,1) -> unscaled (-1/2,1,1).
  const glm::vec3 expectedNormal = glm::normalize(glm::vec3{-1, 2, 2});
  ASSERT_EQ(mesh.normals.size(), 3u);
  for (const glm::vec3& n : mesh.normals) {
    EXPECT_NEAR(glm::distance(n, expectedNormal), 0.0f, 1e-6f);
  }
  EXPECT_GT(glm::dot(FaceNormal(mesh, 0), expectedNormal), 0.0f);
  EXPECT_EQ(scene.bounds.min, glm::vec3(8, 21, 30));
  EXPECT_EQ(scene.bounds.max, glm::vec3(10, 22, 31));
}

TEST(SceneGltf, MirroringMatrixKeepsFrontFacesCounterClockwise) {
  GltfWriter writer;
  const int position = writer.AddVec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const int normals = writer.AddVec3({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
  writer.AddMesh("[" + Primitive(position, -1, 4, normals) + "]");
  writer.nodes = {R"({"mesh":0,"matrix":[-1,0,0,0, 0,1,0,0, 0,0,1,0, 5,0,0,1]})"};
  const scenes::Scene scene = scenes::LoadGltf(WriteGltf(writer, "mirror.gltf"), kAspect);
  const scenes::Mesh& mesh = scene.meshes.at(0);
  EXPECT_EQ(mesh.positions[1], glm::vec3(4, 0, 0));
  EXPECT_EQ(mesh.indices, (std::vector<std::uint32_t>{0, 2, 1}));
  EXPECT_EQ(mesh.normals[0], glm::vec3(0, 0, 1));
  EXPECT_GT(glm::dot(FaceNormal(mesh, 0), mesh.normals[0]), 0.0f);
}

TEST(SceneGltf, ReadsEveryIndexComponentType) {
  GltfWriter writer;
  const int position = writer.AddVec3(kSquare);
  for (int type : {kUnsignedByte, kUnsignedShort, kUnsignedInt}) {
    const int indices = writer.AddIndices(kSquareIndices, type);
    writer.AddMesh(JoinJson({Primitive(position, indices)}));
  }
  writer.nodes = {R"({"children":[1,2,3]})", R"({"mesh":0})", R"({"mesh":1})", R"({"mesh":2})"};
  const scenes::Scene scene = scenes::LoadGltf(WriteGltf(writer, "indices.gltf"), kAspect);
  ASSERT_EQ(scene.meshes.size(), 3u);
  for (const scenes::Mesh& mesh : scene.meshes) {
    EXPECT_EQ(mesh.indices, kSquareIndices);
    EXPECT_EQ(mesh.positions, kSquare);
    EXPECT_TRUE(mesh.normals.empty());
  }
  EXPECT_EQ(scene.TriangleCount(), 6u);
  EXPECT_EQ(scene.VertexCount(), 12u);
}

TEST(SceneGltf, ReadsNonIndexedTriangleList) {
  GltfWriter writer;
  const std::vector<glm::vec3> corners = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0},
                                          {0, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  writer.AddMesh("[" + Primitive(writer.AddVec3(corners), -1) + "]");
  writer.nodes = {R"({"mesh":0})"};
  const scenes::Scene scene = scenes::LoadGltf(WriteGltf(writer, "soup.gltf"), kAspect);
  ASSERT_EQ(scene.meshes.size(), 1u);
  EXPECT_EQ(scene.meshes[0].indices, (std::vector<std::uint32_t>{0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(scene.meshes[0].positions, corners);
}

TEST(SceneGltf, ConvertsStripsAndFansToLists) {
  GltfWriter writer;
  const std::vector<glm::vec3> five = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 2, 0}};
  const int position = writer.AddVec3(five);
  const int order = writer.AddIndices({0, 1, 2, 3, 4}, kUnsignedShort);
  writer.AddMesh("[" + Primitive(position, order, 5) + "]");
  writer.AddMesh("[" + Primitive(position, -1, 6) + "]");
  writer.nodes = {R"({"children":[1,2]})", R"({"mesh":0})", R"({"mesh":1})"};
  const scenes::Scene scene = scenes::LoadGltf(WriteGltf(writer, "strip.gltf"), kAspect);
  ASSERT_EQ(scene.meshes.size(), 2u);
  EXPECT_EQ(scene.meshes[0].indices, (std::vector<std::uint32_t>{0, 1, 2, 1, 3, 2, 2, 3, 4}));
  EXPECT_EQ(scene.meshes[1].indices, (std::vector<std::uint32_t>{1, 2, 0, 2, 3, 0, 3, 4, 0}));
  // The strip's triangles all keep the first one's (counter-clockwise) winding.
  for (std::size_t t = 0; t < 3; ++t) EXPECT_GT(FaceNormal(scene.meshes[0], t).z, 0.0f);
}

TEST(SceneGltf, RespectsByteStrideOfInterleavedData) {
  GltfWriter writer;
  const std::vector<glm::vec3> normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  const auto [position, normal] = writer.AddInterleaved(kSquare, normals);
  const int indices = writer.AddIndices(kSquareIndices, kUnsignedByte);
  writer.AddMesh("[" + Primitive(position, indices, 4, normal) + "]");
  writer.nodes = {R"({"mesh":0})"};
  const scenes::Scene scene = scenes::LoadGltf(WriteGltf(writer, "interleaved.gltf"), kAspect);
  EXPECT_EQ(scene.meshes.at(0).positions, kSquare);
  EXPECT_EQ(scene.meshes.at(0).normals, normals);
}

TEST(SceneGltf, SkipsPointsAndLinesWithOneWarningPerKind) {
  GltfWriter writer;
  const int position = writer.AddVec3(kSquare);
  const int indices = writer.AddIndices(kSquareIndices, kUnsignedShort);
  writer.AddMesh("[" + Primitive(position, indices) + "," + Primitive(position, -1, 1) + "," +
                 Primitive(position, -1, 1) + "," + Primitive(position, -1, 0) + "]");
  writer.nodes = {R"({"mesh":0})"};
  const fs::path path = WriteGltf(writer, "mixed.gltf");
  ::testing::internal::CaptureStderr();
  const scenes::Scene scene = scenes::LoadGltf(path, kAspect);
  const std::string warnings = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(scene.TriangleCount(), 2u);
  EXPECT_EQ(std::count(warnings.begin(), warnings.end(), '\n'), 2) << warnings;
  EXPECT_NE(warnings.find("skipped 2 LINES primitives"), std::string::npos) << warnings;
  EXPECT_NE(warnings.find("skipped 1 POINTS primitive"), std::string::npos) << warnings;
}

TEST(SceneGltf, ComposesMatrixAndTrsDownThreeLevels) {
  GltfWriter writer;
  writer.AddMesh("[" + Primitive(writer.AddVec3({{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}), -1) + "]");
  // Root: a matrix scaling by 2 and moving +100 in x. Middle: 90 degrees about y. Leaf: moved
  // (0, 0, 3) and scaled (1, 1, 2). World = T(100,0,0) S(2) Ry(90) T(0,0,3) S(1,1,2).
  writer.nodes = {R"({"children":[1],"matrix":[2,0,0,0, 0,2,0,0, 0,0,2,0, 100,0,0,1]})",
                  R"({"children":[2],"rotation":[0,0.7071067811865476,0,0.7071067811865476]})",
                  R"({"mesh":0,"translation":[0,0,3],"scale":[1,1,2]})"};
  const scenes::Scene scene = scenes::LoadGltf(WriteGltf(writer, "levels.gltf"), kAspect);
  const scenes::Mesh& mesh = scene.meshes.at(0);
  // (1,0,0) -> (1,0,3) -> Ry: (3,0,-1) -> (106,0,-2); (0,0,1) -> (0,0,5) -> (5,0,0) -> (110,0,0).
  EXPECT_NEAR(glm::distance(mesh.positions[0], glm::vec3(106, 0, -2)), 0.0f, 1e-4f);
  EXPECT_NEAR(glm::distance(mesh.positions[1], glm::vec3(106, 2, 0)), 0.0f, 1e-4f);
  EXPECT_NEAR(glm::distance(mesh.positions[2], glm::vec3(110, 0, 0)), 0.0f, 1e-4f);
}

TEST(SceneGltf, ReadsTexcoordsOfEveryComponentType) {
  GltfWriter writer;
  const int position = writer.AddVec3(kSquare);
  const int indices = writer.AddIndices(kSquareIndices, kUnsignedByte);
  const std::vector<glm::vec2> uv = {{0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 1.0f}, {0.5f, 0.25f}};
  for (int type : {kFloat, kUnsignedByte, kUnsignedShort}) {
    writer.AddMesh("[" + Primitive(position, indices, 4, -1, writer.AddTexcoords(uv, type)) + "]");
  }
  writer.nodes = {R"({"children":[1,2,3]})", R"({"mesh":0})", R"({"mesh":1})", R"({"mesh":2})"};
  const scenes::Scene scene = scenes::LoadGltf(WriteGltf(writer, "texcoords.gltf"), kAspect);
  ASSERT_EQ(scene.meshes.size(), 3u);
  EXPECT_EQ(scene.meshes[0].texcoords, uv);
  // Normalized integers decode as code / max: 0.5 is stored as 128/255 and 32768/65535.
  const std::vector<glm::vec2> fromBytes = {
      {0, 0}, {1, 0}, {1, 1}, {128.0f / 255.0f, 64.0f / 255.0f}};
  const std::vector<glm::vec2> fromShorts = {
      {0, 0}, {1, 0}, {1, 1}, {32768.0f / 65535.0f, 16384.0f / 65535.0f}};
  EXPECT_EQ(scene.meshes[1].texcoords, fromBytes);
  EXPECT_EQ(scene.meshes[2].texcoords, fromShorts);
  for (const scenes::Mesh& mesh : scene.meshes) EXPECT_EQ(mesh.material, -1);
}

TEST(SceneGltf, TexcoordsFollowStripsAndMirrorsPerVertex) {
  GltfWriter writer;
  const std::vector<glm::vec2> uv = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
  const int texcoord = writer.AddTexcoords(uv, kFloat);
  writer.AddMesh("[" + Primitive(writer.AddVec3(kSquare), -1, 5, -1, texcoord) + "]");
  writer.nodes = {R"({"mesh":0,"scale":[-1,1,1]})"};
  const scenes::Scene scene = scenes::LoadGltf(WriteGltf(writer, "strip_uv.gltf"), kAspect);
  EXPECT_EQ(scene.meshes.at(0).texcoords, uv);  // per vertex, untouched by index reordering
}

TEST(SceneGltf, ReadsBaseColourFactorAndSharesMaterials) {
  GltfWriter writer;
  const int position = writer.AddVec3(kSquare);
  writer.AddMesh("[" + Primitive(position, -1, 6, -1, -1, 1) + "," +
                 Primitive(position, -1, 6, -1, -1, 1) + "," + Primitive(position, -1, 6) + "]");
  writer.materials = {R"({"name":"unused"})", R"({"name":"paint","pbrMetallicRoughness":)"
                                              R"({"baseColorFactor":[0.5,0.25,1,0.75]}})"};
  writer.nodes = {R"({"mesh":0})"};
  const scenes::Scene scene = scenes::LoadGltf(WriteGltf(writer, "factor.gltf"), kAspect);
  ASSERT_EQ(scene.meshes.size(), 3u);
  ASSERT_EQ(scene.materials.size(), 1u);  // only materials that are drawn are converted
  EXPECT_EQ(scene.materials[0].name, "paint");
  EXPECT_EQ(scene.materials[0].baseColourFactor, glm::vec4(0.5f, 0.25f, 1.0f, 0.75f));
  EXPECT_EQ(scene.materials[0].baseColourTexture, -1);
  EXPECT_EQ(scene.meshes[0].material, 0);
  EXPECT_EQ(scene.meshes[1].material, 0);
  EXPECT_EQ(scene.meshes[2].material, -1);
  EXPECT_TRUE(scene.textures.empty());
}

TEST(SceneTexture, SrgbCurveMatchesIec61966) {
  EXPECT_EQ(scenes::SrgbToLinear(0.0f), 0.0f);
  EXPECT_NEAR(scenes::SrgbToLinear(1.0f), 1.0f, 1e-6f);
  EXPECT_NEAR(scenes::SrgbToLinear(0.04045f), 0.04045f / 12.92f, 1e-7f);  // the linear segment
  EXPECT_NEAR(scenes::SrgbToLinear(0.5f), 0.2140411f, 1e-6f);
  EXPECT_NEAR(scenes::SrgbToLinear(128.0f / 255.0f), 0.2158605f, 1e-6f);
}

TEST(SceneTexture, DecodesEveryChannelCountAndBitDepth) {
  const float srgb128 = scenes::SrgbToLinear(128.0f / 255.0f);
  const float srgb32768 = scenes::SrgbToLinear(32768.0f / 65535.0f);
  // One texel of each layout; colour goes through the sRGB curve, alpha does not.
  const std::vector<unsigned char> grey8 = {128};
  const std::vector<unsigned char> greyAlpha8 = {128, 128};
  const std::vector<unsigned char> rgb8 = {0, 128, 255};
  const std::vector<unsigned char> rgba8 = {255, 0, 128, 64};
  const std::uint16_t wide[] = {32768, 65535, 0, 32768};
  std::vector<unsigned char> rgba16(sizeof(wide));
  std::memcpy(rgba16.data(), wide, sizeof(wide));
  using scenes::ColourEncoding;
  EXPECT_EQ(scenes::DecodeTexels("g", 1, 1, 1, 8, grey8, ColourEncoding::Srgb).texels[0],
            glm::vec4(srgb128, srgb128, srgb128, 1.0f));
  EXPECT_EQ(scenes::DecodeTexels("ga", 1, 1, 2, 8, greyAlpha8, ColourEncoding::Srgb).texels[0],
            glm::vec4(srgb128, srgb128, srgb128, 128.0f / 255.0f));
  EXPECT_EQ(scenes::DecodeTexels("rgb", 1, 1, 3, 8, rgb8, ColourEncoding::Srgb).texels[0],
            glm::vec4(0.0f, srgb128, 1.0f, 1.0f));
  EXPECT_EQ(scenes::DecodeTexels("rgba", 1, 1, 4, 8, rgba8, ColourEncoding::Srgb).texels[0],
            glm::vec4(1.0f, 0.0f, srgb128, 64.0f / 255.0f));
  EXPECT_EQ(scenes::DecodeTexels("w", 1, 1, 4, 16, rgba16, ColourEncoding::Srgb).texels[0],
            glm::vec4(srgb32768, 1.0f, 0.0f, 32768.0f / 65535.0f));
  EXPECT_EQ(scenes::DecodeTexels("lin", 1, 1, 1, 8, grey8, ColourEncoding::Linear).texels[0],
            glm::vec4(glm::vec3(128.0f / 255.0f), 1.0f));
  EXPECT_THROW(scenes::DecodeTexels("short", 2, 1, 3, 8, rgb8, ColourEncoding::Srgb),
               scenes::SceneError);
  EXPECT_THROW(scenes::DecodeTexels("five", 1, 1, 5, 8, rgb8, ColourEncoding::Srgb),
               scenes::SceneError);
  EXPECT_THROW(scenes::DecodeTexels("float", 1, 1, 1, 32, rgba16, ColourEncoding::Srgb),
               scenes::SceneError);
}

TEST(SceneGltf, DecodesEmbeddedPngBaseColourTexturesFromSrgb) {
  // 2x2 RGBA, 8 bit: rows top first, so texel (1, 0) is the top-right one.
  const std::vector<std::uint16_t> rgba = {0, 64, 128, 255,  255, 255, 255, 128,
                                           10, 20, 30, 40,   200, 100, 50, 0};
  // 2x1 grey + alpha, 16 bit.
  const std::vector<std::uint16_t> greyAlpha = {32768, 65535, 1000, 0};
  for (const auto& png : {std::tuple{4, 8, rgba}, std::tuple{2, 16, greyAlpha}}) {
    const int channels = std::get<0>(png), bits = std::get<1>(png);
    const std::vector<std::uint16_t>& samples = std::get<2>(png);
    const int width = 2;
    const int height = static_cast<int>(samples.size()) / (width * channels);
    GltfWriter writer = TexturedSquare(
        R"({"name":"logo","pbrMetallicRoughness":{"baseColorTexture":{"index":0},)"
        R"("baseColorFactor":[1,0.5,1,1]}})");
    writer.images = {R"({"name":"pixels","uri":")" +
                     PngDataUri(EncodePng(width, height, channels, bits, samples)) + R"("})"};
    const scenes::Scene scene = scenes::LoadGltf(WriteGltf(writer, "png.gltf"), kAspect);
    ASSERT_EQ(scene.textures.size(), 1u);
    const scenes::Texture& texture = scene.textures[0];
    EXPECT_EQ(texture.name, "pixels");
    ASSERT_EQ(texture.width, width);
    ASSERT_EQ(texture.height, height);
    ASSERT_EQ(scene.materials.size(), 1u);
    EXPECT_EQ(scene.materials[0].baseColourTexture, 0);
    EXPECT_EQ(scene.materials[0].baseColourFactor, glm::vec4(1.0f, 0.5f, 1.0f, 1.0f));
    EXPECT_EQ(scene.meshes.at(0).material, 0);
    const float maxCode = bits == 8 ? 255.0f : 65535.0f;
    for (std::size_t t = 0; t < texture.texels.size(); ++t) {
      const auto code = [&](std::size_t c) {
        return static_cast<float>(samples[t * static_cast<std::size_t>(channels) + c]) / maxCode;
      };
      const glm::vec4 expected =
          channels == 4 ? glm::vec4(scenes::SrgbToLinear(code(0)), scenes::SrgbToLinear(code(1)),
                                    scenes::SrgbToLinear(code(2)), code(3))
                        : glm::vec4(glm::vec3(scenes::SrgbToLinear(code(0))), code(1));
      EXPECT_NEAR(glm::distance(texture.texels[t], expected), 0.0f, 1e-6f)
          << channels << " channels, " << bits << " bits, texel " << t;
    }
  }
}

TEST(SceneGltf, ReadsTextureFilesNextToTheGltf) {
  GltfWriter writer =
      TexturedSquare(R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}})");
  writer.images = {R"({"uri":"grey.png"})"};
  const fs::path path = WriteGltf(writer, "external.gltf");
  const std::vector<unsigned char> png = EncodePng(1, 1, 1, 8, {255});
  std::ofstream(path.parent_path() / "grey.png", std::ios::binary)
      .write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
  const scenes::Scene scene = scenes::LoadGltf(path, kAspect);
  ASSERT_EQ(scene.textures.size(), 1u);
  EXPECT_EQ(scene.textures[0].name, "grey.png");
  EXPECT_EQ(scene.textures[0].texels.at(0), glm::vec4(1.0f));
}

TEST(SceneGltf, TexturedMaterialWithoutTexcoordsFallsBackToItsFactorOnce) {
  GltfWriter writer = TexturedSquare(
      R"({"name":"m","pbrMetallicRoughness":{"baseColorTexture":{"index":0},)"
      R"("baseColorFactor":[0,1,0,1]}})");
  writer.images = {R"({"uri":")" + PngDataUri(EncodePng(1, 1, 3, 8, {0, 0, 255})) + R"("})"};
  const int position = writer.AddVec3(kSquare);
  writer.AddMesh("[" + Primitive(position, -1, 6, -1, -1, 0) + "," +
                 Primitive(position, -1, 6, -1, -1, 0) + "]");
  writer.nodes = {R"({"children":[1,2]})", R"({"mesh":0})", R"({"mesh":1})"};
  const fs::path path = WriteGltf(writer, "nouv.gltf");
  ::testing::internal::CaptureStderr();
  const scenes::Scene scene = scenes::LoadGltf(path, kAspect);
  const std::string warnings = ::testing::internal::GetCapturedStderr();
  ASSERT_EQ(scene.meshes.size(), 3u);
  ASSERT_EQ(scene.materials.size(), 2u);
  EXPECT_EQ(scene.meshes[0].material, 0);
  EXPECT_EQ(scene.meshes[1].material, 1);
  EXPECT_EQ(scene.meshes[2].material, 1);  // one untextured copy, shared
  EXPECT_EQ(scene.materials[1].name, "m (untextured)");
  EXPECT_EQ(scene.materials[1].baseColourTexture, -1);
  EXPECT_EQ(scene.materials[1].baseColourFactor, glm::vec4(0, 1, 0, 1));
  EXPECT_EQ(LineCount(warnings), 1u) << warnings;
  EXPECT_NE(warnings.find("without TEXCOORD_0"), std::string::npos) << warnings;
}

TEST(SceneGltf, UnsupportedFeaturesWarnOncePerKind) {
  const std::string texture =
      R"({"index":0,"extensions":{"KHR_texture_transform":{"offset":[0.5,0]}}})";
  GltfWriter writer = TexturedSquare(R"({"pbrMetallicRoughness":{"baseColorTexture":)" + texture +
                                     R"(},"normalTexture":{"index":0},"alphaMode":"MASK"})");
  writer.materials.push_back(writer.materials[0]);
  writer.materials.push_back(
      R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":0,"texCoord":1}}})");
  writer.images = {R"({"uri":")" + PngDataUri(EncodePng(1, 1, 1, 8, {0})) + R"("})"};
  writer.samplers = {R"({"wrapS":33071,"magFilter":9728})"};
  writer.textures = {R"({"source":0,"sampler":0})"};
  writer.extensionsUsed = {R"("KHR_texture_transform")"};
  const int position = writer.AddVec3(kSquare);
  const int texcoord = writer.AddTexcoords({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, kFloat);
  writer.AddMesh("[" + Primitive(position, -1, 6, -1, texcoord, 1) + "," +
                 Primitive(position, -1, 6, -1, texcoord, 2) + "," +
                 Primitive(position, -1, 6, -1, texcoord, 2) + "]");
  writer.nodes = {R"({"children":[1,2]})", R"({"mesh":0})", R"({"mesh":1})"};
  const fs::path path = WriteGltf(writer, "features.gltf");
  ::testing::internal::CaptureStderr();
  const scenes::Scene scene = scenes::LoadGltf(path, kAspect);
  const std::string warnings = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(scene.TriangleCount(), 8u);
  for (const char* expected :
       {"extension KHR_texture_transform is ignored", "normal maps are ignored",
        "alphaMode MASK is ignored", "TEXCOORD_1 are not supported",
        "wrap modes other than REPEAT", "NEAREST texture filters"}) {
    EXPECT_NE(warnings.find(expected), std::string::npos) << expected << "\n" << warnings;
  }
  EXPECT_EQ(LineCount(warnings), 6u) << warnings;
  // The texCoord 1 material keeps its factor and no texture; the others share the one texture.
  ASSERT_EQ(scene.textures.size(), 1u);
  const auto texCoord1 = static_cast<std::size_t>(scene.meshes[2].material);
  EXPECT_EQ(scene.materials.at(texCoord1).baseColourTexture, -1);
  std::istringstream lines(warnings);
  for (std::string line; std::getline(lines, line);) {
    EXPECT_EQ(line.rfind(path.string() + ": warning: ", 0), 0u) << line;
  }
}

// ---------------------------------------------------------------------------------------------
// glTF cameras

// The file's planes, pulled in to the bounding sphere with 5% slack where they lie outside it.
void ExpectPlanesTightenedAroundTheScene(const scenes::Scene& scene, float fileNear,
                                         float fileFar) {
  const float distance = glm::distance(scene.camera.eye, scene.bounds.Centre());
  const float radius = scene.bounds.Radius();
  EXPECT_GE(scene.camera.zNear, fileNear);
  EXPECT_LE(scene.camera.zFar, fileFar);
  const float tolerance = 1e-5f * (distance + radius);
  EXPECT_NEAR(scene.camera.zNear, std::max(fileNear, distance - 1.05f * radius), tolerance);
  EXPECT_NEAR(scene.camera.zFar, std::min(fileFar, distance + 1.05f * radius), tolerance);
}

// One triangle far down -z, so that any camera on the +z side sees it.
GltfWriter SceneWithCamera(const std::string& camera, const std::string& cameraNode) {
  GltfWriter writer;
  writer.AddMesh("[" + Primitive(writer.AddVec3({{-1, -1, -10}, {1, -1, -10}, {0, 1, -10}}), -1) +
                 "]");
  writer.cameras = {camera};
  writer.nodes = {R"({"children":[1,2]})", R"({"mesh":0})", cameraNode};
  return writer;
}

TEST(SceneGltfCamera, UsesTheFirstPerspectiveCameraWithItsNodeTransform) {
  // The camera node sits under a parent turned 90 degrees about y and moved to (5, 1, 0): the
  // camera's own -z then points along world -x.
  GltfWriter writer = SceneWithCamera(
      R"({"type":"perspective","perspective":{"yfov":0.5,"znear":0.25,"zfar":400}})",
      R"({"translation":[5,1,0],"rotation":[0,0.7071067811865476,0,0.7071067811865476],)"
      R"("children":[3]})");
  writer.nodes.push_back(R"({"camera":0,"translation":[0,0,2]})");
  writer.cameras.push_back(R"({"type":"perspective","perspective":{"yfov":1.0,"znear":1}})");
  writer.nodes.push_back(R"({"camera":1})");
  writer.nodes[0] = R"({"children":[1,2,4]})";
  const scenes::Scene scene = scenes::LoadGltf(WriteGltf(writer, "camera.gltf"), kAspect);
  const scenes::Camera& camera = scene.camera;
  EXPECT_NEAR(glm::distance(camera.eye, glm::vec3(7, 1, 0)), 0.0f, 1e-5f);
  const glm::vec3 forward = glm::normalize(camera.target - camera.eye);
  EXPECT_NEAR(glm::distance(forward, glm::vec3(-1, 0, 0)), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::distance(camera.up, glm::vec3(0, 1, 0)), 0.0f, 1e-5f);
  EXPECT_FLOAT_EQ(camera.verticalFovRadians, 0.5f);
  ExpectPlanesTightenedAroundTheScene(scene, 0.25f, 400.0f);
}

TEST(SceneGltfCamera, KeepsTheFilesPlanesWhenTheyCutIntoTheScene) {
  GltfWriter writer = SceneWithCamera(
      R"({"type":"perspective","perspective":{"yfov":0.7,"znear":14,"zfar":15.5}})",
      R"({"camera":0,"translation":[0,0,5]})");
  const scenes::Scene scene = scenes::LoadGltf(WriteGltf(writer, "tight.gltf"), kAspect);
  EXPECT_EQ(scene.camera.zNear, 14.0f);
  EXPECT_EQ(scene.camera.zFar, 15.5f);
}

TEST(SceneGltfCamera, InfiniteFarPlaneIsChosenFromTheBoundsAndSaidSo) {
  GltfWriter writer = SceneWithCamera(
      R"({"type":"perspective","perspective":{"yfov":0.7,"znear":0.1}})",
      R"({"camera":0,"translation":[0,0,5]})");
  const fs::path path = WriteGltf(writer, "infinite.gltf");
  ::testing::internal::CaptureStderr();
  const scenes::Scene scene = scenes::LoadGltf(path, kAspect);
  const std::string warnings = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(warnings.find("camera 0 has an infinite far plane; aasim uses zfar = "),
            std::string::npos) << warnings;
  EXPECT_EQ(LineCount(warnings), 1u) << warnings;
  // The triangle is 15 units in front: the far plane lies just beyond it.
  EXPECT_GT(scene.camera.zFar, 15.0f);
  EXPECT_LT(scene.camera.zFar, 16.0f);
  const glm::vec4 clip = scene.camera.Projection(kAspect) * scene.camera.View() *
                         glm::vec4(0.0f, 0.0f, -10.0f, 1.0f);
  EXPECT_GT(clip.z, 0.0f);
  EXPECT_LT(clip.z, clip.w);
}

TEST(SceneGltfCamera, OrthographicCameraWarnsAndFramesTheBounds) {
  GltfWriter writer = SceneWithCamera(
      R"({"type":"orthographic","orthographic":{"xmag":1,"ymag":1,"znear":0.1,"zfar":50}})",
      R"({"camera":0,"translation":[0,0,5]})");
  const fs::path path = WriteGltf(writer, "ortho.gltf");
  ::testing::internal::CaptureStderr();
  const scenes::Scene scene = scenes::LoadGltf(path, kAspect);
  const std::string warnings = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(warnings.find("orthographic camera 0 is not supported"), std::string::npos)
      << warnings;
  const scenes::Camera framed = scenes::FrameBounds(scene.bounds, kAspect);
  EXPECT_EQ(scene.camera.eye, framed.eye);
  EXPECT_EQ(scene.camera.zFar, framed.zFar);
}

TEST(SceneGltfCamera, RejectsBadLensValues) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"({"yfov":0,"znear":0.1,"zfar":10})",
       "/cameras/0/perspective/yfov: expected a number > 0, found 0"},
      {R"({"yfov":0.5,"znear":-1,"zfar":10})",
       "/cameras/0/perspective/znear: expected a number > 0, found -1"},
      {R"({"yfov":0.5,"znear":2,"zfar":1})",
       "/cameras/0/perspective/zfar: 1 is not beyond znear 2"}};
  for (const auto& [lens, problem] : cases) {
    GltfWriter writer = SceneWithCamera(R"({"type":"perspective","perspective":)" + lens + "}",
                                        R"({"camera":0})");
    const std::string message = LoadError(WriteGltf(writer, "lens.gltf"));
    EXPECT_NE(message.find("lens.gltf: " + problem), std::string::npos) << message;
  }
}

// ---------------------------------------------------------------------------------------------
// glTF errors: one line naming the file and the problem

TEST(SceneGltfErrors, NonFiniteVertex) {
  GltfWriter writer;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  writer.AddMesh("[" + Primitive(writer.AddVec3({{0, 0, 0}, {1, 0, 0}, {nan, 0, 1}}), -1) + "]");
  writer.nodes = {R"({"name":"n","mesh":0})"};
  writer.meshes[0].insert(1, R"("name":"Cube",)");
  const std::string message = LoadError(WriteGltf(writer, "nan.gltf"));
  EXPECT_NE(message.find("nan.gltf: mesh 'Cube'"), std::string::npos) << message;
  EXPECT_NE(message.find("vertex 2 has a non-finite position (nan, 0, 1)"), std::string::npos)
      << message;
}

TEST(SceneGltfErrors, IndexOutOfRange) {
  GltfWriter writer;
  const int position = writer.AddVec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const int indices = writer.AddIndices({0, 1, 2, 0, 7, 1}, kUnsignedInt);
  writer.AddMesh(JoinJson({Primitive(position, indices)}));
  writer.nodes = {R"({"mesh":0})"};
  const std::string message = LoadError(WriteGltf(writer, "range.gltf"));
  EXPECT_NE(message.find("range.gltf: mesh 0 primitive 0: index 7 at position 4 is out of range "
                         "(3 vertices)"),
            std::string::npos)
      << message;
}

TEST(SceneGltfErrors, MissingFile) {
  const fs::path path = TestDir() / "absent.glb";
  const std::string message = LoadError(path);
  EXPECT_NE(message.find("absent.glb: no such file"), std::string::npos) << message;
}

TEST(SceneGltfErrors, MalformedJsonIsOneLine) {
  const fs::path path = WriteText(TestDir() / "broken.gltf", "{\n \"asset\": {\"version\": \n");
  const std::string message = LoadError(path);
  EXPECT_NE(message.find("broken.gltf: "), std::string::npos) << message;
  EXPECT_NE(message.find("parse error"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

TEST(SceneGltfErrors, RecursiveNodes) {
  GltfWriter writer;
  writer.AddMesh("[" + Primitive(writer.AddVec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}), -1) + "]");
  writer.nodes = {R"({"children":[1]})", R"({"children":[2]})", R"({"mesh":0,"children":[1]})"};
  const std::string message = LoadError(WriteGltf(writer, "loop.gltf"));
  EXPECT_NE(message.find("loop.gltf: node 1 is its own ancestor (recursive node graph 0 -> 1 -> "
                         "2 -> 1)"),
            std::string::npos)
      << message;
}

TEST(SceneGltfErrors, MissingBufferFile) {
  GltfWriter writer;
  writer.AddMesh("[" + Primitive(writer.AddVec3(kSquare), -1) + "]");
  writer.nodes = {R"({"mesh":0})"};
  writer.bufferUri = "geometry.bin";
  const std::string message = LoadError(WriteGltf(writer, "nobin.gltf"));
  EXPECT_NE(message.find("nobin.gltf: "), std::string::npos) << message;
  EXPECT_NE(message.find("geometry.bin"), std::string::npos) << message;
}

TEST(SceneGltfErrors, AccessorPastEndOfBufferView) {
  GltfWriter writer;
  writer.AddVec3(kSquare);
  writer.accessors[0] =
      R"({"bufferView":0,"byteOffset":4,"componentType":5126,"count":4,"type":"VEC3"})";
  writer.AddMesh("[" + Primitive(0, -1, 6) + "]");
  writer.nodes = {R"({"mesh":0})"};
  const std::string message = LoadError(WriteGltf(writer, "overrun.gltf"));
  EXPECT_NE(message.find("overrun.gltf: mesh 0 primitive 0: POSITION accessor 0 (4 elements at "
                         "byte offset 4, stride 12) reads past the end of bufferView 0 (48 bytes)"),
            std::string::npos)
      << message;
}

TEST(SceneGltfErrors, NoTriangles) {
  GltfWriter writer;
  writer.AddMesh("[" + Primitive(writer.AddVec3(kSquare), -1, 3) + "]");
  writer.nodes = {R"({"mesh":0})"};
  const fs::path path = WriteGltf(writer, "lines.gltf");
  ::testing::internal::CaptureStderr();
  const std::string message = LoadError(path);
  ::testing::internal::GetCapturedStderr();
  EXPECT_NE(message.find("lines.gltf: contains no triangles"), std::string::npos) << message;
}

TEST(SceneGltfErrors, UnknownExtensionListsGltfAndGlb) {
  try {
    scenes::LoadScene("model.obj", kAspect);
    ADD_FAILURE() << "model.obj loaded";
  } catch (const scenes::SceneError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("model.obj"), std::string::npos) << message;
    EXPECT_NE(message.find(".gltf"), std::string::npos) << message;
    EXPECT_NE(message.find(".glb"), std::string::npos) << message;
  }
}

TEST(SceneGltfErrors, TexcoordsMustBeNormalizedIntegersOrFloats) {
  GltfWriter writer;
  const int position = writer.AddVec3(kSquare);
  const int texcoord = writer.AddTexcoords({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, kUnsignedByte, false);
  writer.AddMesh("[" + Primitive(position, -1, 6, -1, texcoord) + "]");
  writer.nodes = {R"({"mesh":0})"};
  const std::string message = LoadError(WriteGltf(writer, "raw_uv.gltf"));
  EXPECT_NE(message.find("raw_uv.gltf: mesh 0 primitive 0: TEXCOORD_0 accessor 1 holds unsigned "
                         "byte components without \"normalized\": true"),
            std::string::npos)
      << message;
}

TEST(SceneGltfErrors, MissingOrBrokenBaseColourImage) {
  GltfWriter missing =
      TexturedSquare(R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}})");
  missing.images = {R"({"uri":"absent.png"})"};
  // tinygltf itself warns about the missing file; only the error matters here.
  ::testing::internal::CaptureStderr();
  std::string message = LoadError(WriteGltf(missing, "noimage.gltf"));
  EXPECT_NE(message.find("noimage.gltf: /images/0/uri 'absent.png': no such file"),
            std::string::npos) << message;
  GltfWriter broken = missing;
  broken.images = {R"({"uri":"data:image/png;base64,)" + Base64({1, 2, 3, 4, 5, 6, 7, 8}) +
                   R"("})"};
  message = LoadError(WriteGltf(broken, "badpng.gltf"));
  EXPECT_NE(message.find("badpng.gltf: image 0: cannot decode: "), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  GltfWriter dangling = missing;
  dangling.materials = {R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":3}}})"};
  message = LoadError(WriteGltf(dangling, "dangling.gltf"));
  EXPECT_NE(message.find("dangling.gltf: /materials/0/pbrMetallicRoughness/baseColorTexture/index: "
                         "index 3 is out of range: the file has 1 textures"),
            std::string::npos) << message;
  ::testing::internal::GetCapturedStderr();
}

TEST(SceneGltfErrors, AssimpModelsWithKnownDefects) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"IndexOutOfRange/IndexOutOfRange.gltf", "is out of range (24 vertices)"},
      {"BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb", "has a non-finite position (-inf"},
      {"RecursiveNodes/RecursiveNodes.gltf", "recursive node graph"},
      {"MissingBin/BoxTextured.gltf", "BoxTextured0.bin"},
      {"draco/2CylinderEngine.gltf", "Draco-compressed meshes"},
      {"IncorrectVertexArrays/Cube.gltf", "/bufferViews/2: bytes 504 to 936 run past the end"}};
  for (const auto& [file, problem] : cases) {
    const fs::path path = scenes_test::Gltf2Models() / file;
    const std::string message = LoadError(path);
    EXPECT_EQ(message.rfind(path.string() + ": ", 0), 0u) << message;
    EXPECT_NE(message.find(problem), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

// ---------------------------------------------------------------------------------------------
// Real assets

TEST(SceneGltfAssets, TwoCylinderEngineLoads) {
  ::testing::internal::CaptureStderr();
  const scenes::Scene scene = scenes::LoadScene(
      (scenes_test::Gltf2Models() / "2CylinderEngine-glTF-Binary/2CylinderEngine.glb").string(), kAspect);
  ::testing::internal::GetCapturedStderr();
  // The file's own camera (yfov 0.3143), its planes 0.05..10^6 pulled in around the engine.
  EXPECT_NEAR(scene.camera.verticalFovRadians, 0.3143f, 1e-4f);
  ExpectPlanesTightenedAroundTheScene(scene, 0.05f, 1e6f);
  EXPECT_GT(scene.camera.zNear, 100.0f);
  EXPECT_EQ(scene.TriangleCount(), 121496u);
  EXPECT_EQ(scene.meshes.size(), 115u);
  EXPECT_EQ(scene.name, "2CylinderEngine.glb");
  for (const glm::vec3& corner : {scene.bounds.min, scene.bounds.max}) {
    EXPECT_TRUE(std::isfinite(corner.x) && std::isfinite(corner.y) && std::isfinite(corner.z));
  }
  EXPECT_NEAR(scene.bounds.max.x - scene.bounds.min.x, 743.4f, 0.1f);
  for (const scenes::Mesh& mesh : scene.meshes) {
    EXPECT_EQ(mesh.normals.size(), mesh.positions.size()) << mesh.name;
  }
}

// What every loaded scene must satisfy, whatever the file: per-vertex attributes line up,
// material and texture references resolve, textured materials only on meshes with texcoords,
// texels are decoded colours, the camera is usable.
void ExpectConsistent(const scenes::Scene& scene, const std::string& what) {
  for (const scenes::Mesh& mesh : scene.meshes) {
    EXPECT_TRUE(mesh.texcoords.empty() || mesh.texcoords.size() == mesh.positions.size()) << what;
    ASSERT_LT(mesh.material, static_cast<int>(scene.materials.size())) << what;
    if (mesh.material >= 0 &&
        scene.materials[static_cast<std::size_t>(mesh.material)].baseColourTexture >= 0) {
      EXPECT_FALSE(mesh.texcoords.empty()) << what << " " << mesh.name;
    }
    for (const glm::vec2& uv : mesh.texcoords) {
      ASSERT_TRUE(std::isfinite(uv.x) && std::isfinite(uv.y)) << what;
    }
  }
  for (const scenes::Material& material : scene.materials) {
    EXPECT_LT(material.baseColourTexture, static_cast<int>(scene.textures.size())) << what;
  }
  for (const scenes::Texture& texture : scene.textures) {
    ASSERT_EQ(texture.texels.size(), static_cast<std::size_t>(texture.width * texture.height))
        << what;
    for (const glm::vec4& texel : texture.texels) {
      for (int c = 0; c < 4; ++c) ASSERT_TRUE(texel[c] >= 0.0f && texel[c] <= 1.0f) << what;
    }
  }
  EXPECT_GT(scene.camera.zNear, 0.0f) << what;
  EXPECT_GT(scene.camera.zFar, scene.camera.zNear) << what;
  EXPECT_GT(glm::length(scene.camera.target - scene.camera.eye), 0.0f) << what;
}

TEST(SceneGltfAssets, EveryAssimpGltf2FileLoadsOrThrowsSceneError) {
  std::size_t files = 0;
  std::size_t loaded = 0;
  std::size_t textured = 0;
  ::testing::internal::CaptureStderr();
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(scenes_test::Gltf2Models())) {
    const std::string extension = entry.path().extension().string();
    if (extension != ".gltf" && extension != ".glb") continue;
    ++files;
    try {
      const scenes::Scene scene = scenes::LoadScene(entry.path().string(), kAspect);
      EXPECT_GT(scene.TriangleCount(), 0u) << entry.path();
      ExpectConsistent(scene, entry.path().string());
      textured += scene.textures.empty() ? 0 : 1;
      ++loaded;
    } catch (const scenes::SceneError& e) {
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).rfind(entry.path().string() + ": ", 0), 0u) << e.what();
    } catch (const std::exception& e) {
      ADD_FAILURE() << entry.path() << " threw a non-SceneError: " << e.what();
    }
  }
  ::testing::internal::GetCapturedStderr();
  EXPECT_GE(files, 40u);
  EXPECT_GE(loaded, 20u);
  EXPECT_GE(textured, 8u);
}

TEST(SceneGltfAssets, BoxTexturedInEveryContainerCarriesItsTexture) {
  for (const char* file :
       {"BoxTextured-glTF/BoxTextured.gltf", "BoxTextured-glTF-Binary/BoxTextured.glb",
        "BoxTextured-glTF-Embedded/BoxTextured.gltf"}) {
    ::testing::internal::CaptureStderr();
    const scenes::Scene scene = scenes::LoadGltf(scenes_test::Gltf2Models() / file, kAspect);
    ::testing::internal::GetCapturedStderr();
    ASSERT_EQ(scene.meshes.size(), 1u) << file;
    const scenes::Mesh& mesh = scene.meshes[0];
    EXPECT_EQ(mesh.texcoords.size(), mesh.positions.size()) << file;
    ASSERT_EQ(scene.textures.size(), 1u) << file;
    EXPECT_EQ(scene.textures[0].width, 211) << file;
    EXPECT_EQ(scene.textures[0].height, 211) << file;
    ASSERT_EQ(mesh.material, 0) << file;
    EXPECT_EQ(scene.materials[0].baseColourTexture, 0) << file;
    // The Cesium logo is mostly a light background with green and grey: not one flat colour.
    const auto [darkest, lightest] = std::minmax_element(
        scene.textures[0].texels.begin(), scene.textures[0].texels.end(),
        [](const glm::vec4& a, const glm::vec4& b) { return a.g < b.g; });
    EXPECT_GT(lightest->g - darkest->g, 0.5f) << file;
  }
}

TEST(SceneGltfAssets, TextureTransformTestDecodesAllFiveImages) {
  ::testing::internal::CaptureStderr();
  const scenes::Scene scene =
      scenes::LoadGltf(scenes_test::Gltf2Models() / "textureTransform/TextureTransformTest.gltf", kAspect);
  const std::string warnings = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(scene.textures.size(), 5u);
  EXPECT_EQ(scene.materials.size(), 9u);
  EXPECT_NE(warnings.find("KHR_texture_transform is ignored"), std::string::npos) << warnings;
  for (const scenes::Mesh& mesh : scene.meshes) EXPECT_FALSE(mesh.texcoords.empty());
}

TEST(SceneGltfAssets, CamerasGltfUsesItsPerspectiveCamera) {
  ::testing::internal::CaptureStderr();
  const scenes::Scene scene = scenes::LoadGltf(scenes_test::Gltf2Models() / "cameras/Cameras.gltf", kAspect);
  const std::string warnings = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(scene.camera.eye, glm::vec3(0.5f, 0.5f, 3.0f));
  EXPECT_NEAR(glm::distance(glm::normalize(scene.camera.target - scene.camera.eye),
                            glm::vec3(0, 0, -1)),
              0.0f, 1e-6f);
  EXPECT_FLOAT_EQ(scene.camera.verticalFovRadians, 0.7f);
  ExpectPlanesTightenedAroundTheScene(scene, 0.01f, 100.0f);
  // Its aspectRatio of 1 differs from the image's; yfov wins and the user is told.
  EXPECT_NE(warnings.find("aspectRatio 1 differs"), std::string::npos) << warnings;
}

// ---------------------------------------------------------------------------------------------
// Built-in scenes

// Edges used once are boundary; interior edges must be used exactly twice, in opposite
// directions. Returns the number of boundary edges.
std::size_t CheckWatertight(const scenes::Mesh& mesh) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    for (std::size_t k = 0; k < 3; ++k) {
      ++directed[{mesh.indices[t + k], mesh.indices[t + (k + 1) % 3]}];
    }
  }
  std::size_t boundary = 0;
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1) << "edge " << edge.first << "-" << edge.second << " repeats a direction";
    if (directed.find({edge.second, edge.first}) == directed.end()) ++boundary;
  }
  return boundary;
}

TEST(SceneBuiltin, NamesAreListedAndEachLoads) {
  const std::vector<std::string> names = scenes::BuiltinSceneNames();
  EXPECT_EQ(names, (std::vector<std::string>{"default", "thin-fan", "subpixel-grid", "spike-room",
                                             "fence", "subpixel", "pixel-crossing",
                                             "intersecting-planes", "wheel", "stair-steps",
                                             "textured-plane"}));
  for (const std::string& name : names) {
    const scenes::Scene scene = scenes::LoadScene("builtin:" + name, kAspect);
    EXPECT_EQ(scene.name, name);
    EXPECT_GT(scene.TriangleCount(), 0u);
    for (const scenes::Mesh& mesh : scene.meshes) {
      EXPECT_EQ(mesh.normals.size(), mesh.positions.size()) << mesh.name;
      for (std::uint32_t index : mesh.indices) ASSERT_LT(index, mesh.positions.size());
    }
  }
}

TEST(SceneBuiltin, UnknownNameListsTheNames) {
  try {
    scenes::LoadScene("builtin:teapot", kAspect);
    ADD_FAILURE() << "builtin:teapot loaded";
  } catch (const scenes::SceneError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("builtin:teapot"), std::string::npos) << message;
    EXPECT_NE(message.find("default, thin-fan, subpixel-grid"), std::string::npos) << message;
  }
}

TEST(SceneBuiltin, ThinFanIsWatertight) {
  const scenes::Scene scene = scenes::MakeBuiltinScene("thin-fan", kAspect);
  ASSERT_EQ(scene.meshes.size(), 1u);
  EXPECT_EQ(scene.TriangleCount(), 256u);
  EXPECT_EQ(CheckWatertight(scene.meshes[0]), 256u);  // the rim
}

TEST(SceneBuiltin, SubpixelGridIsWatertight) {
  const scenes::Scene scene = scenes::MakeBuiltinScene("subpixel-grid", kAspect);
  ASSERT_EQ(scene.meshes.size(), 1u);
  EXPECT_EQ(scene.TriangleCount(), 2u * 400u * 400u);
  EXPECT_EQ(CheckWatertight(scene.meshes[0]), 4u * 400u);  // the outline
}

TEST(SceneBuiltin, IsDeterministic) {
  for (const std::string& name : scenes::BuiltinSceneNames()) {
    const scenes::Scene first = scenes::MakeBuiltinScene(name, kAspect);
    const scenes::Scene second = scenes::MakeBuiltinScene(name, kAspect);
    ASSERT_EQ(first.meshes.size(), second.meshes.size()) << name;
    for (std::size_t m = 0; m < first.meshes.size(); ++m) {
      EXPECT_EQ(first.meshes[m].positions, second.meshes[m].positions) << name;
      EXPECT_EQ(first.meshes[m].normals, second.meshes[m].normals) << name;
      EXPECT_EQ(first.meshes[m].indices, second.meshes[m].indices) << name;
    }
  }
}

TEST(SceneBuiltin, DefaultFrontFacesAgreeWithNormals) {
  const scenes::Scene scene = scenes::MakeBuiltinScene("default", kAspect);
  EXPECT_EQ(scene.meshes.size(), 4u);
  for (const scenes::Mesh& mesh : scene.meshes) {
    for (std::size_t t = 0; t < mesh.indices.size() / 3; ++t) {
      const glm::vec3 vertexNormals = mesh.normals[mesh.indices[3 * t]] +
                                      mesh.normals[mesh.indices[3 * t + 1]] +
                                      mesh.normals[mesh.indices[3 * t + 2]];
      ASSERT_GT(glm::dot(FaceNormal(mesh, t), vertexNormals), 0.0f) << mesh.name << " " << t;
    }
  }
}

glm::vec4 ToClip(const scenes::Camera& camera, float aspect, const glm::vec3& p) {
  return camera.Projection(aspect) * camera.View() * glm::vec4(p, 1.0f);
}

// Seen through the scene's camera, every triangle is counter-clockwise (front-facing).
TEST(SceneBuiltin, FlatScenesFaceTheCamera) {
  for (const char* name : {"thin-fan", "subpixel-grid"}) {
    const scenes::Scene scene = scenes::MakeBuiltinScene(name, kAspect);
    const scenes::Mesh& mesh = scene.meshes.at(0);
    std::vector<glm::vec2> ndc;
    for (const glm::vec3& p : mesh.positions) {
      const glm::vec4 clip = ToClip(scene.camera, kAspect, p);
      ndc.emplace_back(clip.x / clip.w, clip.y / clip.w);
    }
    for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
      const glm::vec2 a = ndc[mesh.indices[t]];
      const glm::vec2 b = ndc[mesh.indices[t + 1]];
      const glm::vec2 c = ndc[mesh.indices[t + 2]];
      const float area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
      ASSERT_GT(area, 0.0f) << name << " triangle " << t / 3;
    }
  }
}

TEST(SceneBuiltin, SubpixelGridCellsAreSmallerThanHalfAPixelAt1080p) {
  const scenes::Scene scene = scenes::MakeBuiltinScene("subpixel-grid", kAspect);
  const scenes::Mesh& mesh = scene.meshes.at(0);
  const auto toPixels = [&](const glm::vec3& p) {
    const glm::vec4 clip = ToClip(scene.camera, kAspect, p);
    return glm::vec2(clip.x / clip.w * 960.0f, clip.y / clip.w * 540.0f);
  };
  const std::size_t centre = 200 * 401 + 200;
  const float width = glm::distance(toPixels(mesh.positions[centre]),
                                    toPixels(mesh.positions[centre + 1]));
  const float height = glm::distance(toPixels(mesh.positions[centre]),
                                     toPixels(mesh.positions[centre + 401]));
  EXPECT_LT(width, 0.5f);
  EXPECT_LT(height, 0.5f);
  EXPECT_GT(width, 0.1f);  // still on screen as a visible patch of ~175 px
}

// ---------------------------------------------------------------------------------------------
// Camera

std::array<glm::vec3, 8> Corners(const scenes::Bounds& bounds) {
  std::array<glm::vec3, 8> corners;
  for (std::size_t i = 0; i < 8; ++i) {
    corners[i] = {(i & 1) ? bounds.max.x : bounds.min.x, (i & 2) ? bounds.max.y : bounds.min.y,
                  (i & 4) ? bounds.max.z : bounds.min.z};
  }
  return corners;
}

void ExpectInsideClipVolume(const scenes::Camera& camera, float aspect,
                            const scenes::Bounds& bounds) {
  for (const glm::vec3& corner : Corners(bounds)) {
    const glm::vec4 clip = ToClip(camera, aspect, corner);
    EXPECT_LE(std::abs(clip.x), clip.w) << "aspect " << aspect;
    EXPECT_LE(std::abs(clip.y), clip.w) << "aspect " << aspect;
    EXPECT_GE(clip.z, 0.0f) << "aspect " << aspect;
    EXPECT_LE(clip.z, clip.w) << "aspect " << aspect;
  }
}

TEST(SceneCamera, FrameBoundsKeepsAllCornersInsideClipVolume) {
  const std::vector<scenes::Bounds> boxes = {
      {{-1, -1, -1}, {1, 1, 1}},
      {{100, -3, 7}, {140, -2, 7}},
      {{-371.7f, -181.0f, -140.0f}, {371.7f, 92.0f, 128.0f}},
      {{0.001f, 0.001f, 0.001f}, {0.002f, 0.5f, 0.002f}},
      {{3, 3, 3}, {3, 3, 3}}};
  for (const scenes::Bounds& bounds : boxes) {
    for (float aspect : {16.0f / 9.0f, 1.0f, 0.5f, 4.0f}) {
      ExpectInsideClipVolume(scenes::FrameBounds(bounds, aspect), aspect, bounds);
    }
  }
}

// textured-plane's floor runs out of the sides of the view on purpose; every other built-in
// scene is seen whole.
TEST(SceneCamera, BuiltinCamerasFrameTheirScenes) {
  for (const std::string& name : scenes::BuiltinSceneNames()) {
    if (name == "textured-plane") continue;
    const scenes::Scene scene = scenes::MakeBuiltinScene(name, kAspect);
    ExpectInsideClipVolume(scene.camera, kAspect, scene.bounds);
  }
}

TEST(SceneCamera, BuiltinCamerasKeepEveryVertexBetweenTheClipPlanes) {
  for (const std::string& name : scenes::BuiltinSceneNames()) {
    const scenes::Scene scene = scenes::MakeBuiltinScene(name, kAspect);
    for (const scenes::Mesh& mesh : scene.meshes) {
      for (const glm::vec3& p : mesh.positions) {
        const glm::vec4 clip = ToClip(scene.camera, kAspect, p);
        ASSERT_GE(clip.z, 0.0f) << name << " " << mesh.name;
        ASSERT_LE(clip.z, clip.w) << name << " " << mesh.name;
      }
    }
  }
}

TEST(SceneCamera, ProjectionUsesD3DDepthRangeAndYUp) {
  scenes::Camera camera;
  camera.eye = {0, 0, 10};
  camera.target = {0, 0, 0};
  const glm::vec4 nearPoint = ToClip(camera, 1.0f, {0, 0, 10 - camera.zNear});
  const glm::vec4 farPoint = ToClip(camera, 1.0f, {0, 0, 10 - camera.zFar});
  const glm::vec4 above = ToClip(camera, 1.0f, {0, 1, 0});
  EXPECT_NEAR(nearPoint.z / nearPoint.w, 0.0f, 1e-6f);
  EXPECT_NEAR(farPoint.z / farPoint.w, 1.0f, 1e-5f);
  EXPECT_GT(above.y, 0.0f);
}

TEST(SceneCamera, FrameBoundsRejectsBadAspect) {
  const scenes::Bounds bounds{{-1, -1, -1}, {1, 1, 1}};
  EXPECT_THROW(scenes::FrameBounds(bounds, 0.0f), scenes::SceneError);
  EXPECT_THROW(scenes::FrameBounds(bounds, std::numeric_limits<float>::quiet_NaN()),
               scenes::SceneError);
}

TEST(SceneCamera, ComputeBoundsCoversAllMeshes) {
  scenes::Mesh a;
  a.positions = {{1, 2, 3}, {-1, 0, 5}};
  scenes::Mesh b;
  b.positions = {{0, -4, 0}};
  const scenes::Bounds bounds = scenes::ComputeBounds({a, b});
  EXPECT_EQ(bounds.min, glm::vec3(-1, -4, 0));
  EXPECT_EQ(bounds.max, glm::vec3(1, 2, 5));
  EXPECT_FLOAT_EQ(bounds.Radius(), 0.5f * std::sqrt(4.0f + 36.0f + 25.0f));
  EXPECT_EQ(scenes::ComputeBounds({}).Radius(), 0.0f);
}

}  // namespace
