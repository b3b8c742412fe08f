// Small statistics for timings, shared by `shadowref bench` and the benchmarks in bench/: the median
// (timings jump, the mean follows the jumps) and a least-squares line with its R² (to show that
// cost grows linearly with houses or lights).
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

struct LineFit {
  double slope = 0.0, intercept = 0.0;
  double r2 = 0.0;  // 1 for points exactly on the line
};

inline LineFit fitLine(const std::vector<double>& x, const std::vector<double>& y) {
  LineFit f;
  const size_t n = std::min(x.size(), y.size());
  if (n < 2) return f;
  double mx = 0, my = 0;
  for (size_t i = 0; i < n; ++i) mx += x[i], my += y[i];
  mx /= double(n);
  my /= double(n);
  double sxx = 0, sxy = 0, syy = 0;
  for (size_t i = 0; i < n; ++i) {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
    syy += (y[i] - my) * (y[i] - my);
  }
  if (sxx == 0.0) return f;
  f.slope = sxy / sxx;
  f.intercept = my - f.slope * mx;
  f.r2 = syy == 0.0 ? 1.0 : (sxy * sxy) / (sxx * syy);
  return f;
}

}  // namespace shadowref::timing
