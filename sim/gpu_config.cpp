#include "sim/gpu_config.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <sstream>
#include <system_error>

#include <nlohmann/json.hpp>

#include "raster/json_input.h"
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

// One table (sim/gpu_config.h) drives the required-key, unknown-key, type and range checks so they
// cannot drift apart.
constexpr const char* kNameKey = "name";

bool IsKnownKey(const std::string& key) {
  if (key == kNameKey) return true;
  const auto sameKey = [&](const auto& entry) { return key == entry.key; };
  return std::ranges::any_of(kGpuIntKeys, sameKey) || std::ranges::any_of(kGpuDoubleKeys, sameKey);
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
    for (const GpuIntKey& entry : kGpuIntKeys) config.*entry.member = IntInRange(root, entry);
    for (const GpuDoubleKey& entry : kGpuDoubleKeys) config.*entry.member = DoubleInRange(root, entry);
    CheckConsistency(config);
    return config;
  }

 private:
  [[noreturn]] void Fail(const std::string& problem) const { throw GpuConfigError(source_ + ": " + problem); }

  nlohmann::json ParseText(std::string_view text) const {
    nlohmann::json root;
    try {
      root = raster::ParseJsonText(text, /*allowComments=*/true);
    } catch (const raster::JsonTextError& error) {
      Fail(error.what());
    }
    if (!root.is_object()) Fail("must hold one JSON object, found " + raster::JsonExcerpt(root));
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
      Fail(std::string("key '") + kNameKey + "' must be a non-empty string, found " + raster::JsonExcerpt(value));
    }
    return value.get<std::string>();
  }

  [[noreturn]] void FailRange(const char* key, const nlohmann::json& value, const std::string& range) const {
    Fail(std::string("key '") + key + "' must be " + range + ", found " + raster::JsonExcerpt(value));
  }

  int IntInRange(const nlohmann::json& root, const GpuIntKey& entry) const {
    const nlohmann::json& value = Required(root, entry.key);
    const std::string range = "an integer in [" + std::to_string(entry.min) + ", " + std::to_string(entry.max) + "]";
    if (!value.is_number_integer()) FailRange(entry.key, value, range);
    // Parsed text holds non-negative integers as unsigned, which get<std::int64_t> would wrap.
    const bool inRange = value.is_number_unsigned()
                             ? value.get<std::uint64_t>() >= static_cast<std::uint64_t>(std::max(entry.min, 0)) &&
                                   value.get<std::uint64_t>() <= static_cast<std::uint64_t>(entry.max)
                             : value.get<std::int64_t>() >= entry.min && value.get<std::int64_t>() <= entry.max;
    if (!inRange) FailRange(entry.key, value, range);
    return static_cast<int>(value.get<std::int64_t>());
  }

  double DoubleInRange(const nlohmann::json& root, const GpuDoubleKey& entry) const {
    const nlohmann::json& value = Required(root, entry.key);
    std::ostringstream range;
    range << "a number in [" << entry.min << ", " << entry.max << "]";
    if (!value.is_number()) FailRange(entry.key, value, range.str());
    const auto number = value.get<double>();
    if (!(number >= entry.min && number <= entry.max)) FailRange(entry.key, value, range.str());
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
    // The key ranges bound both sides far below int's limits, so these cannot overflow.
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
  std::string text;
  try {
    text = raster::ReadJsonFile(path);
  } catch (const raster::JsonTextError& error) {
    throw GpuConfigError(path.string() + ": " + error.what());
  }
  return ParseGpuConfig(text, path.string());
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
