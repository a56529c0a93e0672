// `aasim smaa-tables` end to end: the real binary writes the generated SMAA tables as raw bytes,
// PNG previews that decode back to the same texels, and a manifest; a missing --out is a usage
// error and an unwritable one a runtime error that leaves nothing behind.

#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <stb_image.h>

#include "cli/smaa_tables_command.h"
#include "cli_test_util.h"
#include "passes/smaa/area_tex.h"
#include "passes/smaa/search_tex.h"

namespace {

namespace fs = std::filesystem;
using Bytes = std::vector<std::uint8_t>;
using cli::testing::CommandResult;
using passes::smaa::kAreaTexHeight, passes::smaa::kAreaTexWidth, passes::smaa::kSearchTexHeight,
    passes::smaa::kSearchTexWidth;

Bytes ReadBytes(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(file), {});
}

// Decodes a PNG, requiring exactly `channels` channels in the file itself.
Bytes ReadTablePng(const fs::path& path, int width, int height, int channels) {
  int w = 0, h = 0, c = 0;
  stbi_uc* pixels = stbi_load(path.c_str(), &w, &h, &c, 0);
  EXPECT_NE(pixels, nullptr) << path;
  if (pixels == nullptr) return {};
  EXPECT_EQ(w, width);
  EXPECT_EQ(h, height);
  EXPECT_EQ(c, channels);
  Bytes bytes(pixels, pixels + static_cast<std::size_t>(w) * h * c);
  stbi_image_free(pixels);
  return bytes;
}

class CliSmaaTables : public cli::testing::ScratchDirTest {
 protected:
  CommandResult Run(const std::vector<std::string>& args) const {
    const fs::path out = scratch_ / "stdout.txt", err = scratch_ / "stderr.txt";
    const pid_t pid = cli::testing::SpawnAasim(args, out.string(), err.string());
    EXPECT_GT(pid, 0);
    int status = 0;
    if (pid > 0) ::waitpid(pid, &status, 0);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, cli::testing::ReadText(out), cli::testing::ReadText(err)};
  }
};

TEST_F(CliSmaaTables, WritesBothTablesAsRawBytesPngsAndAManifest) {
  const fs::path dir = scratch_ / "tables";
  const CommandResult run = Run({"smaa-tables", "--out", dir.string()});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(run.err, "");
  EXPECT_EQ(run.out.rfind("wrote SMAA AreaTex 160x560 RG8 and SearchTex 64x16 R8 to ", 0), 0u) << run.out;
  EXPECT_EQ(cli::testing::FilesIn(dir), (std::vector<std::string>{"smaa_area_tex.png", "smaa_area_tex.rg8",
                                                                   "smaa_search_tex.png", "smaa_search_tex.r8",
                                                                   "smaa_tables.json"}));

  const Bytes area = ReadBytes(dir / "smaa_area_tex.rg8"), search = ReadBytes(dir / "smaa_search_tex.r8");
  ASSERT_EQ(area.size(), 2u * kAreaTexWidth * kAreaTexHeight);
  ASSERT_EQ(search.size(), static_cast<std::size_t>(kSearchTexWidth) * kSearchTexHeight);
  const std::span<const std::uint8_t> areaTable = passes::smaa::AreaTexBytes();
  EXPECT_TRUE(std::equal(area.begin(), area.end(), areaTable.begin()));
  EXPECT_EQ(search, Bytes(passes::smaa::SearchTexBytes().begin(), passes::smaa::SearchTexBytes().end()));
  // Published values (tests/passes_smaa_tables_test.cpp): texel (120, 0) and SearchTex (0, 0), (3, 0).
  EXPECT_EQ(area[2 * 120], 0x04);
  EXPECT_EQ(area[2 * 120 + 1], 0x7f);
  EXPECT_EQ(search[0], 0xfe);
  EXPECT_EQ(search[3], 0x7f);

  const Bytes areaPng = ReadTablePng(dir / "smaa_area_tex.png", kAreaTexWidth, kAreaTexHeight, 3);
  ASSERT_EQ(areaPng.size(), 3 * area.size() / 2);
  for (std::size_t texel = 0; texel < area.size() / 2; ++texel) {
    ASSERT_EQ(areaPng[3 * texel], area[2 * texel]) << texel;
    ASSERT_EQ(areaPng[3 * texel + 1], area[2 * texel + 1]) << texel;
    ASSERT_EQ(areaPng[3 * texel + 2], 0) << texel;
  }
  EXPECT_EQ(ReadTablePng(dir / "smaa_search_tex.png", kSearchTexWidth, kSearchTexHeight, 1), search);

  const nlohmann::json manifest = nlohmann::json::parse(cli::testing::ReadText(dir / "smaa_tables.json"));
  EXPECT_EQ(manifest["schema"], cli::kSmaaTablesSchema);
  EXPECT_EQ(manifest["version"], cli::kSmaaTablesVersion);
  EXPECT_EQ(manifest["tables"]["area"]["bytes"], area.size());
  EXPECT_EQ(manifest["tables"]["area"]["fnv1a64"], "247a58bbba65292d");
  EXPECT_EQ(manifest["tables"]["search"]["format"], "R8");
  EXPECT_EQ(manifest["tables"]["search"]["fnv1a64"], "21c1fcf0aa631065");
}

TEST_F(CliSmaaTables, MissingOutIsAUsageError) {
  const CommandResult run = Run({"smaa-tables"});
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_EQ(run.err.rfind("aasim smaa-tables: ", 0), 0u) << run.err;
  EXPECT_NE(run.err.find("--out"), std::string::npos) << run.err;
}

TEST_F(CliSmaaTables, UnwritableOutFailsAndLeavesNothing) {
  cli::testing::WriteFile(scratch_ / "file", "not a directory");
  const CommandResult run = Run({"smaa-tables", "--out", (scratch_ / "file" / "tables").string()});
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_EQ(run.err.rfind("aasim: --out ", 0), 0u) << run.err;
  EXPECT_EQ(cli::testing::FilesIn(scratch_), (std::vector<std::string>{"file", "stderr.txt", "stdout.txt"}));
}

}  // namespace
