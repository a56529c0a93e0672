#pragma once
// Resolves of an EQAA surface beyond the frame's own box resolve (sim/eqaa_resolve.h): kernels
// that turn a frame's FMASK and colour fragments into one colour per pixel, compared in the EQAA
// study (issue 14). They have no work set, so no dispatch strategies: each is one or more
// full-screen dispatches whose FMASK, fragment and table reads are counted.
//
// This file is the only list of them; a resolve joins the study, `aasim run --resolves` and the
// tests with one line in resolve.cpp.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec4.hpp>

#include "fmask/eqaa_surface.h"
#include "raster/sample_pattern.h"
#include "sim/dispatch.h"

namespace passes {

struct ResolveInfo {
  std::string_view name;         // registry key: "craa-lut"
  std::string_view description;  // one line for --help and the report
  std::string_view source;       // header with the resolve's diagram
  std::string_view surfaces;     // which surfaces it reads, for messages: "1F surfaces"
  bool (*reads)(const fmask::EqaaConfig& mode);
};

// What a resolve is built from: the frame's sample pattern (CRAA needs the sample positions) and
// where tables derived from it may be cached between runs.
struct ResolveContext {
  const raster::SamplePattern* pattern = nullptr;
  std::optional<std::filesystem::path> tableCache;  // nullopt: derive tables on every run
  // Synthetic configurations the CRAA LUT is fitted to; 0 = the generator's default (craa_lut.h).
  // Fewer make a coarser table faster (tests).
  std::int64_t tableConfigurations = 0;
};

class Resolve {
 public:
  virtual ~Resolve() = default;
  virtual const ResolveInfo& Info() const = 0;
  // Resolves `surface` (a mode Info().reads accepts) into linear RGBA; dispatches go to the
  // machine's report list, named "resolve/<name>[/step]".
  virtual sim::Texture2D<glm::vec4> Run(sim::Machine& machine, const fmask::EqaaSurface& surface) = 0;
};

struct RegisteredResolve {
  const ResolveInfo& (*info)();
  // Throws std::invalid_argument naming the problem (no pattern, a pattern of another sample
  // count, an unreadable table cache).
  std::unique_ptr<Resolve> (*make)(const ResolveContext& context);
};

std::span<const RegisteredResolve> AllResolves();
std::vector<std::string> ResolveNames();
// Throws std::invalid_argument naming the unknown resolve and listing the registered ones.
const RegisteredResolve& ResolveByName(std::string_view name);

}  // namespace passes
