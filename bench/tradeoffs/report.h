// The bench's outputs: the CSV (one row per configuration), the plot data for gnuplot, and
// docs/tradeoffs.md with the tables and the documents' own figures beside ours.
#pragma once

#include <string>
#include <vector>

#include "tradeoffs/experiments.h"
#include "tradeoffs/shadow_error.h"
#include "tradeoffs/timing_probe.h"

namespace shadowref::bench {

struct Row {
  Experiment experiment;
  ProbeResult timing;
  ShadowError error;
  std::string errorMessage;  // why the error could not be measured ("" when it was)
  int lightsRendered = 0;    // lights after soft expansion (shadow passes per frame)
  bool pareto = false;       // on the error-against-time front of its plot
};

struct RunInfo {
  std::string commit;
  std::string cpu;
  int cores = 0;
  int threads = 1;
  int frames = 5;
  int rounds = 5;  // rounds of probes of every configuration (round_timing.h)
  int referenceSamples = 256;
  BenchSize size;
  long baselineRssKiB = 0;
  std::string loadBefore, loadAfter;  // /proc/loadavg
  std::string date;
  double wallSeconds = 0.0;
};

// Marks each row that no other row of the same plot beats in both time and error.
void markParetoFronts(std::vector<Row>& rows);

void writeCsv(const std::string& path, const RunInfo& info, const std::vector<Row>& rows);
// plot-<name>.dat (every point) and plot-<name>-front.dat (the front, by time) per plot, and
// series files for the resolution and house-count plots.
void writePlotData(const std::string& directory, const std::vector<Row>& rows);
void writeMarkdown(const std::string& path, const RunInfo& info, const std::vector<Row>& rows);

}  // namespace shadowref::bench
