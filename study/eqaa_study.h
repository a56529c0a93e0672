#pragma once
// The EQAA study of a run (issue 14): every mode's surface under every resolve that reads it,
// side by side — quality against the ground truth, what the colour block wrote and the resolve
// read per pixel, the UNKNOWN samples it had to reconstruct, and the resolve's lanes and time.
// The rows are derived from a Study's frames and dispatch log; nothing here is typed twice.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "fmask/eqaa_surface.h"
#include "passes/metrics.h"

namespace study {

struct Study;
struct StudyFrame;

// UNKNOWN samples of a surface at the end of its frame, by the cause that made them so.
struct UnknownSamples {
  std::uint64_t initial = 0, eviction = 0, untestable = 0;
  std::uint64_t Total() const { return initial + eviction + untestable; }
};
UnknownSamples CountUnknownSamples(const fmask::EqaaSurface& surface);

// What the colour block wrote while the frame was drawn, modelled from its counters (docs/eqaa.md
// "Counters"): every pixel update reads and writes the pixel's FMASK element; an update whose
// fragment claimed a sample writes one 4-byte RGBA8 colour fragment. Not counted by the machine's
// views (the colour block is fixed function), so labelled a model wherever it is shown.
struct ColourBlockBytes {
  std::uint64_t fmaskRead = 0, fmaskWritten = 0, colourWritten = 0;
};
ColourBlockBytes ModelColourBlockBytes(const fmask::FragmentCounters& counters, const fmask::EqaaConfig& mode);

struct EqaaStudyRow {
  std::string mode;     // "8S/8Z/1F"
  std::string policy;   // arbitration policy of the frame
  std::string resolve;  // "box" (the frame's own), or a registered resolve's name
  passes::QualityScores quality;
  std::uint64_t pixels = 0;
  ColourBlockBytes written;          // the frame's draw, per frame (divide by pixels for per pixel)
  std::uint64_t fmaskBytesRead = 0;      // by the resolve's dispatches
  std::uint64_t fragmentBytesRead = 0;   // colour fragments, the pixel's and its neighbours'
  std::uint64_t tableBytesRead = 0;      // every other resource the resolve read (the CRAA LUT)
  UnknownSamples unknown;
  std::uint64_t evictions = 0;
  std::uint64_t resolveWaves = 0, resolveLanesActive = 0, resolveLanesLaunched = 0;
  double resolveMicroseconds = 0.0;  // an estimate (docs/timing-model.md)
};

// Rows in frame order, the box resolve first within a frame, then its resolves in registry order.
std::vector<EqaaStudyRow> EqaaStudyRows(const Study& study);

}  // namespace study
