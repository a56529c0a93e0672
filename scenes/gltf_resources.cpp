// Reading what a glTF document refers to (see gltf_resources.h).

#include "scenes/gltf_resources.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <string_view>

#include <nlohmann/json.hpp>

#include "scenes/gltf_loader.h"
#include "scenes/gltf_messages.h"
#include "scenes/scene.h"

namespace scenes::gltf {
namespace {

using nlohmann::json;

// glTF's padding rule for the BIN chunk behind buffer 0 (glTF 2.0, "Binary buffer").
constexpr std::size_t kMaxBinPadding = 3;

class FileDescriptor {
 public:
  explicit FileDescriptor(int fd) : fd_(fd) {}
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  ~FileDescriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  int Get() const { return fd_; }

 private:
  int fd_;
};

// Empty for a regular file, else what the file is.
std::string NotRegular(const struct stat& info) {
  if (S_ISREG(info.st_mode)) return {};
  if (S_ISDIR(info.st_mode)) return "is a directory";
  if (S_ISFIFO(info.st_mode)) return "is a FIFO";
  if (S_ISCHR(info.st_mode) || S_ISBLK(info.st_mode)) return "is a device";
  if (S_ISSOCK(info.st_mode)) return "is a socket";
  return "is not a file";
}

std::string SizeProblem(std::uint64_t size, std::uint64_t maxBytes) {
  return "is " + std::to_string(size) + " bytes, more than the " + std::to_string(maxBytes) +
         " bytes aasim reads";
}

void ReadAll(int fd, std::vector<std::uint8_t>& bytes, const std::string& prefix) {
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t got = ::read(fd, bytes.data() + done, bytes.size() - done);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) throw SceneError(prefix + "cannot read: " + std::strerror(errno));
    if (got == 0) throw SceneError(prefix + "the file shrank while it was read");
    done += static_cast<std::size_t>(got);
  }
}

bool IsSchemeChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '+' || c == '-' || c == '.';
}

// RFC 3986: a scheme is a letter then letters, digits, "+", "-" or "." up to the first ":",
// which must come before any "/", "?" or "#".
std::string_view Scheme(std::string_view uri) {
  const std::size_t colon = uri.find(':');
  if (colon == std::string_view::npos || colon == 0) return {};
  if (std::isalpha(static_cast<unsigned char>(uri[0])) == 0) return {};
  const std::string_view candidate = uri.substr(0, colon);
  return std::all_of(candidate.begin(), candidate.end(), IsSchemeChar) ? candidate
                                                                       : std::string_view{};
}

int HexValue(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

std::string PercentDecode(std::string_view uri, const std::string& prefix) {
  std::string decoded;
  for (std::size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] != '%') {
      decoded += uri[i];
      continue;
    }
    const int high = i + 2 < uri.size() ? HexValue(uri[i + 1]) : -1;
    const int low = i + 2 < uri.size() ? HexValue(uri[i + 2]) : -1;
    if (high < 0 || low < 0) {
      throw SceneError(prefix + "'%' at character " + std::to_string(i) +
                       " is not followed by two hex digits");
    }
    decoded += static_cast<char>(high * 16 + low);
    i += 2;
  }
  return decoded;
}

int Base64Value(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+') return 62;
  if (c == '/') return 63;
  return -1;
}

// RFC 4648 base64 with padding; `offset` places `text` in the URI for messages.
std::vector<std::uint8_t> DecodeBase64(std::string_view text, std::size_t offset,
                                       const std::string& prefix) {
  if (text.size() % 4 != 0) {
    throw SceneError(prefix + "base64 data of " + std::to_string(text.size()) +
                     " characters is not a multiple of 4");
  }
  const std::size_t padding = text.ends_with("==") ? 2 : text.ends_with("=") ? 1 : 0;
  std::vector<std::uint8_t> bytes;
  bytes.reserve(text.size() / 4 * 3);
  std::uint32_t group = 0;
  for (std::size_t i = 0; i < text.size() - padding; ++i) {
    const int value = Base64Value(text[i]);
    if (value < 0) {
      throw SceneError(prefix + Quoted(text.substr(i, 1)) + " at character " +
                       std::to_string(offset + i) + " is not base64");
    }
    group = group << 6 | static_cast<std::uint32_t>(value);
    if (i % 4 == 3) {
      bytes.insert(bytes.end(),
                   {static_cast<std::uint8_t>(group >> 16), static_cast<std::uint8_t>(group >> 8),
                    static_cast<std::uint8_t>(group)});
    }
  }
  if (padding == 2) bytes.push_back(static_cast<std::uint8_t>(group >> 4));
  if (padding == 1) {
    bytes.insert(bytes.end(),
                 {static_cast<std::uint8_t>(group >> 10), static_cast<std::uint8_t>(group >> 2)});
  }
  return bytes;
}

