// The fetch-path resolve (see fetch.h).

#include "passes/resolves/fetch.h"

#include "sim/eqaa_resolve.h"

namespace passes::resolves {
namespace {

// Only surfaces with UNKNOWN samples differ from the box resolve (1S and MSAA surfaces have none);
// on a 1F surface every sample reads the one fragment, which is also the box resolve's only known
// colour, so the two are equal by definition (docs/craa.md).
bool ReadsEqaaModes(const fmask::EqaaConfig& mode) { return mode.fragments > 1 && mode.fragments < mode.coverageSamples; }

class FetchResolve final : public Resolve {
 public:
  const ResolveInfo& Info() const override { return FetchInfo(); }
  sim::Texture2D<glm::vec4> Run(sim::Machine& machine, const fmask::EqaaSurface& surface) override {
    sim::Texture2D<glm::vec4> colour("resolve/fetch", surface.Width(), surface.Height(), 4);
    sim::RunFetchResolve(machine, surface, colour, "resolve/fetch");
    return colour;
  }
};

}  // namespace

const ResolveInfo& FetchInfo() {
  static const ResolveInfo info{
      .name = "fetch",
      .description = "the shader resolve through the fetch path: mean of every sample's fetch, UNKNOWN reading "
                     "fragment 0 (hw-facts §1.4)",
      .source = "passes/resolves/fetch.h",
      .surfaces = "EQAA surfaces with 1 < F < S",
      .reads = ReadsEqaaModes};
  return info;
}

std::unique_ptr<Resolve> MakeFetch(const ResolveContext&) { return std::make_unique<FetchResolve>(); }

}  // namespace passes::resolves
