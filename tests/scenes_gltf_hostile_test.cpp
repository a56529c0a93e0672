// The glTF reader against hostile input (issue 10): nesting depth, the GLB container, URIs that
// name FIFOs, directories and devices, image dimensions, the glTF 2.0 schema of every property,
// numbers that break later stages, and a mutation sweep over three small valid documents. Every
// reproducer is built here, in a fresh directory per test.

#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <set>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>
#include <stb_image_write.h>

#include "scenes/gltf_loader.h"
#include "scenes/scene.h"
#include "scenes/texture.h"
#include "scenes_test_util.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using Bytes = std::vector<std::uint8_t>;

fs::path WriteBytes(const fs::path& path, const Bytes& bytes) {
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
  return path;
}

Bytes ToBytes(const std::string& text) { return {text.begin(), text.end()}; }

using scenes_test::Base64;
using scenes_test::kAspect;
using scenes_test::TestDir;
using scenes_test::WriteText;

template <typename T>
void Append(Bytes& bytes, const std::vector<T>& values) {
  const auto* first = reinterpret_cast<const std::uint8_t*>(values.data());
  bytes.insert(bytes.end(), first, first + values.size() * sizeof(T));
}

void AppendU32(Bytes& bytes, std::uint32_t value) {
  for (int b = 0; b < 4; ++b) bytes.push_back(static_cast<std::uint8_t>(value >> (8 * b)));
}

void PutU32(Bytes& bytes, std::size_t at, std::uint32_t value) {
  for (std::size_t b = 0; b < 4; ++b) bytes[at + b] = static_cast<std::uint8_t>(value >> (8 * b));
}

std::string DataUri(const Bytes& bytes, const std::string& mediaType) {
  return "data:" + mediaType + ";base64," + Base64(bytes);
}

// --- Images ------------------------------------------------------------------------------------

void AppendToBytes(void* context, void* data, int size) {
  auto* out = static_cast<Bytes*>(context);
  const auto* first = static_cast<const std::uint8_t*>(data);
  out->insert(out->end(), first, first + size);
}

Bytes EncodePng(int width, int height, int channels, const Bytes& pixels) {
  Bytes png;
  EXPECT_NE(stbi_write_png_to_func(&AppendToBytes, &png, width, height, channels, pixels.data(),
                                   width * channels),
            0);
  return png;
}

Bytes EncodeJpeg(int width, int height, const Bytes& rgb) {
  Bytes jpeg;
  EXPECT_NE(stbi_write_jpg_to_func(&AppendToBytes, &jpeg, width, height, 3, rgb.data(), 100), 0);
  return jpeg;
}

std::uint32_t Crc32(const Bytes& data) {
  std::uint32_t crc = ~0u;
  for (std::uint8_t byte : data) {
    crc ^= byte;
    for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

void AppendBigEndian(Bytes& bytes, std::uint32_t value) {
  for (int b = 3; b >= 0; --b) bytes.push_back(static_cast<std::uint8_t>(value >> (8 * b)));
}

// A PNG signature and IHDR claiming `width` x `height` 8-bit grey, and nothing else: what a
// decoder would allocate for is in the header, so no pixel data is needed to provoke it.
// (stb_image itself refuses more than 2^30 bytes of 8-bit texels; grey stays under that.)
Bytes PngHeaderOnly(std::uint32_t width, std::uint32_t height) {
  Bytes png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  Bytes chunk = {'I', 'H', 'D', 'R'};
  AppendBigEndian(chunk, width);
  AppendBigEndian(chunk, height);
  chunk.insert(chunk.end(), {8, 0, 0, 0, 0});
  AppendBigEndian(png, 13);
  png.insert(png.end(), chunk.begin(), chunk.end());
  AppendBigEndian(png, Crc32(chunk));
  return png;
}

// --- Three small valid documents ---------------------------------------------------------------

// One triangle; its buffer a data URI (or, for a GLB, the BIN chunk).
json TriangleDocument(Bytes* glbBin = nullptr) {
  Bytes buffer;
  Append(buffer, std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0});
  json document = json::parse(R"({
    "asset": {"version": "2.0", "generator": "aasim tests"},
    "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                   "min": [0, 0, 0], "max": [1, 1, 0]}],
    "bufferViews": [{"buffer": 0, "byteLength": 36}],
    "buffers": [{"byteLength": 36}]})");
  if (glbBin != nullptr) {
    *glbBin = buffer;
  } else {
    document["buffers"][0]["uri"] = DataUri(buffer, "application/octet-stream");
  }
  return document;
}

// A square with texture coordinates, indices and a textured, tinted material.
json TexturedQuadDocument() {
  Bytes buffer;
  Append(buffer, std::vector<float>{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0});
  Append(buffer, std::vector<float>{0, 1, 1, 1, 1, 0, 0, 0});
  Append(buffer, std::vector<std::uint16_t>{0, 1, 2, 0, 2, 3});
  const Bytes png =
      EncodePng(2, 2, 4, {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 9, 9, 9, 9});
  json document = json::parse(R"({
    "asset": {"version": "2.0"},
    "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2,
                                "material": 0, "mode": 4}]}],
    "accessors": [
      {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3"},
      {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
      {"bufferView": 2, "byteOffset": 0, "componentType": 5123, "count": 6, "type": "SCALAR"}],
    "bufferViews": [{"buffer": 0, "byteLength": 48},
                    {"buffer": 0, "byteOffset": 48, "byteLength": 32},
                    {"buffer": 0, "byteOffset": 80, "byteLength": 12, "target": 34963}],
    "materials": [{"name": "paint", "pbrMetallicRoughness": {
        "baseColorFactor": [1, 0.5, 0.25, 1], "baseColorTexture": {"index": 0, "texCoord": 0},
        "metallicFactor": 0}}],
    "textures": [{"sampler": 0, "source": 0}],
    "samplers": [{"magFilter": 9729, "minFilter": 9987, "wrapS": 10497, "wrapT": 10497}],
    "images": [{"name": "checker"}],
    "buffers": [{"byteLength": 92}]})");
  document["images"][0]["uri"] = DataUri(png, "image/png");
  document["buffers"][0]["uri"] = DataUri(buffer, "application/octet-stream");
  return document;
}

