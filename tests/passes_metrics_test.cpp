// Image-quality metrics on synthetic pairs whose answers are known: identical images, constant
// offsets built in the encoded domain (closed-form PSNR and SSIM), a step edge moved by one pixel,
// flat colour patches; FLIP against a slow 2-D reference; argument checks and determinism.

#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/common.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "passes/metrics.h"
#include "raster_test_util.h"

namespace passes {
namespace {

struct MetricsImage {
  MetricsImage(int w, int h, glm::vec4 fill = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f))
      : width(w), height(h), pixels(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), fill) {}
  glm::vec4& At(int x, int y) { return pixels[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)]; }
  ImageView View() const { return ImageView{pixels, width, height}; }

  int width, height;
  std::vector<glm::vec4> pixels;
};

// Inverse of the sRGB encoding, so images can be built from the encoded values the metrics see.
float DecodeSrgb(double encoded) {
  return static_cast<float>(encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4));
}

glm::vec4 EncodedGrey(double encoded) {
  const float v = DecodeSrgb(encoded);
  return glm::vec4(v, v, v, 1.0f);
}

MetricsImage RandomMetricsImage(int w, int h, std::uint64_t seed) {
  raster::testing::Random rng(seed);
  MetricsImage image(w, h);
  for (glm::vec4& p : image.pixels) {
    p = glm::vec4(static_cast<float>(rng.Uniform(0, 1)), static_cast<float>(rng.Uniform(0, 1)),
                  static_cast<float>(rng.Uniform(0, 1)), 1.0f);
  }
  return image;
}

// A vertical step: dark left of column edgeX, light from it on.
MetricsImage Step(int w, int h, int edgeX) {
  MetricsImage image(w, h, glm::vec4(0.8f, 0.7f, 0.6f, 1.0f));
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < edgeX; ++x) image.At(x, y) = glm::vec4(0.05f, 0.1f, 0.15f, 1.0f);
  }
  return image;
}

std::vector<float> ColumnMask(int w, int h, int x0, int x1) {
  std::vector<float> mask(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), 0.0f);
  for (int y = 0; y < h; ++y) {
    for (int x = x0; x <= x1; ++x) mask[static_cast<std::size_t>(y * w + x)] = 1.0f;
  }
  return mask;
}

TEST(PassesMetrics, PixelsPerDegreeForTheDefaultViewingCondition) {
  // aa-facts §9.1: 0.7 m away from a 0.7 m wide 3840-pixel monitor.
  EXPECT_NEAR(PixelsPerDegree({}), 67.0206, 1e-4);
}

TEST(PassesMetrics, IdenticalImagesScorePerfectly) {
  const MetricsImage a = RandomMetricsImage(61, 37, 3);
  const std::vector<float> mask = ColumnMask(a.width, a.height, 10, 12);
  const QualityResult r = ScoreWithMaps(a.View(), a.View(), mask);
  EXPECT_EQ(r.scores.psnr, std::numeric_limits<double>::infinity());
  EXPECT_EQ(r.scores.edgePsnr, std::numeric_limits<double>::infinity());
  EXPECT_EQ(r.scores.ssim, 1.0);
  EXPECT_EQ(r.scores.edgeSsim, 1.0);
  EXPECT_EQ(r.scores.flip, 0.0);
  EXPECT_EQ(r.scores.edgeFlip, 0.0);
  EXPECT_EQ(r.scores.edgePixels, 3u * 37u);
  for (std::size_t i = 0; i < mask.size(); ++i) {
    ASSERT_EQ(r.maps.squaredError[i], 0.0f);
    ASSERT_EQ(r.maps.ssimError[i], 0.0f);
    ASSERT_EQ(r.maps.flip[i], 0.0f);
  }
}

