#include "sim/gpu_config.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <sstream>
#include <system_error>

#include <nlohmann/json.hpp>

#include "sim/wave.h"

namespace sim {
namespace {

struct BuiltinGpu {
  std::string_view name;
  std::string_view text;
};

// {name, file text} per sim/gpus/NAME.jsonc, generated at configure time by sim/CMakeLists.txt.
constexpr BuiltinGpu kBuiltinGpus[] = {
#include "sim/builtin_gpus.inc"
};

// The keys of a GPU file besides "name", in file order; one table drives the required-key,
// unknown-key and type checks so they cannot drift apart.
struct IntKey {
  const char* key;
  int GpuConfig::*member;
};
struct DoubleKey {
  const char* key;
  double GpuConfig::*member;
};

constexpr IntKey kIntKeys[] = {
    {"shaderEngines", &GpuConfig::shaderEngines},
    {"computeUnits", &GpuConfig::computeUnits},
    {"simdsPerCu", &GpuConfig::simdsPerCu},
    {"waveSlotsPerSimd", &GpuConfig::waveSlotsPerSimd},
    {"vgprsPerSimdLane", &GpuConfig::vgprsPerSimdLane},
    {"vgprGranule", &GpuConfig::vgprGranule},
    {"maxVgprsPerWave", &GpuConfig::maxVgprsPerWave},
    {"sgprsPerSimd", &GpuConfig::sgprsPerSimd},
    {"sgprGranule", &GpuConfig::sgprGranule},
    {"maxSgprsPerWave", &GpuConfig::maxSgprsPerWave},
    {"ldsBytesPerCu", &GpuConfig::ldsBytesPerCu},
    {"ldsGranuleBytes", &GpuConfig::ldsGranuleBytes},
    {"maxLdsBytesPerGroup", &GpuConfig::maxLdsBytesPerGroup},
    {"maxGroupsPerCu", &GpuConfig::maxGroupsPerCu},
    {"maxThreadsPerGroup", &GpuConfig::maxThreadsPerGroup},
};

constexpr DoubleKey kDoubleKeys[] = {
    {"clockMhz", &GpuConfig::clockMhz},
    {"dramGBytesPerSecond", &GpuConfig::dramGBytesPerSecond},
    {"waveLaunchesPerClockPerSe", &GpuConfig::waveLaunchesPerClockPerSe},
    {"rasterPixelsPerClockPerSe", &GpuConfig::rasterPixelsPerClockPerSe},
    {"hiStencilTilesPerClockPerSe", &GpuConfig::hiStencilTilesPerClockPerSe},
    {"wavesPerSimdToHideLatency", &GpuConfig::wavesPerSimdToHideLatency},
    {"dispatchOverheadMicroseconds", &GpuConfig::dispatchOverheadMicroseconds},
};

constexpr const char* kNameKey = "name";

bool IsKnownKey(const std::string& key) {
  if (key == kNameKey) return true;
  const auto sameKey = [&](const auto& entry) { return key == entry.key; };
  return std::ranges::any_of(kIntKeys, sameKey) || std::ranges::any_of(kDoubleKeys, sameKey);
}

std::string BuiltinList() {
  std::string list;
  for (const BuiltinGpu& gpu : kBuiltinGpus) {
    if (!list.empty()) list += ", ";
    list += gpu.name;
  }
  return list;
}

class GpuFileParser {
 public:
  explicit GpuFileParser(const std::string& source) : source_(source) {}

  GpuConfig Parse(std::string_view text) const {
    const nlohmann::json root = ParseText(text);
    for (const auto& item : root.items()) {
      if (!IsKnownKey(item.key())) Fail("unknown key '" + item.key() + "'");
    }
    GpuConfig config;
    config.source = source_;
    config.name = Name(root);
    for (const IntKey& entry : kIntKeys) config.*entry.member = PositiveInt(root, entry.key);
    for (const DoubleKey& entry : kDoubleKeys) config.*entry.member = PositiveDouble(root, entry.key);
    CheckConsistency(config);
    return config;
  }

 private:
  [[noreturn]] void Fail(const std::string& problem) const { throw GpuConfigError(source_ + ": " + problem); }

  nlohmann::json ParseText(std::string_view text) const {
    nlohmann::json root;
    try {
      root = nlohmann::json::parse(text.begin(), text.end(), nullptr, /*allow_exceptions=*/true,
                                   /*ignore_comments=*/true);
    } catch (const nlohmann::json::parse_error& error) {
      Fail(std::string("not valid JSON: ") + error.what());
    }
    if (!root.is_object()) Fail("must hold one JSON object, found " + root.dump());
    return root;
  }

  const nlohmann::json& Required(const nlohmann::json& root, const char* key) const {
    const auto it = root.find(key);
    if (it == root.end()) Fail(std::string("missing key '") + key + "'");
    return *it;
  }

  std::string Name(const nlohmann::json& root) const {
    const nlohmann::json& value = Required(root, kNameKey);
    if (!value.is_string() || value.get_ref<const std::string&>().empty()) {
      Fail(std::string("key '") + kNameKey + "' must be a non-empty string, found " + value.dump());
    }
    return value.get<std::string>();
  }

