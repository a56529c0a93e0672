// The resolve registry (see resolve.h).

#include "passes/resolve.h"

#include <stdexcept>

#include "passes/craa/craa_lut_resolve.h"
#include "passes/craa/craa_simple.h"
#include "passes/resolves/fetch.h"

namespace passes {

std::span<const RegisteredResolve> AllResolves() {
  static const RegisteredResolve kResolves[] = {
      {resolves::FetchInfo, resolves::MakeFetch},
      {craa::SimpleInfo, craa::MakeSimple},
      {craa::LutInfo, craa::MakeLut},
  };
  return kResolves;
}

std::vector<std::string> ResolveNames() {
  std::vector<std::string> names;
  for (const RegisteredResolve& resolve : AllResolves()) names.emplace_back(resolve.info().name);
  return names;
}

const RegisteredResolve& ResolveByName(std::string_view name) {
  for (const RegisteredResolve& resolve : AllResolves()) {
    if (resolve.info().name == name) return resolve;
  }
  std::string names;
  for (const std::string& each : ResolveNames()) names += (names.empty() ? "" : ", ") + each;
  throw std::invalid_argument("unknown resolve '" + std::string(name) + "' (resolves: " + names + ")");
}

}  // namespace passes