TEST(PassesMetrics, PsnrOfAConstantOffsetInTheEncodedDomainIsClosedForm) {
  const int w = 40, h = 30;
  raster::testing::Random rng(5);
  for (const double d : {0.01, 0.05, 0.2}) {
    MetricsImage reference(w, h), test(w, h);
    for (std::size_t i = 0; i < reference.pixels.size(); ++i) {
      const double r = rng.Uniform(0.05, 0.7), g = rng.Uniform(0.05, 0.7), b = rng.Uniform(0.05, 0.7);
      reference.pixels[i] = glm::vec4(DecodeSrgb(r), DecodeSrgb(g), DecodeSrgb(b), 1.0f);
      test.pixels[i] = glm::vec4(DecodeSrgb(r + d), DecodeSrgb(g + d), DecodeSrgb(b + d), 1.0f);
    }
    EXPECT_NEAR(Psnr(test.View(), reference.View()), 10.0 * std::log10(1.0 / (d * d)), 1e-3) << "offset " << d;
  }
}

TEST(PassesMetrics, MaskedPsnrCountsOnlyTheMaskedPixels) {
  // Offset d on columns 10..14 only: the mask over them sees MSE d^2, the whole image d^2 * 5/40.
  const int w = 40, h = 8;
  const double d = 0.1;
  MetricsImage reference(w, h, EncodedGrey(0.3)), test(w, h, EncodedGrey(0.3));
  for (int y = 0; y < h; ++y) {
    for (int x = 10; x <= 14; ++x) test.At(x, y) = EncodedGrey(0.3 + d);
  }
  const std::vector<float> mask = ColumnMask(w, h, 10, 14);
  EXPECT_NEAR(Psnr(test.View(), reference.View(), mask), 10.0 * std::log10(1.0 / (d * d)), 1e-3);
  EXPECT_NEAR(Psnr(test.View(), reference.View()), 10.0 * std::log10(1.0 / (d * d * 5.0 / 40.0)), 1e-3);
}

TEST(PassesMetrics, SsimOfAConstantOffsetOnAFlatImageIsTheLuminanceTerm) {
  // Flat images have no variance, so SSIM reduces to (2 mx my + C1) / (mx^2 + my^2 + C1); the
  // Rec. 709 luma of an encoded grey is the grey itself.
  const double mx = 0.55, my = 0.4, c1 = 0.01 * 0.01;
  const MetricsImage test(23, 17, EncodedGrey(mx)), reference(23, 17, EncodedGrey(my));
  const MetricMap ssim = Ssim(test.View(), reference.View());
  const double expected = (2.0 * mx * my + c1) / (mx * mx + my * my + c1);
  EXPECT_NEAR(ssim.mean, expected, 1e-6);
  for (const float v : ssim.map) ASSERT_NEAR(v, expected, 1e-6);
}

TEST(PassesMetrics, AShiftedEdgeConcentratesTheErrorAtTheEdge) {
  const int w = 96, h = 40, edgeX = 48;
  const MetricsImage reference = Step(w, h, edgeX), test = Step(w, h, edgeX + 1);  // column 48 changes colour
  const std::vector<float> edges = ColumnMask(w, h, edgeX - 1, edgeX + 1);
  const QualityResult r = ScoreWithMaps(test.View(), reference.View(), edges);

  for (int y = 0; y < h; ++y) {
    float peak = 0.0f;
    int peakX = -1;
    for (int x = 0; x < w; ++x) {
      const std::size_t i = static_cast<std::size_t>(y * w + x);
      EXPECT_EQ(r.maps.squaredError[i] > 0.0f, x == edgeX) << x << "," << y;
      // The widest FLIP filter (the blue-yellow CSF) reaches 10 pixels at 67 pixels per degree.
      if (std::abs(x - edgeX) > 11) {
        ASSERT_EQ(r.maps.flip[i], 0.0f) << x << "," << y;
      }
      if (std::abs(x - edgeX) > 5) {
        ASSERT_EQ(r.maps.ssimError[i], 0.0f) << x << "," << y;
      }
      if (r.maps.flip[i] > peak) {
        peak = r.maps.flip[i];
        peakX = x;
      }
    }
    EXPECT_NEAR(peakX, edgeX, 1) << "row " << y;
    EXPECT_GT(peak, 0.5f);
  }
  EXPECT_LT(r.scores.edgePsnr, r.scores.psnr);
  EXPECT_LT(r.scores.edgeSsim, r.scores.ssim);
  EXPECT_GT(r.scores.edgeFlip, r.scores.flip);
  EXPECT_EQ(r.scores.edgePixels, 3u * static_cast<std::uint64_t>(h));
}

