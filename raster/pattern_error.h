#pragma once
// Sample-pattern error: a Laine–Aila-style weighted coverage error for straight edges over all
// orientations and offsets (aa-facts §8; definition, choices and values in
// docs/sample-patterns.md "Pattern error"). It scores a pixel's resolve footprint: the sample
// positions a resolve reads for the pixel and the weights it gives them.

#include <array>
#include <string>
#include <vector>

#include "raster/limits.h"
#include "raster/sample_pattern.h"

namespace raster {

// One sample of a footprint: position in px from the pixel centre (+y down) and its weight.
struct FootprintSample {
  double x = 0.0;
  double y = 0.0;
  double weight = 0.0;
  friend bool operator==(const FootprintSample&, const FootprintSample&) = default;
};

// The samples one pixel's resolve reads, weights summing to 1. Positions may lie on the pixel's
// border and belong to a neighbour (quincunx corners, FLIPQUAD edge points).
struct Footprint {
  std::vector<FootprintSample> samples;
};

// What the footprint's estimate is compared with: the half-plane's coverage of
//   kBox   the pixel square (area coverage, what a box resolve estimates);
//   kTent  the pixel square convolved with itself (a separable tent of radius 1 px): the pixel
//          widened by the 0.5-px-radius blur seed 001 attributes to quincunx and FLIPQUAD.
enum class ReferenceFilter { kBox, kTent };
const char* ReferenceFilterName(ReferenceFilter reference);

// The pixel's own samples with equal weights (the box resolve).
Footprint BoxFootprint(const SamplePattern& pattern, int quadPixel);
// Every sample of the 3x3 pixel neighbourhood that lies on the closed pixel square, each weighted
// by 1 / (the number of pixels whose closed square holds it), normalised to sum 1: the resolve of
// patterns that share border samples (quincunx: centre 1/2, corners 1/8; FLIPQUAD: four edge
// points 1/4, two of them the neighbours').
Footprint SharedFootprint(const SamplePattern& pattern, int quadPixel);
// The footprints a pattern is resolved with: shared for the built-in `quincunx` and `flipquad`
// (compared by offsets), box otherwise.
bool IsSharedSamplePattern(const SamplePattern& pattern);
std::array<Footprint, kQuadPixels> ResolveFootprints(const SamplePattern& pattern);

// e(phi) = integral over all offsets t of (reference coverage - footprint estimate)^2 for the
// half-plane {p : p . (cos phi, sin phi) < t}, in px (docs/sample-patterns.md).
double EdgeError(const Footprint& footprint, double normalAngle, ReferenceFilter reference);
// E = sqrt(12 * weighted mean of e over orientations); 1 = a centre sample on axis-aligned edges
// against the box reference.
double FootprintError(const Footprint& footprint, ReferenceFilter reference);
// Root mean square of FootprintError over the four quad pixels' footprints.
double PatternError(const std::array<Footprint, kQuadPixels>& footprints, ReferenceFilter reference);
double PatternError(const SamplePattern& pattern, ReferenceFilter reference);

// Orientation discretisation and weighting (docs/sample-patterns.md "Pattern error").
inline constexpr int kErrorOrientations = 256;  // midpoints over [0, pi); a multiple of 4
inline constexpr double kAxisEmphasis = 0.25;     // w(phi) = 1 + kAxisEmphasis cos(4 phi)

}  // namespace raster
