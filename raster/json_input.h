#pragma once
// Reading JSON that a user hands aasim (sample patterns, GPU files, fixture manifests). It lives
// in raster/ because raster is the lowest layer every such reader may use (DESIGN.md layering).
//
// Two rules every reader follows: a document nested deeper than kMaxJsonDepth is refused before
// any value is built (deep nesting made recursive code overflow the stack), and an input value
// is quoted in a message only as a bounded excerpt, never dumped whole.

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace raster {

// Far deeper than any aasim input needs (patterns nest three levels) and far shallower than the
// stack allows.
inline constexpr int kMaxJsonDepth = 64;
inline constexpr std::size_t kMaxJsonExcerpt = 48;  // characters of a value quoted in a message
inline constexpr std::size_t kMaxJsonReason = 160;  // characters of the parser's own message

// Larger than any pattern, GPU file or fixture manifest aasim writes (the manifest of the
// canonical fixture set is about 1.4 MB), small enough to read whole without a memory check.
inline constexpr std::uintmax_t kMaxJsonFileBytes = 64u << 20;

// The reason a text is not an acceptable JSON document, without the caller's prefix.
class JsonTextError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Reads a JSON input file whole. Refuses, without opening it, anything that is not a regular
// file (a FIFO would block, a device never end) or is larger than kMaxJsonFileBytes. Throws
// JsonTextError with the reason only; the caller names the file.
std::string ReadJsonFile(const std::filesystem::path& path);

// Parses `text` as one JSON document; `allowComments` accepts // and /* */ comments.
// Throws JsonTextError ("is not valid JSON: ..." or "nests deeper than 64 levels").
template <typename JsonType = nlohmann::json>
JsonType ParseJsonText(std::string_view text, bool allowComments) {
  // The callback sees every start of an object or array with the number of containers already
  // open, before the parser descends, so a hostile document stops at the first level too deep.
  const typename JsonType::parser_callback_t limitDepth =
      [](int depth, typename JsonType::parse_event_t event, JsonType&) {
        const bool opens = event == JsonType::parse_event_t::object_start ||
                           event == JsonType::parse_event_t::array_start;
        if (opens && depth >= kMaxJsonDepth) {
          throw JsonTextError("nests deeper than " + std::to_string(kMaxJsonDepth) + " levels");
        }
        return true;
      };
  try {
    return JsonType::parse(text.begin(), text.end(), limitDepth, /*allow_exceptions=*/true,
                           allowComments);
  } catch (const typename JsonType::exception& error) {
    // parse_error for syntax, out_of_range for a number beyond a double (1e400).
    // The parser quotes the token it stopped at, which in hostile input can be megabytes long.
    std::string reason = error.what();
    if (reason.size() > kMaxJsonReason) reason = reason.substr(0, kMaxJsonReason) + "...";
    throw JsonTextError("is not valid JSON: " + reason);
  }
}

// A short description of `value` for messages: scalars as JSON cut to kMaxJsonExcerpt
// characters, containers by kind and size ("an array of 3 values", "an object with 2 keys").
template <typename JsonType>
std::string JsonExcerpt(const JsonType& value) {
  if (value.is_array()) return "an array of " + std::to_string(value.size()) + " values";
  if (value.is_object()) return "an object with " + std::to_string(value.size()) + " keys";
  if (value.is_number_float() && !std::isfinite(value.template get<double>())) {
    return "a number beyond the range of a double";
  }
  std::string text = value.dump(-1, ' ', /*ensure_ascii=*/true, JsonType::error_handler_t::replace);
  if (text.size() > kMaxJsonExcerpt) text = text.substr(0, kMaxJsonExcerpt) + "...";
  return text;
}

}  // namespace raster
