// GPU configs: both built-ins load with the published figures, the embedded copies match the
// files in sim/gpus/, files from anywhere load, and every malformed file fails with one line that
// names the file and the key.

#include "sim/gpu_config.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace sim {
namespace {

const std::filesystem::path kSourceGpus = std::filesystem::path(AASIM_SOURCE_DIR) / "sim" / "gpus";

// A valid GPU file as JSON, typed here independently of sim/gpus/.
nlohmann::ordered_json ValidFile() {
  return {
      {"name", "test-gpu"},
      {"clockMhz", 800},
      {"shaderEngines", 2},
      {"computeUnits", 18},
      {"simdsPerCu", 4},
      {"waveSlotsPerSimd", 10},
      {"vgprsPerSimdLane", 256},
      {"vgprGranule", 4},
      {"maxVgprsPerWave", 256},
      {"sgprsPerSimd", 512},
      {"sgprGranule", 8},
      {"maxSgprsPerWave", 104},
      {"ldsBytesPerCu", 65536},
      {"ldsGranuleBytes", 512},
      {"maxLdsBytesPerGroup", 65536},
      {"maxGroupsPerCu", 16},
      {"maxThreadsPerGroup", 1024},
      {"dramGBytesPerSecond", 176.0},
      {"waveLaunchesPerClockPerSe", 1},
      {"rasterPixelsPerClockPerSe", 16},
      {"hiStencilTilesPerClockPerSe", 1},
      {"wavesPerSimdToHideLatency", 4},
      {"dispatchOverheadMicroseconds", 1.5},
  };
}

void ExpectAllPositive(const GpuConfig& gpu) {
  EXPECT_FALSE(gpu.name.empty());
  for (int value : {gpu.shaderEngines, gpu.computeUnits, gpu.simdsPerCu, gpu.waveSlotsPerSimd, gpu.vgprsPerSimdLane,
                    gpu.vgprGranule, gpu.maxVgprsPerWave, gpu.sgprsPerSimd, gpu.sgprGranule, gpu.maxSgprsPerWave,
                    gpu.ldsBytesPerCu, gpu.ldsGranuleBytes, gpu.maxLdsBytesPerGroup, gpu.maxGroupsPerCu,
                    gpu.maxThreadsPerGroup}) {
    EXPECT_GT(value, 0);
  }
  for (double value : {gpu.clockMhz, gpu.dramGBytesPerSecond, gpu.waveLaunchesPerClockPerSe,
                       gpu.rasterPixelsPerClockPerSe, gpu.hiStencilTilesPerClockPerSe, gpu.wavesPerSimdToHideLatency,
                       gpu.dispatchOverheadMicroseconds}) {
    EXPECT_GT(value, 0.0);
  }
}

// The per-CU facts shared by both GFX7 consoles.
void ExpectGfx7ComputeUnit(const GpuConfig& gpu) {
  EXPECT_EQ(gpu.simdsPerCu, 4);
  EXPECT_EQ(gpu.waveSlotsPerSimd, 10);
  EXPECT_EQ(gpu.vgprsPerSimdLane, 256);
  EXPECT_EQ(gpu.vgprGranule, 4);
  EXPECT_EQ(gpu.maxVgprsPerWave, 256);
  EXPECT_EQ(gpu.sgprsPerSimd, 512);
  EXPECT_EQ(gpu.sgprGranule, 8);
  EXPECT_EQ(gpu.maxSgprsPerWave, 104);
  EXPECT_EQ(gpu.ldsBytesPerCu, 65536);
  EXPECT_EQ(gpu.ldsGranuleBytes, 512);
  EXPECT_EQ(gpu.maxLdsBytesPerGroup, 65536);
  EXPECT_EQ(gpu.maxGroupsPerCu, 16);
  EXPECT_EQ(gpu.maxThreadsPerGroup, 1024);
}

// Expects `parse` to throw one line naming `source` and `key`.
void ExpectError(const std::function<void()>& parse, const std::string& source, const std::string& key) {
  try {
    parse();
    ADD_FAILURE() << "no error for key '" << key << "'";
  } catch (const GpuConfigError& error) {
    const std::string message = error.what();
    EXPECT_EQ(message.rfind(source + ": ", 0), 0u) << message;
    EXPECT_NE(message.find(key), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

// A directory per test, named after it because ctest runs tests in parallel; removed afterwards.
class TempDir {
 public:
  TempDir()
      : path_(std::filesystem::temp_directory_path() /
              (std::string("aasim_sim_gpu_config_") +
               ::testing::UnitTest::GetInstance()->current_test_info()->name())) {
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code error;
    std::filesystem::remove_all(path_, error);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  std::filesystem::path Write(const std::string& name, const std::string& text) const {
    const std::filesystem::path file = path_ / name;
    std::ofstream(file, std::ios::binary) << text;
    return file;
  }
  const std::filesystem::path& Path() const { return path_; }

 private:
  std::filesystem::path path_;
};

TEST(SimGpuConfig, BuiltinNames) {
  EXPECT_EQ(BuiltinGpuNames(), (std::vector<std::string>{"ps4-class", "xbox-one-class"}));
  const std::vector<std::string> names = BuiltinGpuNames();
  EXPECT_NE(std::ranges::find(names, std::string(kDefaultGpuName)), names.end());
}

TEST(SimGpuConfig, BothBuiltinsLoadWithEveryFieldPositive) {
  for (const std::string& name : BuiltinGpuNames()) {
    SCOPED_TRACE(name);
    const GpuConfig gpu = GpuConfigByName(name);
    EXPECT_EQ(gpu.name, name);
    EXPECT_EQ(gpu.source, "built-in");
    ExpectAllPositive(gpu);
    ExpectGfx7ComputeUnit(gpu);
  }
}

TEST(SimGpuConfig, Ps4ClassPublishedFigures) {
  const GpuConfig gpu = GpuConfigByName("ps4-class");
  EXPECT_EQ(gpu.computeUnits, 18);
  EXPECT_DOUBLE_EQ(gpu.clockMhz, 800.0);
  EXPECT_EQ(gpu.shaderEngines, 2);
  EXPECT_DOUBLE_EQ(gpu.dramGBytesPerSecond, 176.0);
}

TEST(SimGpuConfig, XboxOneClassPublishedFigures) {
  const GpuConfig gpu = GpuConfigByName("xbox-one-class");
  EXPECT_EQ(gpu.computeUnits, 12);
  EXPECT_DOUBLE_EQ(gpu.clockMhz, 853.0);
  EXPECT_EQ(gpu.shaderEngines, 2);
  EXPECT_DOUBLE_EQ(gpu.dramGBytesPerSecond, 68.3);
}

TEST(SimGpuConfig, EmbeddedBuiltinsMatchTheSourceFiles) {
  for (const std::string& name : BuiltinGpuNames()) {
    SCOPED_TRACE(name);
    const std::filesystem::path file = kSourceGpus / (name + ".jsonc");
    GpuConfig fromFile = LoadGpuConfig(file);
    EXPECT_EQ(fromFile.source, file.string());
    fromFile.source = "built-in";
    const GpuConfig builtin = GpuConfigByName(name);
    EXPECT_EQ(fromFile.name, builtin.name);
    EXPECT_EQ(fromFile.computeUnits, builtin.computeUnits);
    EXPECT_DOUBLE_EQ(fromFile.clockMhz, builtin.clockMhz);
    EXPECT_DOUBLE_EQ(fromFile.dramGBytesPerSecond, builtin.dramGBytesPerSecond);
    EXPECT_DOUBLE_EQ(fromFile.rasterPixelsPerClockPerSe, builtin.rasterPixelsPerClockPerSe);
    EXPECT_DOUBLE_EQ(fromFile.dispatchOverheadMicroseconds, builtin.dispatchOverheadMicroseconds);
  }
}

TEST(SimGpuConfig, FileWithCommentsLoadsFromATempDir) {
  const TempDir dir;
  const std::string text = "// a test GPU\n/* block comment */\n" + ValidFile().dump(2) + "\n// trailing\n";
  const std::filesystem::path file = dir.Write("test-gpu.jsonc", text);
  for (const GpuConfig& gpu : {LoadGpuConfig(file), GpuConfigByName(file.string())}) {
    EXPECT_EQ(gpu.name, "test-gpu");
    EXPECT_EQ(gpu.source, file.string());
    EXPECT_EQ(gpu.computeUnits, 18);
    EXPECT_DOUBLE_EQ(gpu.dispatchOverheadMicroseconds, 1.5);
    ExpectAllPositive(gpu);
  }
}

TEST(SimGpuConfig, EveryKeyIsRequired) {
  const nlohmann::ordered_json valid = ValidFile();
  for (const auto& item : valid.items()) {
    nlohmann::ordered_json file = valid;
    file.erase(item.key());
    ExpectError([&] { ParseGpuConfig(file.dump(), "test.jsonc"); }, "test.jsonc", "'" + item.key() + "'");
  }
}

TEST(SimGpuConfig, UnknownKeyIsNamed) {
  nlohmann::ordered_json file = ValidFile();
  file["vgprsPerSIMD"] = 256;
  ExpectError([&] { ParseGpuConfig(file.dump(), "test.jsonc"); }, "test.jsonc", "'vgprsPerSIMD'");
  file = ValidFile();
  file["source"] = "elsewhere";  // set by the loader, never by the file
  ExpectError([&] { ParseGpuConfig(file.dump(), "test.jsonc"); }, "test.jsonc", "'source'");
}

TEST(SimGpuConfig, WrongTypesAndNonPositiveValuesAreNamed) {
  struct Case {
    const char* key;
    nlohmann::ordered_json value;
  };
  const std::vector<Case> cases = {
      {"name", 4},
      {"name", ""},
      {"computeUnits", "18"},
      {"computeUnits", 18.5},
      {"computeUnits", 0},
      {"computeUnits", -18},
      {"computeUnits", 4294967296LL},
      {"vgprGranule", nullptr},
      {"clockMhz", "800"},
      {"clockMhz", 0},
      {"clockMhz", -800.0},
      {"dramGBytesPerSecond", nlohmann::ordered_json::array({176})},
      {"dispatchOverheadMicroseconds", 0.0},
      {"wavesPerSimdToHideLatency", false},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(std::string(c.key) + " = " + c.value.dump());
    nlohmann::ordered_json file = ValidFile();
    file[c.key] = c.value;
    ExpectError([&] { ParseGpuConfig(file.dump(), "test.jsonc"); }, "test.jsonc", std::string("'") + c.key + "'");
  }
}

TEST(SimGpuConfig, InconsistentValuesAreNamed) {
  struct Case {
    const char* key;
    int value;
  };
  const Case cases[] = {
      {"vgprGranule", 3},            // does not divide 256
      {"maxVgprsPerWave", 512},      // more than the file holds
      {"sgprGranule", 7},            // does not divide 512
      {"maxSgprsPerWave", 600},      // more than the file holds
      {"ldsGranuleBytes", 500},      // does not divide 65536
      {"maxLdsBytesPerGroup", 70000},  // more than the CU holds
      {"shaderEngines", 19},         // more engines than CUs
      {"maxThreadsPerGroup", 4096},  // 64 waves > 40 slots per CU
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.key);
    nlohmann::ordered_json file = ValidFile();
    file[c.key] = c.value;
    ExpectError([&] { ParseGpuConfig(file.dump(), "test.jsonc"); }, "test.jsonc", std::string("'") + c.key + "'");
  }
  nlohmann::ordered_json file = ValidFile();
  file["wavesPerSimdToHideLatency"] = 10.5;  // above the 10 slots: latency could never be hidden
  ExpectError([&] { ParseGpuConfig(file.dump(), "test.jsonc"); }, "test.jsonc", "'wavesPerSimdToHideLatency'");
}

TEST(SimGpuConfig, MalformedFilesAreOneLineErrorsNamingTheFile) {
  const TempDir dir;
  const std::filesystem::path broken = dir.Write("broken.jsonc", "{\n  \"name\": \"x\",\n  \"clockMhz\": \n}\n");
  ExpectError([&] { LoadGpuConfig(broken); }, broken.string(), "JSON");
  const std::filesystem::path array = dir.Write("array.jsonc", "[1, 2]");
  ExpectError([&] { LoadGpuConfig(array); }, array.string(), "object");
  nlohmann::ordered_json file = ValidFile();
  file["ldsGranuleBytes"] = 500;
  const std::filesystem::path inconsistent = dir.Write("inconsistent.jsonc", "// comment\n" + file.dump(2));
  ExpectError([&] { GpuConfigByName(inconsistent.string()); }, inconsistent.string(), "'ldsGranuleBytes'");
}

TEST(SimGpuConfig, UnreadableFilesAreNamed) {
  const TempDir dir;
  const std::filesystem::path missing = dir.Path() / "missing.jsonc";
  ExpectError([&] { LoadGpuConfig(missing); }, missing.string(), "opened");
  ExpectError([&] { GpuConfigByName(missing.string()); }, missing.string(), "opened");
  ExpectError([&] { LoadGpuConfig(dir.Path()); }, dir.Path().string(), "directory");
}

// Values that parse but describe no GPU are refused where they are read, naming file and key;
// maxThreadsPerGroup 2147483647 used to overflow the consistency check (UBSan) and be accepted.
TEST(SimGpuConfig, ImplausibleValuesAreRefusedWithTheirRange) {
  struct Case {
    const char* key;
    nlohmann::json value;
  };
  const Case cases[] = {
      {"maxVgprsPerWave", 4},
      {"maxThreadsPerGroup", 2147483647},
      {"simdsPerCu", 2147483647},
      {"waveSlotsPerSimd", -10},
      {"computeUnits", 0},
      {"clockMhz", 1e300},
      {"dispatchOverheadMicroseconds", -1.0},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.key);
    nlohmann::ordered_json file = ValidFile();
    file[c.key] = c.value;
    ExpectError([&] { ParseGpuConfig(file.dump(), "test.jsonc"); }, "test.jsonc",
                std::string("'") + c.key + "' must be");
  }
  // 1e400 is beyond a double: the parser's out_of_range exception used to escape unnamed.
  std::string text = ValidFile().dump();
  const std::string clock = "\"clockMhz\":800";
  text.replace(text.find(clock), clock.size(), "\"clockMhz\":1e400");
  ExpectError([&] { ParseGpuConfig(text, "test.jsonc"); }, "test.jsonc", "number overflow parsing '1e400'");
}

// Nesting 70,000 deep crashed the error message's dump(); the depth limit stops it at parse time
// and no message quotes more than an excerpt of the input.
TEST(SimGpuConfig, DeepNestingAndHugeValuesGiveShortMessages) {
  const std::string deep = std::string(70000, '[') + std::string(70000, ']');
  ExpectError([&] { ParseGpuConfig(deep, "deep.jsonc"); }, "deep.jsonc", "nests deeper than 64 levels");
  const std::string deepValue = "{\"name\": " + deep + "}";
  ExpectError([&] { ParseGpuConfig(deepValue, "deep.jsonc"); }, "deep.jsonc", "nests deeper");
  nlohmann::ordered_json file = ValidFile();
  file["name"] = nlohmann::json::array({std::string(100000, 'x')});
  try {
    ParseGpuConfig(file.dump(), "huge.jsonc");
    ADD_FAILURE() << "no error";
  } catch (const GpuConfigError& error) {
    EXPECT_LT(std::string(error.what()).size(), 200u) << error.what();
  }
}

TEST(SimGpuConfig, FifosAndDevicesAreRefusedWithoutBlocking) {
  const TempDir dir;
  const std::filesystem::path fifo = dir.Path() / "gpu.jsonc";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  ExpectError([&] { LoadGpuConfig(fifo); }, fifo.string(), "not a regular file");
  ExpectError([&] { LoadGpuConfig("/dev/zero"); }, "/dev/zero", "not a regular file");
}

TEST(SimGpuConfig, UnknownNameListsTheBuiltins) {
  try {
    GpuConfigByName("ps5-class");
    ADD_FAILURE() << "no error";
  } catch (const GpuConfigError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("'ps5-class'"), std::string::npos) << message;
    for (const std::string& name : BuiltinGpuNames()) EXPECT_NE(message.find(name), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
  EXPECT_THROW(GpuConfigByName(""), GpuConfigError);
}

}  // namespace
}  // namespace sim
