// The EQAA surface as shader resources (see eqaa_resources.h).

#include "sim/eqaa_resources.h"

#include <string>

#include "fmask/layout.h"
#include "sim/views.h"

namespace sim {
namespace {

constexpr std::size_t kFragmentBytes = 4;  // RGBA8 colour fragments

std::size_t Pixels(const fmask::EqaaSurface& surface) {
  return static_cast<std::size_t>(surface.Width()) * static_cast<std::size_t>(surface.Height());
}

}  // namespace

EqaaResources::EqaaResources(const fmask::EqaaSurface& surface)
    : surface_(&surface),
      fmaskBytesPerPixel_(static_cast<std::size_t>(surface.Layout().ElementBits()) / 8),
      fmask_("eqaa/fmask", Pixels(surface) * fmaskBytesPerPixel_),
      fragments_("eqaa/fragments",
                 Pixels(surface) * static_cast<std::size_t>(surface.Config().fragments) * kFragmentBytes) {}

bool EqaaView::Contains(int x, int y) const {
  return x >= 0 && y >= 0 && x < Surface().Width() && y < Surface().Height();
}

fmask::FmaskElement EqaaView::Fmask(const LaneBase& lane, int x, int y) const {
  const std::size_t bytes = eqaa_->FmaskBytesPerPixel();
  if (bytes == 0) return 0;  // 1S/1F has no FMASK to read
  ResourceTraffic& traffic = detail::Traffic(lane, fmask_);
  ++traffic.fetches;
  traffic.bytesRead += bytes;
  if (!Contains(x, y)) return 0;
  const std::size_t pixel = static_cast<std::size_t>(y) * static_cast<std::size_t>(Surface().Width()) +
                            static_cast<std::size_t>(x);
  eqaa_->FmaskResource().TouchRead(pixel * bytes, bytes);
  return Surface().Fmask(x, y);
}

fmask::Colour EqaaView::Fragment(const LaneBase& lane, int x, int y, int slot) const {
  detail::CheckOrigin(lane, fmask_);
  ResourceTraffic& traffic = detail::Traffic(lane, fragmentSlot_);
  ++traffic.fetches;
  traffic.bytesRead += kFragmentBytes;
  if (!Contains(x, y) || slot < 0 || slot >= Surface().Config().fragments) return {};
  const std::size_t pixels = Pixels(Surface());
  const std::size_t pixel = static_cast<std::size_t>(y) * static_cast<std::size_t>(Surface().Width()) +
                            static_cast<std::size_t>(x);
  eqaa_->FragmentResource().TouchRead((static_cast<std::size_t>(slot) * pixels + pixel) * kFragmentBytes,
                                      kFragmentBytes);
  return Surface().Slot(x, y, slot).colour;
}

fmask::Colour EqaaView::FetchSample(const LaneBase& lane, int x, int y, int sample) const {
  const std::uint64_t visible = fmask::ShaderVisibleMask(Surface().Layout(), Fmask(lane, x, y));
  return Fragment(lane, x, y, fmask::FetchFragmentIndex(visible, sample));
}

}  // namespace sim
