#pragma once
// Low-footprint velocity buffers (seed 000 "Low-Footprint Velocity Buffers" and "Faster Closest
// Velocity and Halfres Velocities"), an option of multi-frame runs: the frame's float velocity
// target (8 bytes a pixel, the seed's "7.91MB for 1080p@16 bit" being 4) packed into 8 bits per
// component by a two-piece linear function over 0..40 px, at full resolution or at half
// resolution keeping, in each 2x2 block, the velocity of the pixel nearest the camera (the
// seed's 0.98 MB at 1080p).
//
// The pack is a compute dispatch on the machine ("frame/velocity-pack", bytes counted). Passes
// then read the decoded values through FrameInputs::velocity, a full-resolution texture whose
// texels are counted at the packed buffer's 2 bytes (at half resolution, a nearest upsample:
// fetches are counted per full-resolution texel, more lines than a half-resolution fetch moves).
//
// The seed gives the range and the shape, not the breakpoint: ours (a choice, docs/temporal.md)
// spends half the codes on |v| <= 2 px at 1/32 px a step, the other half on 2..40 px at 38/63 px
// a step, continuous at 2 px. A component beyond 40 px stores 40 px and is counted
// (velocity/clamped): the format's range, not a silent repair.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>

#include "sim/dispatch.h"

namespace study {

enum class VelocityBuffer : std::uint8_t { Float, Rg8, Rg8Half };
std::string_view VelocityBufferName(VelocityBuffer buffer);  // "float", "rg8", "rg8-half"
std::vector<std::string> VelocityBufferNames();
std::optional<VelocityBuffer> VelocityBufferByName(std::string_view name);

inline constexpr float kVelocityRangePixels = 40.0f;  // seed 000: "0..40 pixels range"
std::uint8_t EncodeVelocityComponent(float pixels);
float DecodeVelocityComponent(std::uint8_t code);

inline constexpr sim::KernelInfo kVelocityPackKernel{
    .vgprs = 16, .sgprs = 16, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 40,
    .source = "hand count of study/velocity_buffer.cpp's pack kernel: 4 depth compares and selects (~8), two "
              "components' sign, magnitude, two-piece scale and round (~2 x 12), address and export (~8)"};

// Packs `velocity` (with `depth` for the half-resolution choice) on the machine and returns what
// passes read: the decoded velocities at full resolution. Float returns a copy of `velocity`.
sim::Texture2D<glm::vec2> PackVelocity(sim::Machine& machine, VelocityBuffer buffer,
                                       const sim::Texture2D<glm::vec2>& velocity, const sim::Texture2D<float>& depth);

}  // namespace study
