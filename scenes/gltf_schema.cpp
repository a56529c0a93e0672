// glTF 2.0 schema checks (see gltf_schema.h). The property lists and ranges are those of the
// specification's JSON schema (glTF.schema.json, accessor.schema.json, ...), one function per
// schema file; the rules from the specification's text are named where they are checked.

#include "scenes/gltf_schema.h"

#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <iomanip>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>
#include <vector>

#include "scenes/gltf_loader.h"
#include "scenes/scene.h"

namespace scenes::gltf {
namespace {

using nlohmann::json;

// Byte counts, offsets and element counts: every one exact in a double and far beyond any file
// aasim reads (kMaxGltfFileBytes), so sums of two never overflow.
constexpr std::int64_t kMaxInteger = (std::int64_t{1} << 53) - 1;
constexpr std::int64_t kMaxInt32 = std::numeric_limits<std::int32_t>::max();
constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Unit quaternions written by exporters are rounded; anything further off is not a rotation.
constexpr double kUnitQuaternionTolerance = 1e-3;
// Distinct ignored-property warnings per file; a hostile file could have millions.
constexpr std::size_t kMaxIgnoredPropertyWarnings = 16;

struct NumberRange {
  double min = -kInfinity;
  double max = kInfinity;
  bool minExclusive = false;
};
constexpr NumberRange kAnyNumber{};
constexpr NumberRange kUnitInterval{0.0, 1.0};
constexpr NumberRange kSignedUnit{-1.0, 1.0};
constexpr NumberRange kPositive{0.0, kInfinity, true};
constexpr NumberRange kNonNegative{0.0, kInfinity};
constexpr NumberRange kNodeValue{-kMaxGltfCoordinate, kMaxGltfCoordinate};

constexpr std::array<std::string_view, 13> kTopLevelArrays = {
    "accessors", "animations", "buffers",  "bufferViews", "cameras", "images",  "materials",
    "meshes",    "nodes",      "samplers", "scenes",      "skins",   "textures"};

enum class Need { Optional, Required };

struct DepthExceeded {};

std::string FormatNumber(double value) {
  std::ostringstream text;
  text << std::setprecision(9) << value;
  return text.str();
}

// A JSON value as a message may show it: numbers and literals in full, strings excerpted,
// arrays and objects only by their kind (never dumped: they may be arbitrarily large).
std::string Describe(const json& value) {
  switch (value.type()) {
    case json::value_t::string:
      return "the string \"" + Excerpt(value.get_ref<const std::string&>()) + "\"";
    case json::value_t::array: return "an array of " + std::to_string(value.size()) + " items";
    case json::value_t::object: return "an object";
    case json::value_t::null:
    case json::value_t::boolean:
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
    case json::value_t::number_float: return value.dump();
    case json::value_t::binary:
    case json::value_t::discarded: break;
  }
  return "a value";
}

std::string RangeText(const NumberRange& range) {
  if (range.min == -kInfinity && range.max == kInfinity) return "a number";
  if (range.max == kInfinity) {
    return std::string("a number ") + (range.minExclusive ? "> " : ">= ") + FormatNumber(range.min);
  }
  return "a number from " + FormatNumber(range.min) + " to " + FormatNumber(range.max);
}

bool InRange(double value, const NumberRange& range) {
  const bool aboveMin = range.minExclusive ? value > range.min : value >= range.min;
  return aboveMin && value <= range.max;
}

std::string IntegerText(std::int64_t min, std::int64_t max) {
  if (max == kMaxInteger) return "an integer >= " + std::to_string(min);
  return "an integer from " + std::to_string(min) + " to " + std::to_string(max);
}

std::string Join(std::initializer_list<int> values) {
  std::string text;
  for (int value : values) text.append(text.empty() ? "" : ", ").append(std::to_string(value));
  return text;
}

std::string Join(std::initializer_list<std::string_view> values) {
  std::string text;
  for (std::string_view value : values) {
    text.append(text.empty() ? "\"" : ", \"").append(value).append("\"");
  }
  return text;
}

bool Contains(std::initializer_list<std::string_view> list, std::string_view value) {
  for (std::string_view item : list) {
    if (item == value) return true;
  }
  return false;
}

std::size_t ComponentCount(std::string_view type) {
  if (type == "SCALAR") return 1;
  if (type == "VEC2") return 2;
  if (type == "VEC3") return 3;
  if (type == "MAT3") return 9;
  if (type == "MAT4") return 16;
  return 4;  // VEC4, MAT2
}

// glTF 2.0, "Meshes": the attribute semantics of the core, and "_"-prefixed application ones.
bool IsAttributeSemantic(std::string_view name) {
  if (name.starts_with("_") || name == "POSITION" || name == "NORMAL" || name == "TANGENT") {
    return true;
  }
  for (std::string_view set : {"TEXCOORD_", "COLOR_", "JOINTS_", "WEIGHTS_"}) {
    if (!name.starts_with(set) || name.size() == set.size()) continue;
    const std::string_view digits = name.substr(set.size());
    if (digits.find_first_not_of("0123456789") == std::string_view::npos) return true;
  }
  return false;
}

class SchemaValidator {
 public:
  SchemaValidator(const json& document, bool binary, const std::string& file, WarningLog& warnings)
      : doc_(document), binary_(binary), file_(file), warnings_(warnings) {}

