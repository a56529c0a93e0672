#pragma once
// Temporal stability of an image sequence (issue 15; aa-facts §9.3, "suggested practice"):
// frame-to-frame change with the known motion compensated, so only flicker counts; error on
// recently disoccluded pixels (ghosting); frames until a sequence settles (convergence).
//
// Differences are taken on display values: sRGB-encoded channels in 8-bit codes (0..255),
// averaged over R, G and B, because flicker is seen on the display, not in linear light. Images
// are kept in that form (3 bytes a pixel), so a sequence's frames cost little to keep.

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "sim/resources.h"

namespace study {

// An image as the display shows it: sim::EncodeSrgb8 of each of R, G, B, row-major.
struct DisplayImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
  friend bool operator==(const DisplayImage&, const DisplayImage&) = default;
};
DisplayImage ToDisplay(const sim::Texture2D<glm::vec4>& linear);

// Where each pixel of frame k was in frame k - 1: its centre minus its velocity. A pixel is
// tracked when that point lies on the screen and the previous frame's pixel nearest to it shows
// the same object; otherwise it is disoccluded (newly visible, or moved in from off screen).
struct Reprojection {
  int width = 0, height = 0;
  std::vector<glm::vec2> source;       // previous-frame pixel coordinates (pixel centres at x + 0.5)
  std::vector<std::uint8_t> tracked;   // 1 = tracked
  std::uint64_t disoccludedPixels = 0;
};
Reprojection Reproject(const sim::Texture2D<glm::vec2>& velocity, const sim::Texture2D<std::uint32_t>& objectId,
                       const sim::Texture2D<std::uint32_t>& previousObjectId);

// Mean over tracked pixels of |current(p) - previous(source(p))| in codes, the previous image's
// codes interpolated bilinearly (exact for integer motion). 0 when nothing is tracked.
double CompensatedDifference(const DisplayImage& current, const DisplayImage& previous, const Reprojection& reprojection);

// Frames since each pixel was last disoccluded, carried along the motion: 0 for a disoccluded
// pixel, else the age at its source (nearest previous pixel) + 1, capped at `cap`. Frame 0 has
// every pixel at `cap` (nothing was disoccluded before the sequence began).
std::vector<std::uint8_t> AdvanceAges(const std::vector<std::uint8_t>& previousAges, const Reprojection& reprojection,
                                      std::uint8_t cap);

// Mean |image - reference| in codes over pixels whose age is below `young`; nullopt when none is.
std::optional<double> YoungPixelError(const DisplayImage& image, const DisplayImage& reference,
                                      const std::vector<std::uint8_t>& ages, std::uint8_t young);

// Mean |a - b| in codes over the pixels `mask` selects (non-zero), or every pixel when it selects
// none or is empty.
double MeanCodeDifference(const DisplayImage& a, const DisplayImage& b, std::span<const float> mask = {});

// The first frame from which every later distance (to the sequence's final frame) stays within
// `tolerance`; nullopt for an empty list.
std::optional<int> ConvergenceFrame(const std::vector<double>& distanceToFinal, double tolerance);

}  // namespace study
