#pragma once
// `craa-simple`: the CRAA simple resolve of a 1F surface (seed 001, "8xCRAA: Simple Resolve").
//
//   resolve/craa-simple   full-screen PS
//     in:  FMASK of the 1F surface (S bits: 0 = the stored fragment hit the sample, 1 = UNKNOWN),
//          fragment 0 of the pixel, fragment 0 of one neighbour (up, bottom, left or right),
//          the sample positions (constants: the frame's pattern)
//     out: colour (RGBA, modelled RGBA8)
//
// Per pixel, as the seed's slides list it:
//   coverage c = (S - countbits(FMASK)) / S                 ("Immediately know Color Fragment coverage")
//   v = the sum of the UNKNOWN samples' offsets from the pixel centre ("Treat Sample Pos as vector,
//       add together": v points into the part of the pixel the stored fragment does not cover)
//   the half plane's direction is vertical when |v.y| >= |v.x| (the unknown part lies above or
//       below), else horizontal; the sign of the dominant component ("slope") picks the side:
//       up (v.y < 0, +y down), bottom, left (v.x < 0) or right
//   the inferred colour is that neighbour's stored fragment ("infer UNKNOWN sample colors from the
//       other side of derived edge"; issue 14: the neighbour's own fragment)
//   result = fragment * c + inferred * (1 - c)              ("Resolved Pixel = ...")
// Choices the slides leave open (docs/craa.md): a tie |v.y| == |v.x| goes vertical; v = 0 with
// UNKNOWN samples (they balance around the centre, e.g. all unknown) infers the mean of the four
// neighbours; a neighbour beyond the screen is the pixel itself (clamp addressing). With no
// UNKNOWN sample the pixel is its fragment and no neighbour is fetched.

#include <cstdint>
#include <memory>

#include "passes/resolve.h"

namespace passes::craa {

// Which neighbour the simple resolve infers the UNKNOWN samples from; `Balanced` averages all four.
enum class Side : std::uint8_t { None, Up, Bottom, Left, Right, Balanced };

// The side of the UNKNOWN samples of quad pixel `quadPixel` whose FMASK bits are `unknown`.
Side InferredSide(const raster::SamplePattern& pattern, int quadPixel, std::uint32_t unknown);

const ResolveInfo& SimpleInfo();
std::unique_ptr<Resolve> MakeSimple(const ResolveContext& context);

}  // namespace passes::craa
