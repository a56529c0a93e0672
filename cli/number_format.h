#pragma once
// Numbers as the command line prints them (tables, the summary, the report): one formatter so the
// same value never reads differently in two outputs.

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>

namespace cli {

// "%.*f", with "n/a" for NaN (a score with nothing to average) and "inf" / "-inf".
inline std::string FormatFixed(double value, int decimals) {
  if (!std::isfinite(value)) return std::isnan(value) ? "n/a" : (value > 0 ? "inf" : "-inf");
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

// part / whole as a percentage with one decimal; "-" when there is no whole.
inline std::string FormatPercent(std::uint64_t part, std::uint64_t whole) {
  return whole == 0 ? "-" : FormatFixed(100.0 * static_cast<double>(part) / static_cast<double>(whole), 1);
}

}  // namespace cli