// A node hierarchy with translation, rotation, scale and a matrix, and a perspective camera.
json HierarchyWithCameraDocument() {
  Bytes buffer;
  Append(buffer, std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0});
  Append(buffer, std::vector<float>{0, 0, 1, 0, 0, 1, 0, 0, 1});
  Append(buffer, std::vector<std::uint8_t>{0, 1, 2, 0});
  json document = json::parse(R"({
    "asset": {"version": "2.0", "minVersion": "2.0"},
    "scene": 0, "scenes": [{"name": "main", "nodes": [0]}],
    "nodes": [
      {"name": "root", "children": [1, 2], "translation": [1, 2, 3], "extras": {"note": [1]}},
      {"mesh": 0, "rotation": [0, 0, 0.7071067811865476, 0.7071067811865476],
       "scale": [2, 2, 2]},
      {"camera": 0, "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 10, 1]}],
    "cameras": [{"type": "perspective",
                 "perspective": {"yfov": 0.8, "znear": 0.1, "zfar": 100, "aspectRatio": 1.5}}],
    "meshes": [{"name": "tri", "primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1},
                                               "indices": 2}]}],
    "accessors": [
      {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
      {"bufferView": 0, "byteOffset": 36, "componentType": 5126, "count": 3, "type": "VEC3"},
      {"bufferView": 1, "componentType": 5121, "count": 3, "type": "SCALAR"}],
    "bufferViews": [{"buffer": 0, "byteLength": 72}, {"buffer": 0, "byteOffset": 72,
                                                       "byteLength": 3}],
    "buffers": [{"byteLength": 76}]})");
  document["buffers"][0]["uri"] = DataUri(buffer, "application/octet-stream");
  return document;
}

// A GLB container: JSON chunk padded with spaces, BIN chunk with zeros (glTF 2.0, "Chunks").
Bytes MakeGlb(const std::string& text, const Bytes& bin) {
  Bytes jsonChunk(text.begin(), text.end());
  while (jsonChunk.size() % 4 != 0) jsonChunk.push_back(' ');
  Bytes binChunk = bin;
  while (binChunk.size() % 4 != 0) binChunk.push_back(0);
  Bytes glb;
  AppendU32(glb, 0x46546C67u);
  AppendU32(glb, 2);
  AppendU32(glb, static_cast<std::uint32_t>(12 + 8 + jsonChunk.size() + 8 + binChunk.size()));
  AppendU32(glb, static_cast<std::uint32_t>(jsonChunk.size()));
  AppendU32(glb, 0x4E4F534Au);
  glb.insert(glb.end(), jsonChunk.begin(), jsonChunk.end());
  AppendU32(glb, static_cast<std::uint32_t>(binChunk.size()));
  AppendU32(glb, 0x004E4942u);
  glb.insert(glb.end(), binChunk.begin(), binChunk.end());
  return glb;
}

// --- Loading -----------------------------------------------------------------------------------

// `dir`: where URIs resolve; a fresh empty one unless given.
scenes::Scene LoadText(const std::string& text, const std::string& name = "doc.gltf",
                       const fs::path& dir = {}) {
  return scenes::LoadGltfFromMemory(ToBytes(text), false, dir.empty() ? TestDir() : dir, name,
                                    kAspect);
}

// The SceneError message, or a test failure if the load succeeds or throws anything else.
std::string LoadErrorOf(const std::function<void()>& load) {
  try {
    load();
  } catch (const scenes::SceneError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_LT(message.size(), 600u) << message;
    return message;
  }
  ADD_FAILURE() << "loaded, expected a SceneError";
  return {};
}

std::string FileError(const fs::path& path) {
  return LoadErrorOf([&] { scenes::LoadGltf(path, kAspect); });
}

std::string TextError(const std::string& text) {
  return LoadErrorOf([&] { LoadText(text); });
}

std::string DocumentError(const json& document) { return TextError(document.dump()); }

#define EXPECT_CONTAINS(text, part) \
  EXPECT_NE(std::string(text).find(part), std::string::npos) << "in: " << (text)

// ---------------------------------------------------------------------------------------------
// JSON nesting

// Before the fix: SIGSEGV in tinygltf's recursive copy of `extras`.
TEST(GltfHostileJson, TwentyThousandNestedArraysInExtrasAreRefused) {
  json document = TriangleDocument();
  document["extras"] = 0;
  std::string text = document.dump();
  const std::string nested = std::string(20000, '[') + std::string(20000, ']');
  text.replace(text.find("\"extras\":0"), 10, "\"extras\":" + nested);
  ASSERT_GT(text.size(), 40000u);
  const std::string message = FileError(WriteText(TestDir() / "deep.gltf", text));
  EXPECT_CONTAINS(message, "deep.gltf: JSON arrays and objects nest more than 64 levels deep");
}

TEST(GltfHostileJson, NestingLimitIsExactly64Levels) {
  // The document is level 1 and `extras` holds the rest.
  for (const int levels : {64, 65}) {
    json document = TriangleDocument();
    document["extras"] = 0;
    std::string text = document.dump();
    const int arrays = levels - 1;
    text.replace(text.find("\"extras\":0"), 10,
                 "\"extras\":" + std::string(static_cast<std::size_t>(arrays), '[') +
                     std::string(static_cast<std::size_t>(arrays), ']'));
    if (levels == 64) {
      EXPECT_EQ(LoadText(text).TriangleCount(), 1u);
    } else {
      EXPECT_CONTAINS(TextError(text), "more than 64 levels");
    }
  }
}

TEST(GltfHostileJson, ParserReportsQuoteNoMoreThanAnExcerpt) {
  // Built with append: GCC 12 warns falsely (-Wrestrict) on "literal" + temporary.
  std::string hugeNumber = R"({"asset":{"version":"2.0"},"scene":1)";
  std::string message = TextError(hugeNumber.append(100000, '0').append("}"));
  EXPECT_CONTAINS(message, "doc.gltf: cannot load glTF: malformed JSON: ");
  std::string badString = "{\"asset\":\"";
  message = TextError(badString.append(50000, 'x').append("\x01\"}"));
  EXPECT_CONTAINS(message, "malformed JSON: parse error");
}

// ---------------------------------------------------------------------------------------------
// GLB container

struct GlbCase {
  std::string what;
  std::function<void(Bytes&)> damage;
  std::string problem;
};

