#pragma once
// SMAA T2x and SMAA 4x (aa-facts §1.8; iryoku/smaa SMAA.hlsl SMAAResolvePS and the demo's
// runSMAA in Demo/DX10/Code/Demo.cpp): SMAA 1x (T2x) or S2x (4x) every frame with the frame's
// subsample indices, written into one of two RGBA8 sRGB targets kept by the instance, then the
// temporal resolve of this frame's target with the previous frame's.
//
//   frame colour-srgb8 RGBA8_SRGB (T2x)               frame EQAA surface (4x, 2 samples)
//   frame velocity ──store──► velocity RG16F (W x H, UV units, reprojection only; see below)
//
//   smaa-t2x/{edge-detection,       SMAA 1x (smaa.h's diagram, both strategies through the work
//     blending-weights,             set) with subsample indices (1,1,1,0) on even frames and
//     neighbourhood-blending}       (2,2,2,0) on odd ones (frameIndex parity: the t2x schedule's
//                                   (+0.25,+0.25) then (-0.25,-0.25) px samples, aa-facts §1.8)
//   smaa-4x/separate,               S2x (s2x.h) with indices 2 * (frameIndex mod 2) + sample of
//   smaa-4x/s<k>/{...}              the table: (5,3,1,3), (4,6,2,3) then (3,5,1,4), (6,4,2,4)
//       -> history[current] RGBA8_SRGB (W x H; the demo's finalRT[currentIndex]). With
//          reprojection, neighbourhood blending blends the velocity like the colour and writes
//          alpha = sqrt(5 |v|) (SMAA_REPROJECTION).
//   <pass>/resolve                  full-screen PS, point samples: history[current] and
//                                   history[previous] through sRGB views, velocity RG16F ->
//                                   output RGBA8_SRGB (W x H)
//       without reprojection: lerp(current, previous, 0.5)
//       with reprojection:    previous fetched at uv - v; weight =
//                             0.5 * saturate(1 - sqrt(|a_cur^2 - a_prev^2| / 5) * scale)
//                             (REPROJECTION_WEIGHT_SCALE, 30 by default); lerp(current, previous,
//                             weight)
//
// History: the two RGBA8 sRGB targets swap every frame (the demo's finalRT[2]); the resolve reads
// the previous frame's SMAA output (not the previous resolve: T2x averages two frames, it keeps no
// recursive history). Their reads and writes are the views' bytes like any target.
//
// Velocity: FrameInputs::velocity is in pixels, current - previous, +y down. The reference's is
// the demo's motion-blur velocity (Simple.fx: current minus previous projected position, halved
// into texture units and y flipped, so also current - previous with v down) in UV units, stored
// RG16F (the demo's velocityRT). So v_uv = (v_px.x / W, v_px.y / H), no sign change, stored
// through RG16F; the resolve negates it (SMAAResolvePS) and fetches the previous frame at
// uv - v_uv, i.e. at pixel p - v_px.
//
// Frame 0 (or a frame after a size change): no previous frame. The demo creates its two targets
// without initial data and never clears them: its very first T2x frame after start-up resolves
// against a never-written target (undefined in D3D10; zero-filled memory in practice, a half-dark
// first frame), and when T2x or SMAA is switched on it renders one extra frame to "refill the
// temporal buffer" before showing one (Demo.cpp onGUIEvent). We follow the refill's intent, not
// the undefined read: a sequence has no frame before its first, so the previous target is this
// frame's own output, as the CMAA2 sample's SMAA wrapper does when its history is not valid
// (GameTechDev/CMAA2 vaSMAAWrapper: previous = current). Frame 0's output is its SMAA 1x/S2x
// output (with reprojection, up to the resolve's fetch at p - v of the same image).
//
// Settings: SMAA's (smaa.h, luma edges), `reprojection` (0/1; on by default as the demo's
// "Temporal Reprojection" checkbox; SMAA.hlsl's macro default is 0) and
// `reprojection_weight_scale` (SMAA_REPROJECTION_WEIGHT_SCALE, 30, range [0, 80]). Layers: SMAA
// 1x's "edges" and "weights" (T2x), S2x's per-sample ones (4x).

#include <array>
#include <memory>

#include <glm/vec4.hpp>

#include "passes/pass.h"

namespace passes::smaa {

// aa-facts §1.8: (vertical ortho, horizontal ortho, diagonal 1, diagonal 2) per frame.
glm::vec4 T2xSubsampleIndices(int frameIndex);
std::array<glm::vec4, 2> FourXSubsampleIndices(int frameIndex);

const PassInfo& T2xInfo();
std::unique_ptr<Pass> MakeT2x(const PassSettings& settings);
const PassInfo& FourXInfo();
std::unique_ptr<Pass> MakeFourX(const PassSettings& settings);

}  // namespace passes::smaa
