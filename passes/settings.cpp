// Pass settings: schema checks and "name:key=value" parsing (see settings.h).

#include "passes/settings.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>

namespace passes {
namespace {

std::string Quote(std::string_view text) { return "'" + std::string(text) + "'"; }

}  // namespace

std::string FormatValue(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", value);
  return text;
}

std::string RangeText(const SettingInfo& info) {
  std::string text;
  if (!info.allowed.empty()) {
    // Appended piece by piece: GCC 12's -Wrestrict misfires on "{" + std::string.
    text += '{';
    for (const double value : info.allowed) {
      if (text.size() > 1) text += ", ";
      text += FormatValue(value);
    }
    text += '}';
    return text;
  }
  text += info.minExclusive ? '(' : '[';
  text += FormatValue(info.min);
  text += ", ";
  text += FormatValue(info.max);
  text += ']';
  return text;
}

namespace {

std::string Keys(std::span<const SettingInfo> schema) {
  std::string keys;
  for (const SettingInfo& info : schema) keys += (keys.empty() ? "" : ", ") + std::string(info.name);
  return keys.empty() ? "none" : keys;
}

double ParseNumber(std::string_view pass, std::string_view key, std::string_view text) {
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
    throw SettingsError("pass " + std::string(pass) + ": " + std::string(key) + "=" + std::string(text) +
                        " is not a finite decimal number");
  }
  return value;
}

}  // namespace

PassSettings::PassSettings(std::string_view pass, std::span<const SettingInfo> schema)
    : pass_(pass), schema_(schema) {
  for (const SettingInfo& info : schema) values_.push_back(info.defaultValue);
}

std::size_t PassSettings::IndexOf(std::string_view key) const {
  for (std::size_t i = 0; i < schema_.size(); ++i) {
    if (schema_[i].name == key) return i;
  }
  throw SettingsError("pass " + pass_ + ": unknown setting " + Quote(key) + " (settings: " + Keys(schema_) +
                      (key == "preset" ? "; this pass has no presets" : "") + ")");
}

void PassSettings::Set(std::string_view key, double value) {
  const std::size_t index = IndexOf(key);
  const SettingInfo& info = schema_[index];
  const bool aboveMin = info.minExclusive ? value > info.min : value >= info.min;
  if (!std::isfinite(value) || !aboveMin || value > info.max) {
    throw SettingsError("pass " + pass_ + ": " + std::string(key) + "=" + FormatValue(value) + " outside " +
                        RangeText(info));
  }
  if (info.integer && value != std::floor(value)) {
    throw SettingsError("pass " + pass_ + ": " + std::string(key) + "=" + FormatValue(value) +
                        " must be an integer");
  }
  if (!info.allowed.empty() && std::find(info.allowed.begin(), info.allowed.end(), value) == info.allowed.end()) {
    throw SettingsError("pass " + pass_ + ": " + std::string(key) + "=" + FormatValue(value) + " is not one of " +
                        RangeText(info));
  }
  values_[index] = value;
}

double PassSettings::Get(std::string_view key) const { return values_[IndexOf(key)]; }

PassSpec ParsePassSpec(std::string_view text) {
  PassSpec spec;
  const std::size_t colon = text.find(':');
  spec.name = std::string(text.substr(0, colon));
  if (spec.name.empty()) throw SettingsError("pass spec " + Quote(text) + ": no pass name before ':'");
  if (colon == std::string_view::npos) return spec;
  std::string_view rest = text.substr(colon + 1);
  while (true) {
    const std::size_t comma = rest.find(',');
    const std::string_view item = rest.substr(0, comma);
    const std::size_t equals = item.find('=');
    if (equals == std::string_view::npos || equals == 0) {
      throw SettingsError("pass " + spec.name + ": " + Quote(item) + " is not key=value");
    }
    std::string key(item.substr(0, equals));
    const bool repeated = std::any_of(spec.values.begin(), spec.values.end(),
                                      [&](const auto& entry) { return entry.first == key; });
    if (repeated) throw SettingsError("pass " + spec.name + ": " + key + " is given twice");
    spec.values.emplace_back(std::move(key), std::string(item.substr(equals + 1)));
    if (comma == std::string_view::npos) break;
    rest = rest.substr(comma + 1);
  }
  return spec;
}

std::vector<std::string> SplitPassList(std::string_view text) {
  std::vector<std::string> specs;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string_view item = text.substr(start, comma - start);
    if (item.empty()) throw SettingsError("pass list " + Quote(text) + ": empty item");
    const std::size_t equals = item.find('='), colon = item.find(':');
    const bool continuesSettings = equals != std::string_view::npos && (colon == std::string_view::npos || colon > equals);
    if (!continuesSettings) {
      specs.emplace_back(item);
    } else if (specs.empty()) {
      throw SettingsError("pass list " + Quote(text) + ": setting " + Quote(item) + " before any pass name");
    } else {
      specs.back().push_back(specs.back().find(':') == std::string::npos ? ':' : ',');
      specs.back().append(item);
    }
    start = comma + 1;
  }
  return specs;
}

PassSettings ResolveSettings(const PassSpec& spec, std::span<const SettingInfo> schema,
                             std::span<const Preset> presets) {
  PassSettings settings(spec.name, schema);
  for (const auto& entry : spec.values) {
    const std::string& key = entry.first;
    const std::string& value = entry.second;
    if (key != "preset" || presets.empty()) continue;
    const auto preset = std::find_if(presets.begin(), presets.end(), [&](const Preset& p) { return p.name == value; });
    if (preset == presets.end()) {
      std::string names;
      for (const Preset& p : presets) names += (names.empty() ? "" : ", ") + std::string(p.name);
      throw SettingsError("pass " + spec.name + ": unknown preset " + Quote(value) + " (presets: " + names + ")");
    }
    for (const auto& [presetKey, presetValue] : preset->values) settings.Set(presetKey, presetValue);
  }
  for (const auto& [key, value] : spec.values) {
    if (key == "preset" && !presets.empty()) continue;
    settings.Set(key, ParseNumber(spec.name, key, value));
  }
  return settings;
}

std::string DescribeSettings(const PassSettings& settings) {
  std::string text;
  for (std::size_t i = 0; i < settings.Schema().size(); ++i) {
    text += (text.empty() ? "" : ", ") + std::string(settings.Schema()[i].name) + "=" +
            FormatValue(settings.Values()[i]);
  }
  return text;
}

}  // namespace passes
