// Tests of scenes/: glTF flattening and validation on files written here and on the assimp test
// models, the built-in scenes' claimed properties, and camera framing.

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
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "scenes/scene.h"

// Readable failure output for vectors compared with EXPECT_EQ (found by argument lookup).
// Static: the suite is one binary and other test files may print glm types their own way.
namespace glm {
static void PrintTo(const vec3& v, std::ostream* out) {
  *out << '(' << v.x << ", " << v.y << ", " << v.z << ')';
}
}  // namespace glm

#ifndef AASIM_TESTMODELS_DIR
#define AASIM_TESTMODELS_DIR "/usr/share/assimp/models"
#endif

namespace {

namespace fs = std::filesystem;

constexpr float kAspect = 16.0f / 9.0f;
constexpr int kUnsignedByte = 5121;
constexpr int kUnsignedShort = 5123;
constexpr int kUnsignedInt = 5125;
constexpr int kFloat = 5126;
const fs::path kGltf2Models = fs::path(AASIM_TESTMODELS_DIR) / "glTF2";

std::string Base64(const std::vector<unsigned char>& bytes) {
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
  std::vector<int> sceneNodes{0};
  std::string bufferUri;

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
    std::string json = R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":)";
    json.append(JoinJson(roots)).append(R"(}],"nodes":)").append(JoinJson(nodes));
    json.append(R"(,"meshes":)").append(JoinJson(meshes));
    json.append(R"(,"accessors":)").append(JoinJson(accessors));
    json.append(R"(,"bufferViews":)").append(JoinJson(bufferViews));
    json.append(R"(,"buffers":[{"byteLength":)").append(std::to_string(buffer_.size()));
    json.append(R"(,"uri":")");
    if (bufferUri.empty()) {
      json.append("data:application/octet-stream;base64,").append(Base64(buffer_));
    } else {
      json.append(bufferUri);
    }
    return json.append(R"("}]})");
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

// A fresh directory per test, so tests can run in parallel processes.
fs::path TestDir() {
  const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::temp_directory_path() / "aasim_scenes_test" /
                       (std::string(info->test_suite_name()) + "." + info->name());
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

fs::path WriteText(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

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

std::string Primitive(int position, int indices, int mode = 4, int normal = -1) {
  std::string attributes = R"("POSITION":)" + std::to_string(position);
  if (normal >= 0) attributes += R"(,"NORMAL":)" + std::to_string(normal);
  std::string text = R"({"attributes":{)" + attributes + "}";
  if (indices >= 0) text += R"(,"indices":)" + std::to_string(indices);
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
    writer.AddMesh("[" + Primitive(position, indices) + "]");
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
  writer.AddMesh("[" + Primitive(position, indices) + "]");
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

TEST(SceneGltfErrors, AssimpModelsWithKnownDefects) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"IndexOutOfRange/IndexOutOfRange.gltf", "is out of range (24 vertices)"},
      {"BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb", "has a non-finite position (-inf"},
      {"RecursiveNodes/RecursiveNodes.gltf", "recursive node graph"},
      {"MissingBin/BoxTextured.gltf", "BoxTextured0.bin"},
      {"draco/2CylinderEngine.gltf", "Draco-compressed meshes"},
      {"IncorrectVertexArrays/Cube.gltf", "not a multiple of 3"}};
  for (const auto& [file, problem] : cases) {
    const fs::path path = kGltf2Models / file;
    const std::string message = LoadError(path);
    EXPECT_EQ(message.rfind(path.string() + ": ", 0), 0u) << message;
    EXPECT_NE(message.find(problem), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

// ---------------------------------------------------------------------------------------------
// Real assets

TEST(SceneGltfAssets, TwoCylinderEngineLoads) {
  const scenes::Scene scene = scenes::LoadScene(
      (kGltf2Models / "2CylinderEngine-glTF-Binary/2CylinderEngine.glb").string(), kAspect);
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

TEST(SceneGltfAssets, EveryAssimpGltf2FileLoadsOrThrowsSceneError) {
  std::size_t files = 0;
  std::size_t loaded = 0;
  ::testing::internal::CaptureStderr();
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(kGltf2Models)) {
    const std::string extension = entry.path().extension().string();
    if (extension != ".gltf" && extension != ".glb") continue;
    ++files;
    try {
      const scenes::Scene scene = scenes::LoadScene(entry.path().string(), kAspect);
      EXPECT_GT(scene.TriangleCount(), 0u) << entry.path();
      ++loaded;
    } catch (const scenes::SceneError& e) {
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    } catch (const std::exception& e) {
      ADD_FAILURE() << entry.path() << " threw a non-SceneError: " << e.what();
    }
  }
  ::testing::internal::GetCapturedStderr();
  EXPECT_GE(files, 40u);
  EXPECT_GE(loaded, 20u);
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
  EXPECT_EQ(names, (std::vector<std::string>{"default", "thin-fan", "subpixel-grid"}));
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

TEST(SceneCamera, BuiltinCamerasFrameTheirScenes) {
  for (const std::string& name : scenes::BuiltinSceneNames()) {
    const scenes::Scene scene = scenes::MakeBuiltinScene(name, kAspect);
    ExpectInsideClipVolume(scene.camera, kAspect, scene.bounds);
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
