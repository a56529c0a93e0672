// The CRAA LUT generator and its fixture format (docs/craa.md "CRAA LUT").
//
// Fit: every configuration is a partition of the plane into 2 or 3 surfaces. For one image of
// it (one of its 8 mirror/rotation images, one draw order, one quad pixel of the centre) the
// centre's FMASK, own surface o and neighbours' stored surfaces s_n are known, and the LUT's
// predicted coverage of surface k is
//   p_k = [k = o] + sum_n (w_n / S) ([k = s_n] - [k = o]),
// so with d = e_o - area and v_n = e_{s_n} - e_o the squared error |p - area|^2 is
//   |d|^2 + (2 / S) sum_n w_n (v_n . d) + (1 / S^2) sum_nm w_n w_m (v_n . v_m).
// Per FMASK the generator sums v_n . v_m, v_n . d and |d|^2 in 64-bit integers (areas in units
// of 1/kAreaUnit), so the sums, and with them the table, do not depend on the thread count or
// the order the configurations are visited in; then it searches the integer weights exactly.

#include "passes/craa/craa_lut.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <span>

#include <nlohmann/json.hpp>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "raster/json_input.h"

namespace passes::craa {
namespace {

constexpr int kNeighbours = 4;  // up, bottom, left, right: the order of LutEntry
constexpr int kLegalSampleCounts[] = {1, 2, 4, 8, 16};

bool LegalSampleCount(int samples) { return std::ranges::find(kLegalSampleCounts, samples) != std::end(kLegalSampleCounts); }

// ---- Entry rules -----------------------------------------------------------------------------

int Weight(const LutEntry& entry, int n) {
  const std::array<int, kNeighbours> weights = {entry.up, entry.bottom, entry.left, entry.right};
  return weights[n];
}

// Empty when `entry` is legal for `fmask`, else the problem.
std::optional<std::string> EntryProblem(const LutEntry& entry, std::uint32_t fmask) {
  constexpr std::array<const char*, kNeighbours> kNames = {"up", "bottom", "left", "right"};
  for (int n = 0; n < kNeighbours; ++n) {
    if (Weight(entry, n) > kMaxLutWeight) {
      return std::string(kNames[n]) + " weight " + std::to_string(Weight(entry, n)) + " is above " +
             std::to_string(kMaxLutWeight);
    }
  }
  const int unknown = std::popcount(fmask);
  if (entry.Sum() > unknown) {
    return "weights sum to " + std::to_string(entry.Sum()) + " but the FMASK has " + std::to_string(unknown) +
           " UNKNOWN samples";
  }
  return std::nullopt;
}

std::optional<std::string> OffsetsProblem(const std::vector<raster::SampleOffset>& offsets, int samples) {
  if (std::ssize(offsets) != samples) {
    return "has " + std::to_string(offsets.size()) + " offsets, expected " + std::to_string(samples);
  }
  for (int s = 0; s < samples; ++s) {
    const raster::SampleOffset o = offsets[s];
    const auto onGrid = [](int v) { return v >= raster::kSampleOffsetMin && v <= raster::kSampleOffsetMax; };
    if (!onGrid(o.x) || !onGrid(o.y)) {
      return "sample " + std::to_string(s) + " offset (" + std::to_string(o.x) + ", " + std::to_string(o.y) +
             ") is off the sample grid -8..7";
    }
  }
  return std::nullopt;
}

}  // namespace

std::uint16_t PackLutEntry(const LutEntry& entry) {
  return static_cast<std::uint16_t>(entry.up | entry.bottom << 4 | entry.left << 8 | entry.right << 12);
}

LutEntry UnpackLutEntry(std::uint16_t packed) {
  const auto nibble = [packed](int shift) { return static_cast<std::uint8_t>((packed >> shift) & 0xF); };
  return {nibble(0), nibble(4), nibble(8), nibble(12)};
}

// ---- CraaLut ---------------------------------------------------------------------------------

CraaLut::CraaLut(std::string patternName, int samples, std::vector<std::vector<raster::SampleOffset>> offsets,
                 std::vector<LutEntry> entries, std::vector<LutEntrySource> sources)
    : patternName_(std::move(patternName)),
      samples_(samples),
      offsets_(std::move(offsets)),
      entries_(std::move(entries)),
      sources_(std::move(sources)) {
  const auto fail = [](const std::string& problem) { throw std::invalid_argument("CRAA LUT: " + problem); };
  if (!LegalSampleCount(samples_)) fail(std::to_string(samples_) + " samples; legal counts are 1, 2, 4, 8, 16");
  if (offsets_.size() != 1 && offsets_.size() != raster::kQuadPixels) fail("needs 1 or 4 tables");
  for (std::size_t t = 0; t < offsets_.size(); ++t) {
    if (auto problem = OffsetsProblem(offsets_[t], samples_)) fail("table " + std::to_string(t) + " " + *problem);
  }
  if (entries_.size() != offsets_.size() << samples_) fail("entry count does not match the tables");
  if (!sources_.empty() && sources_.size() != entries_.size()) fail("source count does not match the entries");
  const std::uint32_t mask = (1u << samples_) - 1;
  for (std::size_t i = 0; i < entries_.size(); ++i) {
    if (auto problem = EntryProblem(entries_[i], static_cast<std::uint32_t>(i) & mask)) {
      fail("entry " + std::to_string(i) + ": " + *problem);
    }
  }
}

std::size_t CraaLut::Index(int quadPixel, std::uint32_t fmask) const {
  if (quadPixel < 0 || quadPixel >= raster::kQuadPixels || fmask >= (1u << samples_)) {
    throw std::out_of_range("CRAA LUT: no entry for quad pixel " + std::to_string(quadPixel) + ", FMASK " +
                            std::to_string(fmask));
  }
  const std::size_t table = Tables() == 1 ? 0 : static_cast<std::size_t>(quadPixel);
  return (table << samples_) | fmask;
}

LutEntrySource CraaLut::Source(int quadPixel, std::uint32_t fmask) const {
  const std::size_t index = Index(quadPixel, fmask);
  if (!sources_.empty()) return sources_[index];
  return fmask == 0 ? LutEntrySource::kFixed : LutEntrySource::kFitted;
}

// ---- Generator -------------------------------------------------------------------------------

namespace {

// Areas are rounded to 1/kAreaUnit of a pixel: fine against the 1/S steps of the weights, and
// coarse enough that the integer sums cannot overflow (bounds at kMaxConfigurations).
constexpr std::int64_t kAreaUnit = std::int64_t{1} << 16;
// Bounds every accumulator: weight per FMASK <= 2^21 * 8 images * 6 orders < 2^27, so
// |M| < 2^28, |b| < 2^45, c < 2^61 and the search's 2 S (w . b) + kAreaUnit (w M w) < 2^58.
constexpr std::int64_t kMaxConfigurations = kMaxLutConfigurations;
constexpr int kSymmetries = 8;
constexpr int kMaxRegions = 3;
constexpr int kOrderWeight = 6;  // 3! : each configuration weighs the same whatever its surface count

struct Vec2 {
  double x = 0.0, y = 0.0;
};

// a x + b y + c >= 0 is inside.
struct HalfPlane {
  double a = 0.0, b = 0.0, c = 0.0;
  bool Inside(Vec2 p) const { return a * p.x + b * p.y + c >= 0.0; }
};

struct Shape {
  std::array<HalfPlane, 3> planes{};
  int count = 0;
  bool Inside(Vec2 p) const {
    for (int i = 0; i < count; ++i) {
      if (!planes[i].Inside(p)) return false;
    }
    return true;
  }
  void Add(HalfPlane plane) { planes[count++] = plane; }
};

// Region 0 is the background; region k >= 1 is shapes[k - 1] minus the shapes after it.
struct Configuration {
  int regions = 2;
  std::array<Shape, kMaxRegions - 1> shapes{};
  std::array<std::int64_t, kMaxRegions> area{};  // of the centre pixel, in 1/kAreaUnit

