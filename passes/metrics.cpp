// Image-quality metrics (see metrics.h and docs/metrics.md). SSIM and FLIP share one separable,
// clamp-to-edge filter run in bands of rows (vertical pass, then horizontal, per output row) so the
// working set stays in cache; each row is computed in a fixed order whatever thread runs it, so
// maps and means are bit-identical for any thread count.

#include "passes/metrics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

#include <glm/common.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <glm/vec3.hpp>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "sim/colour.h"

namespace passes {

namespace {

// ---- Checks ---------------------------------------------------------------------------------

std::string SizeText(int width, int height) { return std::to_string(width) + "x" + std::to_string(height); }

std::size_t PixelCount(int width, int height) {
  return static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
}

void CheckImage(const ImageView& image, const std::string& role) {
  if (image.width < 1 || image.height < 1) {
    throw std::invalid_argument("metrics: the " + role + " image has no pixels (" + SizeText(image.width, image.height) + ")");
  }
  if (image.pixels.size() != PixelCount(image.width, image.height)) {
    throw std::invalid_argument("metrics: the " + role + " image holds " + std::to_string(image.pixels.size()) +
                                " pixels but is declared " + SizeText(image.width, image.height));
  }
}

// A test image against a reference of width x height (already checked).
std::size_t CheckTest(const ImageView& test, int width, int height) {
  CheckImage(test, "test");
  if (test.width != width || test.height != height) {
    throw std::invalid_argument("metrics: the test image is " + SizeText(test.width, test.height) +
                                " but the reference is " + SizeText(width, height));
  }
  return test.pixels.size();
}

std::size_t CheckPair(const ImageView& test, const ImageView& reference) {
  CheckImage(reference, "reference");
  return CheckTest(test, reference.width, reference.height);
}

void CheckMask(PixelMask mask, std::size_t pixels) {
  if (mask.size() != pixels) {
    throw std::invalid_argument("metrics: the mask has " + std::to_string(mask.size()) + " values for " +
                                std::to_string(pixels) + " pixels");
  }
  if (CountSelected(mask) == 0) throw std::invalid_argument("metrics: the mask selects no pixels (every value is 0)");
}

// ---- Rows and planes ------------------------------------------------------------------------

// Per-pixel loops over rows: rows are independent, so any partition gives the same bits.
template <typename Body>
void ForEachRowBlock(int height, Body&& body) {
  tbb::parallel_for(tbb::blocked_range<int>(0, height),
                    [&](const tbb::blocked_range<int>& rows) { body(rows.begin(), rows.end()); });
}

// Rows [first, first + count) of one channel of a width x height image: a band plus the apron
// its vertical filters read. float for FLIP; double for SSIM's moments, where E[x^2] - mean^2
// cancels and float rounding is not small next to C2. Reset keeps the allocation between bands.
template <typename T>
struct RowBlock {
  void Reset(int w, int h, int firstRow, int rowCount) {
    width = w;
    height = h;
    first = firstRow;
    values.resize(PixelCount(w, rowCount));
  }
  T* Row(int y) { return values.data() + PixelCount(width, y - first); }
  const T* Row(int y) const { return values.data() + PixelCount(width, y - first); }

