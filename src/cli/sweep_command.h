// `shadowref sweep SPEC`: the jobs of a sweep file (src/sweep, docs/sweeps.md) listed, run (all,
// or one shard of them) or merged into a CSV, plots and a Markdown table.
#pragma once

#include <string>

namespace CLI {
class App;
}

namespace shadowref::cli {

struct SweepArgs {
  std::string spec;
  std::string out;    // the records' folder; empty: out/sweeps/<the sweep file's name>
  std::string shard;  // "K/N"; empty: every job
  int threads = -1;   // render threads; -1: the sweep file's
  bool list = false, merge = false, noTiming = false;
  std::string csv, plots, table;  // --merge's outputs; empty: OUTDIR/results.csv, OUTDIR/plots, none
};

void addSweepCommand(CLI::App& app, SweepArgs& args);
int runSweep(const SweepArgs& args);

}  // namespace shadowref::cli