  int Label(Vec2 p) const {
    for (int k = regions - 1; k >= 1; --k) {
      if (shapes[k - 1].Inside(p)) return k;
    }
    return 0;
  }
};

// ---- Exact areas: the centre pixel [0, 1]^2 clipped by convex shapes ----

using Polygon = std::vector<Vec2>;

Polygon Clip(const Polygon& polygon, const HalfPlane& plane) {
  Polygon out;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Vec2 p = polygon[i], q = polygon[(i + 1) % polygon.size()];
    const double fp = plane.a * p.x + plane.b * p.y + plane.c;
    const double fq = plane.a * q.x + plane.b * q.y + plane.c;
    if (fp >= 0.0) out.push_back(p);
    if ((fp >= 0.0) != (fq >= 0.0)) {
      const double t = fp / (fp - fq);
      out.push_back({p.x + t * (q.x - p.x), p.y + t * (q.y - p.y)});
    }
  }
  return out;
}

double PixelArea(std::initializer_list<const Shape*> shapes) {
  Polygon polygon = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (const Shape* shape : shapes) {
    for (int i = 0; i < shape->count && !polygon.empty(); ++i) polygon = Clip(polygon, shape->planes[i]);
  }
  double twice = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Vec2 p = polygon[i], q = polygon[(i + 1) % polygon.size()];
    twice += p.x * q.y - q.x * p.y;
  }
  return std::abs(twice) / 2.0;
}

std::int64_t ToAreaUnits(double area) {
  return std::llround(std::clamp(area, 0.0, 1.0) * static_cast<double>(kAreaUnit));
}

void ComputeAreas(Configuration& config) {
  const Shape& s1 = config.shapes[0];
  std::int64_t top = 0, middle = ToAreaUnits(PixelArea({&s1}));
  if (config.regions == 3) {
    const Shape& s2 = config.shapes[1];
    top = ToAreaUnits(PixelArea({&s2}));
    middle = std::max<std::int64_t>(0, middle - ToAreaUnits(PixelArea({&s1, &s2})));
  }
  config.area = {std::max<std::int64_t>(0, kAreaUnit - middle - top), middle, top};
}

// ---- Configuration families (docs/craa.md "Configurations") ----

// Counter-based uniform numbers in [0, 1): configuration i's numbers never depend on which
// thread builds it.
class Random {
 public:
  Random(std::uint64_t seed, int family, std::int64_t index)
      : state_(seed ^ (static_cast<std::uint64_t>(family) << 56) ^ (static_cast<std::uint64_t>(index) << 8)) {}
  double Next() { return static_cast<double>(Mix(state_++) >> 11) * 0x1.0p-53; }

 private:
  static std::uint64_t Mix(std::uint64_t z) {  // splitmix64's finaliser
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return (z ^ (z >> 29)) * 0x9E3779B97F4A7C15ull;
  }
  std::uint64_t state_;
};