  int PositiveInt(const nlohmann::json& root, const char* key) const {
    const nlohmann::json& value = Required(root, key);
    if (!value.is_number_integer()) {
      Fail(std::string("key '") + key + "' must be an integer, found " + value.dump());
    }
    // Parsed text holds non-negative integers as unsigned, which get<std::int64_t> would wrap.
    constexpr auto kIntMax = static_cast<std::uint64_t>(std::numeric_limits<int>::max());
    if (value.is_number_unsigned() ? value.get<std::uint64_t>() > kIntMax
                                   : value.get<std::int64_t>() > static_cast<std::int64_t>(kIntMax)) {
      Fail(std::string("key '") + key + "' is too large, found " + value.dump());
    }
    const auto number = value.get<std::int64_t>();
    if (number <= 0) Fail(std::string("key '") + key + "' must be positive, found " + value.dump());
    return static_cast<int>(number);
  }

  double PositiveDouble(const nlohmann::json& root, const char* key) const {
    const nlohmann::json& value = Required(root, key);
    if (!value.is_number()) Fail(std::string("key '") + key + "' must be a number, found " + value.dump());
    const auto number = value.get<double>();
    if (!std::isfinite(number) || !(number > 0.0)) {
      Fail(std::string("key '") + key + "' must be positive and finite, found " + value.dump());
    }
    return number;
  }

  void CheckDivides(const char* granuleKey, int granule, const char* poolKey, int pool) const {
    if (pool % granule != 0) {
      Fail(std::string("key '") + granuleKey + "' (" + std::to_string(granule) + ") must divide '" + poolKey +
           "' (" + std::to_string(pool) + ")");
    }
  }

  template <typename T>
  void CheckAtMost(const char* key, T value, const char* limitKey, T limit) const {
    if (value > limit) {
      std::ostringstream message;
      message << "key '" << key << "' (" << value << ") must not exceed '" << limitKey << "' (" << limit << ")";
      Fail(message.str());
    }
  }

  void CheckConsistency(const GpuConfig& config) const {
    CheckDivides("vgprGranule", config.vgprGranule, "vgprsPerSimdLane", config.vgprsPerSimdLane);
    CheckAtMost("maxVgprsPerWave", config.maxVgprsPerWave, "vgprsPerSimdLane", config.vgprsPerSimdLane);
    CheckDivides("sgprGranule", config.sgprGranule, "sgprsPerSimd", config.sgprsPerSimd);
    CheckAtMost("maxSgprsPerWave", config.maxSgprsPerWave, "sgprsPerSimd", config.sgprsPerSimd);
    CheckDivides("ldsGranuleBytes", config.ldsGranuleBytes, "ldsBytesPerCu", config.ldsBytesPerCu);
    CheckAtMost("maxLdsBytesPerGroup", config.maxLdsBytesPerGroup, "ldsBytesPerCu", config.ldsBytesPerCu);
    CheckAtMost("shaderEngines", config.shaderEngines, "computeUnits", config.computeUnits);
    // A group runs on one CU (hw-facts §6.2), so its waves must fit in the CU's wave slots.
    const int wavesPerLargestGroup = (config.maxThreadsPerGroup + kWaveLanes - 1) / kWaveLanes;
    if (wavesPerLargestGroup > config.simdsPerCu * config.waveSlotsPerSimd) {
      Fail("key 'maxThreadsPerGroup' (" + std::to_string(config.maxThreadsPerGroup) + ") needs " +
           std::to_string(wavesPerLargestGroup) + " waves, more than simdsPerCu * waveSlotsPerSimd (" +
           std::to_string(config.simdsPerCu * config.waveSlotsPerSimd) + ")");
    }
    // Above the slot count the latency-hiding efficiency of the timing estimate could never
    // reach 1.
    CheckAtMost("wavesPerSimdToHideLatency", config.wavesPerSimdToHideLatency, "waveSlotsPerSimd",
                static_cast<double>(config.waveSlotsPerSimd));
  }

  std::string source_;
};

}  // namespace

GpuConfig ParseGpuConfig(std::string_view text, const std::string& source) {
  return GpuFileParser(source).Parse(text);
}

GpuConfig LoadGpuConfig(const std::filesystem::path& path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) {
    throw GpuConfigError(path.string() + ": is a directory, not a GPU file");
  }
  std::ifstream file(path, std::ios::binary);
  if (!file) throw GpuConfigError(path.string() + ": cannot be opened");
  std::ostringstream text;
  text << file.rdbuf();
  if (file.bad()) throw GpuConfigError(path.string() + ": cannot be read");
  return ParseGpuConfig(text.str(), path.string());
}

GpuConfig GpuConfigByName(std::string_view nameOrPath) {
  for (const BuiltinGpu& gpu : kBuiltinGpus) {
    if (gpu.name == nameOrPath) {
      GpuConfig config = ParseGpuConfig(gpu.text, "built-in GPU '" + std::string(gpu.name) + "'");
      config.source = "built-in";
      return config;
    }
  }
  const std::filesystem::path path(nameOrPath);
  std::error_code error;
  const bool looksLikePath = nameOrPath.find('/') != std::string_view::npos || nameOrPath.ends_with(".json") ||
                             nameOrPath.ends_with(".jsonc");
  if (looksLikePath || std::filesystem::exists(path, error)) return LoadGpuConfig(path);
  throw GpuConfigError("unknown GPU '" + std::string(nameOrPath) + "': the built-in GPUs are " + BuiltinList() +
                       "; anything else must be the path of a GPU file");
}

std::vector<std::string> BuiltinGpuNames() {
  std::vector<std::string> names;
  for (const BuiltinGpu& gpu : kBuiltinGpus) names.emplace_back(gpu.name);
  std::ranges::sort(names);
  return names;
}

}  // namespace sim
