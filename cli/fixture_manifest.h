#pragma once
// The fixture set's manifest (docs/fixtures.md), read apart from `aasim fixtures` so its fuzz
// target builds without the rest of the command line.

#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace cli {

inline constexpr const char* kFixturesSchema = "aasim.fmask.fixtures";
inline constexpr int kFixturesVersion = 1;

// Parses a manifest's text (`source` names it in errors) and checks its schema, version and that
// it lists exactly the canonical fixture set, each fixture once. Throws std::runtime_error with
// one line naming `source`. The fixtures themselves are verified by RunFixturesCommand.
nlohmann::ordered_json ParseFixtureManifest(std::string_view text, const std::string& source);

}  // namespace cli
