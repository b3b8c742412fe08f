// Statistics of the benchmarks' series (bench/vs-mesa): a least-squares line with its R² (to show
// that cost grows linearly with houses or lights), and the shares of interleaved frames (for those
// lines on a host whose speed changes).
#pragma once

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <vector>

#include "cli/timing_stats.h"

namespace shadowref::timing {

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

// Several scenes' frames timed in turn, frame f of each in cycle f: times[i][f]. Each cycle is short
// beside the host's changes of speed, so a speed that changes from cycle to cycle multiplies every
// time of a cycle alike and leaves each scene's share of it as it is.
struct CycleShares {
  std::vector<std::vector<double>> shares;  // shares[i][f] = times[i][f] / cycles[f]
  std::vector<double> cycles;               // the cycles' times: the sum over the scenes
};

inline CycleShares cycleShares(const std::vector<std::vector<double>>& times) {
  CycleShares c;
  if (times.empty()) return c;
  const size_t frames = times.front().size();
  for (const std::vector<double>& t : times)
    if (t.size() != frames) throw std::invalid_argument("cycleShares: every scene needs one time a cycle");
  c.cycles.assign(frames, 0.0);
  for (const std::vector<double>& t : times)
    for (size_t f = 0; f < frames; ++f) c.cycles[f] += t[f];
  for (const std::vector<double>& t : times) {
    std::vector<double>& s = c.shares.emplace_back();
    for (size_t f = 0; f < frames; ++f) s.push_back(c.cycles[f] > 0.0 ? t[f] / c.cycles[f] : 0.0);
  }
  return c;
}

// A scene's time in the fastest cycle, the one the host slowed least (it only ever adds time): its
// median share of a cycle (a frame slowed alone moves one share, not the median) times that cycle.
inline double fastestCycleTime(const std::vector<double>& shares, const std::vector<double>& cycles) {
  if (cycles.empty()) return 0.0;
  return median(shares) * *std::min_element(cycles.begin(), cycles.end());
}

}  // namespace shadowref::timing
