// JPEG decompression bombs: stb_image decodes a JPEG whose entropy-coded data ends early as if
// zeros followed, so a few hundred bytes declaring 8192 x 8192 once cost seconds and over a GiB.
// A JPEG may declare at most kMaxJpegTexelsPerByte texels per byte of file; real ones, down to a
// single flat colour, stay far below it.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <stb_image_write.h>

#include "scenes/scene.h"
#include "scenes/texture.h"

namespace {

using Bytes = std::vector<std::uint8_t>;

void AppendWritten(void* context, void* data, int size) {
  const auto* bytes = static_cast<const std::uint8_t*>(data);
  static_cast<Bytes*>(context)->insert(static_cast<Bytes*>(context)->end(), bytes, bytes + size);
}

// One flat colour, the most compressible image there is.
Bytes FlatJpeg(int width, int height, int quality) {
  const Bytes rgb(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3, 90);
  Bytes jpeg;
  EXPECT_NE(stbi_write_jpg_to_func(&AppendWritten, &jpeg, width, height, 3, rgb.data(), quality), 0);
  return jpeg;
}

// `jpeg` with the size in its baseline frame header (SOF0: FF C0, length, precision, height,
// width; T.81 B.2.2) replaced.
Bytes WithDeclaredSize(Bytes jpeg, int width, int height) {
  for (std::size_t i = 0; i + 9 < jpeg.size(); ++i) {
    if (jpeg[i] == 0xFF && jpeg[i + 1] == 0xC0) {
      jpeg[i + 5] = static_cast<std::uint8_t>(height >> 8);
      jpeg[i + 6] = static_cast<std::uint8_t>(height & 0xFF);
      jpeg[i + 7] = static_cast<std::uint8_t>(width >> 8);
      jpeg[i + 8] = static_cast<std::uint8_t>(width & 0xFF);
      return jpeg;
    }
  }
  ADD_FAILURE() << "no SOF0 marker";
  return jpeg;
}

std::string DecodeErrorOf(const Bytes& jpeg) {
  try {
    scenes::DecodeImage(jpeg, "bomb.jpg", scenes::ColourEncoding::Srgb);
  } catch (const scenes::SceneError& error) {
    return error.what();
  }
  return "no error";
}

TEST(SceneImageLimits, ASmallJpegDeclaringAHugeSizeIsRefusedFromItsHeader) {
  const Bytes bomb = WithDeclaredSize(FlatJpeg(8, 8, 90), 8192, 8192);
  ASSERT_LT(bomb.size(), 1000u);
  const std::string error = DecodeErrorOf(bomb);
  EXPECT_EQ(error.rfind("bomb.jpg: JPEG image size 8192x8192 is 67108864 texels in " + std::to_string(bomb.size()) +
                            " bytes, more than the 512 texels per byte",
                        0),
            0u)
      << error;
  // The largest square within the bound decodes (as zeros past the real data), one more row and
  // column is refused.
  const auto side = static_cast<int>(std::sqrt(double(scenes::kMaxJpegTexelsPerByte * bomb.size())));
  ASSERT_LE(std::size_t(side) * std::size_t(side), scenes::kMaxJpegTexelsPerByte * bomb.size());
  EXPECT_EQ(scenes::DecodeImage(WithDeclaredSize(bomb, side, side), "ok.jpg", scenes::ColourEncoding::Srgb).width,
            side);
  EXPECT_NE(DecodeErrorOf(WithDeclaredSize(bomb, side + 1, side + 1)).find("texels per byte"), std::string::npos);
}

TEST(SceneImageLimits, FlatJpegsOfEverySizeAndQualityDecode) {
  for (const int quality : {10, 90, 100}) {  // stb_image_write subsamples chroma below 91
    for (const int side : {16, 256, 1024}) {
      const Bytes jpeg = FlatJpeg(side, side, quality);
      SCOPED_TRACE(std::to_string(side) + " px, quality " + std::to_string(quality) + ", " +
                   std::to_string(jpeg.size()) + " bytes");
      EXPECT_LE(std::size_t(side) * std::size_t(side), scenes::kMaxJpegTexelsPerByte * jpeg.size());
      EXPECT_EQ(scenes::DecodeImage(jpeg, "flat.jpg", scenes::ColourEncoding::Srgb).width, side);
    }
  }
}

}  // namespace
