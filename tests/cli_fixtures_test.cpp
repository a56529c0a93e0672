// `aasim fixtures` end to end: the real binary writes a set that verifies, an outside reader
// decodes it from manifest.json alone, and any corruption (a flipped byte, a missing file, a
// wrong checksum or schema) makes --verify exit 1 with one line naming the fixture and file.

#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/fixture_manifest.h"
#include "cli/fixtures_command.h"
#include "cli/output_dir.h"
#include "fmask/fixtures.h"
#include "cli_test_util.h"

namespace {

namespace fs = std::filesystem;
using cli::testing::CommandResult;
using cli::testing::ReadText;
using FileBytes = std::vector<std::uint8_t>;

FileBytes ReadFileBytes(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  return FileBytes(std::istreambuf_iterator<char>(file), {});
}

void WriteFileBytes(const fs::path& path, const FileBytes& bytes) {
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
}

// `aasim fixtures --out` runs once per process: each test corrupts a copy of that set.
class CliFixtures : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    pristine_ = new fs::path(fs::temp_directory_path() /
                             ("aasim-cli-fixtures-" + std::to_string(::getpid()) + "-pristine"));
    fs::remove_all(*pristine_);
    fs::create_directories(*pristine_);
    written_ = new CommandResult(cli::testing::RunAasim({"fixtures", "--out", (*pristine_ / "set").string()}, *pristine_));
  }
  static void TearDownTestSuite() {
    fs::remove_all(*pristine_);
    delete pristine_;
    delete written_;
  }

  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("aasim-cli-fixtures-" + std::to_string(::getpid()) + "-" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  CommandResult Run(const std::vector<std::string>& args) const {
    return cli::testing::RunAasim(args, dir_);
  }

  // This test's own copy of the set `aasim fixtures` wrote.
  fs::path WriteSet() const {
    EXPECT_EQ(written_->exitCode, 0) << written_->err;
    EXPECT_NE(written_->out.find("wrote " + std::to_string(fmask::CanonicalFixtureSet().size()) +
                                 " fixtures"),
              std::string::npos)
        << written_->out;
    const fs::path set = dir_ / "set";
    fs::copy(*pristine_ / "set", set, fs::copy_options::recursive);
    return set;
  }

  // --verify must fail with exit 1 and one stderr line containing every `needle`.
  void ExpectVerifyFails(const fs::path& set, const std::vector<std::string>& needles) const {
    const CommandResult result = Run({"fixtures", "--verify", set.string()});
    EXPECT_EQ(result.exitCode, 1) << result.out;
    EXPECT_EQ(result.err.rfind("aasim: ", 0), 0u) << result.err;
    EXPECT_EQ(result.err.find('\n'), result.err.size() - 1) << result.err;
    for (const std::string& needle : needles) {
      EXPECT_NE(result.err.find(needle), std::string::npos)
          << "no '" << needle << "' in " << result.err;
    }
  }

  fs::path dir_;
  static fs::path* pristine_;
  static CommandResult* written_;
};
fs::path* CliFixtures::pristine_ = nullptr;
CommandResult* CliFixtures::written_ = nullptr;

TEST_F(CliFixtures, WrittenSetVerifies) {
  const fs::path set = WriteSet();
  const CommandResult result = Run({"fixtures", "--verify", set.string()});
  EXPECT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.out,
            "verified " + std::to_string(fmask::CanonicalFixtureSet().size()) + " fixtures\n");
  EXPECT_TRUE(result.err.empty()) << result.err;
  for (const auto& entry : fs::recursive_directory_iterator(set)) {
    EXPECT_EQ(entry.path().filename().string().find(".aasim-tmp-"), std::string::npos)
        << entry.path();
  }
}

std::uint64_t Fnv1a64(const FileBytes& bytes) {
  std::uint64_t hash = 0xcbf29ce484222325ull;
  for (std::uint8_t byte : bytes) hash = (hash ^ byte) * 0x100000001b3ull;
  return hash;
}