TEST(PassesMetrics, FlipGrowsWithTheColourDifferenceOfFlatPatches) {
  const MetricsImage reference(32, 32, glm::vec4(0.3f, 0.3f, 0.3f, 1.0f));
  double previous = 0.0;
  for (const float delta : {0.005f, 0.01f, 0.02f, 0.05f, 0.1f, 0.2f, 0.4f, 0.7f}) {
    const MetricsImage test(32, 32, glm::vec4(0.3f + delta, 0.3f, 0.3f - 0.4f * delta, 1.0f));
    const double flip = Flip(test.View(), reference.View()).mean;
    EXPECT_GT(flip, previous) << "delta " << delta;
    EXPECT_LE(flip, 1.0);
    previous = flip;
  }
}

TEST(PassesMetrics, FlipOfBlackAgainstWhiteAndOfGreenAgainstBlue) {
  // Flat images have no features, so the error is the remapped colour difference alone. Black to
  // white is HyAB 100 -> 100^0.7 = 25.1, above pc*cmax = 16.5 (cmax = 203.3^0.7 from Hunt-adjusted
  // green to blue), so 0.95 + (25.1 - 16.5) / (41.3 - 16.5) * 0.05 = 0.9674; green against blue is
  // the largest difference and maps to 1.
  const MetricsImage black(24, 24, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f)), white(24, 24, glm::vec4(1.0f));
  const MetricMap bw = Flip(black.View(), white.View());
  EXPECT_NEAR(bw.mean, 0.96738, 2e-5);
  for (const float v : bw.map) ASSERT_EQ(v, bw.map.front());
  const MetricsImage green(24, 24, glm::vec4(0.0f, 1.0f, 0.0f, 1.0f)), blue(24, 24, glm::vec4(0.0f, 0.0f, 1.0f, 1.0f));
  const double gb = Flip(green.View(), blue.View()).mean;
  EXPECT_NEAR(gb, 1.0, 1e-4);
  EXPECT_LE(bw.mean, gb);
}

// Slow reference of LDR-FLIP written straight from the published definition, in double: full 2-D
// kernels (not separable passes), explicit per-tap clamping at the borders, no zero-DC rewriting.
namespace slow {

using Rgb = glm::dvec3;

// Linear sRGB to XYZ (IEC 61966-2-1 primaries, D65), written row by row.
glm::dmat3 RgbToXyz() {
  return glm::transpose(glm::dmat3(0.4124564, 0.3575761, 0.1804375, 0.2126729, 0.7151522, 0.0721750, 0.0193339,
                                   0.1191920, 0.9503041));
}
Rgb White() { return RgbToXyz() * Rgb(1.0); }

Rgb ToYcxcz(const Rgb& rgb) {
  const Rgb n = RgbToXyz() * glm::clamp(rgb, 0.0, 1.0) / White();
  return {116.0 * n.y - 16.0, 500.0 * (n.x - n.y), 200.0 * (n.y - n.z)};
}

Rgb FromYcxcz(const Rgb& c) {
  const double ny = (c.x + 16.0) / 116.0;
  return glm::inverse(RgbToXyz()) * (Rgb(c.y / 500.0 + ny, ny, ny - c.z / 200.0) * White());
}

Rgb HuntLab(const Rgb& rgb) {
  const Rgb n = RgbToXyz() * rgb / White();
  auto f = [](double t) { return t > std::pow(6.0 / 29.0, 3.0) ? std::cbrt(t) : t / (3.0 * std::pow(6.0 / 29.0, 2.0)) + 4.0 / 29.0; };
  const double fx = f(n.x), fy = f(n.y), fz = f(n.z);
  const double l = 116.0 * fy - 16.0;
  return {l, 0.01 * l * 500.0 * (fx - fy), 0.01 * l * 200.0 * (fy - fz)};
}

double HyAb(const Rgb& p, const Rgb& q) { return std::fabs(p.x - q.x) + std::hypot(p.y - q.y, p.z - q.z); }

using Kernel2d = std::vector<std::vector<double>>;  // [dy + r][dx + r]

std::vector<double> Convolve(const std::vector<double>& in, int w, int h, const Kernel2d& k) {
  const int r = static_cast<int>(k.size() / 2);
  std::vector<double> out(in.size());
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      double sum = 0.0;
      for (int dy = -r; dy <= r; ++dy) {
        for (int dx = -r; dx <= r; ++dx) {
          sum += k[static_cast<std::size_t>(dy + r)][static_cast<std::size_t>(dx + r)] *
                 in[static_cast<std::size_t>(std::clamp(y + dy, 0, h - 1) * w + std::clamp(x + dx, 0, w - 1))];
        }
      }
      out[static_cast<std::size_t>(y * w + x)] = sum;
    }
  }
  return out;
}