  void Run() {
    Keys(doc_, "", "glTF",
         {"asset", "scene", "extensionsUsed", "extensionsRequired", "accessors", "animations",
          "buffers", "bufferViews", "cameras", "images", "materials", "meshes", "nodes", "samplers",
          "scenes", "skins", "textures"});
    CheckAsset(Required(doc_, "", "asset"), "/asset");
    ExtensionLists();
    for (std::string_view name : kTopLevelArrays) {
      const json* list = Array(doc_, "", name, 1);
      counts_[name] = list == nullptr ? 0 : list->size();
    }
    Each("buffers", &SchemaValidator::CheckBuffer);
    Each("bufferViews", &SchemaValidator::CheckBufferView);
    Each("accessors", &SchemaValidator::CheckAccessor);
    Each("images", &SchemaValidator::CheckImage);
    Each("samplers", &SchemaValidator::CheckSampler);
    Each("textures", &SchemaValidator::CheckTexture);
    Each("materials", &SchemaValidator::CheckMaterial);
    Each("meshes", &SchemaValidator::CheckMesh);
    Each("cameras", &SchemaValidator::CheckCamera);
    Each("nodes", &SchemaValidator::CheckNode);
    Each("skins", &SchemaValidator::CheckSkin);
    Each("animations", &SchemaValidator::CheckAnimation);
    Each("scenes", &SchemaValidator::CheckScene);
    Index(doc_, "", "scene", "scenes");
  }

 private:
  using Check = void (SchemaValidator::*)(const json&, const std::string&, std::size_t);

  [[noreturn]] void Fail(const std::string& at, const std::string& problem) const {
    throw SceneError(file_ + ": " + Where(at) + ": " + problem);
  }

  [[noreturn]] void FailType(const std::string& at, const std::string& expected,
                             const json& found) const {
    Fail(at, "expected " + expected + ", found " + Describe(found));
  }

  void Each(std::string_view array, Check check) {
    const auto it = doc_.find(std::string(array));
    if (it == doc_.end()) return;
    const std::string at = "/" + std::string(array);
    for (std::size_t i = 0; i < it->size(); ++i) (this->*check)((*it)[i], PointerTo(at, i), i);
  }

  // --- Values --------------------------------------------------------------------------------

  std::int64_t ExpectInteger(const json& value, const std::string& at, std::int64_t min,
                             std::int64_t max) const {
    if (value.is_number_unsigned()) {
      const auto number = value.get<std::uint64_t>();
      if (number <= static_cast<std::uint64_t>(max) && static_cast<std::int64_t>(number) >= min) {
        return static_cast<std::int64_t>(number);
      }
    } else if (value.is_number_integer()) {
      const auto number = value.get<std::int64_t>();
      if (number >= min && number <= max) return number;
    }
    FailType(at, IntegerText(min, max), value);
  }

  std::int64_t ExpectIndex(const json& value, const std::string& at, std::string_view array,
                           std::size_t count) const {
    const std::int64_t index = ExpectInteger(value, at, 0, kMaxInteger);
    if (static_cast<std::size_t>(index) >= count) {
      Fail(at, "index " + std::to_string(index) + " is out of range: the file has " +
                   std::to_string(count) + " " + std::string(array));
    }
    return index;
  }

  double ExpectNumber(const json& value, const std::string& at, const NumberRange& range) const {
    if (!value.is_number() || !InRange(value.get<double>(), range)) {
      FailType(at, RangeText(range), value);
    }
    return value.get<double>();
  }

  const std::string& ExpectString(const json& value, const std::string& at) const {
    if (!value.is_string()) FailType(at, "a string", value);
    return value.get_ref<const std::string&>();
  }

  void ExpectObject(const json& value, const std::string& at) const {
    if (!value.is_object()) FailType(at, "a JSON object", value);
  }

  // A float the reader will hold (camera values): representable, and not rounded to zero
  // where zero is not allowed.
  float ExpectFloat(double value, const std::string& at, bool nonZero) const {
    if (std::abs(value) > static_cast<double>(std::numeric_limits<float>::max())) {
      Fail(at, FormatNumber(value) + " does not fit a float");
    }
    const auto single = static_cast<float>(value);
    if (nonZero && single == 0.0f) Fail(at, FormatNumber(value) + " is 0 as a float");
    return single;
  }

