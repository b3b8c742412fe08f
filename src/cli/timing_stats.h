// What `shadowref bench` and the benchmarks in bench/ time frames with: each frame's and each
// pass's milliseconds, and the median they report (timings jump, the mean follows the jumps).
#pragma once

#include <algorithm>
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "shadow/frame_renderer.h"

namespace shadowref::timing {

inline double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Frames timed at one thread count: each frame's time and each pass's, the passes in order.
struct FrameTimes {
  std::vector<double> frameMs;
  std::map<std::string, std::vector<double>> passMs;
  std::vector<std::string> passOrder;

  void add(const FrameResult& frame, double ms) {
    frameMs.push_back(ms);
    for (const PassTiming& t : frame.timings) {
      if (!passMs.count(t.pass)) passOrder.push_back(t.pass);
      passMs[t.pass].push_back(t.milliseconds);
    }
  }
};

}  // namespace shadowref::timing