Kernel2d Csf(double a1, double b1, double a2, double b2, int r, double ppd) {
  Kernel2d k(static_cast<std::size_t>(2 * r + 1), std::vector<double>(static_cast<std::size_t>(2 * r + 1)));
  double sum = 0.0;
  for (int dy = -r; dy <= r; ++dy) {
    for (int dx = -r; dx <= r; ++dx) {
      const double d2 = (dx * dx + dy * dy) / (ppd * ppd);
      double& v = k[static_cast<std::size_t>(dy + r)][static_cast<std::size_t>(dx + r)];
      v = a1 * std::sqrt(std::numbers::pi / b1) * std::exp(-std::numbers::pi * std::numbers::pi * d2 / b1) + a2 * std::sqrt(std::numbers::pi / b2) * std::exp(-std::numbers::pi * std::numbers::pi * d2 / b2);
      sum += v;
    }
  }
  for (auto& row : k) {
    for (double& v : row) v /= sum;
  }
  return k;
}

// Along x; the y kernel is its transpose.
Kernel2d Feature(bool point, double sigma, bool transpose) {
  const int r = static_cast<int>(std::ceil(3.0 * sigma));
  Kernel2d k(static_cast<std::size_t>(2 * r + 1), std::vector<double>(static_cast<std::size_t>(2 * r + 1)));
  double positive = 0.0, negative = 0.0;
  for (int dy = -r; dy <= r; ++dy) {
    for (int dx = -r; dx <= r; ++dx) {
      const int along = transpose ? dy : dx;
      const double g = std::exp(-(dx * dx + dy * dy) / (2.0 * sigma * sigma));
      const double v = point ? (along * along / (sigma * sigma) - 1.0) * g : -along * g;
      k[static_cast<std::size_t>(dy + r)][static_cast<std::size_t>(dx + r)] = v;
      (v > 0.0 ? positive : negative) += v;
    }
  }
  for (auto& row : k) {
    for (double& v : row) v = v > 0.0 ? v / positive : v / -negative;
  }
  return k;
}