constexpr Vec2 kCentre = {0.5, 0.5};
constexpr double kPi = std::numbers::pi;

// Points on the side n . (p - centre) >= t.
HalfPlane Side(double angle, double t) {
  const double nx = std::cos(angle), ny = std::sin(angle);
  return {nx, ny, -(nx * kCentre.x + ny * kCentre.y) - t};
}

// Half the pixel's extent along the normal at `angle`: lines at |t| < this cross the pixel.
double Reach(double angle) { return (std::abs(std::cos(angle)) + std::abs(std::sin(angle))) / 2.0; }

Shape EdgeShape(Random& random) {
  const double angle = kPi * random.Next();
  Shape shape;
  shape.Add(Side(angle, Reach(angle) * (2.0 * random.Next() - 1.0)));
  return shape;
}

Shape SliverShape(Random& random, double maxWidth) {
  const double angle = kPi * random.Next();
  const double width = maxWidth * (1.0 - random.Next());
  const double reach = Reach(angle) + width / 2.0;
  const double t = reach * (2.0 * random.Next() - 1.0);
  Shape shape;
  shape.Add(Side(angle, t - width / 2.0));
  shape.Add(Side(angle + kPi, -t - width / 2.0));
  return shape;
}

// The wedge swept counter-clockwise (in +y-down coordinates, clockwise on screen) from `from` to
// `from + opening`, opening < pi, so it is the intersection of two half-planes.
Shape WedgeShape(Vec2 apex, double from, double opening) {
  const double to = from + opening;
  HalfPlane first{-std::sin(from), std::cos(from), 0.0};
  HalfPlane second{std::sin(to), -std::cos(to), 0.0};
  for (HalfPlane* plane : {&first, &second}) plane->c = -(plane->a * apex.x + plane->b * apex.y);
  Shape shape;
  shape.Add(first);
  shape.Add(second);
  return shape;
}

Vec2 RandomPoint(Random& random, double lo, double hi) {
  const double x = lo + (hi - lo) * random.Next();
  return {x, lo + (hi - lo) * random.Next()};
}

Configuration Edge(Random& random, const LutGeneratorSettings&) {
  Configuration config;
  config.shapes[0] = EdgeShape(random);
  return config;
}

Configuration Corner(Random& random, const LutGeneratorSettings& settings) {
  const Vec2 apex = RandomPoint(random, -settings.apexMargin, 1.0 + settings.apexMargin);
  const double from = 2.0 * kPi * random.Next();
  Configuration config;
  config.shapes[0] = WedgeShape(apex, from, kPi * random.Next());
  return config;
}

// Three rays from a point inside the pixel; the widest of the three sectors (the only one that
// can exceed pi) is the background, so the other two are convex wedges.
Configuration Junction(Random& random, const LutGeneratorSettings&) {
  const Vec2 apex = RandomPoint(random, 0.0, 1.0);
  std::array<double, 3> rays{};
  for (double& ray : rays) ray = 2.0 * kPi * random.Next();
  std::ranges::sort(rays);
  const std::array<double, 3> gaps = {rays[1] - rays[0], rays[2] - rays[1], 2.0 * kPi - (rays[2] - rays[0])};
  const int widest = static_cast<int>(std::ranges::max_element(gaps) - gaps.begin());
  Configuration config;
  config.regions = 3;
  for (int k = 0; k < 2; ++k) {
    const int sector = (widest + 1 + k) % 3;
    config.shapes[k] = WedgeShape(apex, rays[sector], gaps[sector]);
  }
  return config;
}

Configuration Sliver(Random& random, const LutGeneratorSettings& settings) {
  Configuration config;
  config.shapes[0] = SliverShape(random, settings.maxSliverWidth);
  return config;
}

Configuration SliverEdge(Random& random, const LutGeneratorSettings& settings) {
  Configuration config;
  config.regions = 3;
  config.shapes[0] = EdgeShape(random);
  config.shapes[1] = SliverShape(random, settings.maxSliverWidth);
  return config;
}

// Vertices anywhere in the 3x3 neighbourhood [-1, 2]^2.
Configuration Triangle(Random& random, const LutGeneratorSettings&) {
  std::array<Vec2, 3> v = {RandomPoint(random, -1.0, 2.0), RandomPoint(random, -1.0, 2.0),
                           RandomPoint(random, -1.0, 2.0)};
  const double turn = (v[1].x - v[0].x) * (v[2].y - v[0].y) - (v[1].y - v[0].y) * (v[2].x - v[0].x);
  if (turn < 0.0) std::swap(v[1], v[2]);
  Configuration config;
  for (int i = 0; i < 3; ++i) {
    const Vec2 p = v[i], q = v[(i + 1) % 3];
    // Inside is to the left of p -> q when the turn is positive.
    config.shapes[0].Add({-(q.y - p.y), q.x - p.x, (q.y - p.y) * p.x - (q.x - p.x) * p.y});
  }
  return config;
}

using Family = Configuration (*)(Random&, const LutGeneratorSettings&);

struct FamilyCount {
  Family make;
  int count;
};

std::array<FamilyCount, 6> Families(const LutGeneratorSettings& s) {
  return {{{Edge, s.edges},
           {Corner, s.corners},
           {Junction, s.junctions},
           {Sliver, s.slivers},
           {SliverEdge, s.sliverEdges},
           {Triangle, s.triangles}}};
}

