#pragma once
// Internal to the glTF reader: the GLB container (glTF 2.0, "Binary glTF Layout"), checked
// byte by byte before anything reads a chunk, so that no length in the file is trusted.

#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "scenes/gltf_messages.h"

namespace scenes::gltf {

struct GlbChunks {
  std::span<const std::uint8_t> json;
  std::optional<std::span<const std::uint8_t>> bin;
};

// A 12-byte header (magic "glTF", version 2, total length equal to the byte count), then chunks
// that fill the rest exactly, each an 8-byte header (length, type) and a length that is a
// multiple of 4: a non-empty JSON chunk first, an optional BIN chunk second, then chunks of
// other types, which the glTF spec says to skip (with one warning). Throws SceneError
// "FILE: GLB ..." naming the field and its byte offset.
GlbChunks SplitGlb(std::span<const std::uint8_t> bytes, const std::string& file,
                   WarningLog& warnings);

}  // namespace scenes::gltf
