// GLB container checks (see glb_container.h).

#include "scenes/glb_container.h"

#include <sstream>

#include "scenes/scene.h"

namespace scenes::gltf {
namespace {

constexpr std::uint32_t kMagic = 0x46546C67u;          // "glTF" read little-endian
constexpr std::uint32_t kJsonChunkType = 0x4E4F534Au;  // "JSON"
constexpr std::uint32_t kBinChunkType = 0x004E4942u;   // "BIN\0"
constexpr std::size_t kHeaderBytes = 12;
constexpr std::size_t kChunkHeaderBytes = 8;

std::uint32_t ReadU32(std::span<const std::uint8_t> bytes, std::size_t at) {
  return static_cast<std::uint32_t>(bytes[at]) | static_cast<std::uint32_t>(bytes[at + 1]) << 8 |
         static_cast<std::uint32_t>(bytes[at + 2]) << 16 |
         static_cast<std::uint32_t>(bytes[at + 3]) << 24;
}

std::string Hex(std::uint32_t value) {
  std::ostringstream text;
  text << "0x" << std::hex << std::uppercase << value;
  return text.str();
}

class GlbReader {
 public:
  GlbReader(std::span<const std::uint8_t> bytes, const std::string& file, WarningLog& warnings)
      : bytes_(bytes), file_(file), warnings_(warnings) {}

  GlbChunks Split() {
    CheckHeader();
    GlbChunks chunks;
    std::size_t at = kHeaderBytes;
    for (std::size_t index = 0; at < bytes_.size(); ++index) {
      const auto [type, data] = Chunk(index, at);
      Place(chunks, index, type, data, at);
      at += kChunkHeaderBytes + data.size();
    }
    if (chunks.json.empty()) Fail("has no chunks after its 12-byte header");
    return chunks;
  }

 private:
  [[noreturn]] void Fail(const std::string& problem) const {
    throw SceneError(file_ + ": GLB " + problem);
  }

  void CheckHeader() const {
    if (bytes_.size() < kHeaderBytes) {
      Fail("header: the file is " + std::to_string(bytes_.size()) +
           " bytes, shorter than the 12-byte header");
    }
    if (ReadU32(bytes_, 0) != kMagic) {
      Fail("magic (byte 0) is " + Hex(ReadU32(bytes_, 0)) + ", expected \"glTF\" (" + Hex(kMagic) +
           ")");
    }
    if (ReadU32(bytes_, 4) != 2) {
      Fail("version (byte 4) is " + std::to_string(ReadU32(bytes_, 4)) + "; aasim reads version 2");
    }
    if (ReadU32(bytes_, 8) != bytes_.size()) {
      Fail("length (byte 8) is " + std::to_string(ReadU32(bytes_, 8)) + ", but the file holds " +
           std::to_string(bytes_.size()) + " bytes");
    }
  }

  std::pair<std::uint32_t, std::span<const std::uint8_t>> Chunk(std::size_t index,
                                                                std::size_t at) const {
    const std::string name = "chunk " + std::to_string(index) + " at byte " + std::to_string(at);
    const std::size_t left = bytes_.size() - at;
    if (left < kChunkHeaderBytes) {
      Fail(name + ": " + std::to_string(left) +
           " trailing bytes, too few for a chunk header (8 bytes)");
    }
    const std::uint32_t length = ReadU32(bytes_, at);
    if (length % 4 != 0) {
      Fail(name + ": chunk length " + std::to_string(length) + " is not a multiple of 4");
    }
    if (length > left - kChunkHeaderBytes) {
      Fail(name + ": chunk length " + std::to_string(length) + " runs " +
           std::to_string(length - (left - kChunkHeaderBytes)) +
           " bytes past the end of the file (" + std::to_string(bytes_.size()) + " bytes)");
    }
    return {ReadU32(bytes_, at + 4), bytes_.subspan(at + kChunkHeaderBytes, length)};
  }

  void Place(GlbChunks& chunks, std::size_t index, std::uint32_t type,
             std::span<const std::uint8_t> data, std::size_t at) {
    const std::string name = "chunk " + std::to_string(index) + " at byte " + std::to_string(at);
    if (index == 0) {
      if (type != kJsonChunkType) {
        Fail(name + ": type " + Hex(type) + ", expected JSON (" + Hex(kJsonChunkType) + ")");
      }
      if (data.empty()) Fail(name + ": the JSON chunk is empty");
      chunks.json = data;
    } else if (type == kJsonChunkType) {
      Fail(name + ": a second JSON chunk (only the first chunk holds JSON)");
    } else if (type == kBinChunkType) {
      if (index != 1) Fail(name + ": a BIN chunk that is not the second chunk");
      chunks.bin = data;
    } else if (!skippedUnknown_) {
      skippedUnknown_ = true;  // one line, however many chunks a hostile file holds
      warnings_.Warn("GLB chunks of unknown types are skipped (first: " + name + ", type " +
                     Hex(type) + ")");
    }
  }

  std::span<const std::uint8_t> bytes_;
  const std::string& file_;
  WarningLog& warnings_;
  bool skippedUnknown_ = false;
};

}  // namespace

GlbChunks SplitGlb(std::span<const std::uint8_t> bytes, const std::string& file,
                   WarningLog& warnings) {
  return GlbReader(bytes, file, warnings).Split();
}

}  // namespace scenes::gltf
