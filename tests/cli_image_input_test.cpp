// The readers of `aasim post`'s images, in process: every 8-bit sRGB code decodes to the linear
// value an sRGB view reads and encodes back to itself, alpha is kept as code / 255 or is 1, and
// OpenEXR files are read from their data window whatever its origin and pixel type.

#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <Imath/half.h>

#include "cli/image_input.h"
#include "cli/image_io.h"
#include "sim/formats.h"

namespace {

namespace fs = std::filesystem;

class CliImageInputTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("aasim_cli_input_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path dir_;
};

const cli::ImageSizeCheck kAnySize = [](int, int) {};

TEST(CliImageInput, EverySrgbCodeDecodesToWhatEncodesBackToIt) {
  for (int k = 0; k < 256; ++k) {
    const auto code = static_cast<std::uint8_t>(k);
    EXPECT_EQ(cli::EncodeSrgb8(sim::Srgb8ToFloat(code)), code) << k;
  }
}

TEST_F(CliImageInputTest, APngHoldsEveryCodeAsAnSrgbViewReadsIt) {
  std::vector<std::uint8_t> rgba;
  for (int k = 0; k < 256; ++k) rgba.insert(rgba.end(), {std::uint8_t(k), std::uint8_t(255 - k), std::uint8_t(k / 2), std::uint8_t(k)});
  cli::WritePng(dir_ / "codes.png", 256, 1, 4, rgba);
  int checkedWidth = 0;
  const cli::InputImage image =
      cli::ReadInputImage(dir_ / "codes.png", [&](int width, int) { checkedWidth = width; });
  EXPECT_EQ(checkedWidth, 256);
  EXPECT_EQ(image.format, "png");
  EXPECT_TRUE(image.alpha);
  for (int k = 0; k < 256; ++k) {
    const glm::vec4 texel = image.colour.At(k, 0);
    EXPECT_EQ(texel.r, sim::Srgb8ToFloat(std::uint8_t(k))) << k;
    EXPECT_EQ(texel.g, sim::Srgb8ToFloat(std::uint8_t(255 - k))) << k;
    EXPECT_EQ(texel.a, sim::Unorm8ToFloat(std::uint8_t(k))) << k;
    EXPECT_EQ(cli::EncodeSrgb8(texel.r), k);
    EXPECT_EQ(cli::EncodeSrgb8(texel.b), k / 2);
  }
}

TEST_F(CliImageInputTest, GreyPngIsGreyWithOpaqueAlpha) {
  const std::vector<std::uint8_t> grey{0, 64, 128, 255};
  cli::WritePng(dir_ / "grey.png", 2, 2, 1, grey);
  const cli::InputImage image = cli::ReadInputImage(dir_ / "grey.png", kAnySize);
  EXPECT_FALSE(image.alpha);
  const glm::vec4 texel = image.colour.At(1, 0);
  EXPECT_EQ(texel, glm::vec4(glm::vec3(sim::Srgb8ToFloat(64)), 1.0f));
}

TEST_F(CliImageInputTest, TheSizeCheckRunsBeforeAnyTexelIsDecoded) {
  cli::WritePng(dir_ / "a.png", 3, 2, 3, std::vector<std::uint8_t>(18, 7));
  const auto refuse = [](int width, int height) {
    throw cli::InputImageError("refused " + std::to_string(width) + "x" + std::to_string(height));
  };
  EXPECT_THROW(
      {
        try {
          cli::ReadInputImage(dir_ / "a.png", refuse);
        } catch (const cli::InputImageError& error) {
          EXPECT_STREQ(error.what(), "refused 3x2");
          throw;
        }
      },
      cli::InputImageError);
}

// A half-float RGBA file whose data window starts at (10, -3), as OpenEXR allows.
fs::path WriteOffsetHalfExr(const fs::path& path, int width, int height, std::vector<half>& values) {
  const Imath::Box2i window({10, -3}, {10 + width - 1, -3 + height - 1});
  Imf::Header header(window, window);
  Imf::FrameBuffer frameBuffer;
  const char* names[] = {"R", "G", "B", "A"};
  values.resize(std::size_t(width) * std::size_t(height) * 4);
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = half(float(i % 97) * 0.125f);
  for (int c = 0; c < 4; ++c) {
    header.channels().insert(names[c], Imf::Channel(Imf::HALF));
    frameBuffer.insert(names[c],
                       Imf::Slice::Make(Imf::HALF, values.data() + c, window, 4 * sizeof(half), 4 * sizeof(half) * width));
  }
  Imf::OutputFile file(path.c_str(), header);
  file.setFrameBuffer(frameBuffer);
  file.writePixels(height);
  return path;
}

TEST_F(CliImageInputTest, ExrIsReadFromItsDataWindowInAnyPixelType) {
  std::vector<half> values;
  const cli::InputImage image = cli::ReadInputImage(WriteOffsetHalfExr(dir_ / "h.exr", 5, 4, values), kAnySize);
  EXPECT_EQ(image.format, "exr");
  EXPECT_TRUE(image.alpha);
  ASSERT_EQ(image.colour.Width(), 5);
  ASSERT_EQ(image.colour.Height(), 4);
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 5; ++x) {
      const std::size_t at = (std::size_t(y) * 5 + std::size_t(x)) * 4;
      const glm::vec4 expected{static_cast<float>(values[at]), static_cast<float>(values[at + 1]),
                               static_cast<float>(values[at + 2]), static_cast<float>(values[at + 3])};
      EXPECT_EQ(image.colour.At(x, y), expected) << x << "," << y;
    }
  }
}

TEST_F(CliImageInputTest, DepthPrefersZThenYThenR) {
  const std::vector<float> z(6, 0.75f), y(6, 0.5f), r(6, 0.25f);
  const cli::ExrChannel all[] = {{"R", r}, {"Y", y}, {"Z", z}};
  cli::WriteExr(dir_ / "d.exr", 3, 2, all);
  const cli::DepthImage depth = cli::ReadDepthExr(dir_ / "d.exr", 3, 2, "in.png");
  EXPECT_EQ(depth.channel, "Z");
  EXPECT_EQ(depth.depth.At(2, 1), 0.75f);
  const cli::ExrChannel justR[] = {{"R", r}};
  cli::WriteExr(dir_ / "r.exr", 3, 2, justR);
  EXPECT_EQ(cli::ReadDepthExr(dir_ / "r.exr", 3, 2, "in.png").channel, "R");
}

}  // namespace
