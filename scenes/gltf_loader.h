#pragma once
// The glTF 2.0 reader's entry points and its limits (docs/scenes.md, "glTF 2.0 subset").
// LoadGltf (scene.h) reads a file and calls LoadGltfFromMemory; a fuzz target can call
// LoadGltfFromMemory directly, with no files of its own.
//
// Every input is hostile until checked: the GLB container byte by byte, the JSON nesting depth
// before the document is built, the glTF 2.0 schema of every property (types, ranges, required
// properties, enum values, indices into arrays) before tinygltf sees the document, every
// buffer and image URI before any file is opened, every image's dimensions before it is
// decoded. Problems are one-line SceneErrors naming the file and where in it (a JSON pointer
// such as /accessors/3/byteOffset, or the GLB field and its byte offset).

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string_view>

#include "scenes/scene.h"

namespace scenes {

// Arrays and objects nested deeper than this are refused before the document is built: glTF
// itself needs 8 levels, `extras` may add some; tinygltf copies `extras` recursively.
inline constexpr int kMaxGltfJsonDepth = 64;

// Largest file aasim reads for one glTF: the .gltf or .glb itself, each buffer and each image
// file (1 GiB), checked with stat() before the file is opened; and the most that the buffers
// and images of one glTF may hold together (2 GiB).
inline constexpr std::uint64_t kMaxGltfFileBytes = std::uint64_t{1} << 30;
inline constexpr std::uint64_t kMaxGltfResourceBytes = std::uint64_t{2} << 30;

// Every world-space coordinate (after node transforms), node transform value and camera
// position must lie within +-kMaxGltfCoordinate. Float spacing there is 1/16 unit, and squared
// distances (below 1.3e13) stay far from float overflow in framing, projection and the ground
// truth; beyond it a scene is better re-exported in other units.
inline constexpr double kMaxGltfCoordinate = 1e6;

// The flattened scene, every mesh instance after node transforms, holds at most this many
// vertices (1 GiB with normals and texture coordinates) and triangle-list indices: instancing
// through a node graph can repeat one mesh up to 2^20 times, so a small file could otherwise
// claim any amount of memory. Checked before each primitive is read.
inline constexpr std::size_t kMaxGltfSceneVertices = std::size_t{1} << 25;
inline constexpr std::size_t kMaxGltfSceneIndices = std::size_t{1} << 26;

// All base colour textures of one scene together hold at most this many texels (2 GiB as the
// linear RGBA floats of scenes::Texture); texture.h bounds each image.
inline constexpr std::size_t kMaxGltfSceneTexels = std::size_t{1} << 27;

// A .gltf document (`binary` false) or a .glb container (`binary` true) held in memory. Buffer
// and image URIs are resolved against `baseDir`; `name` stands for the file in every message
// and becomes Scene::name. Throws SceneError ("NAME: problem", one line) for any defect,
// prints warnings for what aasim does not model ("NAME: warning: ...") on stderr.
Scene LoadGltfFromMemory(std::span<const std::uint8_t> bytes, bool binary,
                         const std::filesystem::path& baseDir, std::string_view name, float aspect);

}  // namespace scenes
