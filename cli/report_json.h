#pragma once
// JSON forms shared by report.json's sections (docs/report.md).

#include <cmath>

#include <nlohmann/json.hpp>

#include "passes/metrics.h"

namespace cli {

// The seeds' timing tables are for 1080p frames (seed 001, "Single Pass / Timing (ms)" and the
// temporal table): the report scales aasim's estimates to this many pixels to set them beside.
inline constexpr double kSeedTimingPixels = 1920.0 * 1080.0;

// Non-finite values (a score with nothing to average) are null.
inline nlohmann::ordered_json Number(double value) {
  return std::isfinite(value) ? nlohmann::ordered_json(value) : nlohmann::ordered_json(nullptr);
}

inline nlohmann::ordered_json QualityJson(const passes::QualityScores& s) {
  return {{"psnr_db", Number(s.psnr)},          {"ssim", Number(s.ssim)},
          {"flip", Number(s.flip)},             {"edge_psnr_db", Number(s.edgePsnr)},
          {"edge_ssim", Number(s.edgeSsim)},    {"edge_flip", Number(s.edgeFlip)},
          {"edge_pixels", s.edgePixels}};
}

}  // namespace cli
