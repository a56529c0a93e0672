#pragma once
// The EQAA colour surface as shader resources (hw-facts §1): its FMASK and its colour fragments
// bound to a dispatch as two resources, so a resolve kernel (the fetch-path resolve, CRAA's
// resolves) counts what it reads where it reads it, like any other view (sim/views.h).
//
// Modelled sizes: FMASK is ElementBits() / 8 bytes per pixel (the FMASK formats of hw-facts
// §1.1; none for 1S/1F); the fragments are RGBA8, 4 bytes per slot per pixel, one plane per slot
// (fragment k of every pixel together, as the CB stores colour fragment planes).

#include <cstdint>

#include "fmask/eqaa_surface.h"
#include "sim/lanes.h"
#include "sim/resources.h"

namespace sim {

class EqaaResources {
 public:
  // `surface` must outlive this object; reads go to it as it is when the kernel runs.
  explicit EqaaResources(const fmask::EqaaSurface& surface);

  const fmask::EqaaSurface& Surface() const { return *surface_; }
  const Resource& FmaskResource() const { return fmask_; }
  const Resource& FragmentResource() const { return fragments_; }
  std::size_t FmaskBytesPerPixel() const { return fmaskBytesPerPixel_; }

 private:
  const fmask::EqaaSurface* surface_;
  std::size_t fmaskBytesPerPixel_;
  Resource fmask_;
  Resource fragments_;
};

// Reads of one binding of EqaaResources (Dispatch::Read). Out-of-range pixels read 0 / a zero
// colour, as other views do.
class EqaaView {
 public:
  EqaaView(const EqaaResources& eqaa, ViewBinding fmask, int fragmentSlot)
      : eqaa_(&eqaa), fmask_(std::move(fmask)), fragmentSlot_(fragmentSlot) {}

  const fmask::EqaaSurface& Surface() const { return eqaa_->Surface(); }
  // The pixel's FMASK element: one fetch of FmaskBytesPerPixel() bytes (none without FMASK).
  fmask::FmaskElement Fmask(const LaneBase& lane, int x, int y) const;
  // Colour fragment `slot` of the pixel: one fetch of 4 bytes.
  fmask::Colour Fragment(const LaneBase& lane, int x, int y, int slot) const;
  // hw-facts §1.4, the shader fetch path of one sample: the FMASK element, then the fragment its
  // shader-visible code names (UNKNOWN reads fragment 0). A kernel resolving every sample reads
  // the FMASK once and calls Fragment per sample instead, as a real resolve shader does.
  fmask::Colour FetchSample(const LaneBase& lane, int x, int y, int sample) const;

 private:
  bool Contains(int x, int y) const;

  const EqaaResources* eqaa_;
  ViewBinding fmask_;
  int fragmentSlot_;
};

}  // namespace sim