  // --- Properties: absent (nullptr / nullopt / empty) unless required ------------------------

  const json* Get(const json& object, const std::string& at, std::string_view key,
                  Need need) const {
    const auto it = object.find(std::string(key));
    if (it != object.end()) return &*it;
    if (need == Need::Required) {
      Fail(at, "the required property \"" + std::string(key) + "\" is missing");
    }
    return nullptr;
  }

  const json& Required(const json& object, const std::string& at, std::string_view key) const {
    return *Get(object, at, key, Need::Required);
  }

  static std::string Child(const std::string& at, std::string_view key) {
    return at + "/" + std::string(key);
  }

  std::optional<std::int64_t> Integer(const json& object, const std::string& at,
                                      std::string_view key, std::int64_t min, std::int64_t max,
                                      Need need = Need::Optional) const {
    const json* value = Get(object, at, key, need);
    if (value == nullptr) return std::nullopt;
    return ExpectInteger(*value, Child(at, key), min, max);
  }

  std::optional<std::int64_t> Index(const json& object, const std::string& at, std::string_view key,
                                    std::string_view array, Need need = Need::Optional) const {
    const json* value = Get(object, at, key, need);
    if (value == nullptr) return std::nullopt;
    return ExpectIndex(*value, Child(at, key), array, counts_.at(array));
  }

  std::optional<double> Number(const json& object, const std::string& at, std::string_view key,
                               const NumberRange& range, Need need = Need::Optional) const {
    const json* value = Get(object, at, key, need);
    if (value == nullptr) return std::nullopt;
    return ExpectNumber(*value, Child(at, key), range);
  }

  const std::string* String(const json& object, const std::string& at, std::string_view key,
                            Need need = Need::Optional) const {
    const json* value = Get(object, at, key, need);
    return value == nullptr ? nullptr : &ExpectString(*value, Child(at, key));
  }

  std::optional<bool> Boolean(const json& object, const std::string& at,
                              std::string_view key) const {
    const json* value = Get(object, at, key, Need::Optional);
    if (value == nullptr) return std::nullopt;
    if (!value->is_boolean()) FailType(Child(at, key), "true or false", *value);
    return value->get<bool>();
  }

  std::optional<int> Enum(const json& object, const std::string& at, std::string_view key,
                          std::initializer_list<int> allowed, Need need = Need::Optional) const {
    const json* value = Get(object, at, key, need);
    if (value == nullptr) return std::nullopt;
    if (value->is_number_integer()) {
      for (int candidate : allowed) {
        if (*value == candidate) return candidate;
      }
    }
    FailType(Child(at, key), "one of " + Join(allowed), *value);
  }

  const std::string* StringEnum(const json& object, const std::string& at, std::string_view key,
                                std::initializer_list<std::string_view> allowed,
                                Need need = Need::Optional) const {
    const json* value = Get(object, at, key, need);
    if (value == nullptr) return nullptr;
    if (!value->is_string() || !Contains(allowed, value->get_ref<const std::string&>())) {
      FailType(Child(at, key), "one of " + Join(allowed), *value);
    }
    return &value->get_ref<const std::string&>();
  }

  const json* Object(const json& object, const std::string& at, std::string_view key,
                     Need need = Need::Optional) const {
    const json* value = Get(object, at, key, need);
    if (value != nullptr) ExpectObject(*value, Child(at, key));
    return value;
  }

  const json* Array(const json& object, const std::string& at, std::string_view key,
                    std::size_t minItems, Need need = Need::Optional) const {
    const json* value = Get(object, at, key, need);
    if (value != nullptr && (!value->is_array() || value->size() < minItems)) {
      FailType(Child(at, key), minItems > 0 ? "a non-empty array" : "an array", *value);
    }
    return value;
  }

  // `size` 0: any non-empty array.
  std::vector<double> Numbers(const json& object, const std::string& at, std::string_view key,
                              std::size_t size, const NumberRange& range) const {
    const json* value = Get(object, at, key, Need::Optional);
    if (value == nullptr) return {};
    const std::string where = Child(at, key);
    if (!value->is_array() || (size == 0 ? value->empty() : value->size() != size)) {
      FailType(where,
               size == 0 ? "a non-empty array of numbers"
                         : "an array of " + std::to_string(size) + " numbers",
               *value);
    }
    std::vector<double> numbers;
    for (std::size_t i = 0; i < value->size(); ++i) {
      numbers.push_back(ExpectNumber((*value)[i], PointerTo(where, i), range));
    }
    return numbers;
  }

