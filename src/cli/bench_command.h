// `shadowref bench [SCENE]`: renders the same frame several times and reports the median time per
// frame and per pass. It prints timings and judges none: a time is a measurement of this machine
// at this moment, never a pass/fail test. (The benchmarks in bench/ look inside a frame's threads
// and compare with Mesa.)
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
  std::string pipeline = "fast";  // reference, fast
  bool csv = false;
};

void addBenchCommand(CLI::App& app, BenchArgs& args);
int runBench(const BenchArgs& args);

}  // namespace shadowref::cli