class ResourceReader {
 public:
  ResourceReader(const json& document, std::optional<std::span<const std::uint8_t>> glbBin,
                 const std::filesystem::path& baseDir, const std::string& file,
                 WarningLog& warnings)
      : document_(document), glbBin_(glbBin), baseDir_(baseDir), file_(file), warnings_(warnings) {}

  GltfResources Read() {
    GltfResources resources;
    const json empty = json::array();
    const json& buffers = document_.contains("buffers") ? document_["buffers"] : empty;
    for (std::size_t i = 0; i < buffers.size(); ++i) {
      resources.buffers.push_back(Buffer(buffers[i], PointerTo("/buffers", i)));
    }
    if (glbBin_ && !binUsed_) {
      warnings_.Warn("the GLB BIN chunk is not used: no buffer without uri refers to it");
    }
    const json& images = document_.contains("images") ? document_["images"] : empty;
    for (std::size_t i = 0; i < images.size(); ++i) {
      ImageOrigin origin;
      resources.images.push_back(Image(images[i], PointerTo("/images", i), origin));
      resources.imageOrigins.push_back(std::move(origin));
    }
    return resources;
  }

 private:
  std::vector<std::uint8_t> Buffer(const json& buffer, const std::string& at) {
    const auto byteLength = buffer["byteLength"].get<std::uint64_t>();
    std::vector<std::uint8_t> bytes;
    std::string source;
    if (buffer.contains("uri")) {
      const auto& uri = buffer["uri"].get_ref<const std::string&>();
      std::string mediaType;
      bytes = FromUri(uri, PointerTo(at, "uri"), mediaType);
      source = "uri " + Quoted(uri);
    } else {
      bytes = BinChunk(byteLength, at);
      source = "the GLB BIN chunk";
    }
    if (bytes.size() < byteLength) {
      throw SceneError(file_ + ": " + PointerTo(at, "byteLength") + ": " +
                       std::to_string(byteLength) + " bytes, but " + source + " holds only " +
                       std::to_string(bytes.size()));
    }
    bytes.resize(static_cast<std::size_t>(byteLength));
    return bytes;
  }

  std::vector<std::uint8_t> BinChunk(std::uint64_t byteLength, const std::string& at) {
    if (!glbBin_) {
      throw SceneError(file_ + ": " + at + ": a buffer without uri, but the GLB has no BIN chunk");
    }
    if (glbBin_->size() > byteLength + kMaxBinPadding) {
      throw SceneError(file_ + ": " + PointerTo(at, "byteLength") + ": " +
                       std::to_string(byteLength) + " bytes, but the GLB BIN chunk holds " +
                       std::to_string(glbBin_->size()) + " (at most 3 bytes of padding allowed)");
    }
    binUsed_ = true;
    Spend(glbBin_->size(), file_ + ": " + at + ": ");
    return {glbBin_->begin(), glbBin_->end()};
  }

  std::vector<std::uint8_t> Image(const json& image, const std::string& at, ImageOrigin& origin) {
    if (image.contains("mimeType")) origin.mediaType = image["mimeType"].get<std::string>();
    if (!image.contains("uri")) return {};
    const auto& uri = image["uri"].get_ref<const std::string&>();
    std::string uriMediaType;
    std::vector<std::uint8_t> bytes = FromUri(uri, PointerTo(at, "uri"), uriMediaType);
    if (origin.mediaType.empty()) origin.mediaType = std::move(uriMediaType);
    if (Scheme(uri) != "data") origin.uri = uri;
    if (bytes.empty()) {
      throw SceneError(file_ + ": " + PointerTo(at, "uri") + " " + Quoted(uri) +
                       ": the image is empty");
    }
    return bytes;
  }