  // A non-empty list of distinct indices into `array`.
  void Indices(const json& object, const std::string& at, std::string_view key,
               std::string_view array, Need need = Need::Optional) const {
    const json* list = Array(object, at, key, 1, need);
    if (list == nullptr) return;
    std::set<std::int64_t> seen;
    for (std::size_t i = 0; i < list->size(); ++i) {
      const std::string where = PointerTo(Child(at, key), i);
      const std::int64_t index = ExpectIndex((*list)[i], where, array, counts_.at(array));
      if (!seen.insert(index).second) {
        Fail(where, "index " + std::to_string(index) + " appears twice in the list");
      }
    }
  }

  // Checks `object` is an object, its name, extensions and extras, and warns about properties
  // outside `known`.
  void Keys(const json& object, const std::string& at, std::string_view kind,
            std::initializer_list<std::string_view> known) {
    ExpectObject(object, at);
    for (const auto& [key, value] : object.items()) {
      const std::string where = PointerTo(at, key);
      if (key == "extensions") {
        Extensions(value, where);
      } else if (key == "name" && Contains(known, key)) {
        ExpectString(value, where);
      } else if (key != "extras" && !Contains(known, key)) {
        WarnIgnored(kind, key, where);
      }
    }
  }

  // extension.schema.json: every extension's value is an object.
  void Extensions(const json& extensions, const std::string& at) const {
    ExpectObject(extensions, at);
    for (const auto& [name, value] : extensions.items()) ExpectObject(value, PointerTo(at, name));
  }

  void WarnIgnored(std::string_view kind, const std::string& key, const std::string& at) {
    if (!ignored_.insert(std::string(kind) + "/" + key).second) return;
    if (ignored_.size() > kMaxIgnoredPropertyWarnings) {
      if (ignored_.size() == kMaxIgnoredPropertyWarnings + 1) {
        warnings_.Warn("more properties outside glTF 2.0 are ignored; not listed");
      }
      return;
    }
    warnings_.Warn("property " + Quoted(key) + " is not part of glTF 2.0's " + std::string(kind) +
                   " and is ignored (first at " + at + ")");
  }

  // --- Schema objects ------------------------------------------------------------------------

  void CheckAsset(const json& asset, const std::string& at) {
    Keys(asset, at, "asset", {"copyright", "generator", "version", "minVersion"});
    String(asset, at, "copyright");
    String(asset, at, "generator");
    const std::string& version = *String(asset, at, "version", Need::Required);
    if (Version(version, Child(at, "version")).first != 2) {
      Fail(Child(at, "version"), "glTF version \"" + Excerpt(version) + "\"; aasim reads 2.x");
    }
    if (const std::string* minimum = String(asset, at, "minVersion")) {
      if (Version(*minimum, Child(at, "minVersion")) > std::pair<unsigned, unsigned>{2, 0}) {
        Fail(Child(at, "minVersion"),
             "the file requires glTF " + Excerpt(*minimum) + "; aasim reads glTF 2.0");
      }
    }
  }

  // asset.schema.json: "^[0-9]+\.[0-9]+$".
  std::pair<unsigned, unsigned> Version(const std::string& text, const std::string& at) const {
    std::pair<unsigned, unsigned> version{};
    const char* end = text.data() + text.size();
    const auto [afterMajor, majorError] = std::from_chars(text.data(), end, version.first);
    const bool dot = majorError == std::errc() && afterMajor != end && *afterMajor == '.';
    if (dot && afterMajor + 1 != end && std::isdigit(static_cast<unsigned char>(afterMajor[1]))) {
      const auto [afterMinor, minorError] = std::from_chars(afterMajor + 1, end, version.second);
      if (minorError == std::errc() && afterMinor == end) return version;
    }
    Fail(at, "\"" + Excerpt(text) + "\" is not a version MAJOR.MINOR");
  }

  void ExtensionLists() const {
    std::set<std::string> used;
    for (const char* list : {"extensionsUsed", "extensionsRequired"}) {
      const json* names = Array(doc_, "", list, 1);
      if (names == nullptr) continue;
      std::set<std::string> seen;
      for (std::size_t i = 0; i < names->size(); ++i) {
        const std::string at = PointerTo(Child("", list), i);
        const std::string& name = ExpectString((*names)[i], at);
        if (!seen.insert(name).second) Fail(at, Quoted(name) + " appears twice in the list");
        if (list == std::string_view("extensionsUsed")) used.insert(name);
        if (list == std::string_view("extensionsRequired") && !used.contains(name)) {
          Fail(at, Quoted(name) + " is required but not listed in extensionsUsed");
        }
      }
    }
  }