std::vector<double> Flip(const MetricsImage& test, const MetricsImage& reference) {
  const int w = test.width, h = test.height;
  const double ppd = 0.7 * 3840.0 / 0.7 * std::numbers::pi / 180.0;
  const int r = static_cast<int>(std::ceil(3.0 * std::sqrt(0.04 / (2.0 * std::numbers::pi * std::numbers::pi)) * ppd));
  const double sigma = 0.5 * 0.082 * ppd;
  struct Prepared {
    std::vector<Rgb> lab;
    std::vector<double> edge, point;
  };
  auto prepare = [&](const MetricsImage& image) {
    std::array<std::vector<double>, 3> channels;
    std::vector<double> luminance;
    for (const glm::vec4& p : image.pixels) {
      const Rgb c = ToYcxcz({p.r, p.g, p.b});
      for (std::size_t i = 0; i < 3; ++i) channels[i].push_back(c[static_cast<glm::length_t>(i)]);
      luminance.push_back((c.x + 16.0) / 116.0);
    }
    const std::vector<double> fy = Convolve(channels[0], w, h, Csf(1.0, 0.0047, 0.0, 1e-5, r, ppd));
    const std::vector<double> fcx = Convolve(channels[1], w, h, Csf(1.0, 0.0053, 0.0, 1e-5, r, ppd));
    const std::vector<double> fcz = Convolve(channels[2], w, h, Csf(34.1, 0.04, 13.5, 0.025, r, ppd));
    const std::vector<double> ex = Convolve(luminance, w, h, Feature(false, sigma, false));
    const std::vector<double> ey = Convolve(luminance, w, h, Feature(false, sigma, true));
    const std::vector<double> px = Convolve(luminance, w, h, Feature(true, sigma, false));
    const std::vector<double> py = Convolve(luminance, w, h, Feature(true, sigma, true));
    Prepared out;
    for (std::size_t i = 0; i < fy.size(); ++i) {
      out.lab.push_back(HuntLab(glm::clamp(FromYcxcz({fy[i], fcx[i], fcz[i]}), 0.0, 1.0)));
      out.edge.push_back(std::hypot(ex[i], ey[i]));
      out.point.push_back(std::hypot(px[i], py[i]));
    }
    return out;
  };
  const Prepared t = prepare(test), ref = prepare(reference);
  const double cMax = std::pow(HyAb(HuntLab({0.0, 1.0, 0.0}), HuntLab({0.0, 0.0, 1.0})), 0.7), cutoff = 0.4 * cMax;
  std::vector<double> map;
  for (std::size_t i = 0; i < t.lab.size(); ++i) {
    const double c = std::pow(HyAb(t.lab[i], ref.lab[i]), 0.7);
    const double colour = c < cutoff ? 0.95 / cutoff * c : 0.95 + (c - cutoff) / (cMax - cutoff) * 0.05;
    const double feature = std::pow(std::max(std::fabs(t.edge[i] - ref.edge[i]), std::fabs(t.point[i] - ref.point[i])) / std::sqrt(2.0), 0.5);
    map.push_back(std::pow(colour, 1.0 - feature));
  }
  return map;
}

}  // namespace slow

TEST(PassesMetrics, FlipMatchesASlowTwoDimensionalReference) {
  // Random pixels with half of them changed: strong colour and feature differences everywhere,
  // and an image smaller than the filters so every pixel sees the clamped borders.
  const MetricsImage reference = RandomMetricsImage(23, 19, 21);
  MetricsImage test = reference;
  raster::testing::Random rng(22);
  for (glm::vec4& p : test.pixels) {
    if (rng.Uniform(0, 1) < 0.5) p = glm::vec4(static_cast<float>(rng.Uniform(0, 1)), static_cast<float>(rng.Uniform(0, 1)), static_cast<float>(rng.Uniform(0, 1)), 1.0f);
  }
  const MetricMap fast = Flip(test.View(), reference.View());
  const std::vector<double> expected = slow::Flip(test, reference);
  for (std::size_t i = 0; i < expected.size(); ++i) ASSERT_NEAR(fast.map[i], expected[i], 1e-5) << "pixel " << i;
}

TEST(PassesMetrics, AMaskThatSelectsNothingIsAnError) {
  const MetricsImage a = RandomMetricsImage(16, 8, 1), b = RandomMetricsImage(16, 8, 2);
  const std::vector<float> none(16 * 8, 0.0f);
  for (const auto& call : std::vector<std::function<void()>>{
           [&] { (void)Psnr(a.View(), b.View(), none); },
           [&] { (void)ScoreWithMaps(a.View(), b.View(), none); },
           [&] { (void)MaskedMean(Ssim(a.View(), b.View()).map, none); }}) {
    try {
      call();
      ADD_FAILURE() << "expected std::invalid_argument";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("mask selects no pixels"), std::string::npos) << e.what();
    }
  }
}