// A reader with nothing but docs/fixtures.md: manifest.json, the checksums, the bit layout.
TEST_F(CliFixtures, ManifestAloneDecodesEveryFixture) {
  const fs::path set = WriteSet();
  const nlohmann::json manifest = nlohmann::json::parse(ReadText(set / "manifest.json"));
  ASSERT_EQ(manifest["schema"], "aasim.fmask.fixtures");
  ASSERT_EQ(manifest["version"], 1);
  for (const nlohmann::json& fixture : manifest["fixtures"]) {
    const std::string name = fixture["name"];
    SCOPED_TRACE(name);
    for (const nlohmann::json& file : fixture["files"]) {
      const FileBytes bytes = ReadFileBytes(set / name / file["name"].get<std::string>());
      char hex[17];
      std::snprintf(hex, sizeof(hex), "%016llx", static_cast<unsigned long long>(Fnv1a64(bytes)));
      EXPECT_EQ(bytes.size(), file["bytes"].get<std::size_t>());
      EXPECT_EQ(hex, file["fnv1a64"].get<std::string>());
    }
    const int samples = fixture["samples"], fragments = fixture["fragments"];
    const int bits = fixture["fmask"]["bits_per_sample"],
              elementBytes = fixture["fmask"]["element_bytes"];
    const nlohmann::json unknownCode = fixture["fmask"]["unknown_code"];
    const FileBytes fmask = ReadFileBytes(set / name / "fmask.bin"),
                colours = ReadFileBytes(set / name / "colours.bin");
    const FileBytes decoded = ReadFileBytes(set / name / "decoded.bin");
    const int pixels = fixture["width"].get<int>() * fixture["height"].get<int>();
    for (int pixel = 0; pixel < pixels; ++pixel) {
      std::uint64_t element = 0;
      for (int i = 0; i < elementBytes; ++i)
        element |= std::uint64_t{fmask[pixel * elementBytes + i]} << (8 * i);
      for (int s = 0; s < samples; ++s) {
        const int code = static_cast<int>((element >> (s * bits)) & ((1u << bits) - 1));
        const int slot = !unknownCode.is_null() && code == unknownCode.get<int>() ? 0 : code;
        ASSERT_LT(slot, fragments);
        for (int c = 0; c < 4; ++c) {
          ASSERT_EQ(decoded[4 * (pixel * samples + s) + c],
                    colours[4 * (pixel * fragments + slot) + c])
              << "pixel " << pixel << " sample " << s;
        }
      }
    }
  }
}

TEST_F(CliFixtures, FlippedByteFailsNamingFixtureAndFile) {
  const fs::path set = WriteSet();
  const fs::path file = set / "8S4Z2F-standard-t-junction" / "fmask.bin";
  FileBytes bytes = ReadFileBytes(file);
  bytes[17] ^= 0x01;
  WriteFileBytes(file, bytes);
  ExpectVerifyFails(set, {"fixture 8S4Z2F-standard-t-junction", "fmask.bin", "byte 17"});
}

TEST_F(CliFixtures, FlippedPreviewByteFails) {
  const fs::path set = WriteSet();
  const fs::path file = set / "16S8Z8F-eqaa-five-way-vertex" / "preview.png";
  FileBytes bytes = ReadFileBytes(file);
  bytes[bytes.size() / 2] ^= 0x40;
  WriteFileBytes(file, bytes);
  ExpectVerifyFails(set, {"fixture 16S8Z8F-eqaa-five-way-vertex", "preview.png"});
}

TEST_F(CliFixtures, MissingFileFailsNamingIt) {
  const fs::path set = WriteSet();
  fs::remove(set / "4S2Z2F-eqaa-corner" / "depth.bin");
  ExpectVerifyFails(set, {"fixture 4S2Z2F-eqaa-corner", "depth.bin", "missing"});
}

TEST_F(CliFixtures, ManifestChecksumMismatchFails) {
  const fs::path set = WriteSet();
  nlohmann::ordered_json manifest = nlohmann::ordered_json::parse(ReadText(set / "manifest.json"));
  manifest["fixtures"][3]["files"][1]["fnv1a64"] = "0000000000000000";
  const std::string name = manifest["fixtures"][3]["name"];
  std::ofstream(set / "manifest.json") << manifest.dump();
  ExpectVerifyFails(set, {"fixture " + name, "colours.bin", "checksum"});
}

TEST_F(CliFixtures, ManifestFieldEditFails) {
  const fs::path set = WriteSet();
  nlohmann::ordered_json manifest = nlohmann::ordered_json::parse(ReadText(set / "manifest.json"));
  manifest["fixtures"][5]["fmask"]["bits_per_sample"] = 3;
  const std::string name = manifest["fixtures"][5]["name"];
  std::ofstream(set / "manifest.json") << manifest.dump();
  ExpectVerifyFails(set, {"fixture " + name, "'fmask'"});
}

TEST_F(CliFixtures, UnknownSchemaVersionAndMissingManifestFail) {
  const fs::path set = WriteSet();
  nlohmann::ordered_json manifest = nlohmann::ordered_json::parse(ReadText(set / "manifest.json"));
  manifest["version"] = 2;
  std::ofstream(set / "manifest.json") << manifest.dump();
  ExpectVerifyFails(set, {"manifest.json", "version 2 is not supported"});
  std::ofstream(set / "manifest.json") << "{\"schema\": \"other\"}";
  ExpectVerifyFails(set, {"manifest.json", "schema"});
  std::ofstream(set / "manifest.json") << "{not json";
  ExpectVerifyFails(set, {"manifest.json", "not valid JSON"});
  fs::remove(set / "manifest.json");
  ExpectVerifyFails(set, {"manifest.json", "cannot be opened"});
}

// A manifest naming the canonical set, without the per-fixture fields set-level checks ignore.
nlohmann::ordered_json NamesOnlyManifest() {
  nlohmann::ordered_json fixtures = nlohmann::ordered_json::array();
  for (const fmask::FixtureSpec& spec : fmask::CanonicalFixtureSet()) {
    fixtures.push_back({{"name", fmask::FixtureName(spec)}});
  }
  return {{"schema", cli::kFixturesSchema}, {"version", cli::kFixturesVersion}, {"fixtures", fixtures}};
}

