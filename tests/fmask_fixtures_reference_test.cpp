// Every byte of every fixture (except the PNG preview's encoding) re-derived by a second,
// deliberately slow implementation written from docs/fixtures.md, docs/raster.md and
// docs/eqaa.md alone: it shares no code with raster/ or fmask/ beyond the case list and the
// sample offsets, which a reader takes from the manifest. A difference means the documents are
// wrong or silent about something the fixtures depend on.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "fmask/fixtures.h"
#include "raster/sample_pattern.h"

namespace {

using Bytes = std::vector<std::uint8_t>;
using Rgba = std::array<std::uint8_t, 4>;

constexpr int kTileSize = 8;  // every case is one 8x8 tile
constexpr int kMaxPlanes = 4;
constexpr float kClearDepth = 1.0f;
constexpr Rgba kClearColour{0, 0, 0, 255};

// docs/fixtures.md, "fmask.bin": bits per sample and element size by S and F.
int BitsPerSample(int s, int f) {
  if (f == 1) return 1;
  if (f == 2) return s == 2 ? 1 : 2;
  if (f == 4) return s == 4 ? 2 : 4;
  return 4;
}

// docs/raster.md, "Triangle setup".
struct Vertex {
  std::int64_t x, y;
  float z;
};

struct Plane {
  double a, b, c;
  float At(std::int64_t x, std::int64_t y) const {
    return static_cast<float>(a * static_cast<double>(x) + b * static_cast<double>(y) + c);
  }
  bool operator==(const Plane& o) const { return a == o.a && b == o.b && c == o.c; }
};

struct Edge {
  std::int64_t a, b, c;
};

struct Files {
  Bytes fmask, colours, depth, decoded, resolve;
};

struct Setup {
  std::array<Vertex, 3> v;
  std::array<Edge, 3> edges;
  Plane plane;
  float zMin, zMax;
};

bool SetUp(const fmask::FixtureTriangle& triangle, Setup& out) {
  for (int i = 0; i < 3; ++i) {
    const fmask::FixtureVertex& fv = triangle.vertices[i];
    const float clipX = static_cast<float>(fv.x / kTileSize * 2.0 - 1.0);
    const float clipY = static_cast<float>(1.0 - fv.y / kTileSize * 2.0);
    const double invW = 1.0 / 1.0;
    const double ndcX = static_cast<double>(clipX) * invW, ndcY = static_cast<double>(clipY) * invW;
    out.v[i] = {std::llround((ndcX * 0.5 + 0.5) * kTileSize * 256.0), std::llround((0.5 - ndcY * 0.5) * kTileSize * 256.0),
                static_cast<float>(static_cast<double>(fv.z) * invW)};
  }
  auto area = [&] {
    return (out.v[1].x - out.v[0].x) * (out.v[2].y - out.v[0].y) - (out.v[2].x - out.v[0].x) * (out.v[1].y - out.v[0].y);
  };
  if (area() == 0) return false;
  if (area() < 0) std::swap(out.v[1], out.v[2]);  // reorient first
  const std::int64_t doubled = area();
  for (int i = 0; i < 3; ++i) {
    const Vertex& p = out.v[(i + 1) % 3];
    const Vertex& q = out.v[(i + 2) % 3];
    const std::int64_t dx = q.x - p.x, dy = q.y - p.y;
    const bool topLeft = dy < 0 || (dy == 0 && dx > 0);
    out.edges[i] = {-dy, dx, -(-dy * p.x + dx * p.y) - (topLeft ? 0 : 1)};
  }
  const Vertex &v0 = out.v[0], &v1 = out.v[1], &v2 = out.v[2];
  const double dx1 = static_cast<double>(v1.x - v0.x), dy1 = static_cast<double>(v1.y - v0.y);
  const double dx2 = static_cast<double>(v2.x - v0.x), dy2 = static_cast<double>(v2.y - v0.y);
  const double dz1 = static_cast<double>(v1.z) - static_cast<double>(v0.z);
  const double dz2 = static_cast<double>(v2.z) - static_cast<double>(v0.z);
  const double det = static_cast<double>(doubled);
  out.plane.a = (dz1 * dy2 - dz2 * dy1) / det;
  out.plane.b = (dx1 * dz2 - dx2 * dz1) / det;
  out.plane.c = static_cast<double>(v0.z) - out.plane.a * static_cast<double>(v0.x) - out.plane.b * static_cast<double>(v0.y);
  out.zMin = std::min({v0.z, v1.z, v2.z});
  out.zMax = std::max({v0.z, v1.z, v2.z});
  return true;
}

class ReferenceDecoder {
 public:
  ReferenceDecoder(const fmask::FixtureSpec& spec, raster::SamplePattern pattern)
      : s_(spec.config.coverageSamples), z_(spec.config.depthSamples), f_(spec.config.fragments),
        unknown_(f_), pattern_(std::move(pattern)) {
    const std::size_t pixels = kTileSize * kTileSize;
    code_.assign(pixels * s_, 0);
    occupied_.assign(pixels * f_, false);
    colour_.assign(pixels * f_, kClearColour);
    for (std::size_t p = 0; p < pixels; ++p) occupied_[p * f_] = true;
    planeOf_.assign(pixels * s_, 0);
    anchorDepth_.assign(pixels * z_, kClearDepth);
  }

