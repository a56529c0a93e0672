#pragma once
// Image-quality metrics against the ground truth (issue 5): PSNR and SSIM on sRGB-encoded values,
// and LDR-FLIP (Andersson et al. 2020, v1.6 defaults, aa-facts §9.1) on linear RGB, each overall
// and restricted to a pixel mask (the edge pixels), with per-pixel error maps for the report.
// Host-side code, not a machine kernel: the metrics score the passes, they are not part of them.
// Definitions, constants, colour spaces and border handling: docs/metrics.md.

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <glm/vec4.hpp>

#include "sim/resources.h"

namespace passes {

// A linear RGB(A) image, row-major with the top row first; alpha is ignored by every metric.
struct ImageView {
  std::span<const glm::vec4> pixels;
  int width = 0;
  int height = 0;
};
ImageView ViewOf(const sim::Texture2D<glm::vec4>& texture);

// Pixel masks are width*height floats in the images' order; a pixel is selected when its value is
// non-zero (the edge masks are 0/1). An empty span means "no mask" where a mask is optional.
using PixelMask = std::span<const float>;

// A per-pixel map (width*height, the images' order) and its mean over all pixels.
struct MetricMap {
  double mean = 0.0;
  std::vector<float> map;
};

// Per pixel: the squared difference of the sRGB-encoded values, clamped to [0,1], averaged over R,
// G and B. PSNR is 10*log10(1 / mean of this map) with MAX = 1; +infinity when the images (or the
// masked pixels) are identical. Throws std::invalid_argument for mismatched sizes, a mask of the
// wrong size, or a mask that selects no pixels.
std::vector<float> SquaredErrorMap(const ImageView& test, const ImageView& reference);
double Psnr(const ImageView& test, const ImageView& reference, PixelMask mask = {});

// SSIM (Wang et al. 2004) on the luma of the sRGB-encoded values; the map holds SSIM per pixel
// (in [-1, 1], 1 where the images agree), the mean is MSSIM.
MetricMap Ssim(const ImageView& test, const ImageView& reference);

// FLIP's viewing condition (aa-facts §9.1): a monitor of monitorWidthPixels across
// monitorWidthMetres seen from viewingDistanceMetres.
struct FlipSettings {
  double viewingDistanceMetres = 0.7;
  double monitorWidthMetres = 0.7;
  int monitorWidthPixels = 3840;
};
double PixelsPerDegree(const FlipSettings& settings);  // 67.02 for the defaults

// LDR-FLIP: the map holds the per-pixel error in [0,1], the mean is the usual scalar. Inputs are
// clamped to [0,1]. Throws std::invalid_argument for mismatched sizes or invalid settings.
MetricMap Flip(const ImageView& test, const ImageView& reference, const FlipSettings& settings = {});

// Mean of a map over the selected pixels. Throws std::invalid_argument when the sizes differ or
// the mask selects no pixels.
double MaskedMean(std::span<const float> map, PixelMask mask);
std::uint64_t CountSelected(PixelMask mask);

struct QualityScores {
  double psnr, ssim, flip;
  double edgePsnr, edgeSsim, edgeFlip;  // over the pixels of the edge mask only
  std::uint64_t edgePixels;
};

// Error images for the report, all width*height: squared error (PSNR), 1 - SSIM (in [0, 2]) and
// FLIP.
struct QualityMaps {
  std::vector<float> squaredError;
  std::vector<float> ssimError;
  std::vector<float> flip;
};

struct QualityResult {
  QualityScores scores;
  QualityMaps maps;
};

// The reference's half of every metric (its sRGB encoding; FLIP's filtered colour and features),
// computed once: a study scores every mode and pass against one ground truth, and the reference
// half is independent of the image scored. Scores are bit-identical to scoring against the
// reference image itself. Keeps no reference to the image; copies share the prepared data.
class ScoringReference {
 public:
  explicit ScoringReference(const ImageView& reference, const FlipSettings& settings = {});
  // What it keeps per reference pixel, for memory estimates: the encoded RGB and FLIP's five planes.
  static constexpr std::size_t kBytesPerPixel = 3 * sizeof(float) + 5 * sizeof(float);

 private:
  friend QualityResult ScoreWithMaps(const ImageView&, const ScoringReference&, PixelMask);
  struct Prepared;
  std::shared_ptr<const Prepared> prepared_;
};

// Every metric overall and over the edge mask (the pixels the ground truth shows as partially
// covered; the caller supplies it). The edge mask is required and must select at least one pixel.
QualityResult ScoreWithMaps(const ImageView& test, const ScoringReference& reference, PixelMask edgeMask);
QualityResult ScoreWithMaps(const ImageView& test, const ImageView& reference, PixelMask edgeMask,
                            const FlipSettings& settings = {});

}  // namespace passes
