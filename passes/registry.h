#pragma once
// The only list of post passes. The command line (`aasim run --post`, `aasim frame --post`), the
// memory guards, the benchmarks and the tests iterate it; a pass joins all of them with one line
// in registry.cpp.

#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "passes/pass.h"

namespace passes {

struct RegisteredPass {
  const PassInfo& (*info)();
  std::unique_ptr<Pass> (*make)(const PassSettings& settings);
};

std::span<const RegisteredPass> AllPasses();
std::vector<std::string> PassNames();
// Throws SettingsError naming the unknown pass and listing the registered ones.
const RegisteredPass& PassByName(std::string_view name);

// A pass and its validated settings, as the command line resolves "name[:key=value,...]".
struct PassConfig {
  const RegisteredPass* pass = nullptr;
  PassSettings settings;

  const PassInfo& Info() const { return pass->info(); }
  std::unique_ptr<Pass> Make() const { return pass->make(settings); }
};
// Throws SettingsError naming the pass and the offending key or value.
PassConfig ResolvePass(std::string_view spec);

}  // namespace passes