TEST(GltfHostileGlb, WellFormedContainerLoads) {
  Bytes bin;
  const json document = TriangleDocument(&bin);
  const Bytes glb = MakeGlb(document.dump(), bin);
  const scenes::Scene scene =
      scenes::LoadGltf(WriteBytes(TestDir() / "triangle.glb", glb), kAspect);
  EXPECT_EQ(scene.TriangleCount(), 1u);
  EXPECT_EQ(scene.meshes.at(0).positions.at(1), glm::vec3(1, 0, 0));
}

// Before the fix the first case loaded, and tinygltf read 8 bytes past the heap buffer.
TEST(GltfHostileGlb, EveryLayoutDefectNamesItsFieldAndByte) {
  Bytes bin;
  const std::string text = TriangleDocument(&bin).dump();
  const Bytes good = MakeGlb(text, bin);
  const std::size_t binHeader = good.size() - 8 - 36;
  const auto jsonLength = static_cast<std::uint32_t>(binHeader - 20);
  const std::vector<GlbCase> cases = {
      {"BIN chunk 8 bytes longer than the file", [&](Bytes& b) { PutU32(b, binHeader, 44); },
       "GLB chunk 1 at byte " + std::to_string(binHeader) +
           ": chunk length 44 runs 8 bytes past the end of the file"},
      {"short header", [](Bytes& b) { b.resize(10); },
       "GLB header: the file is 10 bytes, shorter than the 12-byte header"},
      {"magic", [](Bytes& b) { b[0] = 'G'; }, "GLB magic (byte 0) is 0x46546C47"},
      {"version", [](Bytes& b) { PutU32(b, 4, 1); },
       "GLB version (byte 4) is 1; aasim reads version 2"},
      {"length too large",
       [&](Bytes& b) { PutU32(b, 8, static_cast<std::uint32_t>(b.size() + 4)); },
       "GLB length (byte 8) is " + std::to_string(good.size() + 4) + ", but the file holds " +
           std::to_string(good.size()) + " bytes"},
      {"trailing garbage",
       [](Bytes& b) {
         b.insert(b.end(), {1, 2, 3, 4});
         PutU32(b, 8, static_cast<std::uint32_t>(b.size()));
       },
       "GLB chunk 2 at byte " + std::to_string(good.size()) +
           ": 4 trailing bytes, too few for a chunk header"},
      {"JSON length not a multiple of 4", [&](Bytes& b) { PutU32(b, 12, jsonLength - 1); },
       "GLB chunk 0 at byte 12: chunk length " + std::to_string(jsonLength - 1) +
           " is not a multiple of 4"},
      {"BIN first", [](Bytes& b) { PutU32(b, 16, 0x004E4942u); },
       "GLB chunk 0 at byte 12: type 0x4E4942, expected JSON (0x4E4F534A)"},
      {"second JSON chunk", [&](Bytes& b) { PutU32(b, binHeader + 4, 0x4E4F534Au); },
       "GLB chunk 1 at byte " + std::to_string(binHeader) + ": a second JSON chunk"},
      {"no chunks",
       [](Bytes& b) {
         b.resize(12);
         PutU32(b, 8, 12);
       },
       "GLB has no chunks after its 12-byte header"},
  };
  for (const GlbCase& c : cases) {
    Bytes damaged = good;
    c.damage(damaged);
    const std::string message =
        LoadErrorOf([&] { scenes::LoadGltfFromMemory(damaged, true, TestDir(), "x.glb", kAspect); });
    EXPECT_CONTAINS(message, "x.glb: " + c.problem) << c.what;
  }
}

TEST(GltfHostileGlb, BinChunkMustHoldTheBufferAndNoMoreThanItsPadding) {
  Bytes bin;
  json document = TriangleDocument(&bin);
  document["buffers"][0]["byteLength"] = 40;
  document["bufferViews"][0]["byteLength"] = 36;
  std::string message = LoadErrorOf([&] {
    scenes::LoadGltfFromMemory(MakeGlb(document.dump(), bin), true, TestDir(), "x.glb", kAspect);
  });
  EXPECT_CONTAINS(message,
                  "x.glb: /buffers/0/byteLength: 40 bytes, but the GLB BIN chunk holds only 36");
  document["buffers"][0]["byteLength"] = 32;
  document["bufferViews"][0]["byteLength"] = 32;
  document["accessors"][0]["count"] = 2;
  message = LoadErrorOf([&] {
    scenes::LoadGltfFromMemory(MakeGlb(document.dump(), bin), true, TestDir(), "x.glb", kAspect);
  });
  EXPECT_CONTAINS(message, "GLB BIN chunk holds 36 (at most 3 bytes of padding allowed)");
  Bytes glb = MakeGlb(TriangleDocument(&bin).dump(), {});
  glb.resize(glb.size() - 8);
  PutU32(glb, 8, static_cast<std::uint32_t>(glb.size()));
  message = LoadErrorOf([&] { scenes::LoadGltfFromMemory(glb, true, TestDir(), "x.glb", kAspect); });
  EXPECT_CONTAINS(message, "/buffers/0: a buffer without uri, but the GLB has no BIN chunk");
}

TEST(GltfHostileGlb, UnknownChunksAndAnUnusedBinChunkAreSaidAndSkipped) {
  Bytes bin;
  Bytes glb = MakeGlb(TriangleDocument(&bin).dump(), bin);
  AppendU32(glb, 4);
  AppendU32(glb, 0x12345678u);
  AppendU32(glb, 0);
  PutU32(glb, 8, static_cast<std::uint32_t>(glb.size()));
  ::testing::internal::CaptureStderr();
  EXPECT_EQ(scenes::LoadGltfFromMemory(glb, true, TestDir(), "x.glb", kAspect).TriangleCount(), 1u);
  const Bytes unused = MakeGlb(TriangleDocument().dump(), bin);
  EXPECT_EQ(scenes::LoadGltfFromMemory(unused, true, TestDir(), "y.glb", kAspect).TriangleCount(),
            1u);
  const std::string warnings = ::testing::internal::GetCapturedStderr();
  EXPECT_CONTAINS(warnings,
                  "x.glb: warning: GLB chunks of unknown types are skipped (first: "
                  "chunk 2 at byte " +
                      std::to_string(glb.size() - 12) + ", type 0x12345678)");
  EXPECT_CONTAINS(warnings, "y.glb: warning: the GLB BIN chunk is not used");
}

