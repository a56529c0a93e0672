#pragma once
// A pass's settings: a schema (name, default, legal range, help) the pass declares once, presets
// over it, and validated values. The command line, sweeps and --help read the schema; nothing is
// clamped or defaulted silently: a value outside its range or an unknown key is an error naming
// the pass and the key.

#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace passes {

struct SettingInfo {
  std::string_view name;  // "threshold"
  double defaultValue = 0.0;
  double min = 0.0, max = 0.0;
  bool minExclusive = false;  // (min, max] instead of [min, max]
  bool integer = false;
  std::string_view doc;  // one line, with the source of the default
  // When not empty, the only legal values within the range (FXAA's quality presets 10-15, 20-29, 39).
  std::vector<double> allowed = {};
};

// "[0, 1]", "(0, 0.5]", or the legal values "{10, 11, 39}".
std::string RangeText(const SettingInfo& info);

struct Preset {
  std::string_view name;  // "high"
  std::vector<std::pair<std::string_view, double>> values;
};

class SettingsError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// Values for every setting of one pass, in schema order.
class PassSettings {
 public:
  // The defaults.
  PassSettings(std::string_view pass, std::span<const SettingInfo> schema);

  // Throws SettingsError naming the pass and key for an unknown key, a value that is not a finite
  // number, not an integer where one is required, or outside the range.
  void Set(std::string_view key, double value);
  double Get(std::string_view key) const;
  std::span<const SettingInfo> Schema() const { return schema_; }
  std::span<const double> Values() const { return values_; }

 private:
  std::size_t IndexOf(std::string_view key) const;

  std::string pass_;
  std::span<const SettingInfo> schema_;
  std::vector<double> values_;
};

// "smaa:preset=high,threshold=0.05" split into the pass name and its key=value pairs, values
// unparsed. Throws SettingsError for an empty name, an item without '=', or a repeated key.
struct PassSpec {
  std::string name;
  std::vector<std::pair<std::string, std::string>> values;
};
PassSpec ParsePassSpec(std::string_view text);

// "demo:threshold=0.2,smaa:preset=high,threshold=0.05" -> one spec per pass. An item with '='
// and no ':' before it continues the previous pass's settings (pass names never contain '=').
// Throws SettingsError for settings before any pass name or an empty item.
std::vector<std::string> SplitPassList(std::string_view text);

// Applies a spec's values to the schema's defaults: "preset=NAME" first (wherever it appears),
// then every other key in order. Values are decimal numbers ("0.05", "1e-2"); "inf" and "nan" are
// refused.
PassSettings ResolveSettings(const PassSpec& spec, std::span<const SettingInfo> schema,
                             std::span<const Preset> presets);

// "threshold=0.1, ..." for --help and reports.
std::string DescribeSettings(const PassSettings& settings);
// A setting's value as DescribeSettings writes it (9 significant digits).
std::string FormatValue(double value);

}  // namespace passes
