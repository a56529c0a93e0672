// Sample-pattern error (see pattern_error.h; definition in docs/sample-patterns.md).
//
// For one orientation, with s_i the samples' projections on the edge normal, C(t) the reference
// coverage and H the unit step, sum(w) = 1 gives
//   estimate - C = sum_i w_i (H(t - s_i) - C(t)),
// so e = sum_ij w_i w_j K(s_i, s_j) with, for s <= s',
//   K(s, s') = A(s) + D(s') - (B(s') - B(s)),
//   A(s) = int_{-inf}^{s} C^2,  B(s) = int_{-inf}^{s} C (1 - C),  D(s) = int_{s}^{inf} (1 - C)^2.
// A, B and D depend on the orientation and the reference only, so they are tabulated once per
// orientation and read back by cubic Hermite interpolation (their derivatives are known
// exactly); a footprint then costs O(samples^2) per orientation, which the optimiser needs.

#include "raster/pattern_error.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace raster {
namespace {

// Tabulation range and step, px along the normal. The tent reference reaches sqrt(2) px; samples
// of a footprint lie within sqrt(2)/2 px of the centre.
constexpr double kTableHalfWidth = 1.5;
constexpr double kTableStep = 1.0 / 128.0;
constexpr int kTableCells = static_cast<int>(2 * kTableHalfWidth / kTableStep);
constexpr double kWeightSumTolerance = 1e-9;
constexpr double kSampleUnit = 1.0 / 16.0;  // hw-facts §4.2: offsets in 1/16 px

// Gauss–Legendre nodes on [-1, 1]: 3 points are exact to degree 5 (the coverage integrands are
// at most cubic between kinks), 5 points to degree 9 (C^2 of the tent reference has degree 8).
constexpr double kGauss3X[] = {-0.7745966692414834, 0.0, 0.7745966692414834};
constexpr double kGauss3W[] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
constexpr double kGauss5X[] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                               0.9061798459386640};
constexpr double kGauss5W[] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665,
                               0.2369268850561891};

constexpr std::size_t kMaxKinks = 3;

// The reference is separable: the pixel's 1D profile k (box on [-1/2, 1/2] or tent on [-1, 1])
// in x and in y. Its distribution function F and kinks:
struct Profile {
  double halfWidth;
  double (*density)(double);
  double (*cdf)(double);
  std::vector<double> kinks;  // of F, and of the density inside the support; <= kMaxKinks
};

double BoxDensity(double) { return 1.0; }
double BoxCdf(double u) { return std::clamp(u + 0.5, 0.0, 1.0); }
double TentDensity(double y) { return 1.0 - std::fabs(y); }
double TentCdf(double u) {
  if (u <= -1.0) return 0.0;
  if (u <= 0.0) return 0.5 * (1.0 + u) * (1.0 + u);
  if (u < 1.0) return 1.0 - 0.5 * (1.0 - u) * (1.0 - u);
  return 1.0;
}

const Profile& ProfileOf(ReferenceFilter reference) {
  static const Profile box{0.5, BoxDensity, BoxCdf, {-0.5, 0.5}};
  static const Profile tent{1.0, TentDensity, TentCdf, {-1.0, 0.0, 1.0}};
  return reference == ReferenceFilter::kBox ? box : tent;
}

// Reference coverage of {p : p . n < t}: the projection is major * X + minor * Y with X, Y drawn
// from the profile (its symmetry drops the signs), so C(t) = int k(y) F((t - minor y) / major) dy,
// integrated exactly piece by piece between the kinks.
double Coverage(const Profile& profile, double major, double minor, double t) {
  if (minor == 0.0) return profile.cdf(t / major);
  const double r = profile.halfWidth;
  // Kept sorted by insertion: at most 2 + 2 * kMaxKinks cuts.
  std::array<double, 2 + 2 * kMaxKinks> cuts{-r, r};
  std::size_t count = 2;
  auto insert = [&](double cut) {
    std::size_t i = count++;
    for (; i > 0 && cuts[i - 1] > cut; --i) cuts[i] = cuts[i - 1];
    cuts[i] = cut;
  };
  for (const double kink : profile.kinks) {
    if (std::fabs(kink) < r) insert(kink);
    const double y = (t - major * kink) / minor;
    if (y > -r && y < r) insert(y);
  }
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < count; ++i) {
    const double mid = 0.5 * (cuts[i] + cuts[i + 1]), half = 0.5 * (cuts[i + 1] - cuts[i]);
    for (int g = 0; g < 3; ++g) {
      const double y = mid + half * kGauss3X[g];
      sum += kGauss3W[g] * half * profile.density(y) * profile.cdf((t - minor * y) / major);
    }
  }
  return sum;
}

// A, B, D and C at the table nodes t_k = -kTableHalfWidth + k * kTableStep, interleaved so one
// interpolation reads one cache line.
struct Node {
  double a = 0.0, b = 0.0, d = 0.0, c = 0.0;
};

struct AngleTable {
  double cosine = 1.0, sine = 0.0;
  double weight = 1.0;  // w(phi)
  std::vector<Node> nodes;
};

