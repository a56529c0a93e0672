#pragma once
// Helpers shared by the benchmarks.

#include <algorithm>
#include <exception>
#include <iostream>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

namespace bench {

// Frame times are skewed by the odd slow frame; the median is what the tables report.
inline double Median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t mid = values.size() / 2;
  return values.size() % 2 == 1 ? values[mid] : 0.5 * (values[mid - 1] + values[mid]);
}

// Whether --pass chose this pass (no --pass: every pass).
inline bool Selected(const std::vector<std::string>& chosen, std::string_view name) {
  return chosen.empty() || std::ranges::find(chosen, name) != chosen.end();
}

// Parses the command line, then returns run()'s exit code; errors are one stderr line prefixed with
// the program name: exit 2 for bad arguments, 1 for a runtime error.
template <typename Run>
int ParseAndRun(CLI::App& app, int argc, char** argv, Run&& run) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& help) {
    return app.exit(help);
  } catch (const CLI::ParseError& error) {
    std::cerr << app.get_name() << ": " << error.what() << '\n';
    return 2;
  }
  try {
    return run();
  } catch (const std::exception& error) {
    std::cerr << app.get_name() << ": " << error.what() << '\n';
    return 1;
  }
}

}  // namespace bench
