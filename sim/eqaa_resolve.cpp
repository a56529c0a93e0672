// The EQAA surface's box and fetch-path resolves as full-screen pixel shaders (eqaa_resolve.h).

#include "sim/eqaa_resolve.h"

#include <stdexcept>
#include <utility>

#include "sim/dispatch_inl.h"

namespace sim {
namespace {

template <typename ResolvePixel>
DispatchReport RunResolve(Machine& machine, const fmask::EqaaSurface& surface, Texture2D<glm::vec4>& target,
                          std::string name, const KernelInfo& kernel, ResolvePixel&& resolvePixel) {
  if (target.Width() != surface.Width() || target.Height() != surface.Height()) {
    throw std::invalid_argument(name + ": target " + target.Name() + " is not the EQAA surface's size");
  }
  const EqaaResources resources(surface);
  Dispatch dispatch(std::move(name), kernel);
  const EqaaView eqaa = dispatch.Read(resources);
  const RwTextureView<glm::vec4> out = dispatch.ReadWrite(target);
  return machine.FullScreen(dispatch, {.width = surface.Width(), .height = surface.Height()},
                            [&](PixelLane& lane) { out.Store(lane, lane.x, lane.y, resolvePixel(eqaa, lane)); });
}

}  // namespace

DispatchReport RunBoxResolve(Machine& machine, const fmask::EqaaSurface& surface, Texture2D<glm::vec4>& target,
                             std::string name) {
  return RunResolve(machine, surface, target, std::move(name), kBoxResolveKernel,
                    [](const EqaaView& eqaa, const PixelLane& lane) { return BoxResolvePixel(eqaa, lane, lane.x, lane.y); });
}

DispatchReport RunFetchResolve(Machine& machine, const fmask::EqaaSurface& surface, Texture2D<glm::vec4>& target,
                               std::string name) {
  return RunResolve(machine, surface, target, std::move(name), kFetchResolveKernel,
                    [](const EqaaView& eqaa, const PixelLane& lane) { return FetchResolvePixel(eqaa, lane, lane.x, lane.y); });
}

}  // namespace sim