  void Draw(const fmask::FixtureCase& fixtureCase) {
    for (const fmask::FixtureTriangle& triangle : fixtureCase.triangles) {
      Setup tri;
      if (!SetUp(triangle, tri) || HiZRejects(tri)) continue;
      bool wholeTile = true, wrote = false;
      float writtenMin = 0, writtenMax = 0;
      for (int qy = 0; qy < kTileSize; qy += 2) {
        for (int qx = 0; qx < kTileSize; qx += 2) {
          for (int q = 0; q < 4; ++q) {
            const int x = qx + (q & 1), y = qy + (q >> 1);
            const auto [passedAll, lo, hi, any] = Pixel(tri, triangle.colour, x, y);
            wholeTile &= passedAll;
            if (!any) continue;
            writtenMin = wrote ? std::min(writtenMin, lo) : lo;
            writtenMax = wrote ? std::max(writtenMax, hi) : hi;
            wrote = true;
          }
        }
      }
      if (wholeTile) {
        zMin_ = writtenMin;
        zMax_ = writtenMax;
      } else if (wrote) {
        zMin_ = std::min(zMin_, writtenMin);
        zMax_ = std::max(zMax_, writtenMax);
      }
    }
  }

  Files Derive() const {
    Files d;
    const int bits = BitsPerSample(s_, f_), elementBytes = std::max(8, s_ * bits) / 8;
    for (int y = 0; y < kTileSize; ++y) {
      for (int x = 0; x < kTileSize; ++x) {
        const int p = y * kTileSize + x;
        std::uint64_t element = 0;
        for (int s = 0; s < s_; ++s) element |= static_cast<std::uint64_t>(code_[p * s_ + s]) << (s * bits);
        for (int i = 0; i < elementBytes; ++i) d.fmask.push_back(static_cast<std::uint8_t>(element >> (8 * i)));
        for (int k = 0; k < f_; ++k) d.colours.insert(d.colours.end(), colour_[p * f_ + k].begin(), colour_[p * f_ + k].end());
        float sum[4] = {0, 0, 0, 0};
        int known = 0;
        for (int s = 0; s < s_; ++s) {
          const std::uint32_t bitsOfDepth = std::bit_cast<std::uint32_t>(Stored(x, y, s));
          for (int i = 0; i < 4; ++i) d.depth.push_back(static_cast<std::uint8_t>(bitsOfDepth >> (8 * i)));
          const bool isUnknown = f_ < s_ && code_[p * s_ + s] == unknown_;
          const Rgba& c = colour_[p * f_ + (isUnknown ? 0 : code_[p * s_ + s])];
          d.decoded.insert(d.decoded.end(), c.begin(), c.end());
          if (isUnknown) continue;
          for (int i = 0; i < 4; ++i) sum[i] += c[i] / 255.0f;
          ++known;
        }
        for (int i = 0; i < 4; ++i) {
          const float v = known == 0 ? 0.0f : sum[i] * (1.0f / static_cast<float>(known));
          const std::uint32_t b = std::bit_cast<std::uint32_t>(v);
          for (int k = 0; k < 4; ++k) d.resolve.push_back(static_cast<std::uint8_t>(b >> (8 * k)));
        }
      }
    }
    return d;
  }

 private:
  enum class State { Cleared, Compressed, Decompressed };
  static constexpr int kTaken = -1;

  std::int64_t X(int x, int y, int s) const { return x * 256 + 128 + 16 * pattern_.Offset((y % 2) * 2 + x % 2, s).x; }
  std::int64_t Y(int x, int y, int s) const { return y * 256 + 128 + 16 * pattern_.Offset((y % 2) * 2 + x % 2, s).y; }

