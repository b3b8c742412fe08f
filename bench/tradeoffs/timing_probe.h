// Time per frame and peak memory of one configuration, measured in a fresh child process (fork +
// exec) so that its peak resident set (VmHWM) is that configuration's alone.
#pragma once

#include <string>
#include <vector>

namespace shadowref::bench {

struct ProbeRequest {
  std::string sceneFile;
  std::string method;
  std::vector<std::string> overrides;
  int threads = 1;
  int frames = 5;  // timed frames, after one warm-up frame
};

struct ProbeResult {
  bool ok = false;
  std::string error;
  // Process CPU time per frame (CLOCK_PROCESS_CPUTIME_ID): on a shared, loaded machine far steadier
  // than wall time, which also counts the time other processes hold the core.
  double medianMs = 0.0, minMs = 0.0, maxMs = 0.0;
  double wallMedianMs = 0.0;  // wall time per frame (steady_clock), for comparison
  // Probes combined over rounds (round_timing.h): medianMs is then the median of the rounds'
  // medians, this the fastest round's.
  double fastestRoundMs = 0.0;
  long peakRssKiB = 0;  // VmHWM of the child: binary, libraries, scene and every buffer
};

// Runs `self --probe ...` and reads its one line of output. `self` is this program's path.
ProbeResult runProbe(const std::string& self, const ProbeRequest& request);

// The child's side: argv after "--probe" (scene method threads frames [overrides...]); prints
// "ok cpuMedian cpuMin cpuMax peakKiB wallMedian" or "error message" on stdout. Returns the exit status.
int probeMain(const std::vector<std::string>& args);

// Peak resident set of a child that loads nothing and renders nothing: the floor under every
// configuration's figure.
long baselineRssKiB(const std::string& self);

}  // namespace shadowref::bench