  void CheckBuffer(const json& buffer, const std::string& at, std::size_t index) {
    Keys(buffer, at, "buffer", {"uri", "byteLength", "name"});
    // glTF 2.0, "GLB-stored Buffer": only a GLB's first buffer may live in the BIN chunk.
    String(buffer, at, "uri", binary_ && index == 0 ? Need::Optional : Need::Required);
    Integer(buffer, at, "byteLength", 1, kMaxInteger, Need::Required);
  }

  void CheckBufferView(const json& view, const std::string& at, std::size_t) {
    Keys(view, at, "bufferView",
         {"buffer", "byteOffset", "byteLength", "byteStride", "target", "name"});
    const std::int64_t buffer = *Index(view, at, "buffer", "buffers", Need::Required);
    const std::int64_t offset = Integer(view, at, "byteOffset", 0, kMaxInteger).value_or(0);
    const std::int64_t length = *Integer(view, at, "byteLength", 1, kMaxInteger, Need::Required);
    if (const auto stride = Integer(view, at, "byteStride", 4, 252); stride && *stride % 4 != 0) {
      Fail(Child(at, "byteStride"), "expected a multiple of 4, found " + std::to_string(*stride));
    }
    Enum(view, at, "target", {34962, 34963});
    const auto bufferLength =
        doc_["buffers"][static_cast<std::size_t>(buffer)]["byteLength"].get<std::int64_t>();
    if (offset > bufferLength || length > bufferLength - offset) {
      Fail(at, "bytes " + std::to_string(offset) + " to " + std::to_string(offset + length) +
                   " run past the end of buffer " + std::to_string(buffer) + " (" +
                   std::to_string(bufferLength) + " bytes)");
    }
  }