  int Nearest(int x, int y, int s) const {
    if (s < z_) return s;
    int best = 0;
    auto d2 = [&](int a) {
      const std::int64_t dx = X(x, y, s) - X(x, y, a), dy = Y(x, y, s) - Y(x, y, a);
      return dx * dx + dy * dy;
    };
    for (int a = 1; a < z_; ++a) best = d2(a) < d2(best) ? a : best;
    return best;
  }

  float Stored(int x, int y, int s) const {
    const int p = y * kTileSize + x;
    if (state_ == State::Cleared) return kClearDepth;
    if (state_ == State::Decompressed) return anchorDepth_[p * z_ + Nearest(x, y, s)];
    return planes_[planeOf_[p * s_ + s]].At(X(x, y, s), Y(x, y, s));
  }

  // docs/raster.md, "Hi-Z" (depth LESS).
  bool HiZRejects(const Setup& tri) const {
    int minX = 99, maxX = -99, minY = 99, maxY = -99;
    for (int q = 0; q < 4; ++q) {
      for (int s = 0; s < s_; ++s) {
        minX = std::min(minX, pattern_.Offset(q, s).x);
        maxX = std::max(maxX, pattern_.Offset(q, s).x);
        minY = std::min(minY, pattern_.Offset(q, s).y);
        maxY = std::max(maxY, pattern_.Offset(q, s).y);
      }
    }
    const std::int64_t x0 = 128 + 16 * minX, x1 = 7 * 256 + 128 + 16 * maxX;
    const std::int64_t y0 = 128 + 16 * minY, y1 = 7 * 256 + 128 + 16 * maxY;
    // Tiles the triangle cannot touch are skipped before hi-Z: nothing to reject then.
    bool anyInside = false;
    for (int y = 0; y < kTileSize && !anyInside; ++y) {
      for (int x = 0; x < kTileSize && !anyInside; ++x) {
        for (int s = 0; s < s_; ++s) anyInside |= Inside(tri, X(x, y, s), Y(x, y, s));
      }
    }
    if (!anyInside) return false;
    const float corners[4] = {tri.plane.At(x0, y0), tri.plane.At(x1, y0), tri.plane.At(x0, y1), tri.plane.At(x1, y1)};
    const float lo = std::max(*std::min_element(corners, corners + 4), tri.zMin);
    return lo >= zMax_;
  }

  static bool Inside(const Setup& tri, std::int64_t x, std::int64_t y) {
    for (const Edge& e : tri.edges) {
      if (e.a * x + e.b * y + e.c < 0) return false;
    }
    return true;
  }

  struct PixelWrite {
    bool passedAll;
    float lo, hi;
    bool wrote;
  };

  // docs/raster.md "One pixel through the depth unit", then docs/eqaa.md "One pixel update".
  PixelWrite Pixel(const Setup& tri, const Rgba& colour, int x, int y) {
    const int p = y * kTileSize + x;
    unsigned covered = 0, passed = 0;
    std::array<float, 16> incoming{};
    for (int s = 0; s < s_; ++s) {
      if (!Inside(tri, X(x, y, s), Y(x, y, s))) continue;
      covered |= 1u << s;
      incoming[s] = tri.plane.At(X(x, y, s), Y(x, y, s));
      if (incoming[s] < Stored(x, y, s)) passed |= 1u << s;
    }
    const unsigned all = (1u << s_) - 1u;
    if (covered == 0) return {false, 0, 0, false};
    const unsigned anchored = (1u << z_) - 1u;
    const unsigned exact = state_ == State::Decompressed ? covered & anchored : covered;
    PixelWrite write{passed == all, 0, 0, false};
    if (passed != 0) {
      int slot = -1;
      if (state_ != State::Decompressed) slot = PlaneSlot(tri.plane);
      for (int s = 0; s < s_; ++s) {
        if (!((passed >> s) & 1u)) continue;
        if (slot >= 0) {
          planeOf_[p * s_ + s] = slot;
        } else if (s < z_) {
          anchorDepth_[p * z_ + s] = incoming[s];
        } else {
          continue;
        }
        write.lo = write.wrote ? std::min(write.lo, incoming[s]) : incoming[s];
        write.hi = write.wrote ? std::max(write.hi, incoming[s]) : incoming[s];
        write.wrote = true;
      }
    }
    UpdateColour(p, covered, passed, exact, colour);
    return write;
  }