Configuration MakeConfiguration(const LutGeneratorSettings& settings, std::int64_t index) {
  int family = 0;
  for (const FamilyCount& entry : Families(settings)) {
    if (index < entry.count) {
      Random random(settings.seed, family, index);
      Configuration config = entry.make(random, settings);
      ComputeAreas(config);
      return config;
    }
    index -= entry.count;
    ++family;
  }
  return {};  // unreachable: index < the total count
}

std::int64_t TotalConfigurations(const LutGeneratorSettings& settings) {
  std::int64_t total = 0;
  for (const FamilyCount& entry : Families(settings)) total += entry.count;
  return total;
}

void ValidateSettings(const LutGeneratorSettings& s) {
  const auto fail = [](const std::string& problem) {
    throw std::invalid_argument("CRAA LUT generator: " + problem);
  };
  for (const FamilyCount& entry : Families(s)) {
    if (entry.count < 0) fail("configuration counts must be >= 0");
  }
  const std::int64_t total = TotalConfigurations(s);
  if (total < 1 || total > kMaxConfigurations) {
    fail("needs 1.." + std::to_string(kMaxConfigurations) + " configurations, has " + std::to_string(total));
  }
  if (!(s.maxSliverWidth > 0.0 && s.maxSliverWidth <= 1.0)) fail("maxSliverWidth must be in (0, 1]");
  if (!(s.apexMargin >= 0.0 && s.apexMargin <= 1.0)) fail("apexMargin must be in [0, 1]");
  if (s.threads < 0) fail("threads must be >= 0");
}

// ---- Sampling the configurations ----

// Pixel 0 is the centre, then the neighbours in LutEntry order; their centres relative to the
// centre pixel's (+y down).
constexpr std::array<Vec2, 1 + kNeighbours> kPixelCentres = {{{0, 0}, {0, -1}, {0, 1}, {-1, 0}, {1, 0}}};
constexpr int kPixels = 1 + kNeighbours;

// The 8 maps of the square onto itself (about the centre pixel's centre): configuration image
// u samples the configuration at Symmetry(u, p) for every sample point p.
Vec2 Symmetry(int u, Vec2 p) {
  if (u & 4) std::swap(p.x, p.y);
  if (u & 1) p.x = -p.x;
  if (u & 2) p.y = -p.y;
  return {kCentre.x + p.x, kCentre.y + p.y};
}

// The quad pixel of neighbour n when the centre is quad pixel q (raster::QuadPixelIndex).
int NeighbourQuadPixel(int q, int pixel) {
  constexpr std::array<int, kPixels> kFlip = {0, 2, 2, 1, 1};
  return q ^ kFlip[pixel];
}

// Where configuration image u is sampled, for a centre in quad pixel q: [pixel][sample].
using SamplePoints = std::array<std::array<Vec2, raster::kMaxCoverageSamples>, kPixels>;

SamplePoints MakeSamplePoints(const raster::SamplePattern& pattern, int q, int u) {
  SamplePoints points{};
  for (int pixel = 0; pixel < kPixels; ++pixel) {
    const int neighbourQuad = NeighbourQuadPixel(q, pixel);
    for (int s = 0; s < pattern.Count(); ++s) {
      const raster::SampleOffset o = pattern.Offset(neighbourQuad, s);
      const Vec2 local = {kPixelCentres[pixel].x + o.x / 16.0, kPixelCentres[pixel].y + o.y / 16.0};
      points[pixel][s] = Symmetry(u, local);
    }
  }
  return points;
}

// Per table and FMASK: the sums of the quadratic error (see the file comment).
struct Sums {
  std::int64_t weight = 0;
  std::array<std::int64_t, kNeighbours * kNeighbours> vv{};  // v_n . v_m
  std::array<std::int64_t, kNeighbours> vd{};                // v_n . d
  std::int64_t dd = 0;                                       // |d|^2
};

using SumTable = std::vector<Sums>;

void AddSums(SumTable& into, const SumTable& from) {
  for (std::size_t i = 0; i < into.size(); ++i) {
    Sums& a = into[i];
    const Sums& b = from[i];
    a.weight += b.weight;
    for (std::size_t k = 0; k < a.vv.size(); ++k) a.vv[k] += b.vv[k];
    for (std::size_t k = 0; k < a.vd.size(); ++k) a.vd[k] += b.vd[k];
    a.dd += b.dd;
  }
}

// One draw order: rank[k] = when surface k is drawn (the last-drawn covering surface is stored).
using Order = std::array<int, kMaxRegions>;

std::vector<Order> DrawOrders(int regions) {
  Order order = {0, 1, 2};
  std::vector<Order> orders;
  do {
    orders.push_back(order);
  } while (std::next_permutation(order.begin(), order.begin() + regions));
  return orders;
}

// The stored surface of a pixel where `present` (bit k = surface k covers a sample) is visible.
int Stored(unsigned present, const Order& rank) {
  int stored = -1;
  for (int k = 0; k < kMaxRegions; ++k) {
    if ((present >> k & 1u) && (stored < 0 || rank[k] > rank[stored])) stored = k;
  }
  return stored;
}

