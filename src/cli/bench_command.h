// `shadowref bench [SCENE]`: renders the same frame several times and reports the median time per
// frame and per pass. Timing is a measurement, never a pass/fail test.
#pragma once

#include <string>

#include "cli/cli_common.h"

namespace CLI {
class App;
}

namespace shadowref::cli {

struct BenchArgs {
  SceneArgs scene;
  std::string method;
  int frames = 5;
  int threads = 0;
  bool csv = false;
  bool runs = false;  // --runs: each pool run of a frame
  bool alternate = false;  // --alternate: frames at one thread and at --threads in turn, in one process
};

void addBenchCommand(CLI::App& app, BenchArgs& args);
int runBench(const BenchArgs& args);

}  // namespace shadowref::cli