  int width = 0, height = 0, first = 0;
  std::vector<T> values;
};

// Bands of kBandRows output rows run in parallel; Scratch is per thread and reused by its bands.
constexpr int kBandRows = 32;

template <typename Scratch, typename Body>
void ForEachBand(int height, Body&& body) {
  tbb::enumerable_thread_specific<Scratch> scratch;
  const int bands = (height + kBandRows - 1) / kBandRows;
  tbb::parallel_for(0, bands, [&](int band) {
    body(scratch.local(), band * kBandRows, std::min(height, (band + 1) * kBandRows));
  });
}

// Rows a band [y0, y1) needs for filters of the given radius, clamped to the image.
std::pair<int, int> ApronRows(int y0, int y1, int radius, int height) {
  return {std::max(0, y0 - radius), std::min(height, y1 + radius)};
}

// A symmetric-support 1-D kernel. dcGain is the kernel's sum in exact arithmetic (1 for smoothing,
// 0 for derivatives); filtering as dcGain*centre + sum(w*(in - centre)) keeps flat regions exactly
// flat, where the rounded weights do not sum to exactly 1 or 0.
template <typename T>
struct Kernel {
  std::vector<T> weights;  // 2*radius+1, weights[k + radius] for offset k
  T dcGain = 1;
  int Radius() const { return static_cast<int>(weights.size() / 2); }
};

template <typename T>
Kernel<T> NormalisedKernel(const std::vector<double>& raw) {
  double sum = 0.0;
  for (const double w : raw) sum += w;
  Kernel<T> kernel;
  for (const double w : raw) kernel.weights.push_back(static_cast<T>(w / sum));
  return kernel;
}

// Derivative kernels: positive weights scaled to sum to 1 and negative ones to -1 (FLIP paper,
// feature detection), so a unit step gives a response of at most 1 per axis.
Kernel<float> ZeroSumKernel(const std::vector<double>& raw) {
  double positive = 0.0, negative = 0.0;
  for (const double w : raw) (w > 0.0 ? positive : negative) += w;
  Kernel<float> kernel;
  kernel.dcGain = 0.0f;
  for (const double w : raw) kernel.weights.push_back(static_cast<float>(w > 0.0 ? w / positive : w / -negative));
  return kernel;
}

// Horizontal pass over one row; pixels beyond the left and right edges repeat the edge pixel.
template <typename T>
void FilterRow(const T* src, int width, const Kernel<T>& kernel, std::vector<T>& padded, T* dst) {
  const int radius = kernel.Radius();
  padded.resize(static_cast<std::size_t>(width + 2 * radius));
  for (int i = 0; i < width + 2 * radius; ++i) padded[static_cast<std::size_t>(i)] = src[std::clamp(i - radius, 0, width - 1)];
  const T* centre = padded.data() + radius;
  std::fill(dst, dst + width, T{0});
  for (int k = 0; k <= 2 * radius; ++k) {
    const T w = kernel.weights[static_cast<std::size_t>(k)];
    const T* tap = padded.data() + k;
    for (int x = 0; x < width; ++x) dst[x] += w * (tap[x] - centre[x]);
  }
  for (int x = 0; x < width; ++x) dst[x] += kernel.dcGain * centre[x];
}

// Vertical pass for output row y; rows beyond the top and bottom edges repeat the edge row.
template <typename T>
void FilterColumn(const RowBlock<T>& in, const Kernel<T>& kernel, int y, T* dst) {
  const int radius = kernel.Radius();
  const T* centre = in.Row(y);
  std::fill(dst, dst + in.width, T{0});
  for (int k = 0; k <= 2 * radius; ++k) {
    const T w = kernel.weights[static_cast<std::size_t>(k)];
    const T* tap = in.Row(std::clamp(y + k - radius, 0, in.height - 1));
    for (int x = 0; x < in.width; ++x) dst[x] += w * (tap[x] - centre[x]);
  }
  for (int x = 0; x < in.width; ++x) dst[x] += kernel.dcGain * centre[x];
}

// The 2-D separable filter at output row y: vertical pass into `column`, then horizontal.
template <typename T>
void Filter2d(const RowBlock<T>& in, const Kernel<T>& vertical, const Kernel<T>& horizontal, int y,
              std::vector<T>& column, std::vector<T>& padded, T* dst) {
  column.resize(static_cast<std::size_t>(in.width));
  FilterColumn(in, vertical, y, column.data());
  FilterRow(column.data(), in.width, horizontal, padded, dst);
}

double Mean(std::span<const float> map) {
  double sum = 0.0;
  for (const float v : map) sum += static_cast<double>(v);
  return sum / static_cast<double>(map.size());
}

// ---- PSNR, SSIM --------------------------------------------------------------

double PsnrFromMse(double mse) {
  // aa-facts §9.2: PSNR = 10 log10(MAX^2 / MSE) with MAX = 1; identical images have no error.
  return mse == 0.0 ? std::numeric_limits<double>::infinity() : 10.0 * std::log10(1.0 / mse);
}

// aa-facts §9.2 (Wang et al. 2004): 11x11 Gaussian window with sigma 1.5, C1 = (0.01 L)^2,
// C2 = (0.03 L)^2, L = 1 for values in [0,1].
constexpr int kSsimRadius = 5;
constexpr double kSsimSigma = 1.5;
constexpr double kSsimC1 = 0.01 * 0.01;
constexpr double kSsimC2 = 0.03 * 0.03;

struct SsimScratch {
  std::array<RowBlock<double>, 5> moments;  // x, y, x^2, y^2, xy over a band and its apron
  std::array<std::vector<double>, 5> local;  // their windowed means on one row
  std::vector<double> column, padded;
};

Kernel<double> SsimWindow() {
  std::vector<double> raw;
  for (int k = -kSsimRadius; k <= kSsimRadius; ++k) raw.push_back(std::exp(-k * k / (2.0 * kSsimSigma * kSsimSigma)));
  return NormalisedKernel<double>(raw);
}

// ---- FLIP colour spaces -----------------------------------------------------------------------

// aa-facts §9.1 (FLIP v1.6 defaults): colour-difference exponent qc, the cutoff pc and the error it
// maps to pt, the feature filter width gw (degrees) and the feature exponent qf.
constexpr float kFlipQc = 0.7f;
constexpr float kFlipPc = 0.4f;
constexpr float kFlipPt = 0.95f;
constexpr double kFlipGw = 0.082;
constexpr float kFlipQf = 0.5f;

// Linear sRGB (Rec. 709 primaries, D65 white) to CIE XYZ, as derived from the primaries in
// IEC 61966-2-1; rows are X, Y, Z.
constexpr std::array<std::array<double, 3>, 3> kRgbToXyz = {{{0.4124564, 0.3575761, 0.1804375},
                                                             {0.2126729, 0.7151522, 0.0721750},
                                                             {0.0193339, 0.1191920, 0.9503041}}};

struct ColourSpace {
  glm::mat3 rgbToXyz;
  glm::mat3 xyzToRgb;
  glm::vec3 white;     // XYZ of linear RGB (1,1,1): the reference white of YCxCz and L*a*b*
  glm::vec3 invWhite;
};

const ColourSpace& Colours() {
  static const ColourSpace colours = [] {
    glm::dmat3 m(0.0);
    for (int row = 0; row < 3; ++row) {
      for (int col = 0; col < 3; ++col) m[col][row] = kRgbToXyz[static_cast<std::size_t>(row)][static_cast<std::size_t>(col)];
    }
    const glm::dvec3 white = m * glm::dvec3(1.0);
    return ColourSpace{glm::mat3(m), glm::mat3(glm::inverse(m)), glm::vec3(white), glm::vec3(1.0 / white)};
  }();
  return colours;
}

// YCxCz, the linearised CIELAB opponent space the FLIP paper filters in:
// Y = 116 Y/Yn - 16, Cx = 500 (X/Xn - Y/Yn), Cz = 200 (Y/Yn - Z/Zn).
glm::vec3 LinearRgbToYcxcz(const glm::vec3& rgb) {
  const ColourSpace& cs = Colours();
  const glm::vec3 n = (cs.rgbToXyz * rgb) * cs.invWhite;
  return {116.0f * n.y - 16.0f, 500.0f * (n.x - n.y), 200.0f * (n.y - n.z)};
}

glm::vec3 YcxczToLinearRgb(const glm::vec3& ycxcz) {
  const ColourSpace& cs = Colours();
  const float ny = (ycxcz.x + 16.0f) / 116.0f;
  const glm::vec3 n(ycxcz.y / 500.0f + ny, ny, ny - ycxcz.z / 200.0f);
  return cs.xyzToRgb * (n * cs.white);
}

// CIE 15 (CIELAB): cube root above (6/29)^3, linear segment below.
float LabF(float t) {
  constexpr float kDelta = 6.0f / 29.0f;
  return t > kDelta * kDelta * kDelta ? std::cbrt(t) : t / (3.0f * kDelta * kDelta) + 4.0f / 29.0f;
}

// CIELAB with the FLIP paper's Hunt adjustment: a* and b* scaled by 0.01 L*, so dark colours
// count as less colourful.
glm::vec3 LinearRgbToHuntLab(const glm::vec3& rgb) {
  const ColourSpace& cs = Colours();
  const glm::vec3 n = (cs.rgbToXyz * rgb) * cs.invWhite;
  const float fx = LabF(n.x), fy = LabF(n.y), fz = LabF(n.z);
  const float l = 116.0f * fy - 16.0f;
  return {l, 0.01f * l * 500.0f * (fx - fy), 0.01f * l * 200.0f * (fy - fz)};
}

// HyAB (Abasi et al. 2020, adopted by the FLIP paper for large colour differences):
// |dL| + Euclidean distance in the (a, b) plane.
float HyAb(const glm::vec3& p, const glm::vec3& q) {
  return std::fabs(p.x - q.x) + std::hypot(p.y - q.y, p.z - q.z);
}

glm::vec3 ClampRgb(const glm::vec3& rgb) { return glm::clamp(rgb, glm::vec3(0.0f), glm::vec3(1.0f)); }

// ---- FLIP filters -----------------------------------------------------------------------------

// The FLIP paper's contrast sensitivity functions (its fitted constants; aa-facts does not record
// them), one per YCxCz channel, each a sum of two Gaussians a*exp(-b*rho^2) in frequency; in space
// each term is a*sqrt(pi/b)*exp(-pi^2 r^2/b) with r in degrees. Achromatic and red-green use one
// term (a2 = 0; b2 only keeps the paper's table complete).
struct CsfTerms {
  double a1, b1, a2, b2;
};
constexpr CsfTerms kCsfAchromatic{1.0, 0.0047, 0.0, 1e-5};
constexpr CsfTerms kCsfRedGreen{1.0, 0.0053, 0.0, 1e-5};
constexpr CsfTerms kCsfBlueYellow{34.1, 0.04, 13.5, 0.025};

// A 2-D filter sum_i c_i g_i(x) g_i(y), normalised to unit sum, is sum_i w_i (g_i/s_i)(x) (g_i/s_i)(y)
// with s_i = sum g_i and w_i proportional to c_i s_i^2: one separable pass per Gaussian term.
struct CsfFilter {
  std::vector<Kernel<float>> terms;
  std::vector<float> termWeights;  // sum to 1; a single term gets exactly 1
};

CsfFilter MakeCsfFilter(const CsfTerms& csf, int radius, double pixelsPerDegree) {
  std::vector<std::pair<double, double>> ab{{csf.a1, csf.b1}};
  if (csf.a2 != 0.0) ab.emplace_back(csf.a2, csf.b2);
  CsfFilter filter;
  std::vector<double> mass;
  for (const auto& [a, b] : ab) {
    std::vector<double> raw;
    double sum = 0.0;
    for (int k = -radius; k <= radius; ++k) {
      const double r = k / pixelsPerDegree;
      raw.push_back(std::exp(-std::numbers::pi * std::numbers::pi * r * r / b));
      sum += raw.back();
    }
    filter.terms.push_back(NormalisedKernel<float>(raw));
    mass.push_back(a * std::sqrt(std::numbers::pi / b) * sum * sum);
  }
  double total = 0.0;
  for (const double m : mass) total += m;
  for (const double m : mass) filter.termWeights.push_back(static_cast<float>(m / total));
  return filter;
}

// One filtered output row: the weighted sum of each Gaussian term's separable pass.
void CsfRow(const RowBlock<float>& in, const CsfFilter& filter, int y, std::vector<float>& column,
            std::vector<float>& padded, std::vector<float>& term, float* dst) {
  term.resize(static_cast<std::size_t>(in.width));
  std::fill(dst, dst + in.width, 0.0f);
  for (std::size_t t = 0; t < filter.terms.size(); ++t) {
    Filter2d(in, filter.terms[t], filter.terms[t], y, column, padded, term.data());
    for (std::size_t x = 0; x < term.size(); ++x) dst[x] += filter.termWeights[t] * term[x];
  }
}

struct FlipFilters {
  CsfFilter achromatic, redGreen, blueYellow;
  Kernel<float> smooth, edge, point;  // feature detection: Gaussian, its 1st and 2nd derivative
  int apron;                          // the largest radius: rows a band reads beyond its own
};

FlipFilters MakeFlipFilters(double pixelsPerDegree) {
  // The FLIP paper: one radius for every CSF, 3 standard deviations of its widest Gaussian
  // (exp(-pi^2 r^2 / b) has sigma = sqrt(b / (2 pi^2)) degrees).
  double widest = 0.0;
  for (const CsfTerms& csf : {kCsfAchromatic, kCsfRedGreen, kCsfBlueYellow}) widest = std::max({widest, csf.b1, csf.b2});
  const int csfRadius = static_cast<int>(std::ceil(3.0 * std::sqrt(widest / (2.0 * std::numbers::pi * std::numbers::pi)) * pixelsPerDegree));

  // aa-facts §9.1: feature filters with sigma = 0.5 gw PPD pixels and radius ceil(3 sigma).
  const double sigma = 0.5 * kFlipGw * pixelsPerDegree;
  const int featureRadius = static_cast<int>(std::ceil(3.0 * sigma));
  std::vector<double> gauss, firstDerivative, secondDerivative;
  for (int k = -featureRadius; k <= featureRadius; ++k) {
    const double g = std::exp(-k * k / (2.0 * sigma * sigma));
    gauss.push_back(g);
    firstDerivative.push_back(-k * g);
    secondDerivative.push_back((k * k / (sigma * sigma) - 1.0) * g);
  }
  return FlipFilters{MakeCsfFilter(kCsfAchromatic, csfRadius, pixelsPerDegree),
                     MakeCsfFilter(kCsfRedGreen, csfRadius, pixelsPerDegree),
                     MakeCsfFilter(kCsfBlueYellow, csfRadius, pixelsPerDegree),
                     NormalisedKernel<float>(gauss), ZeroSumKernel(firstDerivative), ZeroSumKernel(secondDerivative),
                     std::max(csfRadius, featureRadius)};
}

// One image's inputs over a band and its apron (YCxCz and the normalised luminance), and its
// outputs for one row: the filtered colour in Hunt-adjusted L*a*b* and the feature magnitudes.
struct FlipRows {
  RowBlock<float> y, cx, cz, luminance;
  std::vector<float> l, a, b, edge, point;
};

struct FlipScratch {
  std::array<FlipRows, 2> images;  // test, reference
  std::vector<float> column, padded, term;
  std::array<std::vector<float>, 4> rows;
};

void LoadFlipRows(const ImageView& image, int lo, int hi, FlipRows& rows) {
  const int w = image.width, h = image.height;
  for (RowBlock<float>* block : {&rows.y, &rows.cx, &rows.cz, &rows.luminance}) block->Reset(w, h, lo, hi - lo);
  for (int row = lo; row < hi; ++row) {
    const glm::vec4* src = image.pixels.data() + PixelCount(w, row);
    float* y = rows.y.Row(row);
    float* cx = rows.cx.Row(row);
    float* cz = rows.cz.Row(row);
    float* luminance = rows.luminance.Row(row);
    for (int x = 0; x < w; ++x) {
      const glm::vec3 ycxcz = LinearRgbToYcxcz(ClampRgb(glm::vec3(src[x])));
      y[x] = ycxcz.x;
      cx[x] = ycxcz.y;
      cz[x] = ycxcz.z;
      // aa-facts §9.1: features see the unfiltered Y normalised to [0,1], (Y + 16) / 116.
      luminance[x] = (ycxcz.x + 16.0f) / 116.0f;
    }
  }
}

void FlipRow(FlipRows& rows, const FlipFilters& filters, int y, FlipScratch& s) {
  const auto w = static_cast<std::size_t>(rows.y.width);
  for (std::vector<float>* v : {&rows.l, &rows.a, &rows.b, &rows.edge, &rows.point, &s.rows[0], &s.rows[1], &s.rows[2], &s.rows[3]}) {
    v->resize(w);
  }
  CsfRow(rows.y, filters.achromatic, y, s.column, s.padded, s.term, s.rows[0].data());
  CsfRow(rows.cx, filters.redGreen, y, s.column, s.padded, s.term, s.rows[1].data());
  CsfRow(rows.cz, filters.blueYellow, y, s.column, s.padded, s.term, s.rows[2].data());
  for (std::size_t x = 0; x < w; ++x) {
    // The FLIP paper: filtered colours can leave the gamut; back to linear RGB, clamp, then L*a*b*.
    const glm::vec3 lab = LinearRgbToHuntLab(ClampRgb(YcxczToLinearRgb({s.rows[0][x], s.rows[1][x], s.rows[2][x]})));
    rows.l[x] = lab.x;
    rows.a[x] = lab.y;
    rows.b[x] = lab.z;
  }

  // The 2-D feature kernels are separable: a derivative along one axis times the Gaussian along
  // the other. One vertical Gaussian pass serves both x responses.
  const int width = rows.y.width;
  s.column.resize(w);
  FilterColumn(rows.luminance, filters.smooth, y, s.column.data());
  FilterRow(s.column.data(), width, filters.edge, s.padded, s.rows[0].data());
  FilterRow(s.column.data(), width, filters.point, s.padded, s.rows[2].data());
  FilterColumn(rows.luminance, filters.edge, y, s.column.data());
  FilterRow(s.column.data(), width, filters.smooth, s.padded, s.rows[1].data());
  FilterColumn(rows.luminance, filters.point, y, s.column.data());
  FilterRow(s.column.data(), width, filters.smooth, s.padded, s.rows[3].data());
  for (std::size_t x = 0; x < w; ++x) {
    rows.edge[x] = std::hypot(s.rows[0][x], s.rows[1][x]);
    rows.point[x] = std::hypot(s.rows[2][x], s.rows[3][x]);
  }
}

void CheckFlipSettings(const FlipSettings& settings) {
  if (!(settings.viewingDistanceMetres > 0.0) || !(settings.monitorWidthMetres > 0.0) || settings.monitorWidthPixels < 1) {
    throw std::invalid_argument("metrics: FLIP viewing distance, monitor width and monitor resolution must be positive");
  }
}

}  // namespace

ImageView ViewOf(const sim::Texture2D<glm::vec4>& texture) {
  return ImageView{texture.Texels(), texture.Width(), texture.Height()};
}

std::uint64_t CountSelected(PixelMask mask) {
  return static_cast<std::uint64_t>(std::count_if(mask.begin(), mask.end(), [](float v) { return v != 0.0f; }));
}

double MaskedMean(std::span<const float> map, PixelMask mask) {
  CheckMask(mask, map.size());
  double sum = 0.0;
  std::uint64_t count = 0;
  for (std::size_t i = 0; i < map.size(); ++i) {
    if (mask[i] != 0.0f) {
      sum += static_cast<double>(map[i]);
      ++count;
    }
  }
  return sum / static_cast<double>(count);
}

namespace {

// The sRGB encoding PSNR and SSIM read, per pixel.
std::vector<glm::vec3> EncodedImage(const ImageView& image) {
  std::vector<glm::vec3> encoded(image.pixels.size());
  const int w = image.width;
  ForEachRowBlock(image.height, [&](int y0, int y1) {
    for (std::size_t i = PixelCount(w, y0); i < PixelCount(w, y1); ++i) encoded[i] = sim::EncodeSrgb(glm::vec3(image.pixels[i]));
  });
  return encoded;
}

std::vector<float> SquaredErrorAgainst(const ImageView& test, std::span<const glm::vec3> reference) {
  std::vector<float> map(test.pixels.size());
  const int w = test.width;
  ForEachRowBlock(test.height, [&](int y0, int y1) {
    for (std::size_t i = PixelCount(w, y0); i < PixelCount(w, y1); ++i) {
      const glm::vec3 d = sim::EncodeSrgb(glm::vec3(test.pixels[i])) - reference[i];
      map[i] = (d.r * d.r + d.g * d.g + d.b * d.b) / 3.0f;
    }
  });
  return map;
}

MetricMap SsimAgainst(const ImageView& test, std::span<const glm::vec3> reference) {
  const int w = test.width, h = test.height;
  std::vector<float> lumaTest(test.pixels.size()), lumaReference(test.pixels.size());
  ForEachRowBlock(h, [&](int y0, int y1) {
    for (std::size_t i = PixelCount(w, y0); i < PixelCount(w, y1); ++i) {
      lumaTest[i] = sim::Rec709Luma(sim::EncodeSrgb(glm::vec3(test.pixels[i])));
      lumaReference[i] = sim::Rec709Luma(reference[i]);
    }
  });
  const Kernel<double> window = SsimWindow();
  MetricMap result{0.0, std::vector<float>(PixelCount(w, h))};
  ForEachBand<SsimScratch>(h, [&](SsimScratch& s, int y0, int y1) {
    // Both lumas and the three products whose local means give the (co)variances.
    const auto [lo, hi] = ApronRows(y0, y1, kSsimRadius, h);
    for (RowBlock<double>& block : s.moments) block.Reset(w, h, lo, hi - lo);
    for (std::size_t i = PixelCount(w, lo), j = 0; i < PixelCount(w, hi); ++i, ++j) {
      const auto lx = static_cast<double>(lumaTest[i]), ly = static_cast<double>(lumaReference[i]);
      s.moments[0].values[j] = lx;
      s.moments[1].values[j] = ly;
      s.moments[2].values[j] = lx * lx;
      s.moments[3].values[j] = ly * ly;
      s.moments[4].values[j] = lx * ly;
    }
    for (std::vector<double>& v : s.local) v.resize(static_cast<std::size_t>(w));
    for (int row = y0; row < y1; ++row) {
      for (std::size_t m = 0; m < s.local.size(); ++m) Filter2d(s.moments[m], window, window, row, s.column, s.padded, s.local[m].data());
      float* out = result.map.data() + PixelCount(w, row);
      for (std::size_t i = 0; i < static_cast<std::size_t>(w); ++i) {
        const double muX = s.local[0][i], muY = s.local[1][i];
        // The same expression for all three moments, so identical images give exactly 1.
        const double varX = s.local[2][i] - muX * muX;
        const double varY = s.local[3][i] - muY * muY;
        const double covXY = s.local[4][i] - muX * muY;
        const double ssim = ((2.0 * muX * muY + kSsimC1) * (2.0 * covXY + kSsimC2)) /
                            ((muX * muX + muY * muY + kSsimC1) * (varX + varY + kSsimC2));
        out[i] = static_cast<float>(ssim);
      }
    }
  });
  result.mean = Mean(result.map);
  return result;
}

}  // namespace

std::vector<float> SquaredErrorMap(const ImageView& test, const ImageView& reference) {
  CheckPair(test, reference);
  return SquaredErrorAgainst(test, EncodedImage(reference));
}

double Psnr(const ImageView& test, const ImageView& reference, PixelMask mask) {
  const std::vector<float> squared = SquaredErrorMap(test, reference);
  return PsnrFromMse(mask.empty() ? Mean(squared) : MaskedMean(squared, mask));
}

MetricMap Ssim(const ImageView& test, const ImageView& reference) {
  CheckPair(test, reference);
  return SsimAgainst(test, EncodedImage(reference));
}

double PixelsPerDegree(const FlipSettings& settings) {
  CheckFlipSettings(settings);
  // aa-facts §9.1: PPD = distance * (resolution / monitor width) * pi / 180.
  return settings.viewingDistanceMetres * (settings.monitorWidthPixels / settings.monitorWidthMetres) *
         std::numbers::pi / 180.0;
}

namespace {

// FLIP's per-image half over a whole image: the filtered colour in Hunt-adjusted L*a*b* and the
// feature magnitudes, per pixel (the same rows FlipRow gives a band).
struct FlipImage {
  std::vector<float> l, a, b, edge, point;
};

FlipImage FlipImageOf(const ImageView& image, const FlipFilters& filters) {
  const int w = image.width, h = image.height;
  FlipImage out;
  for (std::vector<float>* v : {&out.l, &out.a, &out.b, &out.edge, &out.point}) v->resize(PixelCount(w, h));
  ForEachBand<FlipScratch>(h, [&](FlipScratch& s, int y0, int y1) {
    const auto [lo, hi] = ApronRows(y0, y1, filters.apron, h);
    FlipRows& rows = s.images[0];
    LoadFlipRows(image, lo, hi, rows);
    for (int row = y0; row < y1; ++row) {
      FlipRow(rows, filters, row, s);
      const std::size_t at = PixelCount(w, row);
      std::copy(rows.l.begin(), rows.l.end(), out.l.begin() + static_cast<std::ptrdiff_t>(at));
      std::copy(rows.a.begin(), rows.a.end(), out.a.begin() + static_cast<std::ptrdiff_t>(at));
      std::copy(rows.b.begin(), rows.b.end(), out.b.begin() + static_cast<std::ptrdiff_t>(at));
      std::copy(rows.edge.begin(), rows.edge.end(), out.edge.begin() + static_cast<std::ptrdiff_t>(at));
      std::copy(rows.point.begin(), rows.point.end(), out.point.begin() + static_cast<std::ptrdiff_t>(at));
    }
  });
  return out;
}

MetricMap FlipAgainst(const ImageView& test, const FlipImage& reference, const FlipFilters& filters) {
  const int w = test.width, h = test.height;
  // aa-facts §9.1: the largest colour difference, Hunt-adjusted green to blue, through the same
  // exponent; errors up to pc*cmax map linearly to [0, pt], the rest to (pt, 1].
  const float cMax = std::pow(HyAb(LinearRgbToHuntLab({0.0f, 1.0f, 0.0f}), LinearRgbToHuntLab({0.0f, 0.0f, 1.0f})), kFlipQc);
  const float cutoff = kFlipPc * cMax;
  const float featureNorm = 1.0f / std::numbers::sqrt2_v<float>;

  MetricMap result{0.0, std::vector<float>(PixelCount(w, h))};
  ForEachBand<FlipScratch>(h, [&](FlipScratch& s, int y0, int y1) {
    const auto [lo, hi] = ApronRows(y0, y1, filters.apron, h);
    LoadFlipRows(test, lo, hi, s.images[0]);
    for (int row = y0; row < y1; ++row) {
      FlipRow(s.images[0], filters, row, s);
      const FlipRows& t = s.images[0];
      const std::size_t at = PixelCount(w, row);
      float* out = result.map.data() + at;
      for (std::size_t x = 0; x < static_cast<std::size_t>(w); ++x) {
        const std::size_t r = at + x;
        const float colour = std::pow(
            HyAb({t.l[x], t.a[x], t.b[x]}, {reference.l[r], reference.a[r], reference.b[r]}), kFlipQc);
        const float colourError = colour < cutoff ? kFlipPt / cutoff * colour
                                                  : kFlipPt + (colour - cutoff) / (cMax - cutoff) * (1.0f - kFlipPt);
        const float edgeDiff = std::fabs(t.edge[x] - reference.edge[r]);
        const float pointDiff = std::fabs(t.point[x] - reference.point[r]);
        const float featureError = std::pow(featureNorm * std::max(edgeDiff, pointDiff), kFlipQf);
        out[x] = std::pow(colourError, 1.0f - featureError);
      }
    }
  });
  result.mean = Mean(result.map);
  return result;
}

}  // namespace

MetricMap Flip(const ImageView& test, const ImageView& reference, const FlipSettings& settings) {
  CheckPair(test, reference);
  const FlipFilters filters = MakeFlipFilters(PixelsPerDegree(settings));
  return FlipAgainst(test, FlipImageOf(reference, filters), filters);
}

struct ScoringReference::Prepared {
  int width, height;
  std::vector<glm::vec3> encoded;
  FlipFilters filters;
  FlipImage flip;
};

ScoringReference::ScoringReference(const ImageView& reference, const FlipSettings& settings) {
  CheckImage(reference, "reference");
  FlipFilters filters = MakeFlipFilters(PixelsPerDegree(settings));
  FlipImage flip = FlipImageOf(reference, filters);
  prepared_ = std::make_shared<const Prepared>(
      Prepared{reference.width, reference.height, EncodedImage(reference), std::move(filters), std::move(flip)});
}

QualityResult ScoreWithMaps(const ImageView& test, const ScoringReference& reference, PixelMask edgeMask) {
  const ScoringReference::Prepared& prepared = *reference.prepared_;
  CheckMask(edgeMask, CheckTest(test, prepared.width, prepared.height));
  QualityResult result{};
  result.maps.squaredError = SquaredErrorAgainst(test, prepared.encoded);
  MetricMap ssim = SsimAgainst(test, prepared.encoded);
  MetricMap flip = FlipAgainst(test, prepared.flip, prepared.filters);

  QualityScores& s = result.scores;
  s.psnr = PsnrFromMse(Mean(result.maps.squaredError));
  s.edgePsnr = PsnrFromMse(MaskedMean(result.maps.squaredError, edgeMask));
  s.ssim = ssim.mean;
  s.edgeSsim = MaskedMean(ssim.map, edgeMask);
  s.flip = flip.mean;
  s.edgeFlip = MaskedMean(flip.map, edgeMask);
  s.edgePixels = CountSelected(edgeMask);

  result.maps.ssimError = std::move(ssim.map);
  for (float& v : result.maps.ssimError) v = 1.0f - v;
  result.maps.flip = std::move(flip.map);
  return result;
}

QualityResult ScoreWithMaps(const ImageView& test, const ImageView& reference, PixelMask edgeMask,
                            const FlipSettings& settings) {
  CheckPair(test, reference);
  return ScoreWithMaps(test, ScoringReference(reference, settings), edgeMask);
}

}  // namespace passes