void Accumulate(Sums& sums, const Configuration& config, int own, const std::array<int, kNeighbours>& stored,
                std::int64_t weight) {
  std::array<std::int64_t, kMaxRegions> d{};
  std::int64_t dd = 0;
  for (int k = 0; k < config.regions; ++k) {
    d[k] = (k == own ? kAreaUnit : 0) - config.area[k];
    dd += d[k] * d[k];
  }
  sums.weight += weight;
  sums.dd += weight * dd;
  for (int n = 0; n < kNeighbours; ++n) {
    if (stored[n] == own) continue;  // v_n = 0
    sums.vd[n] += weight * (d[stored[n]] - d[own]);
    for (int m = 0; m < kNeighbours; ++m) {
      if (stored[m] == own) continue;
      sums.vv[n * kNeighbours + m] += weight * ((stored[n] == stored[m] ? 1 : 0) + 1);
    }
  }
}

struct Evaluator {
  const raster::SamplePattern& pattern;
  int tables;
  std::vector<SamplePoints> points;  // [table * kSymmetries + u]
  std::array<std::vector<Order>, kMaxRegions + 1> orders;

  Evaluator(const raster::SamplePattern& p, int t) : pattern(p), tables(t) {
    for (int q = 0; q < tables; ++q) {
      for (int u = 0; u < kSymmetries; ++u) points.push_back(MakeSamplePoints(pattern, q, u));
    }
    orders[2] = DrawOrders(2);
    orders[3] = DrawOrders(3);
  }

  void Evaluate(const Configuration& config, SumTable& sums) const {
    const int samples = pattern.Count();
    const std::int64_t weight = kOrderWeight / std::ssize(orders[config.regions]);
    for (int q = 0; q < tables; ++q) {
      for (int u = 0; u < kSymmetries; ++u) {
        const SamplePoints& at = points[q * kSymmetries + u];
        std::array<unsigned, kPixels> present{};
        std::array<std::uint32_t, kMaxRegions> centreMask{};
        for (int pixel = 0; pixel < kPixels; ++pixel) {
          for (int s = 0; s < samples; ++s) {
            const int label = config.Label(at[pixel][s]);
            present[pixel] |= 1u << label;
            if (pixel == 0) centreMask[label] |= 1u << s;
          }
        }
        for (const Order& rank : orders[config.regions]) {
          const int own = Stored(present[0], rank);
          std::array<int, kNeighbours> stored{};
          for (int n = 0; n < kNeighbours; ++n) stored[n] = Stored(present[1 + n], rank);
          const std::uint32_t fmask = ~centreMask[own] & ((1u << samples) - 1);
          Accumulate(sums[(static_cast<std::size_t>(q) << samples) | fmask], config, own, stored, weight);
        }
      }
    }
  }
};

SumTable SumConfigurations(const raster::SamplePattern& pattern, int tables, const LutGeneratorSettings& settings) {
  const std::size_t size = static_cast<std::size_t>(tables) << pattern.Count();
  const Evaluator evaluator(pattern, tables);
  tbb::enumerable_thread_specific<SumTable> perThread([size] { return SumTable(size); });
  const std::int64_t total = TotalConfigurations(settings);
  tbb::parallel_for(tbb::blocked_range<std::int64_t>(0, total, 256), [&](const tbb::blocked_range<std::int64_t>& r) {
    SumTable& sums = perThread.local();
    for (std::int64_t i = r.begin(); i != r.end(); ++i) evaluator.Evaluate(MakeConfiguration(settings, i), sums);
  });
  // Integer sums: the order they are combined in does not matter.
  SumTable sums(size);
  perThread.combine_each([&](const SumTable& part) { AddSums(sums, part); });
  return sums;
}

// ---- Fit ----

// S^2 kAreaUnit times the summed squared error, less the constant S^2 |d|^2 / kAreaUnit:
// 2 S (w . vd) + kAreaUnit (w vv w), exact in 64 bits (bounds at kMaxConfigurations).
std::int64_t Objective(const Sums& sums, const std::array<int, kNeighbours>& w, int samples) {
  std::int64_t linear = 0, quadratic = 0;
  for (int n = 0; n < kNeighbours; ++n) {
    linear += w[n] * sums.vd[n];
    for (int m = 0; m < kNeighbours; ++m) quadratic += w[n] * w[m] * sums.vv[n * kNeighbours + m];
  }
  return 2 * samples * linear + kAreaUnit * quadratic;
}

// The squared error of weights `w` summed over the evaluations in `sums` (times their weights).
double TotalError(const Sums& sums, const std::array<int, kNeighbours>& w, int samples) {
  const double unit = static_cast<double>(kAreaUnit);
  const double squareSamples = static_cast<double>(samples) * samples;
  return (static_cast<double>(sums.dd) / unit + static_cast<double>(Objective(sums, w, samples)) / squareSamples) /
         unit;
}

LutEntry ToEntry(const std::array<int, kNeighbours>& w) {
  return {static_cast<std::uint8_t>(w[0]), static_cast<std::uint8_t>(w[1]), static_cast<std::uint8_t>(w[2]),
          static_cast<std::uint8_t>(w[3])};
}

