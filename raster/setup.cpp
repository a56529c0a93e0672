// Triangle setup: clip in homogeneous space, snap to the fixed-point grid, orient, cull and
// build the integer edge functions and the depth plane (see setup.h for the conventions).

#include "raster/setup.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace raster {
namespace {

struct ClipVertex {
  glm::vec4 position;
  std::array<float, 3> barycentrics;  // in the submitted triangle
};

// Clip planes as dot(plane, position) >= 0: near z >= 0 and far z <= w (D3D), a guard band
// that keeps snapped coordinates inside the range proved in limits.h, and w > 0 so the
// perspective divide is defined.
struct ClipPlane {
  float x, y, z, w, bias;  // inside when x*X + y*Y + z*Z + w*W - bias >= 0
};
constexpr float kGuard = static_cast<float>(kGuardBandNdc);
constexpr std::array<ClipPlane, 7> kClipPlanes = {{{0, 0, 1, 0, 0},
                                                   {0, 0, -1, 1, 0},
                                                   {1, 0, 0, kGuard, 0},
                                                   {-1, 0, 0, kGuard, 0},
                                                   {0, 1, 0, kGuard, 0},
                                                   {0, -1, 0, kGuard, 0},
                                                   {0, 0, 0, 1, 1e-7f}}};

float PlaneDistance(const ClipPlane& plane, const glm::vec4& p) {
  return plane.x * p.x + plane.y * p.y + plane.z * p.z + plane.w * p.w - plane.bias;
}

ClipVertex Lerp(const ClipVertex& a, const ClipVertex& b, float t) {
  ClipVertex out;
  out.position = a.position + (b.position - a.position) * t;
  for (int i = 0; i < 3; ++i) out.barycentrics[i] = a.barycentrics[i] + (b.barycentrics[i] - a.barycentrics[i]) * t;
  return out;
}

// Each plane adds at most one vertex to a convex polygon.
struct ClipPolygon {
  std::array<ClipVertex, 3 + std::tuple_size_v<decltype(kClipPlanes)>> vertices;
  std::size_t size = 0;
};

// Sutherland-Hodgman against one plane.
ClipPolygon ClipAgainst(const ClipPolygon& in, const ClipPlane& plane) {
  ClipPolygon out;
  for (std::size_t i = 0; i < in.size; ++i) {
    const ClipVertex& cur = in.vertices[i];
    const ClipVertex& next = in.vertices[(i + 1) % in.size];
    const float dCur = PlaneDistance(plane, cur.position);
    const float dNext = PlaneDistance(plane, next.position);
    if (dCur >= 0) out.vertices[out.size++] = cur;
    if ((dCur >= 0) != (dNext >= 0)) out.vertices[out.size++] = Lerp(cur, next, dCur / (dCur - dNext));
  }
  return out;
}

struct ScreenVertex {
  std::int64_t x = 0, y = 0;  // sub-pixel units
  float z = 0.0f;
  float invW = 0.0f;
  std::array<float, 3> barycentrics{};
};

ScreenVertex ToScreen(const ClipVertex& v, const Viewport& viewport) {
  const double invW = 1.0 / static_cast<double>(v.position.w);
  const double ndcX = static_cast<double>(v.position.x) * invW;
  const double ndcY = static_cast<double>(v.position.y) * invW;
  const double scale = static_cast<double>(kSubPixelScale);
  ScreenVertex s;
  s.x = std::llround((ndcX * 0.5 + 0.5) * viewport.width * scale);
  s.y = std::llround((0.5 - ndcY * 0.5) * viewport.height * scale);
  s.z = static_cast<float>(static_cast<double>(v.position.z) * invW);
  s.invW = static_cast<float>(invW);
  s.barycentrics = v.barycentrics;
  return s;
}

// Edge from p to q, positive on the side of the third vertex once the winding is normalised.
// Top-left rule (y down): a left edge runs upwards (dy < 0); a top edge is horizontal with the
// triangle below it, i.e. runs in +x. Other edges exclude samples exactly on them.
EdgeFunction MakeEdge(const ScreenVertex& p, const ScreenVertex& q) {
  const std::int64_t dx = q.x - p.x;
  const std::int64_t dy = q.y - p.y;
  EdgeFunction e;
  e.a = -dy;
  e.b = dx;
  e.topLeft = dy < 0 || (dy == 0 && dx > 0);
  e.c = -(e.a * p.x + e.b * p.y) - (e.topLeft ? 0 : 1);
  return e;
}

ZPlane MakeZPlane(const std::array<ScreenVertex, 3>& v, std::int64_t doubleArea) {
  const double dx1 = static_cast<double>(v[1].x - v[0].x), dy1 = static_cast<double>(v[1].y - v[0].y);
  const double dx2 = static_cast<double>(v[2].x - v[0].x), dy2 = static_cast<double>(v[2].y - v[0].y);
  const double dz1 = static_cast<double>(v[1].z) - static_cast<double>(v[0].z);
  const double dz2 = static_cast<double>(v[2].z) - static_cast<double>(v[0].z);
  const double det = static_cast<double>(doubleArea);
  ZPlane plane;
  plane.a = (dz1 * dy2 - dz2 * dy1) / det;
  plane.b = (dx1 * dz2 - dx2 * dz1) / det;
  plane.c = static_cast<double>(v[0].z) - plane.a * static_cast<double>(v[0].x) -
            plane.b * static_cast<double>(v[0].y);
  return plane;
}

std::int64_t FloorDiv(std::int64_t a, std::int64_t b) {
  return a >= 0 ? a / b : -((-a + b - 1) / b);
}

// Pixels whose sample extents [x*256, x*256 + 240] (offsets -8..7) can meet the bounding box.
PixelRect SampleBounds(const std::array<ScreenVertex, 3>& v, const Viewport& viewport) {
  const auto [minX, maxX] = std::minmax({v[0].x, v[1].x, v[2].x});
  const auto [minY, maxY] = std::minmax({v[0].y, v[1].y, v[2].y});
  const std::int64_t reach = kSubPixelScale / 2 + kSampleOffsetMax * kSubPixelPerSampleUnit;
  const std::int64_t lowReach = kSubPixelScale / 2 + kSampleOffsetMin * kSubPixelPerSampleUnit;
  auto lo = [&](std::int64_t m) { return FloorDiv(m - reach + kSubPixelScale - 1, kSubPixelScale); };
  auto hi = [&](std::int64_t m) { return FloorDiv(m - lowReach, kSubPixelScale) + 1; };
  PixelRect r;
  r.x0 = static_cast<int>(std::clamp<std::int64_t>(lo(minX), 0, viewport.width));
  r.y0 = static_cast<int>(std::clamp<std::int64_t>(lo(minY), 0, viewport.height));
  r.x1 = static_cast<int>(std::clamp<std::int64_t>(hi(maxX), 0, viewport.width));
  r.y1 = static_cast<int>(std::clamp<std::int64_t>(hi(maxY), 0, viewport.height));
  return r;
}

// Sets up one clipped triangle; false when it produces nothing to rasterize.
void SetupScreenTriangle(std::array<ScreenVertex, 3> v, std::uint32_t primitiveId,
                         const Viewport& viewport, CullMode cull,
                         std::vector<TriangleSetup>& out, RasterCounters& counters) {
  std::int64_t area = (v[1].x - v[0].x) * (v[2].y - v[0].y) - (v[2].x - v[0].x) * (v[1].y - v[0].y);
  if (area == 0) {
    ++counters.trianglesZeroArea;
    return;
  }
  // Screen +y points down, so a counter-clockwise triangle in NDC (y up, front-facing in
  // glTF) has a negative area here.
  const bool frontFacing = area < 0;
  if ((cull == CullMode::Back && !frontFacing) || (cull == CullMode::Front && frontFacing)) {
    ++counters.trianglesCulled;
    return;
  }
  if (area < 0) {
    std::swap(v[1], v[2]);
    area = -area;
  }
  TriangleSetup t;
  t.bounds = SampleBounds(v, viewport);
  if (t.bounds.Empty()) {
    ++counters.trianglesOutsideView;
    return;
  }
  t.edges = {MakeEdge(v[1], v[2]), MakeEdge(v[2], v[0]), MakeEdge(v[0], v[1])};
  t.depth = MakeZPlane(v, area);
  t.zMin = std::min({v[0].z, v[1].z, v[2].z});
  t.zMax = std::max({v[0].z, v[1].z, v[2].z});
  t.doubleArea = area;
  for (int i = 0; i < 3; ++i) {
    t.invW[i] = v[i].invW;
    t.sourceBarycentrics[i] = v[i].barycentrics;
  }
  t.primitiveId = primitiveId;
  t.frontFacing = frontFacing;
  ++counters.trianglesRasterized;
  out.push_back(t);
}

}  // namespace