  void CheckAccessor(const json& accessor, const std::string& at, std::size_t) {
    Keys(accessor, at, "accessor",
         {"bufferView", "byteOffset", "componentType", "normalized", "count", "type", "max", "min",
          "sparse", "name"});
    const bool stored = Index(accessor, at, "bufferView", "bufferViews").has_value();
    if (Integer(accessor, at, "byteOffset", 0, kMaxInteger) && !stored) {
      Fail(Child(at, "byteOffset"), "a byteOffset needs a bufferView");
    }
    const int componentType =
        *Enum(accessor, at, "componentType", {5120, 5121, 5122, 5123, 5125, 5126}, Need::Required);
    // accessor.schema.json, "normalized": not for float and unsigned int components.
    if (Boolean(accessor, at, "normalized").value_or(false) &&
        (componentType == 5126 || componentType == 5125)) {
      Fail(Child(at, "normalized"), "float and unsigned int accessors cannot be normalized");
    }
    Integer(accessor, at, "count", 1, kMaxInteger, Need::Required);
    const std::string& type =
        *StringEnum(accessor, at, "type",
                    {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"}, Need::Required);
    Numbers(accessor, at, "min", ComponentCount(type), kAnyNumber);
    Numbers(accessor, at, "max", ComponentCount(type), kAnyNumber);
    if (const json* sparse = Object(accessor, at, "sparse"))
      CheckSparse(*sparse, Child(at, "sparse"));
  }

  void CheckSparse(const json& sparse, const std::string& at) {
    Keys(sparse, at, "accessor.sparse", {"count", "indices", "values"});
    Integer(sparse, at, "count", 1, kMaxInteger, Need::Required);
    const std::string indicesAt = Child(at, "indices");
    const json& indices = Required(sparse, at, "indices");
    Keys(indices, indicesAt, "accessor.sparse.indices",
         {"bufferView", "byteOffset", "componentType"});
    Index(indices, indicesAt, "bufferView", "bufferViews", Need::Required);
    Integer(indices, indicesAt, "byteOffset", 0, kMaxInteger);
    Enum(indices, indicesAt, "componentType", {5121, 5123, 5125}, Need::Required);
    const std::string valuesAt = Child(at, "values");
    const json& values = Required(sparse, at, "values");
    Keys(values, valuesAt, "accessor.sparse.values", {"bufferView", "byteOffset"});
    Index(values, valuesAt, "bufferView", "bufferViews", Need::Required);
    Integer(values, valuesAt, "byteOffset", 0, kMaxInteger);
  }

  void CheckImage(const json& image, const std::string& at, std::size_t) {
    Keys(image, at, "image", {"uri", "mimeType", "bufferView", "name"});
    const bool hasUri = String(image, at, "uri") != nullptr;
    const bool hasMimeType = String(image, at, "mimeType") != nullptr;
    const bool stored = Index(image, at, "bufferView", "bufferViews").has_value();
    if (hasUri == stored) {
      Fail(at, hasUri ? "an image has a uri or a bufferView, not both"
                      : "an image needs a uri or a bufferView");
    }
    if (stored && !hasMimeType) Fail(at, "an image in a bufferView needs a mimeType");
  }

  void CheckSampler(const json& sampler, const std::string& at, std::size_t) {
    Keys(sampler, at, "sampler", {"magFilter", "minFilter", "wrapS", "wrapT", "name"});
    Enum(sampler, at, "magFilter", {9728, 9729});
    Enum(sampler, at, "minFilter", {9728, 9729, 9984, 9985, 9986, 9987});
    Enum(sampler, at, "wrapS", {33071, 33648, 10497});
    Enum(sampler, at, "wrapT", {33071, 33648, 10497});
  }

  void CheckTexture(const json& texture, const std::string& at, std::size_t) {
    Keys(texture, at, "texture", {"sampler", "source", "name"});
    Index(texture, at, "sampler", "samplers");
    Index(texture, at, "source", "images");
  }

  // textureInfo.schema.json and its normal / occlusion variants (`known` adds their factor).
  const json* CheckTextureInfo(const json& object, const std::string& at, std::string_view key,
                               std::initializer_list<std::string_view> known) {
    const json* info = Object(object, at, key);
    if (info == nullptr) return nullptr;
    const std::string where = Child(at, key);
    Keys(*info, where, key, known);
    Index(*info, where, "index", "textures", Need::Required);
    Integer(*info, where, "texCoord", 0, kMaxInt32);
    return info;
  }

  void CheckMaterial(const json& material, const std::string& at, std::size_t) {
    Keys(material, at, "material",
         {"name", "pbrMetallicRoughness", "normalTexture", "occlusionTexture", "emissiveTexture",
          "emissiveFactor", "alphaMode", "alphaCutoff", "doubleSided"});
    if (const json* pbr = Object(material, at, "pbrMetallicRoughness")) {
      CheckPbrMetallicRoughness(*pbr, Child(at, "pbrMetallicRoughness"));
    }
    if (const json* normal =
            CheckTextureInfo(material, at, "normalTexture", {"index", "texCoord", "scale"})) {
      Number(*normal, Child(at, "normalTexture"), "scale", kAnyNumber);
    }
    if (const json* occlusion =
            CheckTextureInfo(material, at, "occlusionTexture", {"index", "texCoord", "strength"})) {
      Number(*occlusion, Child(at, "occlusionTexture"), "strength", kUnitInterval);
    }
    CheckTextureInfo(material, at, "emissiveTexture", {"index", "texCoord"});
    Numbers(material, at, "emissiveFactor", 3, kUnitInterval);
    StringEnum(material, at, "alphaMode", {"OPAQUE", "MASK", "BLEND"});
    Number(material, at, "alphaCutoff", kNonNegative);
    Boolean(material, at, "doubleSided");
  }

  void CheckPbrMetallicRoughness(const json& pbr, const std::string& at) {
    Keys(pbr, at, "material.pbrMetallicRoughness",
         {"baseColorFactor", "baseColorTexture", "metallicFactor", "roughnessFactor",
          "metallicRoughnessTexture"});
    Numbers(pbr, at, "baseColorFactor", 4, kUnitInterval);
    CheckTextureInfo(pbr, at, "baseColorTexture", {"index", "texCoord"});
    Number(pbr, at, "metallicFactor", kUnitInterval);
    Number(pbr, at, "roughnessFactor", kUnitInterval);
    CheckTextureInfo(pbr, at, "metallicRoughnessTexture", {"index", "texCoord"});
  }

  void CheckMesh(const json& mesh, const std::string& at, std::size_t) {
    Keys(mesh, at, "mesh", {"primitives", "weights", "name"});
    const json& primitives = *Array(mesh, at, "primitives", 1, Need::Required);
    for (std::size_t i = 0; i < primitives.size(); ++i) {
      CheckPrimitive(primitives[i], PointerTo(Child(at, "primitives"), i));
    }
    Numbers(mesh, at, "weights", 0, kAnyNumber);
  }

  void CheckPrimitive(const json& primitive, const std::string& at) {
    Keys(primitive, at, "mesh.primitive", {"attributes", "indices", "material", "mode", "targets"});
    CheckAttributes(Required(primitive, at, "attributes"), Child(at, "attributes"), true);
    if (const auto indices = Index(primitive, at, "indices", "accessors")) {
      // tinygltf cannot read indices without a bufferView, and they would all be 0 anyway.
      if (!doc_["accessors"][static_cast<std::size_t>(*indices)].contains("bufferView")) {
        Fail(Child(at, "indices"),
             "accessor " + std::to_string(*indices) + " has no bufferView; indices must be stored");
      }
    }
    Index(primitive, at, "material", "materials");
    Enum(primitive, at, "mode", {0, 1, 2, 3, 4, 5, 6});
    if (const json* targets = Array(primitive, at, "targets", 1)) {
      for (std::size_t i = 0; i < targets->size(); ++i) {
        CheckAttributes((*targets)[i], PointerTo(Child(at, "targets"), i), false);
      }
    }
  }

  // Attribute (or morph target) name -> accessor index.
  void CheckAttributes(const json& attributes, const std::string& at, bool primitive) {
    ExpectObject(attributes, at);
    if (primitive && attributes.empty()) Fail(at, "a primitive needs at least one attribute");
    for (const auto& [name, accessor] : attributes.items()) {
      const std::string where = PointerTo(at, name);
      ExpectIndex(accessor, where, "accessors", counts_.at("accessors"));
      if (primitive && !IsAttributeSemantic(name)) {
        WarnIgnored("attribute semantics", name, where);
      }
    }
  }

  void CheckCamera(const json& camera, const std::string& at, std::size_t) {
    Keys(camera, at, "camera", {"orthographic", "perspective", "type", "name"});
    const std::string& type =
        *StringEnum(camera, at, "type", {"perspective", "orthographic"}, Need::Required);
    const json* perspective = Object(camera, at, "perspective");
    const json* orthographic = Object(camera, at, "orthographic");
    if (perspective != nullptr && orthographic != nullptr) {
      Fail(at, "a camera is perspective or orthographic, not both");
    }
    if (type == "perspective") {
      CheckPerspective(Required(camera, at, "perspective"), Child(at, "perspective"));
    } else {
      CheckOrthographic(Required(camera, at, "orthographic"), Child(at, "orthographic"));
    }
  }

  // The loader keeps these as floats, so each must still make sense after rounding: in
  // particular pi itself rounds up, and a yfov of pi makes no projection.
  void CheckPerspective(const json& lens, const std::string& at) {
    Keys(lens, at, "camera.perspective", {"aspectRatio", "yfov", "zfar", "znear"});
    const double yfov = *Number(lens, at, "yfov", kPositive, Need::Required);
    const float yfovFloat = ExpectFloat(yfov, Child(at, "yfov"), true);
    if (!(static_cast<double>(yfovFloat) < std::numbers::pi)) {
      Fail(Child(at, "yfov"), FormatNumber(yfov) + " is not below pi as a float (" +
                                  FormatNumber(static_cast<double>(yfovFloat)) + ")");
    }
    const double znear = *Number(lens, at, "znear", kPositive, Need::Required);
    const float znearFloat = ExpectFloat(znear, Child(at, "znear"), true);
    if (const auto zfar = Number(lens, at, "zfar", kPositive)) {
      if (!(ExpectFloat(*zfar, Child(at, "zfar"), true) > znearFloat)) {
        Fail(Child(at, "zfar"),
             FormatNumber(*zfar) + " is not beyond znear " + FormatNumber(znear) + " (as floats)");
      }
    }
    if (const auto aspect = Number(lens, at, "aspectRatio", kPositive)) {
      ExpectFloat(*aspect, Child(at, "aspectRatio"), true);
    }
  }

  void CheckOrthographic(const json& lens, const std::string& at) {
    Keys(lens, at, "camera.orthographic", {"xmag", "ymag", "zfar", "znear"});
    for (const char* key : {"xmag", "ymag"}) {
      const double magnification = *Number(lens, at, key, kAnyNumber, Need::Required);
      ExpectFloat(magnification, Child(at, key), true);
    }
    const double znear = *Number(lens, at, "znear", kNonNegative, Need::Required);
    const double zfar = *Number(lens, at, "zfar", kPositive, Need::Required);
    if (!(ExpectFloat(zfar, Child(at, "zfar"), true) >
          ExpectFloat(znear, Child(at, "znear"), false))) {
      Fail(Child(at, "zfar"),
           FormatNumber(zfar) + " is not beyond znear " + FormatNumber(znear) + " (as floats)");
    }
  }

  void CheckNode(const json& node, const std::string& at, std::size_t) {
    Keys(node, at, "node",
         {"camera", "children", "skin", "matrix", "mesh", "rotation", "scale", "translation",
          "weights", "name"});
    Index(node, at, "camera", "cameras");
    Indices(node, at, "children", "nodes");
    Index(node, at, "skin", "skins");
    Index(node, at, "mesh", "meshes");
    const std::vector<double> matrix = Numbers(node, at, "matrix", 16, kNodeValue);
    const std::vector<double> rotation = Numbers(node, at, "rotation", 4, kSignedUnit);
    const bool scaled = !Numbers(node, at, "scale", 3, kNodeValue).empty();
    const bool translated = !Numbers(node, at, "translation", 3, kNodeValue).empty();
    Numbers(node, at, "weights", 0, kAnyNumber);
    // glTF 2.0, "Transformations": a matrix or TRS properties, and the matrix must be affine.
    if (!matrix.empty() && (scaled || translated || !rotation.empty())) {
      Fail(at, "a node has a matrix or translation, rotation and scale, not both");
    }
    for (std::size_t i : {3u, 7u, 11u, 15u}) {
      const double expected = i == 15 ? 1.0 : 0.0;
      if (!matrix.empty() && matrix[i] != expected) {
        Fail(PointerTo(Child(at, "matrix"), i), "expected " + FormatNumber(expected) + ", found " +
                                                    FormatNumber(matrix[i]) +
                                                    " (a node matrix's last row is 0, 0, 0, 1)");
      }
    }
    if (!rotation.empty()) {
      const double length = std::sqrt(rotation[0] * rotation[0] + rotation[1] * rotation[1] +
                                      rotation[2] * rotation[2] + rotation[3] * rotation[3]);
      if (!(std::abs(length - 1.0) <= kUnitQuaternionTolerance)) {
        Fail(Child(at, "rotation"),
             "a rotation of length " + FormatNumber(length) + " is not a unit quaternion");
      }
    }
  }

  void CheckSkin(const json& skin, const std::string& at, std::size_t) {
    Keys(skin, at, "skin", {"inverseBindMatrices", "skeleton", "joints", "name"});
    Index(skin, at, "inverseBindMatrices", "accessors");
    Index(skin, at, "skeleton", "nodes");
    Indices(skin, at, "joints", "nodes", Need::Required);
  }

  void CheckAnimation(const json& animation, const std::string& at, std::size_t) {
    Keys(animation, at, "animation", {"channels", "samplers", "name"});
    const json& samplers = *Array(animation, at, "samplers", 1, Need::Required);
    for (std::size_t i = 0; i < samplers.size(); ++i) {
      const std::string where = PointerTo(Child(at, "samplers"), i);
      Keys(samplers[i], where, "animation.sampler", {"input", "interpolation", "output"});
      Index(samplers[i], where, "input", "accessors", Need::Required);
      String(samplers[i], where, "interpolation");
      Index(samplers[i], where, "output", "accessors", Need::Required);
    }
    const json& channels = *Array(animation, at, "channels", 1, Need::Required);
    for (std::size_t i = 0; i < channels.size(); ++i) {
      const std::string where = PointerTo(Child(at, "channels"), i);
      Keys(channels[i], where, "animation.channel", {"sampler", "target"});
      ExpectIndex(Required(channels[i], where, "sampler"), Child(where, "sampler"),
                  "samplers in this animation", samplers.size());
      const json& target = Required(channels[i], where, "target");
      const std::string targetAt = Child(where, "target");
      Keys(target, targetAt, "animation.channel.target", {"node", "path"});
      Index(target, targetAt, "node", "nodes");
      String(target, targetAt, "path", Need::Required);
    }
  }

  void CheckScene(const json& scene, const std::string& at, std::size_t) {
    Keys(scene, at, "scene", {"nodes", "name"});
    Indices(scene, at, "nodes", "nodes");
  }

  const json& doc_;
  bool binary_;
  const std::string& file_;
  WarningLog& warnings_;
  std::map<std::string_view, std::size_t> counts_;
  std::set<std::string> ignored_;
};

// nlohmann's report without its "[json.exception...] " tag, excerpted: it quotes the input.
std::string ParserReport(const json::exception& error) {
  std::string_view text = error.what();
  if (const std::size_t tag = text.find("] "); tag != std::string_view::npos) {
    text.remove_prefix(tag + 2);
  }
  return Excerpt(text, 4 * kExcerptBytes);
}

}  // namespace

json ParseGltfJson(std::string_view text, const std::string& file) {
  // nlohmann's parser is iterative; refusing at the opening bracket keeps the document small.
  const json::parser_callback_t limitDepth = [](int depth, json::parse_event_t event, json&) {
    const bool opens =
        event == json::parse_event_t::object_start || event == json::parse_event_t::array_start;
    if (opens && depth >= kMaxGltfJsonDepth) throw DepthExceeded{};
    return true;
  };
  try {
    return json::parse(text.begin(), text.end(), limitDepth);
  } catch (const DepthExceeded&) {
    throw SceneError(file + ": JSON arrays and objects nest more than " +
                     std::to_string(kMaxGltfJsonDepth) + " levels deep, the most aasim reads");
  } catch (const json::exception& error) {
    throw SceneError(file + ": cannot load glTF: malformed JSON: " + ParserReport(error));
  }
}

void ValidateGltfSchema(const json& document, bool binary, const std::string& file,
                        WarningLog& warnings) {
  SchemaValidator(document, binary, file, warnings).Run();
}

}  // namespace scenes::gltf
