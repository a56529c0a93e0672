// Pattern optimiser (see pattern_optimiser.h).

#include "raster/pattern_optimiser.h"

#include <algorithm>
#include <array>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

namespace raster {
namespace {

using Offsets = std::vector<SampleOffset>;

constexpr int kGridSize = kSampleOffsetMax - kSampleOffsetMin + 1;
// Threshold accepting (Dueck & Scheuer 1990): a proposal is kept when it is worse by less than a
// threshold that falls linearly to 0; it starts at this fraction of the start error.
constexpr double kStartThreshold = 0.02;
// One proposal in kJumpOdds moves a sample anywhere on the grid, the others by up to kStep.
constexpr std::uint64_t kJumpOdds = 4;
constexpr int kStep = 2;
constexpr int kMaxPolishSweeps = 16;
// Decorrelates the per-quad-pixel streams of one seed.
constexpr std::uint64_t kStreamStride = 0x9E3779B97F4A7C15ull;

// [0, n) from the top 32 bits, by multiplication, so it depends on nothing but the engine.
int Below(std::mt19937_64& rng, int n) {
  return static_cast<int>(((rng() >> 32) * static_cast<std::uint64_t>(n)) >> 32);
}

Footprint OffsetsFootprint(const Offsets& offsets) {
  Footprint footprint;
  const double weight = 1.0 / static_cast<double>(offsets.size());
  for (const SampleOffset o : offsets) footprint.samples.push_back({o.x / 16.0, o.y / 16.0, weight});
  return footprint;
}

class Search {
 public:
  Search(ReferenceFilter reference, std::int64_t& evaluations) : reference_(reference), evaluations_(evaluations) {}

  double Score(const Offsets& offsets) {
    ++evaluations_;
    return FootprintError(OffsetsFootprint(offsets), reference_);
  }

  // Threshold accepting, then polishing; returns the best offsets seen (the start included).
  Offsets Run(Offsets start, int iterations, std::mt19937_64& rng) {
    Offsets current = std::move(start), best = current;
    double currentError = Score(current), bestError = currentError;
    const double startThreshold = kStartThreshold * currentError;
    for (int k = 0; k < iterations; ++k) {
      Offsets proposal = current;
      Move(proposal[Below(rng, static_cast<int>(proposal.size()))], rng);
      const double error = Score(proposal);
      const double threshold = startThreshold * (iterations - k) / iterations;
      if (error < currentError + threshold) {
        current = std::move(proposal);
        currentError = error;
        if (currentError < bestError) {
          best = current;
          bestError = currentError;
        }
      }
    }
    Polish(best, bestError);
    return best;
  }

 private:
  static void Move(SampleOffset& offset, std::mt19937_64& rng) {
    if (Below(rng, kJumpOdds) == 0) {
      offset = {kSampleOffsetMin + Below(rng, kGridSize), kSampleOffsetMin + Below(rng, kGridSize)};
      return;
    }
    const int dx = Below(rng, 2 * kStep + 1) - kStep, dy = Below(rng, 2 * kStep + 1) - kStep;
    offset = {std::clamp(offset.x + dx, kSampleOffsetMin, kSampleOffsetMax),
              std::clamp(offset.y + dy, kSampleOffsetMin, kSampleOffsetMax)};
  }

  // Each sample in turn tries every grid position; sweeps until none improves.
  void Polish(Offsets& offsets, double& error) {
    for (int sweep = 0; sweep < kMaxPolishSweeps; ++sweep) {
      bool improved = false;
      for (SampleOffset& offset : offsets) {
        const SampleOffset kept = offset;
        SampleOffset bestOffset = kept;
        for (int y = kSampleOffsetMin; y <= kSampleOffsetMax; ++y) {
          for (int x = kSampleOffsetMin; x <= kSampleOffsetMax; ++x) {
            offset = {x, y};
            const double e = Score(offsets);
            if (e < error) {
              error = e;
              bestOffset = offset;
              improved = true;
            }
          }
        }
        offset = bestOffset;
      }
      if (!improved) return;
    }
  }

  ReferenceFilter reference_;
  std::int64_t& evaluations_;
};

Offsets PixelOffsets(const SamplePattern& pattern, int quadPixel) {
  Offsets offsets;
  for (int s = 0; s < pattern.Count(); ++s) offsets.push_back(pattern.Offset(quadPixel, s));
  return offsets;
}

}  // namespace

double OptimiserError(const SamplePattern& pattern, ReferenceFilter reference) {
  std::array<Footprint, kQuadPixels> footprints;
  for (int p = 0; p < kQuadPixels; ++p) footprints[p] = BoxFootprint(pattern, p);
  return PatternError(footprints, reference);
}

OptimiserResult OptimisePattern(const SamplePattern& start, const OptimiserOptions& options, std::string name) {
  if (options.iterations < 0) throw std::invalid_argument("optimiser iterations must be >= 0");
  OptimiserResult result{start, OptimiserError(start, options.reference), 0.0, 0};
  Search search(options.reference, result.evaluations);
  std::array<Offsets, kQuadPixels> perPixel;
  if (options.perQuadPixel) {
    for (int p = 0; p < kQuadPixels; ++p) {
      std::mt19937_64 rng(options.seed + kStreamStride * static_cast<std::uint64_t>(p));
      perPixel[p] = search.Run(PixelOffsets(start, p), options.iterations, rng);
    }
  } else {
    // The start's best pixel bounds the result by the start's root-mean-square error.
    int bestPixel = 0;
    double bestError = 0.0;
    for (int p = 0; p < kQuadPixels; ++p) {
      const double e = search.Score(PixelOffsets(start, p));
      if (p == 0 || e < bestError) bestPixel = p, bestError = e;
    }
    std::mt19937_64 rng(options.seed);
    perPixel.fill(search.Run(PixelOffsets(start, bestPixel), options.iterations, rng));
  }
  result.pattern = SamplePattern::Create(std::move(name), start.Count(), perPixel);
  result.error = OptimiserError(result.pattern, options.reference);
  return result;
}

}  // namespace raster
