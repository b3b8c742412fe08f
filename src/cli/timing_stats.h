// The statistic `shadowref bench` reports timings with, and the benchmarks in bench/ too: the
// median (timings jump, the mean follows the jumps).
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace shadowref::timing {

inline double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace shadowref::timing
