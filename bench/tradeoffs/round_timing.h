// The trade-off bench's times over alternating rounds. This machine's host runs at two speeds
// about 1.5× apart and switches between them within minutes (docs/performance.md); one probe per
// configuration then catches some at the one speed and some at the other (a run at d63f7a0 timed
// 100 houses at 11.7 ms and 64 at 15.4: performance-history.md, round 24). Every configuration
// is therefore probed once per round, forward in one round and backward in the next (as
// bench/vs-mesa alternates its runs), and its time is the median of its rounds' medians: drift of
// the host's speed hits every configuration alike, and a round at the other speed moves the
// median less than it moves a single probe.
#pragma once

#include <algorithm>
#include <cstddef>
#include <span>
#include <vector>

#include "cli/timing_stats.h"
#include "tradeoffs/timing_probe.h"

namespace shadowref::bench {

// Which of `count` configurations is probed k-th in round `round`: 0, 1, … in even rounds,
// count − 1, … 0 in odd ones.
inline size_t alternatingIndex(size_t k, size_t count, int round) { return round % 2 == 0 ? k : count - 1 - k; }

// One configuration's probes, one per round, as one result: the median of the rounds' CPU
// medians (and of their wall medians), the fastest and the slowest frame of any round, the
// largest peak resident set. A round that failed makes the whole result fail with its error:
// a configuration that fails once is not timed by the rounds that happened to work.
inline ProbeResult combineRounds(std::span<const ProbeResult> rounds) {
  ProbeResult combined;
  if (rounds.empty()) {
    combined.error = "no rounds";
    return combined;
  }
  std::vector<double> cpu, wall;
  combined.minMs = rounds.front().minMs;
  combined.maxMs = rounds.front().maxMs;
  for (const ProbeResult& r : rounds) {
    if (!r.ok) {
      combined.error = r.error;
      return combined;
    }
    cpu.push_back(r.medianMs);
    wall.push_back(r.wallMedianMs);
    combined.minMs = std::min(combined.minMs, r.minMs);
    combined.maxMs = std::max(combined.maxMs, r.maxMs);
    combined.peakRssKiB = std::max(combined.peakRssKiB, r.peakRssKiB);
  }
  combined.ok = true;
  combined.medianMs = timing::median(cpu);
  combined.wallMedianMs = timing::median(wall);
  return combined;
}

}  // namespace shadowref::bench
