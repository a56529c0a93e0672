#pragma once
// Internal to the glTF reader (gltf_loader.cpp and its stages): how untrusted text enters a
// one-line message, JSON pointers, and warnings printed once per file.

#include <cstddef>
#include <set>
#include <string>
#include <string_view>

namespace scenes::gltf {

// Longest excerpt of input text a message quotes (names, URIs, keys, parser reports).
inline constexpr std::size_t kExcerptBytes = 64;

// `text` made safe for a one-line message: cut to `maxBytes` at a UTF-8 boundary with "..."
// appended, control characters and bytes that are not UTF-8 written as \xNN.
std::string Excerpt(std::string_view text, std::size_t maxBytes = kExcerptBytes);
// Excerpt in single quotes.
std::string Quoted(std::string_view text);

// RFC 6901 pointers. Keys are escaped ("~" as "~0", "/" as "~1") and excerpted, so a pointer
// into a hostile document stays short.
std::string PointerTo(const std::string& parent, std::string_view key);
std::string PointerTo(const std::string& parent, std::size_t index);
// "/a/b" as is; the empty pointer (the document itself) as "the document root".
std::string Where(const std::string& pointer);

// Prints "FILE: warning: TEXT" on stderr, each distinct text once.
class WarningLog {
 public:
  explicit WarningLog(std::string file) : file_(std::move(file)) {}
  void Warn(const std::string& text);

 private:
  std::string file_;
  std::set<std::string> printed_;
};

}  // namespace scenes::gltf