// Exact search of the weights with w_n <= 15 and sum <= the UNKNOWN samples. Ties go to the
// smaller sum (fewer samples moved), then to the lexicographically largest (up, bottom, left,
// right), so a tie between a vertical and a horizontal neighbour goes to the vertical one, as in
// NearestEdge. The loops visit weights in increasing lexicographic order.
std::array<int, kNeighbours> Fit(const Sums& sums, int unknown, int samples) {
  const int cap = std::min(kMaxLutWeight, unknown);
  std::array<int, kNeighbours> best{}, w{};
  std::int64_t bestValue = 0;
  for (w[0] = 0; w[0] <= cap; ++w[0]) {
    for (w[1] = 0; w[1] <= std::min(cap, unknown - w[0]); ++w[1]) {
      for (w[2] = 0; w[2] <= std::min(cap, unknown - w[0] - w[1]); ++w[2]) {
        for (w[3] = 0; w[3] <= std::min(cap, unknown - w[0] - w[1] - w[2]); ++w[3]) {
          const std::int64_t value = Objective(sums, w, samples);
          const int sum = w[0] + w[1] + w[2] + w[3];
          const int bestSum = best[0] + best[1] + best[2] + best[3];
          if (value < bestValue || (value == bestValue && sum <= bestSum)) {
            bestValue = value;
            best = w;
          }
        }
      }
    }
  }
  return best;
}

// FMASK values no configuration produced: every UNKNOWN sample goes to the neighbour across the
// pixel edge nearest to it (vertical neighbours on |y| == |x| ties; a sample at the centre stays
// own), each weight capped at 15.
std::array<int, kNeighbours> NearestEdge(const std::vector<raster::SampleOffset>& offsets, std::uint32_t fmask) {
  std::array<int, kNeighbours> w{};
  for (std::size_t s = 0; s < offsets.size(); ++s) {
    if (!(fmask >> s & 1u)) continue;
    const raster::SampleOffset o = offsets[s];
    if (o.x == 0 && o.y == 0) continue;
    const int n = std::abs(o.y) >= std::abs(o.x) ? (o.y < 0 ? 0 : 1) : (o.x < 0 ? 2 : 3);
    w[n] = std::min(w[n] + 1, kMaxLutWeight);
  }
  return w;
}

std::vector<std::vector<raster::SampleOffset>> TableOffsets(const raster::SamplePattern& pattern, int tables) {
  std::vector<std::vector<raster::SampleOffset>> offsets(static_cast<std::size_t>(tables));
  for (int q = 0; q < tables; ++q) {
    for (int s = 0; s < pattern.Count(); ++s) offsets[q].push_back(pattern.Offset(q, s));
  }
  return offsets;
}

}  // namespace

LutGeneratorSettings WithConfigurations(LutGeneratorSettings settings, std::int64_t total) {
  // Tenths: edges, corners, junctions and slivers 2 each, sliver-edges and triangles 1 each; the
  // rounding remainder goes to the edges.
  const auto part = [total](int tenths) { return static_cast<int>(total * tenths / 10); };
  settings.corners = settings.junctions = settings.slivers = part(2);
  settings.sliverEdges = settings.triangles = part(1);
  settings.edges = static_cast<int>(total - 3 * std::int64_t{part(2)} - 2 * std::int64_t{part(1)});
  return settings;
}

GeneratedCraaLut GenerateCraaLutWithSummary(const raster::SamplePattern& pattern,
                                            const LutGeneratorSettings& settings) {
  ValidateSettings(settings);
  const int samples = pattern.Count();
  const int tables = pattern.SameInAllPixels() ? 1 : raster::kQuadPixels;
  tbb::task_arena arena(settings.threads == 0 ? tbb::task_arena::automatic : settings.threads);
  const SumTable sums = arena.execute([&] { return SumConfigurations(pattern, tables, settings); });

  const auto offsets = TableOffsets(pattern, tables);
  std::vector<LutEntry> entries(sums.size());
  std::vector<LutEntrySource> sources(sums.size());
  arena.execute([&] {
    tbb::parallel_for(std::size_t{0}, sums.size(), [&](std::size_t i) {
      const std::uint32_t fmask = static_cast<std::uint32_t>(i) & ((1u << samples) - 1);
      if (fmask == 0) {
        sources[i] = LutEntrySource::kFixed;
      } else if (sums[i].weight == 0) {
        sources[i] = LutEntrySource::kFallback;
        entries[i] = ToEntry(NearestEdge(offsets[i >> samples], fmask));
      } else {
        sources[i] = LutEntrySource::kFitted;
        entries[i] = ToEntry(Fit(sums[i], std::popcount(fmask), samples));
      }
    });
  });

  LutFitSummary summary;
  std::vector<double> entryError(sums.size());
  double error = 0.0, allOwn = 0.0, weight = 0.0;
  for (std::size_t i = 0; i < sums.size(); ++i) {
    summary.fitted += sources[i] == LutEntrySource::kFitted ? 1 : 0;
    summary.fallbacks += sources[i] == LutEntrySource::kFallback ? 1 : 0;
    const LutEntry& e = entries[i];
    const double entryTotal = TotalError(sums[i], {e.up, e.bottom, e.left, e.right}, samples);
    if (sums[i].weight > 0) entryError[i] = entryTotal / static_cast<double>(sums[i].weight);
    error += entryTotal;
    allOwn += TotalError(sums[i], {}, samples);
    weight += static_cast<double>(sums[i].weight);
  }
  summary.evaluations = static_cast<std::uint64_t>(TotalConfigurations(settings)) * kSymmetries *
                        static_cast<std::uint64_t>(tables);
  summary.meanError = error / weight;
  summary.meanErrorAllOwn = allOwn / weight;
  return {CraaLut(pattern.Name(), samples, offsets, std::move(entries), std::move(sources)), summary,
          std::move(entryError)};
}

CraaLut GenerateCraaLut(const raster::SamplePattern& pattern, const LutGeneratorSettings& settings) {
  return GenerateCraaLutWithSummary(pattern, settings).lut;
}

// ---- Fixture format (docs/craa.md "File format") ----------------------------------------------

