// Message helpers of the glTF reader (see gltf_messages.h).

#include "scenes/gltf_messages.h"

#include <array>
#include <iostream>

namespace scenes::gltf {
namespace {

// Length of the UTF-8 sequence starting at `at`, or 0 when the bytes there are not one.
std::size_t Utf8SequenceLength(std::string_view text, std::size_t at) {
  const auto lead = static_cast<unsigned char>(text[at]);
  std::size_t length = 0;
  if (lead >= 0xC2 && lead <= 0xDF) length = 2;
  if (lead >= 0xE0 && lead <= 0xEF) length = 3;
  if (lead >= 0xF0 && lead <= 0xF4) length = 4;
  if (length == 0 || at + length > text.size()) return 0;
  for (std::size_t k = 1; k < length; ++k) {
    if ((static_cast<unsigned char>(text[at + k]) & 0xC0u) != 0x80u) return 0;
  }
  return length;
}

std::string HexByte(unsigned char byte) {
  constexpr std::array<char, 16> kDigits = {'0', '1', '2', '3', '4', '5', '6', '7',
                                            '8', '9', 'A', 'B', 'C', 'D', 'E', 'F'};
  return std::string("\\x") + kDigits[byte >> 4] + kDigits[byte & 15u];
}

}  // namespace

std::string Excerpt(std::string_view text, std::size_t maxBytes) {
  std::string out;
  std::size_t at = 0;
  while (at < text.size()) {
    const auto byte = static_cast<unsigned char>(text[at]);
    std::size_t consumed = 1;
    std::string piece;
    if (byte >= 0x20 && byte < 0x7F) {
      piece.assign(1, static_cast<char>(byte));
    } else if (const std::size_t length = Utf8SequenceLength(text, at); length > 0) {
      consumed = length;
      piece.assign(text.substr(at, length));
    } else {
      piece = HexByte(byte);
    }
    if (out.size() + piece.size() > maxBytes) return out + "...";
    out += piece;
    at += consumed;
  }
  return out;
}

// Built with append: GCC 12 warns falsely (-Wrestrict) on "literal" + temporary.
std::string Quoted(std::string_view text) {
  std::string quoted = "'";
  return quoted.append(Excerpt(text)).append("'");
}

std::string PointerTo(const std::string& parent, std::string_view key) {
  std::string escaped;
  for (char c : key) {
    if (c == '~') {
      escaped += "~0";
    } else if (c == '/') {
      escaped += "~1";
    } else {
      escaped += c;
    }
  }
  return parent + "/" + Excerpt(escaped);
}

std::string PointerTo(const std::string& parent, std::size_t index) {
  return parent + "/" + std::to_string(index);
}

std::string Where(const std::string& pointer) {
  return pointer.empty() ? "the document root" : pointer;
}

void WarningLog::Warn(const std::string& text) {
  if (printed_.insert(text).second) std::cerr << file_ << ": warning: " << text << '\n';
}

}  // namespace scenes::gltf
