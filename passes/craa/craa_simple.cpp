// The CRAA simple resolve (see craa_simple.h).

#include "passes/craa/craa_simple.h"

#include <bit>
#include <cstdlib>

#include "passes/craa/craa_common.h"
#include "sim/eqaa_resolve.h"

namespace passes::craa {
namespace {

constexpr sim::KernelInfo kSimpleKernel{
    .vgprs = 20, .sgprs = 24, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 70,
    .source = "hand count of the simple resolve at 8 samples: countbits and the coverage (3), per sample a "
              "bit test and two conditional adds of its constant position (3 x 8 = 24), the direction and side "
              "choice (8), the neighbour address (6), the blend of 4 channels (12), export (10)"};

template <typename Lane>
glm::vec4 SimplePixel(const sim::EqaaView& eqaa, const raster::SamplePattern& pattern, const Lane& lane) {
  const int samples = pattern.Count();
  const std::uint32_t unknown = static_cast<std::uint32_t>(eqaa.Fmask(lane, lane.x, lane.y)) & SampleBits(samples);
  const glm::vec4 own = sim::ToVec4(eqaa.Fragment(lane, lane.x, lane.y, 0));
  const Side side = InferredSide(pattern, lane.quadPixel, unknown);
  if (side == Side::None) return own;
  const glm::vec4 inferred = side == Side::Balanced ? NeighbourMean(eqaa, lane) : Neighbour(eqaa, lane, side);
  const float coverage = static_cast<float>(samples - std::popcount(unknown)) / static_cast<float>(samples);
  return own * coverage + inferred * (1.0f - coverage);
}

class SimpleResolve final : public Resolve {
 public:
  explicit SimpleResolve(const raster::SamplePattern& pattern) : pattern_(pattern) {}
  const ResolveInfo& Info() const override { return SimpleInfo(); }

  sim::Texture2D<glm::vec4> Run(sim::Machine& machine, const fmask::EqaaSurface& surface) override {
    CheckSurface(SimpleInfo(), surface, pattern_);
    return RunResolveDispatch(machine, surface, "resolve/craa-simple", kSimpleKernel,
                              [&](sim::Dispatch&, const sim::EqaaView& eqaa) {
                                return [&, eqaa](const sim::PixelLane& lane) { return SimplePixel(eqaa, pattern_, lane); };
                              });
  }

 private:
  raster::SamplePattern pattern_;
};

}  // namespace

Side InferredSide(const raster::SamplePattern& pattern, int quadPixel, std::uint32_t unknown) {
  if (unknown == 0) return Side::None;
  int sumX = 0, sumY = 0;
  for (int s = 0; s < pattern.Count(); ++s) {
    if ((unknown >> s & 1u) == 0) continue;
    sumX += pattern.Offset(quadPixel, s).x;
    sumY += pattern.Offset(quadPixel, s).y;
  }
  if (sumX == 0 && sumY == 0) return Side::Balanced;
  if (std::abs(sumY) >= std::abs(sumX)) return sumY < 0 ? Side::Up : Side::Bottom;
  return sumX < 0 ? Side::Left : Side::Right;
}

const ResolveInfo& SimpleInfo() {
  static const ResolveInfo info{
      .name = "craa-simple",
      .description = "CRAA simple resolve: fragment x coverage + the neighbour across the half plane the UNKNOWN "
                     "samples' summed positions point at (seed 001)",
      .source = "passes/craa/craa_simple.h",
      .surfaces = "1F surfaces of 2 to 16 samples",
      .reads = ReadsCraaModes};
  return info;
}

std::unique_ptr<Resolve> MakeSimple(const ResolveContext& context) {
  return std::make_unique<SimpleResolve>(RequirePattern(SimpleInfo(), context));
}

}  // namespace passes::craa