// ---------------------------------------------------------------------------------------------
// URIs

json TriangleWithBufferUri(const std::string& uri) {
  json document = TriangleDocument();
  document["buffers"][0]["uri"] = uri;
  return document;
}

Bytes TriangleBufferBytes() {
  Bytes buffer;
  Append(buffer, std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0});
  return buffer;
}

// Before the fix: a FIFO blocked the load forever. Should the loader block, a writer that opens
// and closes the FIFO every 100 ms after the first 2 s lets each open() and read() return, so
// the test fails instead of hanging.
TEST(GltfHostileUri, FifoIsRefusedWithoutOpeningIt) {
  const fs::path dir = TestDir();
  const fs::path fifo = dir / "pipe.bin";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const fs::path gltf = WriteText(dir / "fifo.gltf", TriangleWithBufferUri("pipe.bin").dump());
  std::atomic<bool> done = false;
  std::thread rescue([&] {
    for (int tick = 0; !done; ++tick) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      if (tick < 20) continue;
      const int writer = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
      if (writer >= 0) ::close(writer);
    }
  });
  const auto start = std::chrono::steady_clock::now();
  const std::string message = FileError(gltf);
  done = true;
  rescue.join();
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(2));
  EXPECT_CONTAINS(message, "fifo.gltf: /buffers/0/uri 'pipe.bin': is a FIFO, not a regular file");
}

TEST(GltfHostileUri, DirectoriesDevicesAndMissingFilesAreRefused) {
  const fs::path dir = TestDir();
  fs::create_directory(dir / "folder.bin");
  fs::create_symlink("/dev/zero", dir / "zero.bin");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"folder.bin", "/buffers/0/uri 'folder.bin': is a directory, not a regular file"},
      {"zero.bin", "/buffers/0/uri 'zero.bin': is a device, not a regular file"},
      {"absent.bin", "/buffers/0/uri 'absent.bin': no such file"}};
  for (const auto& [uri, problem] : cases) {
    const fs::path gltf = WriteText(dir / "uri.gltf", TriangleWithBufferUri(uri).dump());
    EXPECT_CONTAINS(FileError(gltf), "uri.gltf: " + problem);
  }
  json document = TexturedQuadDocument();
  document["images"][0] = {{"uri", "zero.bin"}};
  const fs::path gltf = WriteText(dir / "image.gltf", document.dump());
  EXPECT_CONTAINS(FileError(gltf), "image.gltf: /images/0/uri 'zero.bin': is a device");
}

TEST(GltfHostileUri, SizeIsCheckedBeforeReading) {
  const fs::path dir = TestDir();
  const fs::path huge = dir / "huge.bin";
  WriteBytes(huge, {});
  fs::resize_file(huge, scenes::kMaxGltfFileBytes + 1);  // sparse: costs no disk
  fs::path gltf = WriteText(dir / "huge.gltf", TriangleWithBufferUri("huge.bin").dump());
  EXPECT_CONTAINS(FileError(gltf),
                  "/buffers/0/uri 'huge.bin': is 1073741825 bytes, more than the "
                  "1073741824 bytes aasim reads");
  fs::remove(huge);
  Bytes shortBuffer = TriangleBufferBytes();
  shortBuffer.resize(30);
  WriteBytes(dir / "short.bin", shortBuffer);
  gltf = WriteText(dir / "short.gltf", TriangleWithBufferUri("short.bin").dump());
  EXPECT_CONTAINS(FileError(gltf),
                  "short.gltf: /buffers/0/byteLength: 36 bytes, but uri 'short.bin' holds only 30");
}

TEST(GltfHostileUri, RelativePathsArePercentDecodedAgainstTheGltfDirectory) {
  const fs::path dir = TestDir();
  fs::create_directories(dir / "sub dir");
  WriteBytes(dir / "sub dir" / "tri angle.bin", TriangleBufferBytes());
  const std::string text = TriangleWithBufferUri("sub%20dir/tri%20angle.bin").dump();
  EXPECT_EQ(scenes::LoadGltf(WriteText(dir / "a.gltf", text), kAspect).TriangleCount(), 1u);
  // The memory entry point resolves against the directory it is given.
  EXPECT_EQ(scenes::LoadGltfFromMemory(ToBytes(text), false, dir, "mem.gltf", kAspect).name,
            "mem.gltf");
}

TEST(GltfHostileUri, SchemesAbsolutePathsAndBrokenEscapesAreRefused) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"http://example.com/a.bin", "URI scheme 'http' is not supported"},
      {"file:///etc/passwd", "URI scheme 'file' is not supported"},
      {"/etc/passwd", "an absolute path; glTF URIs are relative to the glTF file"},
      {"a%2.bin", "'%' at character 1 is not followed by two hex digits"},
      {"a.bin?x=1", "a URI with a query or fragment names no file"},
      {"a%00.bin", "the path holds a NUL"},
      {"data:application/octet-stream,AAAA", "a data: URI that is not base64"},
      {"data:application/octet-stream;base64,AA*A", "'*' at character 39 is not base64"},
      {"data:application/octet-stream;base64,AAA", "base64 data of 3 characters"},
      {"data:application/octet-stream;base64,AAAA", "36 bytes, but uri 'data:application"}};
  for (const auto& [uri, problem] : cases) {
    const std::string message = DocumentError(TriangleWithBufferUri(uri));
    EXPECT_CONTAINS(message, "doc.gltf: /buffers/0/");
    EXPECT_CONTAINS(message, problem);
  }
}

// ---------------------------------------------------------------------------------------------
// Images

json QuadWithImage(const Bytes& encoded, const std::string& mediaType) {
  json document = TexturedQuadDocument();
  document["images"][0]["uri"] = DataUri(encoded, mediaType);
  return document;
}

// Before the fix the decoder was asked for 20000 x 20000 RGBA texels (6.4 GB as floats).
TEST(GltfHostileImage, DimensionsAreCheckedFromTheHeaderBeforeDecoding) {
  std::string message = DocumentError(QuadWithImage(PngHeaderOnly(20000, 20000), "image/png"));
  EXPECT_CONTAINS(message,
                  "doc.gltf: image 0 'checker': image size 20000x20000 exceeds 16384 "
                  "texels on a side, the most aasim decodes");
  message = LoadErrorOf(
      [] { scenes::DecodeImage(PngHeaderOnly(8192, 8193), "big", scenes::ColourEncoding::Srgb); });
  EXPECT_CONTAINS(message, "big: image size 8192x8193 is 67117056 texels, more than the 67108864");
  message = LoadErrorOf(
      [] { scenes::DecodeImage(PngHeaderOnly(16385, 1), "wide", scenes::ColourEncoding::Srgb); });
  EXPECT_CONTAINS(message, "wide: image size 16385x1 exceeds 16384 texels on a side");
}