TEST(PassesMetrics, MismatchedSizesAreOneLineErrors) {
  const MetricsImage a = RandomMetricsImage(16, 8, 1), b = RandomMetricsImage(8, 16, 2);
  const std::vector<float> mask(16 * 8, 1.0f);
  for (const auto& call : std::vector<std::function<void()>>{
           [&] { (void)Psnr(a.View(), b.View()); }, [&] { (void)Ssim(a.View(), b.View()); },
           [&] { (void)Flip(a.View(), b.View()); }, [&] { (void)ScoreWithMaps(a.View(), b.View(), mask); }}) {
    try {
      call();
      ADD_FAILURE() << "expected std::invalid_argument";
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
      EXPECT_NE(what.find("16x8"), std::string::npos) << what;
      EXPECT_NE(what.find("8x16"), std::string::npos) << what;
    }
  }
  const std::vector<float> shortMask(10, 1.0f);
  EXPECT_THROW((void)ScoreWithMaps(a.View(), a.View(), shortMask), std::invalid_argument);
  const ImageView lying{a.pixels, 15, 8};
  EXPECT_THROW((void)Flip(lying, lying), std::invalid_argument);
}

// A study prepares the ground truth's half of the metrics once and scores every image against
// it: each image scored through one prepared reference gets the maps and scores of the metrics
// computed from the two images, bit for bit, and a size mismatch is still a one-line error.
TEST(PassesMetrics, APreparedReferenceScoresLikeTheReferenceImage) {
  const int w = 97, h = 61;
  const MetricsImage reference = RandomMetricsImage(w, h, 11);
  const ScoringReference prepared(reference.View());
  const std::vector<float> edges = ColumnMask(w, h, 20, 30);
  for (const std::uint64_t seed : {12u, 13u, 14u}) {
    MetricsImage test = reference;
    raster::testing::Random rng(seed);
    for (glm::vec4& p : test.pixels) p += glm::vec4(static_cast<float>(rng.Uniform(-0.1, 0.1)));
    const QualityResult scored = ScoreWithMaps(test.View(), prepared, edges);
    EXPECT_EQ(scored.maps.squaredError, SquaredErrorMap(test.View(), reference.View())) << seed;
    EXPECT_EQ(scored.maps.flip, Flip(test.View(), reference.View()).map) << seed;
    const MetricMap ssim = Ssim(test.View(), reference.View());
    EXPECT_EQ(scored.scores.ssim, ssim.mean) << seed;
    EXPECT_EQ(scored.scores.psnr, Psnr(test.View(), reference.View())) << seed;
    EXPECT_EQ(scored.scores.edgeFlip, MaskedMean(scored.maps.flip, edges)) << seed;
    EXPECT_GT(scored.scores.flip, 0.0) << seed;
  }
  const MetricsImage other = RandomMetricsImage(w + 1, h, 15);
  try {
    (void)ScoreWithMaps(other.View(), prepared, std::vector<float>(static_cast<std::size_t>((w + 1) * h), 1.0f));
    ADD_FAILURE() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "metrics: the test image is 98x61 but the reference is 97x61");
  }
}

TEST(PassesMetrics, MapsAreBitIdenticalForOneAndTwoThreads) {
  const int w = 203, h = 117;
  MetricsImage reference = RandomMetricsImage(w, h, 7), test = reference;
  raster::testing::Random rng(8);
  for (glm::vec4& p : test.pixels) p += glm::vec4(static_cast<float>(rng.Uniform(-0.05, 0.05)));
  const std::vector<float> edges = ColumnMask(w, h, 50, 60);
  auto run = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
    return ScoreWithMaps(test.View(), reference.View(), edges);
  };
  const QualityResult one = run(1), two = run(2);
  auto same = [](const std::vector<float>& x, const std::vector<float>& y) {
    return x.size() == y.size() && std::memcmp(x.data(), y.data(), x.size() * sizeof(float)) == 0;
  };
  EXPECT_TRUE(same(one.maps.squaredError, two.maps.squaredError));
  EXPECT_TRUE(same(one.maps.ssimError, two.maps.ssimError));
  EXPECT_TRUE(same(one.maps.flip, two.maps.flip));
  EXPECT_EQ(one.scores.psnr, two.scores.psnr);
  EXPECT_EQ(one.scores.ssim, two.scores.ssim);
  EXPECT_EQ(one.scores.flip, two.scores.flip);
  EXPECT_EQ(one.scores.edgeFlip, two.scores.edgeFlip);
  EXPECT_GT(one.scores.flip, 0.0);
  EXPECT_LT(one.scores.ssim, 1.0);
}

}  // namespace
}  // namespace passes