std::string ManifestError(const nlohmann::ordered_json& manifest) {
  try {
    cli::ParseFixtureManifest(manifest.dump(), "m.json");
  } catch (const std::runtime_error& error) {
    return error.what();
  }
  return "no error";
}

// --verify used to accept a manifest with fixtures removed, an empty list ("verified 0") and
// duplicated entries: the set must be the canonical one.
TEST(CliFixtureManifest, ListsExactlyTheCanonicalSet) {
  EXPECT_EQ(ManifestError(NamesOnlyManifest()), "no error");
  const std::size_t total = fmask::CanonicalFixtureSet().size();
  nlohmann::ordered_json removed = NamesOnlyManifest();
  const std::string gone = removed["fixtures"][7]["name"];
  removed["fixtures"].erase(7);
  EXPECT_EQ(ManifestError(removed), "m.json: 1 of the " + std::to_string(total) +
                                        " canonical fixtures are missing (" + gone + ")");
  nlohmann::ordered_json empty = NamesOnlyManifest();
  empty["fixtures"] = nlohmann::ordered_json::array();
  EXPECT_NE(ManifestError(empty).find(std::to_string(total) + " of the " + std::to_string(total)),
            std::string::npos);
  nlohmann::ordered_json twice = NamesOnlyManifest();
  twice["fixtures"].push_back(twice["fixtures"][0]);
  EXPECT_EQ(ManifestError(twice),
            "m.json: fixture \"" + twice["fixtures"][0]["name"].get<std::string>() + "\" is listed twice");
  nlohmann::ordered_json unknown = NamesOnlyManifest();
  unknown["fixtures"][0]["name"] = std::string(10000, 'x');
  const std::string message = ManifestError(unknown);
  EXPECT_NE(message.find("is not in the canonical set"), std::string::npos) << message;
  EXPECT_LT(message.size(), 200u);
}

// Nesting ~70,000 deep crashed the version message's dump().
TEST(CliFixtureManifest, DeepNestingIsRefusedWithAShortMessage) {
  const std::string deep = std::string(70000, '[') + std::string(70000, ']');
  nlohmann::ordered_json manifest = NamesOnlyManifest();
  const std::string text = "{\"schema\": \"aasim.fmask.fixtures\", \"version\": " + deep + "}";
  try {
    cli::ParseFixtureManifest(text, "m.json");
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& error) {
    EXPECT_EQ(std::string(error.what()), "m.json: nests deeper than 64 levels");
  }
}

// End to end: the verifier names what is missing, and a checksum under an unknown name is an
// error instead of an unchecked file.
TEST_F(CliFixtures, VerifyNamesMissingFixturesAndUnknownChecksums) {
  const fs::path set = WriteSet();
  const std::string original = ReadText(set / "manifest.json");
  nlohmann::ordered_json manifest = nlohmann::ordered_json::parse(original);
  const std::string gone = manifest["fixtures"][2]["name"];
  manifest["fixtures"].erase(2);
  std::ofstream(set / "manifest.json") << manifest.dump();
  ExpectVerifyFails(set, {"manifest.json", "canonical fixtures are missing (" + gone + ")"});

  manifest = nlohmann::ordered_json::parse(original);
  nlohmann::ordered_json& record = manifest["fixtures"][4]["files"][0];
  record["sha256"] = record["fnv1a64"];
  record.erase("fnv1a64");
  const std::string name = manifest["fixtures"][4]["name"];
  std::ofstream(set / "manifest.json") << manifest.dump();
  ExpectVerifyFails(set, {"fixture " + name, "unknown key \"sha256\""});
}

TEST_F(CliFixtures, UsageErrorsExitTwo) {
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"fixtures"},
        std::vector<std::string>{"fixtures", "--out", "a", "--verify", "b"}}) {
    const CommandResult result = Run(args);
    EXPECT_EQ(result.exitCode, 2);
    EXPECT_EQ(result.err.rfind("aasim fixtures: ", 0), 0u) << result.err;
  }
}

TEST_F(CliFixtures, UnwritableOutFailsWithoutOutput) {
  std::ofstream(dir_ / "file") << "x";
  const CommandResult result = Run({"fixtures", "--out", (dir_ / "file" / "set").string()});
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_EQ(result.err.rfind("aasim: --out ", 0), 0u) << result.err;
}

// OutputDir stages files in subfolders too; abandoned sets leave no folder behind, not even
// the output directory it created.
TEST_F(CliFixtures, OutputDirSubfoldersAreAllOrNothing) {
  {
    cli::OutputDir out(dir_ / "abandoned");
    std::ofstream(out.Stage("a/b/c.bin")) << "x";
  }
  EXPECT_FALSE(fs::exists(dir_ / "abandoned"));
  cli::OutputDir out(dir_ / "kept");
  std::ofstream(out.Stage("a/b/c.bin")) << "x";
  out.Commit();
  EXPECT_EQ(ReadText(dir_ / "kept" / "a" / "b" / "c.bin"), "x");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_ / "kept" / "a" / "b"), {}), 1);
}

}  // namespace