namespace {

constexpr int kEntriesPerLine = 8;

std::string JsonString(const std::string& text) {
  return nlohmann::json(text).dump(-1, ' ', /*ensure_ascii=*/false, nlohmann::json::error_handler_t::replace);
}

// Appended piece by piece: GCC 12 flags `"literal" + string` with a false -Wrestrict.
void AppendList(std::string& out, std::initializer_list<int> values) {
  out += '[';
  for (const int v : values) {
    if (out.back() != '[') out += ", ";
    out += std::to_string(v);
  }
  out += ']';
}

void FormatTable(std::string& out, const CraaLut& lut, int t) {
  out += "    {\n      \"offsets\": [";
  for (const raster::SampleOffset o : lut.Offsets(t)) {
    if (out.back() != '[') out += ", ";
    AppendList(out, {o.x, o.y});
  }
  out += "],\n      \"fallback\": [";
  for (int f = 0; f < lut.EntriesPerTable(); ++f) {
    if (lut.Source(t, static_cast<std::uint32_t>(f)) != LutEntrySource::kFallback) continue;
    if (out.back() != '[') out += ", ";
    out += std::to_string(f);
  }
  out += "],\n      \"entries\": [";
  for (int f = 0; f < lut.EntriesPerTable(); ++f) {
    const LutEntry& e = lut.Entry(t, static_cast<std::uint32_t>(f));
    if (f > 0) out += ',';
    out += f % kEntriesPerLine == 0 ? "\n        " : " ";
    AppendList(out, {e.up, e.bottom, e.left, e.right});
  }
  out += "\n      ]\n    }";
}

const std::array<std::string_view, 5> kRootKeys = {"schema", "version", "pattern", "samples", "tables"};
const std::array<std::string_view, 3> kTableKeys = {"offsets", "fallback", "entries"};

std::string KeyList(std::span<const std::string_view> keys) {
  std::string list;
  for (const std::string_view key : keys) list += (list.empty() ? "" : ", ") + std::string(key);
  return list;
}

class LutFileParser {
 public:
  explicit LutFileParser(std::string_view source) : source_(source) {}

  CraaLut Parse(std::string_view text) const {
    nlohmann::json root;
    try {
      root = raster::ParseJsonText(text, /*allowComments=*/false);
    } catch (const raster::JsonTextError& e) {
      Fail("", e.what());
    }
    if (!root.is_object()) Fail("", "must hold one JSON object, found " + raster::JsonExcerpt(root));
    CheckKeys(root, kRootKeys, "");
    const nlohmann::json& schema = Required(root, "schema", "");
    if (schema != kCraaLutSchema) Fail("", "has schema " + raster::JsonExcerpt(schema) + ", expected \"" + kCraaLutSchema + "\"");
    const nlohmann::json& version = Required(root, "version", "");
    if (version != kCraaLutVersion) {
      Fail("", "has version " + raster::JsonExcerpt(version) + ", expected " + std::to_string(kCraaLutVersion));
    }
    const nlohmann::json& pattern = Required(root, "pattern", "");
    if (!pattern.is_string() || pattern.get_ref<const std::string&>().empty()) {
      Fail("", "needs \"pattern\" to be a non-empty string, found " + raster::JsonExcerpt(pattern));
    }
    const int samples = Samples(Required(root, "samples", ""));
    const nlohmann::json& tables = Required(root, "tables", "");
    if (!tables.is_array() || (tables.size() != 1 && tables.size() != raster::kQuadPixels)) {
      Fail("", "needs \"tables\" to be a list of 1 or 4 tables, found " + raster::JsonExcerpt(tables));
    }
    std::vector<std::vector<raster::SampleOffset>> offsets;
    std::vector<LutEntry> entries;
    std::vector<LutEntrySource> sources;
    for (std::size_t t = 0; t < tables.size(); ++t) {
      ParseTable(tables[t], static_cast<int>(t), samples, offsets, entries, sources);
    }
    try {
      return CraaLut(pattern.get<std::string>(), samples, std::move(offsets), std::move(entries), std::move(sources));
    } catch (const std::invalid_argument& e) {
      Fail("", e.what());  // unreachable: every rule of the constructor is checked above
    }
  }

 private:
  // "craa lut 'f.json': <where> <problem>" (or without the where).
  [[noreturn]] void Fail(const std::string& where, const std::string& problem) const {
    throw CraaLutError("CRAA LUT file '" + source_ + "'" + (where.empty() ? " " : ": " + where + " ") + problem);
  }

  void CheckKeys(const nlohmann::json& object, std::span<const std::string_view> keys, const std::string& where) const {
    for (const auto& item : object.items()) {
      if (std::ranges::find(keys, item.key()) == keys.end()) {
        Fail(where, "has unknown key \"" + item.key().substr(0, raster::kMaxJsonExcerpt) + "\"; the keys are " +
                        KeyList(keys));
      }
    }
  }

  const nlohmann::json& Required(const nlohmann::json& object, const char* key, const std::string& where) const {
    if (!object.contains(key)) Fail(where, std::string("has no \"") + key + "\" key");
    return object.at(key);
  }

  int Samples(const nlohmann::json& samples) const {
    if (!samples.is_number_integer() || !LegalSampleCount(static_cast<int>(std::clamp<std::int64_t>(
                                            samples.get<std::int64_t>(), 0, 64)))) {
      Fail("", "needs \"samples\" to be 1, 2, 4, 8 or 16, found " + raster::JsonExcerpt(samples));
    }
    return samples.get<int>();
  }