double OrientationWeight(double angle) { return 1.0 + kAxisEmphasis * std::cos(4.0 * angle); }

AngleTable MakeAngleTable(double angle, ReferenceFilter reference) {
  const Profile& profile = ProfileOf(reference);
  AngleTable table;
  table.cosine = std::cos(angle);
  table.sine = std::sin(angle);
  table.weight = OrientationWeight(angle);
  const double major = std::max(std::fabs(table.cosine), std::fabs(table.sine));
  const double minor = std::min(std::fabs(table.cosine), std::fabs(table.sine));
  auto coverage = [&](double t) { return Coverage(profile, major, minor, t); };
  std::vector<Node>& nodes = table.nodes;
  nodes.resize(kTableCells + 1);
  std::vector<double> cellD(kTableCells);
  for (int k = 0; k <= kTableCells; ++k) nodes[k].c = coverage(-kTableHalfWidth + k * kTableStep);
  for (int k = 0; k < kTableCells; ++k) {
    const double mid = -kTableHalfWidth + (k + 0.5) * kTableStep, half = 0.5 * kTableStep;
    double a = 0.0, b = 0.0, d = 0.0;
    for (int g = 0; g < 5; ++g) {
      const double value = coverage(mid + half * kGauss5X[g]), weight = kGauss5W[g] * half;
      a += weight * value * value;
      b += weight * value * (1.0 - value);
      d += weight * (1.0 - value) * (1.0 - value);
    }
    nodes[k + 1].a = nodes[k].a + a;
    nodes[k + 1].b = nodes[k].b + b;
    cellD[k] = d;
  }
  for (int k = kTableCells - 1; k >= 0; --k) nodes[k].d = nodes[k + 1].d + cellD[k];
  return table;
}

struct Interpolated {
  double a, b, d;
};

// Cubic Hermite with the exact derivatives A' = C^2, B' = C (1 - C), D' = -(1 - C)^2; outside
// the table C is 0 (left) or 1 (right), so A, B, D continue linearly or stay constant.
Interpolated Interpolate(const AngleTable& table, double s) {
  const std::vector<Node>& nodes = table.nodes;
  if (s <= -kTableHalfWidth) return {0.0, 0.0, nodes.front().d + (-kTableHalfWidth - s)};
  if (s >= kTableHalfWidth) return {nodes.back().a + (s - kTableHalfWidth), nodes.back().b, 0.0};
  const double position = (s + kTableHalfWidth) / kTableStep;
  const int k = std::min(static_cast<int>(position), kTableCells - 1);
  const double u = position - k, u2 = u * u, u3 = u2 * u;
  const double h00 = 2 * u3 - 3 * u2 + 1, h10 = (u3 - 2 * u2 + u) * kTableStep;
  const double h01 = -2 * u3 + 3 * u2, h11 = (u3 - u2) * kTableStep;
  const Node& n0 = nodes[k];
  const Node& n1 = nodes[k + 1];
  return {h00 * n0.a + h10 * n0.c * n0.c + h01 * n1.a + h11 * n1.c * n1.c,
          h00 * n0.b + h10 * n0.c * (1 - n0.c) + h01 * n1.b + h11 * n1.c * (1 - n1.c),
          h00 * n0.d - h10 * (1 - n0.c) * (1 - n0.c) + h01 * n1.d - h11 * (1 - n1.c) * (1 - n1.c)};
}

void CheckWeights(const Footprint& footprint) {
  double sum = 0.0;
  for (const FootprintSample& sample : footprint.samples) sum += sample.weight;
  if (footprint.samples.empty() || std::fabs(sum - 1.0) > kWeightSumTolerance) {
    throw std::invalid_argument("footprint weights sum to " + std::to_string(sum) + ", expected 1");
  }
}

struct Projected {
  double s, w;
  Interpolated f;
};

// `scratch` is reused across orientations: one allocation per footprint, not per orientation.
double EdgeErrorFromTable(const Footprint& footprint, const AngleTable& table, std::vector<Projected>& scratch) {
  const std::size_t n = footprint.samples.size();
  scratch.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const FootprintSample& sample = footprint.samples[i];
    const double s = sample.x * table.cosine + sample.y * table.sine;
    scratch[i] = {s, sample.weight, Interpolate(table, s)};
  }
  double error = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Projected& p = scratch[i];
    error += p.w * p.w * (p.f.a + p.f.d);
    for (std::size_t j = i + 1; j < n; ++j) {
      const Projected& q = scratch[j];
      const Projected& lo = p.s <= q.s ? p : q;
      const Projected& hi = p.s <= q.s ? q : p;
      error += 2 * p.w * q.w * (lo.f.a + hi.f.d - (hi.f.b - lo.f.b));
    }
  }
  return error;
}

double OrientationAngle(int k) { return (k + 0.5) * std::numbers::pi / kErrorOrientations; }

