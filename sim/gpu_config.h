#pragma once
// The modelled GPU as data: machine size, register-file and LDS limits with their allocation
// granules, DRAM bandwidth and the rates the timing estimate assumes (style.md habit 17). Each
// GPU is a JSON-with-comments file that cites a source for every value (sim/gpus/*.jsonc); the
// built-in ones are compiled into the library, so a moved binary still has them.

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace sim {

// A GPU file or name that cannot be used. The message is one line, "SOURCE: problem", and names
// the offending key when there is one.
class GpuConfigError : public std::runtime_error {
 public:
  using runtime_error::runtime_error;
};

// Every field except `source` is a required key of a GPU file, under the same name. Register
// counts are per SIMD: a wave64 VGPR holds 64 lanes, so `vgprsPerSimdLane` is the register file
// depth one lane sees. The defaults are only for configs built in code; files set every key.
struct GpuConfig {
  std::string name;    // e.g. "ps4-class"
  std::string source;  // "built-in" or the file path it was read from
  double clockMhz = 0;
  int shaderEngines = 0;
  int computeUnits = 0;  // total, all shader engines
  int simdsPerCu = 4;
  int waveSlotsPerSimd = 10;
  int vgprsPerSimdLane = 256;
  int vgprGranule = 4;
  int maxVgprsPerWave = 256;
  int sgprsPerSimd = 512;
  int sgprGranule = 8;
  int maxSgprsPerWave = 104;
  int ldsBytesPerCu = 65536;
  int ldsGranuleBytes = 512;
  int maxLdsBytesPerGroup = 65536;
  int maxGroupsPerCu = 16;  // for groups larger than one wave (barrier limit)
  int maxThreadsPerGroup = 1024;
  double dramGBytesPerSecond = 0;
  // Assumptions of the timing model: hw-facts §6.1 says the launch and scan-converter rates are
  // not public, so these are knobs with documented defaults, not facts.
  double waveLaunchesPerClockPerSe = 1;
  double rasterPixelsPerClockPerSe = 16;
  double hiStencilTilesPerClockPerSe = 1;
  double wavesPerSimdToHideLatency = 4;
  double dispatchOverheadMicroseconds = 1;
};

// Every key of a GPU file but "name", with its legal range: the one list the parser checks keys
// and ranges against and the writers (cli/dispatch_output.cpp) echo a configuration from. The
// ranges are plausibility bounds, wide enough for every GCN and later part (the GFX7 values of
// sim/gpus/ sit well inside them) and narrow enough that the occupancy and timing arithmetic
// cannot overflow and a typo (VGPRs 4, a clock of 1e400) is caught where it is read, naming file
// and key.
struct GpuIntKey {
  const char* key;
  int GpuConfig::*member;
  int min;
  int max;
};
struct GpuDoubleKey {
  const char* key;
  double GpuConfig::*member;
  double min;
  double max;
};

inline constexpr GpuIntKey kGpuIntKeys[] = {
    {"shaderEngines", &GpuConfig::shaderEngines, 1, 16},
    {"computeUnits", &GpuConfig::computeUnits, 1, 512},
    {"simdsPerCu", &GpuConfig::simdsPerCu, 1, 8},
    {"waveSlotsPerSimd", &GpuConfig::waveSlotsPerSimd, 1, 32},
    {"vgprsPerSimdLane", &GpuConfig::vgprsPerSimdLane, 64, 2048},
    {"vgprGranule", &GpuConfig::vgprGranule, 1, 64},
    {"maxVgprsPerWave", &GpuConfig::maxVgprsPerWave, 64, 2048},
    {"sgprsPerSimd", &GpuConfig::sgprsPerSimd, 64, 8192},
    {"sgprGranule", &GpuConfig::sgprGranule, 1, 64},
    {"maxSgprsPerWave", &GpuConfig::maxSgprsPerWave, 16, 1024},
    {"ldsBytesPerCu", &GpuConfig::ldsBytesPerCu, 1024, 1 << 20},
    {"ldsGranuleBytes", &GpuConfig::ldsGranuleBytes, 4, 1 << 16},
    {"maxLdsBytesPerGroup", &GpuConfig::maxLdsBytesPerGroup, 1024, 1 << 20},
    {"maxGroupsPerCu", &GpuConfig::maxGroupsPerCu, 1, 64},
    {"maxThreadsPerGroup", &GpuConfig::maxThreadsPerGroup, 64, 4096},
};

inline constexpr GpuDoubleKey kGpuDoubleKeys[] = {
    {"clockMhz", &GpuConfig::clockMhz, 1.0, 1e4},
    {"dramGBytesPerSecond", &GpuConfig::dramGBytesPerSecond, 1.0, 1e5},
    {"waveLaunchesPerClockPerSe", &GpuConfig::waveLaunchesPerClockPerSe, 1e-3, 64.0},
    {"rasterPixelsPerClockPerSe", &GpuConfig::rasterPixelsPerClockPerSe, 1e-3, 256.0},
    {"hiStencilTilesPerClockPerSe", &GpuConfig::hiStencilTilesPerClockPerSe, 1e-3, 64.0},
    {"wavesPerSimdToHideLatency", &GpuConfig::wavesPerSimdToHideLatency, 1e-3, 64.0},
    {"dispatchOverheadMicroseconds", &GpuConfig::dispatchOverheadMicroseconds, 1e-3, 1e6},
};

// Parses a GPU file's text; `source` names it in errors and becomes GpuConfig::source. A missing
// or unknown key, a wrong type, a non-positive value or an inconsistent pair of values (a granule
// that does not divide its pool, a per-wave or per-group maximum above what the CU holds) throws.
GpuConfig ParseGpuConfig(std::string_view text, const std::string& source);
// Reads and parses a GPU file; an unreadable file throws an error naming it.
GpuConfig LoadGpuConfig(const std::filesystem::path& path);
// A built-in GPU by name, otherwise a path to a GPU file. A name that is neither lists the
// built-ins in its error.
GpuConfig GpuConfigByName(std::string_view nameOrPath);
// The built-in GPUs in alphabetical order: {"ps4-class", "xbox-one-class"}.
std::vector<std::string> BuiltinGpuNames();

inline constexpr std::string_view kDefaultGpuName = "ps4-class";

}  // namespace sim