  int PlaneSlot(const Plane& plane) {
    if (state_ == State::Cleared) {
      state_ = State::Compressed;
      planes_ = {Plane{0.0, 0.0, static_cast<double>(kClearDepth)}};
      std::fill(planeOf_.begin(), planeOf_.end(), 0);
    }
    for (std::size_t i = 0; i < planes_.size(); ++i) {
      if (planes_[i] == plane) return static_cast<int>(i);
    }
    if (planes_.size() == kMaxPlanes) {
      std::vector<Plane> kept;
      std::vector<int> renumber(planes_.size(), -1);
      for (std::size_t i = 0; i < planes_.size(); ++i) {
        if (std::find(planeOf_.begin(), planeOf_.end(), static_cast<int>(i)) == planeOf_.end()) continue;
        renumber[i] = static_cast<int>(kept.size());
        kept.push_back(planes_[i]);
      }
      for (int& index : planeOf_) index = renumber[index];
      planes_ = kept;
    }
    if (planes_.size() == kMaxPlanes) {
      for (int y = 0; y < kTileSize; ++y) {
        for (int x = 0; x < kTileSize; ++x) {
          for (int a = 0; a < z_; ++a) anchorDepth_[(y * kTileSize + x) * z_ + a] = Stored(x, y, a);
        }
      }
      state_ = State::Decompressed;
      return -1;
    }
    planes_.push_back(plane);
    return static_cast<int>(planes_.size()) - 1;
  }

  void UpdateColour(int p, unsigned covered, unsigned passed, unsigned exact, const Rgba& colour) {
    int* owner = &code_[p * s_];
    const std::vector<int> before(owner, owner + s_);
    auto occupied = [&](int k) { return occupied_[p * f_ + k]; };
    const unsigned untestable = covered & ~exact, claimExact = passed & exact;
    const unsigned claim = claimExact | (untestable & passed);
    auto freeUnreferenced = [&] {
      for (int k = 0; k < f_; ++k) {
        if (occupied(k) && std::find(owner, owner + s_, k) == owner + s_) occupied_[p * f_ + k] = false;
      }
    };
    auto discardUntestable = [&] {
      for (int s = 0; s < s_; ++s) {
        if (((untestable >> s) & 1u) && owner[s] >= 0 && owner[s] < f_) owner[s] = unknown_;
      }
    };
    for (int s = 0; s < s_; ++s) {
      if ((claimExact >> s) & 1u) owner[s] = kTaken;  // step 1
    }
    if (claim == 0) {
      discardUntestable();  // step 2
    } else {
      freeUnreferenced();  // step 3
      int slot = -1;
      for (int k = 0; k < f_ && slot < 0; ++k) slot = occupied(k) ? -1 : k;  // step 4
      if (slot < 0) {
        std::vector<int> count(f_, 0);
        for (int s = 0; s < s_; ++s) {
          if (!((claimExact >> s) & 1u) && before[s] < f_) ++count[before[s]];
        }
        for (int k = 0; k < f_; ++k) {
          if (slot < 0 || count[k] <= count[slot]) slot = k;  // a tie keeps the lower index
        }
        for (int s = 0; s < s_; ++s) owner[s] = owner[s] == slot ? unknown_ : owner[s];
      }
      discardUntestable();  // step 5
      occupied_[p * f_ + slot] = true;  // step 6
      colour_[p * f_ + slot] = colour;
      for (int s = 0; s < s_; ++s) owner[s] = (claim >> s) & 1u ? slot : owner[s];
    }
    freeUnreferenced();  // step 7
  }

  int s_, z_, f_, unknown_;
  raster::SamplePattern pattern_;
  std::vector<int> code_;
  std::vector<bool> occupied_;
  std::vector<Rgba> colour_;
  State state_ = State::Cleared;
  std::vector<Plane> planes_;
  std::vector<int> planeOf_;
  std::vector<float> anchorDepth_;
  float zMin_ = kClearDepth, zMax_ = kClearDepth;
};

TEST(FmaskFixturesFromTheDocs, EveryFileOfEveryFixture) {
  int checked = 0;
  for (const fmask::FixtureSpec& spec : fmask::CanonicalFixtureSet()) {
    SCOPED_TRACE(fmask::FixtureName(spec));
    const fmask::FixtureData data = fmask::DeriveFixture(spec);
    ReferenceDecoder reference(spec, raster::MakeBuiltinPattern(spec.pattern, spec.config.coverageSamples));
    reference.Draw(fmask::CanonicalCase(spec.caseName));
    const Files expected = reference.Derive();
    EXPECT_EQ(data.fmask, expected.fmask);
    EXPECT_EQ(data.colours, expected.colours);
    EXPECT_EQ(data.depth, expected.depth);
    EXPECT_EQ(data.decoded, expected.decoded);
    EXPECT_EQ(data.resolve, expected.resolve);
    ++checked;
  }
  EXPECT_EQ(checked, 812);
}

}  // namespace
