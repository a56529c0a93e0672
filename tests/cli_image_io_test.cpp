// The command line's writers: PNG and EXR files read back by the libraries themselves equal what
// was written, and output sets are all-or-nothing (cli/output_dir.h).

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <stb_image.h>

#include "cli/image_io.h"
#include "cli/output_dir.h"
#include "cli/output_error.h"

namespace {

namespace fs = std::filesystem;

class CliImageIoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("aasim_cli_io_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::vector<fs::path> Entries(const fs::path& dir) const {
    std::vector<fs::path> entries;
    for (const auto& entry : fs::directory_iterator(dir))
      entries.push_back(entry.path().filename());
    return entries;
  }

  fs::path dir_;
};

std::vector<std::uint8_t> PatternBytes(std::size_t count) {
  std::vector<std::uint8_t> bytes(count);
  for (std::size_t i = 0; i < count; ++i) bytes[i] = static_cast<std::uint8_t>(i * 37 + 11);
  return bytes;
}

void ExpectPngRoundTrip(const fs::path& path, int width, int height, int channels) {
  const std::vector<std::uint8_t> written = PatternBytes(std::size_t(width) * height * channels);
  cli::WritePng(path, width, height, channels, written);
  int readWidth = 0, readHeight = 0, readChannels = 0;
  stbi_uc* read = stbi_load(path.c_str(), &readWidth, &readHeight, &readChannels, 0);
  ASSERT_NE(read, nullptr) << stbi_failure_reason();
  EXPECT_EQ(readWidth, width);
  EXPECT_EQ(readHeight, height);
  EXPECT_EQ(readChannels, channels);
  EXPECT_EQ(std::vector<std::uint8_t>(read, read + written.size()), written);
  stbi_image_free(read);
}

TEST_F(CliImageIoTest, GreyPngReadsBackEqual) { ExpectPngRoundTrip(dir_ / "grey.png", 7, 5, 1); }

TEST_F(CliImageIoTest, RgbPngReadsBackEqual) { ExpectPngRoundTrip(dir_ / "rgb.png", 5, 9, 3); }

TEST_F(CliImageIoTest, PngWithWrongBufferSizeIsRefused) {
  EXPECT_THROW(cli::WritePng(dir_ / "bad.png", 4, 4, 1, PatternBytes(15)), std::invalid_argument);
}

TEST_F(CliImageIoTest, ExrChannelsReadBackEqualWithZipCompression) {
  constexpr int kWidth = 6, kHeight = 4;
  std::vector<float> depth(kWidth * kHeight), coverage(kWidth * kHeight);
  for (int i = 0; i < kWidth * kHeight; ++i) {
    depth[i] = 1.0f / static_cast<float>(i + 3);
    coverage[i] = static_cast<float>(i % 5) * 0.25f;
  }
  const fs::path path = dir_ / "depth.exr";
  const std::vector<cli::ExrChannel> channels{{"depth.s0", depth}, {"coverage", coverage}};
  cli::WriteExr(path, kWidth, kHeight, channels);

  Imf::InputFile file(path.c_str());
  EXPECT_EQ(file.header().compression(), Imf::ZIP_COMPRESSION);
  const Imath::Box2i window = file.header().dataWindow();
  ASSERT_EQ(window.max.x - window.min.x + 1, kWidth);
  ASSERT_EQ(window.max.y - window.min.y + 1, kHeight);
  int channelCount = 0;
  for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it) {
    EXPECT_EQ(it.channel().type, Imf::FLOAT) << it.name();
    ++channelCount;
  }
  EXPECT_EQ(channelCount, 2);

  std::vector<float> readDepth(depth.size()), readCoverage(coverage.size());
  Imf::FrameBuffer frameBuffer;
  frameBuffer.insert("depth.s0", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(readDepth.data()),
                                            sizeof(float), sizeof(float) * kWidth));
  frameBuffer.insert("coverage",
                     Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(readCoverage.data()),
                                sizeof(float), sizeof(float) * kWidth));
  file.setFrameBuffer(frameBuffer);
  file.readPixels(window.min.y, window.max.y);
  EXPECT_EQ(readDepth, depth);
  EXPECT_EQ(readCoverage, coverage);
}