std::vector<AngleTable> BuildTables(ReferenceFilter reference) {
  std::vector<AngleTable> tables;
  tables.reserve(kErrorOrientations);
  for (int k = 0; k < kErrorOrientations; ++k) tables.push_back(MakeAngleTable(OrientationAngle(k), reference));
  return tables;
}

// Built on first use (about 0.06 s each), then shared read-only.
const std::vector<AngleTable>& Tables(ReferenceFilter reference) {
  if (reference == ReferenceFilter::kBox) {
    static const std::vector<AngleTable> box = BuildTables(ReferenceFilter::kBox);
    return box;
  }
  static const std::vector<AngleTable> tent = BuildTables(ReferenceFilter::kTent);
  return tent;
}

// The quad pixel of the neighbour (dx, dy) of quad pixel `quadPixel`.
int NeighbourQuadPixel(int quadPixel, int dx, int dy) {
  return QuadPixelIndex((quadPixel & 1) + dx + 2, (quadPixel >> 1) + dy + 2);
}

bool SameOffsets(const SamplePattern& a, const SamplePattern& b) {
  if (a.Count() != b.Count()) return false;
  for (int p = 0; p < kQuadPixels; ++p) {
    for (int s = 0; s < a.Count(); ++s) {
      if (a.Offset(p, s) != b.Offset(p, s)) return false;
    }
  }
  return true;
}

}  // namespace

const char* ReferenceFilterName(ReferenceFilter reference) {
  return reference == ReferenceFilter::kBox ? "box" : "tent";
}

Footprint BoxFootprint(const SamplePattern& pattern, int quadPixel) {
  Footprint footprint;
  const double weight = 1.0 / pattern.Count();
  for (int s = 0; s < pattern.Count(); ++s) {
    const SampleOffset o = pattern.Offset(quadPixel, s);
    footprint.samples.push_back({o.x * kSampleUnit, o.y * kSampleUnit, weight});
  }
  return footprint;
}

Footprint SharedFootprint(const SamplePattern& pattern, int quadPixel) {
  constexpr int kHalf = -kSampleOffsetMin;  // the pixel border, 8/16 px from the centre
  Footprint footprint;
  double total = 0.0;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      const int neighbour = NeighbourQuadPixel(quadPixel, dx, dy);
      for (int s = 0; s < pattern.Count(); ++s) {
        const SampleOffset o = pattern.Offset(neighbour, s);
        const int x = 2 * kHalf * dx + o.x, y = 2 * kHalf * dy + o.y;
        if (std::abs(x) > kHalf || std::abs(y) > kHalf) continue;
        // A point on a vertical (horizontal) border lies in two columns (rows) of pixels; the
        // sample's own offset is -8 exactly then.
        const int pixels = (o.x == kSampleOffsetMin ? 2 : 1) * (o.y == kSampleOffsetMin ? 2 : 1);
        footprint.samples.push_back({x * kSampleUnit, y * kSampleUnit, 1.0 / pixels});
        total += 1.0 / pixels;
      }
    }
  }
  for (FootprintSample& sample : footprint.samples) sample.weight /= total;
  return footprint;
}

bool IsSharedSamplePattern(const SamplePattern& pattern) {
  if (pattern.Count() != 2) return false;
  return SameOffsets(pattern, MakeBuiltinPattern("quincunx", 2)) ||
         SameOffsets(pattern, MakeBuiltinPattern("flipquad", 2));
}

std::array<Footprint, kQuadPixels> ResolveFootprints(const SamplePattern& pattern) {
  const bool shared = IsSharedSamplePattern(pattern);
  std::array<Footprint, kQuadPixels> footprints;
  for (int p = 0; p < kQuadPixels; ++p) {
    footprints[p] = shared ? SharedFootprint(pattern, p) : BoxFootprint(pattern, p);
  }
  return footprints;
}

double EdgeError(const Footprint& footprint, double normalAngle, ReferenceFilter reference) {
  CheckWeights(footprint);
  std::vector<Projected> scratch;
  return EdgeErrorFromTable(footprint, MakeAngleTable(normalAngle, reference), scratch);
}

double FootprintError(const Footprint& footprint, ReferenceFilter reference) {
  CheckWeights(footprint);
  const std::vector<AngleTable>& tables = Tables(reference);
  double weighted = 0.0, weights = 0.0;
  std::vector<Projected> scratch;
  for (const AngleTable& table : tables) {
    weighted += table.weight * EdgeErrorFromTable(footprint, table, scratch);
    weights += table.weight;
  }
  // Rounding must not make a perfect footprint's square root fail.
  return std::sqrt(std::max(0.0, 12.0 * weighted / weights));
}

double PatternError(const std::array<Footprint, kQuadPixels>& footprints, ReferenceFilter reference) {
  double sum = 0.0;
  for (const Footprint& footprint : footprints) {
    const double e = FootprintError(footprint, reference);
    sum += e * e;
  }
  return std::sqrt(sum / kQuadPixels);
}

double PatternError(const SamplePattern& pattern, ReferenceFilter reference) {
  return PatternError(ResolveFootprints(pattern), reference);
}

}  // namespace raster
