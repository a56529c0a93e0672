#pragma once
// Helpers shared by the benchmarks.

#include <algorithm>
#include <vector>

namespace bench {

// Frame times are skewed by the odd slow frame; the median is what the tables report.
inline double Median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t mid = values.size() / 2;
  return values.size() % 2 == 1 ? values[mid] : 0.5 * (values[mid - 1] + values[mid]);
}

}  // namespace bench