TEST_F(CliImageIoTest, ExrIntoMissingDirectoryThrowsOutputErrorNamingThePath) {
  const std::vector<float> values(4, 0.5f);
  const std::vector<cli::ExrChannel> channels{{"Z", values}};
  const fs::path path = dir_ / "missing" / "depth.exr";
  try {
    cli::WriteExr(path, 2, 2, channels);
    FAIL() << "no error";
  } catch (const cli::OutputError& error) {
    EXPECT_NE(std::string(error.what()).find(path.string()), std::string::npos) << error.what();
  }
}

TEST(CliImageIo, SrgbEncodingMatchesTheTransferFunction) {
  EXPECT_EQ(cli::EncodeSrgb8(0.0f), 0);
  EXPECT_EQ(cli::EncodeSrgb8(1.0f), 255);
  EXPECT_EQ(cli::EncodeSrgb8(0.5f), 188);  // 1.055 * 0.5^(1/2.4) - 0.055 = 0.7354
  EXPECT_EQ(cli::EncodeSrgb8(0.002f), 7);  // linear segment: 12.92 * 0.002 * 255 = 6.6
  EXPECT_EQ(cli::EncodeSrgb8(-1.0f), 0);
  EXPECT_EQ(cli::EncodeSrgb8(2.0f), 255);
}

TEST_F(CliImageIoTest, CommitMovesStagedFilesIntoPlaceAndLeavesNoTemporaries) {
  cli::OutputDir out(dir_ / "set");
  cli::WritePng(out.Stage("a.png"), 2, 2, 1, PatternBytes(4));
  std::ofstream(out.Stage("b.json")) << "{}\n";
  const std::vector<fs::path> written = out.Commit();
  EXPECT_EQ(written, (std::vector<fs::path>{dir_ / "set" / "a.png", dir_ / "set" / "b.json"}));
  std::vector<fs::path> entries = Entries(dir_ / "set");
  std::sort(entries.begin(), entries.end());
  EXPECT_EQ(entries, (std::vector<fs::path>{"a.png", "b.json"}));
}

TEST_F(CliImageIoTest, FailureMidwayLeavesNoFiles) {
  const fs::path setDir = dir_ / "set";
  try {
    cli::OutputDir out(setDir);
    cli::WritePng(out.Stage("coverage.png"), 2, 2, 1, PatternBytes(4));
    const std::vector<float> values(4, 0.0f);
    const std::vector<cli::ExrChannel> channels{{"Z", values}};
    cli::WriteExr(out.Stage("depth.exr"), 2, 3, channels);  // wrong size: throws
    out.Commit();
    FAIL() << "no error";
  } catch (const std::invalid_argument&) {
  }
  // The directory was created by the failed set, so it goes too (issue 10: no partial output).
  EXPECT_FALSE(fs::exists(setDir));
}

TEST_F(CliImageIoTest, FailedCommitRemovesTheFilesAlreadyMoved) {
  const fs::path setDir = dir_ / "set";
  // A non-empty directory where the second file should go makes its rename fail.
  fs::create_directories(setDir / "b.json");
  std::ofstream(setDir / "b.json" / "keep") << "x";
  cli::OutputDir out(setDir);
  std::ofstream(out.Stage("a.json")) << "{}\n";
  std::ofstream(out.Stage("b.json")) << "{}\n";
  EXPECT_THROW(out.Commit(), cli::OutputError);
  EXPECT_EQ(Entries(setDir), std::vector<fs::path>{"b.json"});
}

TEST_F(CliImageIoTest, UncreatableDirectoryThrowsNamingThePathAndTheOsError) {
  std::ofstream(dir_ / "file") << "x";
  const fs::path target = dir_ / "file" / "out";
  try {
    cli::OutputDir out(target);
    FAIL() << "no error";
  } catch (const cli::OutputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(target.string()), std::string::npos) << message;
    EXPECT_NE(message.find("Not a directory"), std::string::npos) << message;
  }
}

}  // namespace
