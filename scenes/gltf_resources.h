#pragma once
// Internal to the glTF reader: every byte a glTF document refers to, read under aasim's rules
// before tinygltf sees the document, so tinygltf never opens a path itself.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "scenes/gltf_messages.h"

namespace scenes::gltf {

// The bytes of a regular file of at most `maxBytes`. The path is examined with stat() first, so
// a FIFO, directory or device is refused without being opened (nothing blocks), and the file is
// opened non-blocking and checked again, in case it was replaced in between. Throws SceneError
// `prefix` + the problem ("no such file", "is a FIFO, not a regular file", ...).
std::vector<std::uint8_t> ReadRegularFile(const std::filesystem::path& path, std::uint64_t maxBytes,
                                          const std::string& prefix);

struct ImageOrigin {
  std::string uri;        // as written, for an image file; empty for data: URIs and bufferViews
  std::string mediaType;  // `mimeType`, else a data: URI's media type; may be empty
};

struct GltfResources {
  std::vector<std::vector<std::uint8_t>> buffers;  // each exactly its byteLength
  std::vector<std::vector<std::uint8_t>> images;   // encoded; empty for bufferView images
  std::vector<ImageOrigin> imageOrigins;           // one per image
};

// Reads every buffer and image of a schema-checked document (ValidateGltfSchema). A data: URI
// must be base64 and is decoded; any other URI must be a relative path without scheme, query
// or fragment, is percent-decoded (RFC 3986) and read with ReadRegularFile from `baseDir`.
// A GLB's buffer 0 without uri is its BIN chunk. A buffer must hold at least its byteLength
// (the rest is dropped; a BIN chunk may carry up to 3 bytes of padding only), and all files
// together at most kMaxGltfResourceBytes. Errors name the URI's JSON pointer; an unused BIN
// chunk is a warning.
GltfResources ReadResources(const nlohmann::json& document,
                            std::optional<std::span<const std::uint8_t>> glbBin,
                            const std::filesystem::path& baseDir, const std::string& file,
                            WarningLog& warnings);

}  // namespace scenes::gltf