TEST(GltfHostileImage, ImagesAtTheSideLimitDecode) {
  const scenes::Texture wide = scenes::DecodeImage(EncodePng(16384, 1, 1, Bytes(16384, 255)),
                                                   "wide", scenes::ColourEncoding::Linear);
  EXPECT_EQ(wide.width, 16384);
  EXPECT_EQ(wide.texels.back(), glm::vec4(1.0f));
  EXPECT_EQ(scenes::ReadImageSize(PngHeaderOnly(8192, 8192), "square").height, 8192);
}

TEST(GltfHostileImage, DecodesPngAndJpeg) {
  const scenes::Texture png = scenes::DecodeImage(EncodePng(2, 1, 3, {255, 0, 0, 0, 0, 255}), "png",
                                                  scenes::ColourEncoding::Linear);
  ASSERT_EQ(png.texels.size(), 2u);
  EXPECT_EQ(png.texels[0], glm::vec4(1, 0, 0, 1));
  EXPECT_EQ(png.texels[1], glm::vec4(0, 0, 1, 1));
  const scenes::Texture jpeg = scenes::DecodeImage(EncodeJpeg(8, 8, Bytes(8 * 8 * 3, 200)), "jpg",
                                                   scenes::ColourEncoding::Linear);
  EXPECT_EQ(jpeg.width, 8);
  EXPECT_NEAR(jpeg.texels[27].g, 200.0f / 255.0f, 2.0f / 255.0f);
  EXPECT_EQ(scenes::SniffImageFormat(EncodeJpeg(1, 1, {1, 2, 3})), scenes::ImageFormat::Jpeg);
}

// Found by fuzz/image: a 74-byte PNG whose second chunk declares 1.9 GB made stb_image allocate
// a quarter of a GiB before it found the data missing.
TEST(GltfHostileImage, ChunkLengthsAreCheckedBeforeDecoding) {
  const Bytes png = {0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44,
                     0x52, 0x00, 0x00, 0x00, 0x03, 0x00, 0x00, 0x00, 0x02, 0x08, 0x06, 0x00, 0x00, 0x00, 0x9d,
                     0x66, 0x00, 0x00, 0x74, 0x1a, 0x00, 0x14, 0x49, 0x44, 0x41, 0x54, 0x78, 0x5e, 0x63, 0x64,
                     0x60, 0xe5, 0xe2, 0x17, 0x81, 0x02, 0x16, 0x1b, 0x20, 0x80, 0x71, 0x00, 0x1a, 0xa8, 0x02,
                     0x54, 0xb6, 0x0d, 0x49, 0x48, 0x44, 0x52, 0x00, 0x00, 0x24, 0x03, 0x00, 0x00, 0xae};
  ASSERT_EQ(png.size(), 74u);
  EXPECT_CONTAINS(LoadErrorOf([&] { scenes::DecodeImage(png, "fuzzed.png", scenes::ColourEncoding::Srgb); }),
                  "fuzzed.png: cannot decode: PNG chunk at byte 33 declares 1947861012 bytes, more than the 29 the file holds");
}

TEST(GltfHostileImage, BrokenImagesAreOneLineErrors) {
  Bytes truncated = EncodePng(4, 4, 4, Bytes(64, 7));
  truncated.resize(truncated.size() - 20);
  EXPECT_CONTAINS(
      LoadErrorOf([&] { scenes::DecodeImage(truncated, "cut", scenes::ColourEncoding::Srgb); }),
      "cut: cannot decode: ");
  EXPECT_CONTAINS(LoadErrorOf([] {
                    scenes::DecodeImage(Bytes{1, 2, 3}, "junk", scenes::ColourEncoding::Srgb);
                  }),
                  "junk: cannot decode: no PNG or JPEG signature");
  EXPECT_CONTAINS(
      LoadErrorOf([] { scenes::DecodeImage(Bytes{}, "empty", scenes::ColourEncoding::Srgb); }),
      "empty: cannot decode");
  // Every prefix of a valid PNG and JPEG: an error or a texture, never a crash.
  for (const Bytes& whole : {EncodePng(3, 2, 2, Bytes(12, 99)), EncodeJpeg(3, 2, Bytes(18, 99))}) {
    for (std::size_t size = 0; size < whole.size(); ++size) {
      const Bytes part(whole.begin(), whole.begin() + static_cast<std::ptrdiff_t>(size));
      try {
        scenes::DecodeImage(part, "part", scenes::ColourEncoding::Srgb);
      } catch (const scenes::SceneError&) {
      }
    }
  }
}

