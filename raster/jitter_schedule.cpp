// Jitter schedules (see jitter_schedule.h).

#include "raster/jitter_schedule.h"

#include <array>

#include "raster/raster_error.h"

namespace raster {
namespace {

std::vector<SamplePattern> Halton(int length) { return HaltonJitterSequence(length); }

SamplePattern Uniform(std::string name, std::vector<SampleOffset> offsets) {
  return SamplePattern::CreateUniform(std::move(name), offsets);
}

// aa-facts §1.8 (y up): T2x frame 0 (+0.25, -0.25), frame 1 (-0.25, +0.25).
std::vector<SamplePattern> T2x() {
  return {Uniform("t2x:0", {{4, 4}}), Uniform("t2x:1", {{-4, -4}})};
}

// aa-facts §1.8 (y up): 4x frame 0 S0 (+0.375, -0.125), S1 (-0.125, +0.375); frame 1 S2
// (+0.125, -0.375), S3 (-0.375, +0.125): the standard 2x pattern ((4, 4), (-4, -4) sixteenths,
// +y down) moved by the frame's camera jitter.
std::vector<SamplePattern> FourX() {
  return {Uniform("4x:0", {{6, 2}, {-2, -6}}), Uniform("4x:1", {{2, 6}, {-6, -2}})};
}

// One sample of a 2-sample pattern as a 1-sample pattern, quad pixel by quad pixel.
SamplePattern SampleOf(const SamplePattern& pattern, int sample, std::string name) {
  std::array<std::vector<SampleOffset>, kQuadPixels> perPixel;
  for (int p = 0; p < kQuadPixels; ++p) perPixel[p] = {pattern.Offset(p, sample)};
  return SamplePattern::Create(std::move(name), 1, perPixel);
}

std::vector<SamplePattern> Split(std::string_view pattern, std::string_view prefix) {
  const SamplePattern two = MakeBuiltinPattern(pattern, 2);
  std::vector<SamplePattern> frames;
  for (int sample = 0; sample < 2; ++sample) {
    std::string name(prefix);
    name += ':';
    name += std::to_string(sample);
    frames.push_back(SampleOf(two, sample, std::move(name)));
  }
  return frames;
}

struct Entry {
  std::string_view name;
  int samples;  // 0: the run's
};
constexpr std::array<Entry, 7> kSchedules = {{{"none", 0},
                                              {"halton8", 1},
                                              {"halton16", 1},
                                              {"t2x", 1},
                                              {"4x", 2},
                                              {"flipquad-split", 1},
                                              {"quincunx", 1}}};

std::string NameList() {
  std::string names;
  for (const Entry& entry : kSchedules) {
    if (!names.empty()) names += ", ";
    names += entry.name;
  }
  return names;
}

}  // namespace

JitterSchedule JitterSchedule::Make(std::string_view name, const SamplePattern& base) {
  const std::string owned(name);
  if (name == "none") return {owned, {base}};
  if (name == "halton8") return {owned, Halton(8)};
  if (name == "halton16") return {owned, Halton(16)};
  if (name == "t2x") return {owned, T2x()};
  if (name == "4x") return {owned, FourX()};
  if (name == "flipquad-split") return {owned, Split("flipquad", "flipquad-split")};
  if (name == "quincunx") return {owned, Split("quincunx", "quincunx-split")};
  throw RasterError("unknown jitter schedule '" + owned + "' (schedules: " + NameList() + ")");
}

const SamplePattern& JitterSchedule::At(int frame) const {
  if (frame < 0) throw RasterError("jitter schedule '" + name_ + "': frame " + std::to_string(frame) + " is negative");
  return patterns_[static_cast<std::size_t>(frame) % patterns_.size()];
}

std::vector<std::string> JitterScheduleNames() {
  std::vector<std::string> names;
  for (const Entry& entry : kSchedules) names.emplace_back(entry.name);
  return names;
}

int JitterScheduleSamples(std::string_view name) {
  for (const Entry& entry : kSchedules) {
    if (entry.name == name) return entry.samples;
  }
  throw RasterError("unknown jitter schedule '" + std::string(name) + "' (schedules: " + NameList() + ")");
}

}  // namespace raster