  // `mediaType` is set from a data: URI and left alone for a file.
  std::vector<std::uint8_t> FromUri(const std::string& uri, const std::string& at,
                                    std::string& mediaType) {
    const std::string prefix = file_ + ": " + at + " " + Quoted(uri) + ": ";
    const std::string_view scheme = Scheme(uri);
    if (scheme == "data") return FromDataUri(uri, prefix, mediaType);
    if (!scheme.empty()) {
      throw SceneError(prefix + "URI scheme " + Quoted(scheme) +
                       " is not supported (aasim reads relative paths and data: URIs)");
    }
    if (uri.find_first_of("?#") != std::string::npos) {
      throw SceneError(prefix + "a URI with a query or fragment names no file");
    }
    const std::string path = PercentDecode(uri, prefix);
    if (path.empty()) throw SceneError(prefix + "the URI names no file");
    if (path.find('\0') != std::string::npos) throw SceneError(prefix + "the path holds a NUL");
    if (path.front() == '/') {
      throw SceneError(prefix + "an absolute path; glTF URIs are relative to the glTF file");
    }
    std::vector<std::uint8_t> bytes = ReadRegularFile(baseDir_ / path, kMaxGltfFileBytes, prefix);
    Spend(bytes.size(), prefix);
    return bytes;
  }

  std::vector<std::uint8_t> FromDataUri(std::string_view uri, const std::string& prefix,
                                        std::string& mediaType) {
    const std::size_t comma = uri.find(',');
    if (comma == std::string_view::npos) throw SceneError(prefix + "a data: URI without ','");
    const std::string_view header = uri.substr(5, comma - 5);
    if (!header.ends_with(";base64")) {
      throw SceneError(prefix + "a data: URI that is not base64 (no ';base64' before ',')");
    }
    mediaType = std::string(header.substr(0, header.find(';')));
    Spend((uri.size() - comma - 1) / 4 * 3, prefix);
    return DecodeBase64(uri.substr(comma + 1), comma + 1, prefix);
  }

  std::uint64_t Budget() const { return kMaxGltfResourceBytes - spent_; }

  void Spend(std::uint64_t bytes, const std::string& prefix) {
    if (bytes > Budget()) {
      throw SceneError(prefix + "the buffers and images of this file exceed the " +
                       std::to_string(kMaxGltfResourceBytes) + " bytes aasim reads");
    }
    spent_ += bytes;
  }

  const json& document_;
  std::optional<std::span<const std::uint8_t>> glbBin_;
  const std::filesystem::path& baseDir_;
  const std::string& file_;
  WarningLog& warnings_;
  std::uint64_t spent_ = 0;
  bool binUsed_ = false;
};

}  // namespace

std::vector<std::uint8_t> ReadRegularFile(const std::filesystem::path& path, std::uint64_t maxBytes,
                                          const std::string& prefix) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) {
    if (errno == ENOENT) throw SceneError(prefix + "no such file");
    throw SceneError(prefix + "cannot examine: " + std::strerror(errno));
  }
  if (const std::string what = NotRegular(info); !what.empty()) {
    throw SceneError(prefix + what + ", not a regular file");
  }
  const auto size = static_cast<std::uint64_t>(info.st_size);
  if (size > maxBytes) throw SceneError(prefix + SizeProblem(size, maxBytes));
  // O_NONBLOCK: should a FIFO replace the file after stat(), open() must not wait for a writer.
  const FileDescriptor fd(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY));
  if (fd.Get() < 0) throw SceneError(prefix + "cannot open: " + std::strerror(errno));
  struct stat opened {};
  if (::fstat(fd.Get(), &opened) != 0 || !S_ISREG(opened.st_mode) ||
      opened.st_size != info.st_size) {
    throw SceneError(prefix + "the file changed while it was opened");
  }
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(size));
  ReadAll(fd.Get(), bytes, prefix);
  return bytes;
}

GltfResources ReadResources(const json& document,
                            std::optional<std::span<const std::uint8_t>> glbBin,
                            const std::filesystem::path& baseDir, const std::string& file,
                            WarningLog& warnings) {
  return ResourceReader(document, glbBin, baseDir, file, warnings).Read();
}

}  // namespace scenes::gltf