// An accessor without a bufferView costs no file bytes; instanced through a node graph, one could
// claim any amount of memory. The budget is checked before the primitive is read.
TEST(GltfHostileMemory, SceneVerticesAreBoundedBeforeReading) {
  json document = TriangleDocument();
  document["accessors"][0] = {{"componentType", 5126}, {"count", (1 << 25) + 2}, {"type", "VEC3"}};
  EXPECT_CONTAINS(DocumentError(document),
                  "doc.gltf: mesh 0 primitive 0: with its 33554434 vertices and 33554434 indices "
                  "the scene's mesh instances exceed 33554432 vertices");
  document["accessors"][0]["count"] = 3;
  document["accessors"].push_back({{"componentType", 5126}, {"count", 4}, {"type", "VEC3"}});
  document["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 1;
  EXPECT_CONTAINS(DocumentError(document), "mesh 0 primitive 0: 4 normals for 3 positions");
}

// ---------------------------------------------------------------------------------------------
// Schema

// Before the fix each of these loaded: the wrong type counted as an absent property.
TEST(GltfHostileSchema, WrongTypesFromTheIssueAreErrorsWithPointers) {
  const std::vector<std::pair<std::function<void(json&)>, std::string>> cases = {
      {[](json& d) { d["accessors"][0]["bufferView"] = "0"; },
       "/accessors/0/bufferView: expected an integer >= 0, found the string \"0\""},
      {[](json& d) {
         d["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = {1, "0.5", 0.2, 1};
       },
       "/materials/0/pbrMetallicRoughness/baseColorFactor/1: expected a number from 0 to 1, "
       "found the string \"0.5\""},
      {[](json& d) { d["accessors"][2]["byteOffset"] = -12; },
       "/accessors/2/byteOffset: expected an integer >= 0, found -12"},
      {[](json& d) { d["bufferViews"][1]["byteOffset"] = -12; },
       "/bufferViews/1/byteOffset: expected an integer >= 0, found -12"},
      {[](json& d) { d["scene"] = "hello"; },
       "/scene: expected an integer >= 0, found the string \"hello\""},
      {[](json& d) { d["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"][0] = 1.5; },
       "/materials/0/pbrMetallicRoughness/baseColorFactor/0: expected a number from 0 to 1, "
       "found 1.5"},
      {[](json& d) {
         d["materials"][0]["emissiveFactor"] = {0, -0.1, 0};
       },
       "/materials/0/emissiveFactor/1: expected a number from 0 to 1, found -0.1"}};
  for (const auto& [mutate, problem] : cases) {
    json document = TexturedQuadDocument();
    mutate(document);
    EXPECT_CONTAINS(DocumentError(document), "doc.gltf: " + problem);
  }
}

TEST(GltfHostileSchema, RequiredPropertiesEnumsIndicesAndSpecRules) {
  const std::vector<std::pair<std::function<void(json&)>, std::string>> cases = {
      {[](json& d) { d.erase("asset"); },
       "the document root: the required property \"asset\" is missing"},
      {[](json& d) { d["asset"]["version"] = "1.0"; },
       "/asset/version: glTF version \"1.0\"; aasim reads 2.x"},
      {[](json& d) { d["asset"]["version"] = "2"; }, "/asset/version: \"2\" is not a version"},
      {[](json& d) { d["asset"]["minVersion"] = "2.1"; },
       "/asset/minVersion: the file requires glTF 2.1"},
      {[](json& d) { d["accessors"][0]["componentType"] = 5124; },
       "/accessors/0/componentType: expected one of 5120, 5121, 5122, 5123, 5125, 5126"},
      {[](json& d) { d["accessors"][0]["type"] = "VEC5"; }, "/accessors/0/type: expected one of"},
      {[](json& d) { d["accessors"][0].erase("count"); },
       "/accessors/0: the required property \"count\" is missing"},
      {[](json& d) { d["accessors"][0]["normalized"] = true; },
       "/accessors/0/normalized: float and unsigned int accessors cannot be normalized"},
      {[](json& d) {
         d["accessors"][0]["min"] = {0, 0};
       },
       "/accessors/0/min: expected an array of 3 numbers, found an array of 2 items"},
      {[](json& d) { d["meshes"][0]["primitives"][0]["mode"] = 7; },
       "/meshes/0/primitives/0/mode: expected one of 0, 1, 2, 3, 4, 5, 6, found 7"},
      {[](json& d) { d["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 9; },
       "/meshes/0/primitives/0/attributes/POSITION: index 9 is out of range: the file has 3 "
       "accessors"},
      {[](json& d) { d["meshes"][0]["primitives"][0]["attributes"] = json::object(); },
       "/meshes/0/primitives/0/attributes: a primitive needs at least one attribute"},
      {[](json& d) {
         d["accessors"][2].erase("bufferView");
         d["accessors"][2].erase("byteOffset");
       },
       "/meshes/0/primitives/0/indices: accessor 2 has no bufferView; indices must be stored"},
      {[](json& d) { d["samplers"][0]["wrapS"] = 1; }, "/samplers/0/wrapS: expected one of 33071"},
      {[](json& d) { d["bufferViews"][0]["byteStride"] = 6; },
       "/bufferViews/0/byteStride: expected a multiple of 4, found 6"},
      {[](json& d) { d["bufferViews"][2]["byteLength"] = 13; },
       "/bufferViews/2: bytes 80 to 93 run past the end of buffer 0 (92 bytes)"},
      {[](json& d) { d["images"][0]["bufferView"] = 0; },
       "/images/0: an image has a uri or a bufferView, not both"},
      {[](json& d) { d["extensionsRequired"] = {"KHR_texture_transform"}; },
       "/extensionsRequired/0: 'KHR_texture_transform' is required but not listed in "
       "extensionsUsed"},
      {[](json& d) {
         d["nodes"] = {{{"mesh", 0}, {"children", {0, 0}}}};
       },
       "/nodes/0/children/1: index 0 appears twice in the list"},
      {[](json& d) { d["scenes"][0]["nodes"] = json::array(); },
       "/scenes/0/nodes: expected a non-empty array, found an array of 0 items"},
      {[](json& d) { d["materials"][0]["alphaMode"] = "opaque"; },
       "/materials/0/alphaMode: expected one of \"OPAQUE\", \"MASK\", \"BLEND\""},
      {[](json& d) {
         d["textures"][0]["extensions"] = {{"KHR_texture_basisu", 3}};
       },
       "/textures/0/extensions/KHR_texture_basisu: expected a JSON object, found 3"}};
  for (const auto& [mutate, problem] : cases) {
    json document = TexturedQuadDocument();
    mutate(document);
    EXPECT_CONTAINS(DocumentError(document), "doc.gltf: " + problem);
  }
}

TEST(GltfHostileSchema, NodeTransformsFollowTheSpec) {
  const std::vector<std::pair<std::function<void(json&)>, std::string>> cases = {
      {[](json& d) {
         d["nodes"][2]["translation"] = {0, 0, 1};
       },
       "/nodes/2: a node has a matrix or translation, rotation and scale, not both"},
      {[](json& d) { d["nodes"][2]["matrix"][3] = 0.5; },
       "/nodes/2/matrix/3: expected 0, found 0.5 (a node matrix's last row is 0, 0, 0, 1)"},
      {[](json& d) {
         d["nodes"][1]["rotation"] = {0, 0, 0.5, 0.5};
       },
       "/nodes/1/rotation: a rotation of length 0.707106781 is not a unit quaternion"},
      {[](json& d) { d["nodes"][1]["rotation"][0] = 2; },
       "/nodes/1/rotation/0: expected a number from -1 to 1, found 2"},
      {[](json& d) { d["cameras"][0]["type"] = "fisheye"; },
       "/cameras/0/type: expected one of \"perspective\", \"orthographic\""},
      {[](json& d) {
         d["cameras"][0]["orthographic"] = {{"xmag", 1}};
       },
       "/cameras/0: a camera is perspective or orthographic, not both"}};
  for (const auto& [mutate, problem] : cases) {
    json document = HierarchyWithCameraDocument();
    mutate(document);
    EXPECT_CONTAINS(DocumentError(document), "doc.gltf: " + problem);
  }
}

// assimp-testmodels' files of wrong types: each fails on its defect, with a JSON pointer.
// (badNumber.gltf's normalTexture has no index, which the schema requires; that is reported
// before its "scale" string.)
TEST(GltfHostileSchema, AssimpWrongTypesAndSchemaFailuresAreRefused) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"wrongTypes/badArray.gltf", "/meshes/0/primitives: expected a non-empty array"},
      {"wrongTypes/badExtension.gltf",
       "/materials/0/pbrMetallicRoughness/baseColorTexture/extensions/KHR_texture_transform: "
       "expected a JSON object"},
      {"wrongTypes/badNumber.gltf",
       "/materials/0/normalTexture: the required property \"index\" is missing"},
      {"wrongTypes/badObject.gltf",
       "/materials/0/pbrMetallicRoughness: expected a JSON object, found an array"},
      {"wrongTypes/badString.gltf", "/scenes/0/name: expected a string, found 42"},
      {"wrongTypes/badUint.gltf",
       "/materials/0/pbrMetallicRoughness/baseColorTexture/index: expected an integer >= 0, "
       "found -1"},
      {"SchemaFailures/sceneWrongType.gltf", "/scene: expected an integer >= 0"}};
  std::size_t files = 0;
  for (const char* dir : {"wrongTypes", "SchemaFailures"}) {
    for (const fs::directory_entry& entry : fs::directory_iterator(scenes_test::Gltf2Models() / dir)) {
      files += entry.path().extension() == ".gltf" ? 1 : 0;
    }
  }
  EXPECT_EQ(files, cases.size()) << "a new file in wrongTypes/ or SchemaFailures/ needs a case";
  for (const auto& [file, problem] : cases) {
    const fs::path path = scenes_test::Gltf2Models() / file;
    EXPECT_CONTAINS(FileError(path), path.string() + ": " + problem);
  }
}

TEST(GltfHostileSchema, PropertiesOutsideTheSchemaWarnOncePerName) {
  json document = TexturedQuadDocument();
  for (json& accessor : document["accessors"]) accessor["byteStrde"] = 4;
  document["meshes"][0]["primitives"][0]["attributes"]["TEXCORD_0"] = 1;
  ::testing::internal::CaptureStderr();
  LoadText(document.dump());
  const std::string warnings = ::testing::internal::GetCapturedStderr();
  EXPECT_CONTAINS(warnings,
                  "doc.gltf: warning: property 'byteStrde' is not part of glTF 2.0's "
                  "accessor and is ignored (first at /accessors/0/byteStrde)\n");
  EXPECT_CONTAINS(warnings, "property 'TEXCORD_0' is not part of glTF 2.0's attribute semantics");
  EXPECT_EQ(std::count(warnings.begin(), warnings.end(), '\n'), 2) << warnings;
}

// ---------------------------------------------------------------------------------------------
// Numbers

// Before the fix: "non-finite clip position" from the rasterizer, naming no file.
TEST(GltfHostileNumbers, CoordinatesBeyondTheBoundNameFileAndBound) {
  json document = TriangleDocument();
  Bytes buffer;
  Append(buffer, std::vector<float>{0, 0, 0, 1e19f, 0, 0, 0, 1, 0});
  document["buffers"][0]["uri"] = DataUri(buffer, "application/octet-stream");
  EXPECT_CONTAINS(DocumentError(document),
                  "doc.gltf: mesh 0 primitive 0: vertex 1 lies at (1e+19, 0, 0) after its node "
                  "transforms, outside the +-1e+06 aasim accepts for world coordinates");
  json scaled = TriangleDocument();
  scaled["nodes"] = {{{"children", {1}}, {"scale", {1000, 1000, 1000}}},
                     {{"mesh", 0}, {"translation", {1001, 0, 0}}}};
  EXPECT_CONTAINS(DocumentError(scaled), "vertex 0 lies at (1.001e+06, 0, 0)");
  json translated = TriangleDocument();
  translated["nodes"][0]["translation"] = {2e6, 0, 0};
  EXPECT_CONTAINS(
      DocumentError(translated),
      "/nodes/0/translation/0: expected a number from -1000000 to 1000000, found 2000000.0");
  json eye = HierarchyWithCameraDocument();
  eye["nodes"][2]["matrix"][14] = 999999;
  eye["nodes"][0]["translation"] = {0, 0, 999999};
  EXPECT_CONTAINS(DocumentError(eye), "node 2 (camera 0): the eye lies at (");
}

// Before the fix a yfov of pi loaded and failed later in the ground truth.
TEST(GltfHostileNumbers, LensValuesMustHoldAsFloats) {
  const std::vector<std::pair<json, std::string>> cases = {
      {{{"yfov", 3.14159265358979}, {"znear", 0.1}},
       "/cameras/0/perspective/yfov: 3.14159265 is not below pi as a float (3.14159274)"},
      {{{"yfov", 1e-50}, {"znear", 0.1}}, "/cameras/0/perspective/yfov: 1e-50 is 0 as a float"},
      {{{"yfov", 0.8}, {"znear", 0.1}, {"zfar", 1e39}},
       "/cameras/0/perspective/zfar: 1e+39 does not fit a float"},
      {{{"yfov", 0.8}, {"znear", 0.1}, {"zfar", 0.1000000001}},
       "/cameras/0/perspective/zfar: 0.1 is not beyond znear 0.1 (as floats)"},
      {{{"yfov", 0.8}}, "/cameras/0/perspective: the required property \"znear\" is missing"}};
  for (const auto& [lens, problem] : cases) {
    json document = HierarchyWithCameraDocument();
    document["cameras"][0]["perspective"] = lens;
    EXPECT_CONTAINS(DocumentError(document), "doc.gltf: " + problem);
  }
  json document = HierarchyWithCameraDocument();
  document["cameras"][0]["perspective"]["yfov"] = 3.1415;
  ::testing::internal::CaptureStderr();
  EXPECT_FLOAT_EQ(LoadText(document.dump()).camera.verticalFovRadians, 3.1415f);
  ::testing::internal::GetCapturedStderr();
}

// ---------------------------------------------------------------------------------------------
// Mutation sweep

bool SameScene(const scenes::Scene& a, const scenes::Scene& b) {
  const auto sameMesh = [](const scenes::Mesh& x, const scenes::Mesh& y) {
    return x.name == y.name && x.positions == y.positions && x.normals == y.normals &&
           x.texcoords == y.texcoords && x.indices == y.indices && x.material == y.material;
  };
  const auto sameMaterial = [](const scenes::Material& x, const scenes::Material& y) {
    return x.name == y.name && x.baseColourFactor == y.baseColourFactor &&
           x.baseColourTexture == y.baseColourTexture;
  };
  const auto sameTexture = [](const scenes::Texture& x, const scenes::Texture& y) {
    return x.name == y.name && x.width == y.width && x.height == y.height && x.texels == y.texels;
  };
  const scenes::Camera& p = a.camera;
  const scenes::Camera& q = b.camera;
  return a.name == b.name &&
         std::equal(a.meshes.begin(), a.meshes.end(), b.meshes.begin(), b.meshes.end(), sameMesh) &&
         std::equal(a.materials.begin(), a.materials.end(), b.materials.begin(), b.materials.end(),
                    sameMaterial) &&
         std::equal(a.textures.begin(), a.textures.end(), b.textures.begin(), b.textures.end(),
                    sameTexture) &&
         p.eye == q.eye && p.target == q.target && p.up == q.up &&
         p.verticalFovRadians == q.verticalFovRadians && p.zNear == q.zNear && p.zFar == q.zFar;
}

// The pointer with each array index written as "#": "/nodes/2/scale/0" is "/nodes/#/scale/#".
std::string Shape(const std::string& pointer) {
  std::string shape;
  std::size_t start = 1;
  while (start <= pointer.size()) {
    const std::size_t end = std::min(pointer.find('/', start), pointer.size());
    const std::string segment = pointer.substr(start, end - start);
    const bool index =
        !segment.empty() && segment.find_first_not_of("0123456789") == std::string::npos;
    shape.append("/").append(index ? "#" : segment);
    start = end + 1;
  }
  return shape;
}

// Mutations that make another valid document with another meaning, which no reader could call
// wrong: a name that is another string, a node, colour or lens number that is another number in
// range, {} for an object whose properties are all optional. (No <regex>: GCC 12 warns inside it
// under the sanitizers.)
bool MayChangeTheScene(const std::string& pointer, const json& replacement) {
  static const std::set<std::string> kNumbers = {
      "/nodes/#/translation/#",
      "/nodes/#/rotation/#",
      "/nodes/#/scale/#",
      "/nodes/#/matrix/#",
      "/materials/#/pbrMetallicRoughness/baseColorFactor/#",
      "/cameras/#/perspective/yfov",
      "/cameras/#/perspective/znear",
      "/cameras/#/perspective/zfar",
      "/cameras/#/perspective/aspectRatio"};
  static const std::set<std::string> kOptionalObjects = {
      "/nodes/#",    "/materials/#", "/textures/#",
      "/samplers/#", "/scenes/#",    "/materials/#/pbrMetallicRoughness"};
  if (replacement.is_string()) return pointer.ends_with("/name");
  if (replacement.is_number()) return kNumbers.contains(Shape(pointer));
  return replacement.is_object() && replacement.empty() &&
         kOptionalObjects.contains(Shape(pointer));
}

void CollectPointers(const json& value, const std::string& at, std::vector<std::string>& out) {
  out.push_back(at);
  if (value.is_array()) {
    for (std::size_t i = 0; i < value.size(); ++i) {
      CollectPointers(value[i], at + "/" + std::to_string(i), out);
    }
  } else if (value.is_object()) {
    for (const auto& [key, item] : value.items()) CollectPointers(item, at + "/" + key, out);
  }
}

// Before the fix about a third of these loaded with a changed meaning and no word.
TEST(GltfHostileMutation, EveryWrongValueIsRefusedOrChangesNothing) {
  const std::vector<json> wrongValues = {"0",     -12,           1e308,         -1, 0.5, true,
                                         nullptr, json::array(), json::object()};
  std::size_t cases = 0;
  std::size_t refused = 0;
  std::size_t unchanged = 0;
  std::vector<std::string> silent;
  const fs::path dir = TestDir();
  ::testing::internal::CaptureStderr();
  for (const json& original :
       {TriangleDocument(), TexturedQuadDocument(), HierarchyWithCameraDocument()}) {
    const scenes::Scene expected = LoadText(original.dump(), "m.gltf", dir);
    std::vector<std::string> pointers;
    CollectPointers(original, "", pointers);
    for (const std::string& pointer : pointers) {
      for (const json& wrong : wrongValues) {
        json mutated = original;
        mutated[json::json_pointer(pointer)] = wrong;
        ++cases;
        try {
          const scenes::Scene scene = LoadText(mutated.dump(), "m.gltf", dir);
          if (SameScene(scene, expected)) {
            ++unchanged;
          } else if (!MayChangeTheScene(pointer, wrong)) {
            silent.push_back(pointer + " = " + wrong.dump());
          }
        } catch (const scenes::SceneError& e) {
          ++refused;
          const std::string message = e.what();
          EXPECT_EQ(message.rfind("m.gltf: ", 0), 0u) << message;
          EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        } catch (const std::exception& e) {
          ADD_FAILURE() << pointer << " = " << wrong.dump() << " threw " << e.what();
        }
      }
    }
  }
  ::testing::internal::GetCapturedStderr();
  std::cout << cases << " mutations: " << refused << " refused, " << unchanged << " unchanged, "
            << cases - refused - unchanged << " legal changes\n";
  EXPECT_GT(cases, 1500u);
  EXPECT_GT(refused, cases * 3 / 4);
  EXPECT_TRUE(silent.empty()) << silent.size() << " of " << cases
                              << " mutations loaded with another meaning, first: " << silent[0];
}

}  // namespace