void SetupTriangle(const std::array<glm::vec4, 3>& clip, std::uint32_t primitiveId,
                   const Viewport& viewport, CullMode cull, std::vector<TriangleSetup>& out,
                   RasterCounters& counters) {
  ++counters.trianglesIn;
  ClipPolygon polygon;
  polygon.vertices[0] = {clip[0], {1, 0, 0}};
  polygon.vertices[1] = {clip[1], {0, 1, 0}};
  polygon.vertices[2] = {clip[2], {0, 0, 1}};
  polygon.size = 3;
  bool clipped = false;
  for (const ClipPlane& plane : kClipPlanes) {
    std::size_t inside = 0;
    for (std::size_t i = 0; i < polygon.size; ++i) inside += PlaneDistance(plane, polygon.vertices[i].position) >= 0;
    if (inside == polygon.size) continue;
    if (inside == 0) {
      ++counters.trianglesOutsideView;
      return;
    }
    polygon = ClipAgainst(polygon, plane);
    clipped = true;
  }
  if (clipped) ++counters.trianglesClipped;
  const ScreenVertex first = ToScreen(polygon.vertices[0], viewport);
  for (std::size_t i = 1; i + 1 < polygon.size; ++i) {
    SetupScreenTriangle({first, ToScreen(polygon.vertices[i], viewport), ToScreen(polygon.vertices[i + 1], viewport)},
                        primitiveId, viewport, cull, out, counters);
  }
}

std::array<float, 3> PerspectiveBarycentrics(const TriangleSetup& tri, double pixelX,
                                             double pixelY) {
  const double x = pixelX * static_cast<double>(kSubPixelScale);
  const double y = pixelY * static_cast<double>(kSubPixelScale);
  std::array<double, 3> weight{};
  double sum = 0.0;
  for (int i = 0; i < 3; ++i) {
    const EdgeFunction& e = tri.edges[i];
    const double unbiasedC = static_cast<double>(e.c + (e.topLeft ? 0 : 1));
    const double screen = (static_cast<double>(e.a) * x + static_cast<double>(e.b) * y + unbiasedC) /
                          static_cast<double>(tri.doubleArea);
    weight[i] = screen * static_cast<double>(tri.invW[i]);
    sum += weight[i];
  }
  std::array<float, 3> result{};
  for (int i = 0; i < 3; ++i) {
    for (int k = 0; k < 3; ++k) {
      result[k] += static_cast<float>(weight[i] / sum) * tri.sourceBarycentrics[i][k];
    }
  }
  return result;
}

}  // namespace raster
