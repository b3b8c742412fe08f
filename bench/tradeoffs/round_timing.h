// The trade-off bench's times over rounds. This machine's host runs at two speeds about 1.5×
// apart and switches between them within minutes; one probe per
// configuration then catches some at the one speed and some at the other (a run at d63f7a0 timed
// 100 houses at 11.7 ms and 64 at 15.4). Every configuration
// is therefore probed once per round, each round starting a step further down the list, so that a
// configuration's probes lie spread over the whole run, and its time is the median of its rounds'
// medians. Not the fastest round: two runs minutes apart at 380cb3d, scaled to agree on the median
// configuration, agreed within 10 % on 84 of 102 configurations by the median of the rounds and
// on 36 by the fastest round (the host's fast moments are not one steady speed).
#pragma once

#include <algorithm>
#include <cstddef>
#include <span>
#include <vector>

#include "cli/timing_stats.h"
#include "tradeoffs/timing_probe.h"

namespace shadowref::bench {

// Which of `count` configurations is probed k-th in round `round` of `rounds`: round r starts at
// configuration r · count / rounds and wraps round, so every configuration is probed once a round
// and its probes are about a round apart — not, as in rounds that alternate their direction, two
// probes close together at each end of the list.
inline size_t rotatedIndex(size_t k, size_t count, int round, int rounds) {
  const size_t start = rounds > 0 ? size_t(round % rounds) * count / size_t(rounds) : 0;
  return (k + start) % count;
}

// One configuration's probes, one per round, as one result: the median of the rounds' medians as
// its time (and of their wall medians), the fastest round's median beside it, the fastest and the
// slowest frame of any round, the largest peak resident set. A round that failed makes the whole
// result fail with its error: a configuration that fails once is not timed by the rounds that
// happened to work.
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
  combined.fastestRoundMs = *std::min_element(cpu.begin(), cpu.end());
  combined.wallMedianMs = timing::median(wall);
  return combined;
}

}  // namespace shadowref::bench