  // An integer in [lo, hi], else a failure naming `what`.
  int Integer(const nlohmann::json& value, int lo, int hi, const std::string& where, const std::string& what) const {
    if (!value.is_number_integer() || value.get<std::int64_t>() < lo || value.get<std::int64_t>() > hi) {
      Fail(where, what + " must be an integer in " + std::to_string(lo) + ".." + std::to_string(hi) + ", found " +
                      raster::JsonExcerpt(value));
    }
    return value.get<int>();
  }

  void ParseTable(const nlohmann::json& table, int t, int samples, std::vector<std::vector<raster::SampleOffset>>& offsets,
                  std::vector<LutEntry>& entries, std::vector<LutEntrySource>& sources) const {
    const std::string where = "table " + std::to_string(t);
    if (!table.is_object()) Fail(where, "must be an object, found " + raster::JsonExcerpt(table));
    CheckKeys(table, kTableKeys, where);
    offsets.push_back(ParseOffsets(Required(table, "offsets", where), samples, where));
    const std::vector<LutEntrySource> tableSources =
        ParseFallback(table.contains("fallback") ? table.at("fallback") : nlohmann::json::array(), samples, where);
    sources.insert(sources.end(), tableSources.begin(), tableSources.end());
    const nlohmann::json& list = Required(table, "entries", where);
    const int count = 1 << samples;
    if (!list.is_array() || std::ssize(list) != count) {
      Fail(where, "needs \"entries\" to be a list of " + std::to_string(count) + " entries, found " +
                      raster::JsonExcerpt(list));
    }
    for (int f = 0; f < count; ++f) entries.push_back(ParseEntry(list[f], f, where));
  }

  std::vector<raster::SampleOffset> ParseOffsets(const nlohmann::json& list, int samples, const std::string& where) const {
    if (!list.is_array() || std::ssize(list) != samples) {
      Fail(where, "needs \"offsets\" to be a list of " + std::to_string(samples) + " [x, y] pairs, found " +
                      raster::JsonExcerpt(list));
    }
    std::vector<raster::SampleOffset> offsets;
    for (int s = 0; s < samples; ++s) {
      const std::string at = where + " sample " + std::to_string(s);
      const nlohmann::json& pair = list[s];
      if (!pair.is_array() || pair.size() != 2) Fail(at, "must be an [x, y] pair, found " + raster::JsonExcerpt(pair));
      offsets.push_back({Integer(pair[0], raster::kSampleOffsetMin, raster::kSampleOffsetMax, at, "x"),
                         Integer(pair[1], raster::kSampleOffsetMin, raster::kSampleOffsetMax, at, "y")});
    }
    return offsets;
  }

  std::vector<LutEntrySource> ParseFallback(const nlohmann::json& list, int samples, const std::string& where) const {
    const int count = 1 << samples;
    if (!list.is_array()) Fail(where, "needs \"fallback\" to be a list of FMASK values, found " + raster::JsonExcerpt(list));
    std::vector<LutEntrySource> sources = {LutEntrySource::kFixed};  // FMASK 0
    sources.resize(static_cast<std::size_t>(count), LutEntrySource::kFitted);
    int previous = 0;
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string at = where + " fallback " + std::to_string(i);
      const int fmask = Integer(list[i], 1, count - 1, at, "an FMASK value");
      if (fmask <= previous) Fail(at, "must be above the one before it (" + std::to_string(previous) + ")");
      sources[fmask] = LutEntrySource::kFallback;
      previous = fmask;
    }
    return sources;
  }

  LutEntry ParseEntry(const nlohmann::json& value, int fmask, const std::string& table) const {
    const std::string where = table + " entry " + std::to_string(fmask);
    if (!value.is_array() || value.size() != kNeighbours) {
      Fail(where, "must be an [up, bottom, left, right] list of 4 weights, found " + raster::JsonExcerpt(value));
    }
    const LutEntry entry = {static_cast<std::uint8_t>(Integer(value[0], 0, kMaxLutWeight, where, "up")),
                            static_cast<std::uint8_t>(Integer(value[1], 0, kMaxLutWeight, where, "bottom")),
                            static_cast<std::uint8_t>(Integer(value[2], 0, kMaxLutWeight, where, "left")),
                            static_cast<std::uint8_t>(Integer(value[3], 0, kMaxLutWeight, where, "right"))};
    if (auto problem = EntryProblem(entry, static_cast<std::uint32_t>(fmask))) Fail(where, *problem);
    return entry;
  }

  std::string source_;
};

}  // namespace

std::string FormatCraaLut(const CraaLut& lut) {
  std::string out = "{\n  \"schema\": \"";
  out += kCraaLutSchema;
  out += "\",\n  \"version\": ";
  out += std::to_string(kCraaLutVersion);
  out += ",\n  \"pattern\": ";
  out += JsonString(lut.PatternName());
  out += ",\n  \"samples\": ";
  out += std::to_string(lut.Samples());
  out += ",\n  \"tables\": [\n";
  for (int t = 0; t < lut.Tables(); ++t) {
    if (t) out += ",\n";
    FormatTable(out, lut, t);
  }
  out += "\n  ]\n}\n";
  return out;
}

CraaLut ParseCraaLut(std::string_view text, std::string_view sourceName) {
  return LutFileParser(sourceName).Parse(text);
}

}  // namespace passes::craa
