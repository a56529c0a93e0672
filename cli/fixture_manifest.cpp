// The fixture manifest reader (see fixture_manifest.h).

#include "cli/fixture_manifest.h"

#include <algorithm>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "fmask/fixtures.h"
#include "raster/json_input.h"

namespace cli {
namespace {

using Json = nlohmann::ordered_json;

// The manifest must list exactly the canonical set this aasim derives, each fixture once: a
// manifest with fixtures removed would otherwise verify what is left and call the set good.
void CheckCanonicalNames(const Json& fixtures, const std::string& source) {
  std::vector<std::string> expected;
  for (const fmask::FixtureSpec& spec : fmask::CanonicalFixtureSet()) {
    expected.push_back(fmask::FixtureName(spec));
  }
  std::ranges::sort(expected);
  std::vector<std::string> listed;
  for (std::size_t i = 0; i < fixtures.size(); ++i) {
    const Json& entry = fixtures[i];
    if (!entry.is_object() || !entry.contains("name") || !entry["name"].is_string()) {
      throw std::runtime_error(source + ": fixtures[" + std::to_string(i) + "] has no 'name' string");
    }
    listed.push_back(entry["name"].get<std::string>());
  }
  std::ranges::sort(listed);
  if (const auto twice = std::ranges::adjacent_find(listed); twice != listed.end()) {
    throw std::runtime_error(source + ": fixture " + raster::JsonExcerpt(Json(*twice)) + " is listed twice");
  }
  std::vector<std::string> extra;
  std::ranges::set_difference(listed, expected, std::back_inserter(extra));
  if (!extra.empty()) {
    throw std::runtime_error(source + ": fixture " + raster::JsonExcerpt(Json(extra.front())) +
                             " is not in the canonical set of " + std::to_string(expected.size()));
  }
  std::vector<std::string> missing;
  std::ranges::set_difference(expected, listed, std::back_inserter(missing));
  if (!missing.empty()) {
    std::string names;
    for (std::size_t i = 0; i < std::min<std::size_t>(missing.size(), 3); ++i) names += (i ? ", " : "") + missing[i];
    throw std::runtime_error(source + ": " + std::to_string(missing.size()) + " of the " +
                             std::to_string(expected.size()) + " canonical fixtures are missing (" + names +
                             (missing.size() > 3 ? ", ..." : "") + ")");
  }
}

}  // namespace

nlohmann::ordered_json ParseFixtureManifest(std::string_view text, const std::string& source) {
  Json manifest;
  try {
    manifest = raster::ParseJsonText<Json>(text, /*allowComments=*/false);
  } catch (const raster::JsonTextError& error) {
    throw std::runtime_error(source + ": " + error.what());
  }
  if (!manifest.is_object() || manifest.value("schema", Json()) != kFixturesSchema) {
    throw std::runtime_error(source + ": schema is not " + std::string(kFixturesSchema));
  }
  if (manifest.value("version", Json()) != kFixturesVersion) {
    throw std::runtime_error(source + ": version " + raster::JsonExcerpt(manifest.value("version", Json())) +
                             " is not supported (this aasim reads version " + std::to_string(kFixturesVersion) +
                             ")");
  }
  if (!manifest.contains("fixtures") || !manifest["fixtures"].is_array()) {
    throw std::runtime_error(source + ": 'fixtures' is not a list");
  }
  CheckCanonicalNames(manifest["fixtures"], source);
  return manifest;
}

}  // namespace cli
