// The trade, measured: every configuration of experiments.cpp timed in its own child
// process (median time per frame, peak memory) and compared with ground truth in this one (the
// ray-cast oracle for hard shadows, an area-light reference for soft ones).
//
//   tradeoffs [--scenes DIR] [--csv FILE] [--plots DIR] [--doc FILE] [--frames N] [--rounds N]
//             [--threads N] [--samples N] [--only GROUP] [--commit TEXT]
//   tradeoffs --probe SCENE METHOD THREADS FRAMES [key=value overrides...]   (the child)
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "scene/scene_loader.h"
#include "shadow/soft_lights.h"
#include "tradeoffs/experiments.h"
#include "tradeoffs/report.h"
#include "tradeoffs/round_timing.h"
#include "tradeoffs/shadow_error.h"
#include "tradeoffs/timing_probe.h"

using namespace shadowref;
using namespace shadowref::bench;

namespace {

struct Args {
  std::string scenes = "scenes", csv = "bench/results/tradeoffs.csv", plots = "bench/results",
              doc = "docs/tradeoffs.md", only, commit = "unknown";
  int frames = 5, rounds = 5, threads = 1, samples = 256;
};

std::string selfPath() {
  char buffer[4096];
  const ssize_t n = readlink("/proc/self/exe", buffer, sizeof buffer - 1);
  return n > 0 ? std::string(buffer, static_cast<size_t>(n)) : "tradeoffs";
}

std::string firstLine(const std::string& path, const std::string& prefix = "") {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(prefix, 0) == 0) return prefix.empty() ? line : line.substr(line.find(':') + 2);
  return "unknown";
}

std::string today() {
  const std::time_t t = std::time(nullptr);
  char buffer[32];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%d %H:%M UTC", std::gmtime(&t));
  return buffer;
}

bool parseArgs(int argc, char** argv, Args& a) {
  for (int i = 1; i < argc; ++i) {
    const std::string k = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::runtime_error(k + " needs a value");
      return argv[++i];
    };
    if (k == "--scenes") a.scenes = value();
    else if (k == "--csv") a.csv = value();
    else if (k == "--plots") a.plots = value();
    else if (k == "--doc") a.doc = value();
    else if (k == "--only") a.only = value();
    else if (k == "--commit") a.commit = value();
    else if (k == "--frames") a.frames = std::stoi(value());
    else if (k == "--rounds") a.rounds = std::stoi(value());
    else if (k == "--threads") a.threads = std::stoi(value());
    else if (k == "--samples") a.samples = std::stoi(value());
    else {
      std::cerr << "tradeoffs: unknown argument " << k << '\n';
      return false;
    }
  }
  if (a.frames < 1 || a.rounds < 1) throw std::runtime_error("--frames and --rounds need at least 1");
  return true;
}

std::string sceneFile(const Experiment& e, const Args& a) { return a.scenes + "/" + e.scene + ".yaml"; }

// The configuration's shadow against its reference (deterministic: measured once) and the lights
// it renders; the timing is measured apart, in rounds (timeInRounds).
Row measureError(const Experiment& e, const Args& a) {
  Row row;
  row.experiment = e;
  const std::string file = sceneFile(e, a);
  try {
    LoadOptions load;
    load.overrides = e.overrides;
    const Scene scene = loadScene(file, load);
    const std::string_view method = e.method;
    for (const Light& l : scene.lights) row.lightsRendered += static_cast<int>(expandSoftLight(l).size());
    ErrorSettings settings;
    settings.reference = e.reference;
    settings.softSpacing = e.softSpacing;
    settings.referenceSamples = a.samples;
    settings.threads = 0;
    settings.forceInfiniteOracle =
        method == "zpass" || method == "zfail" || method == "auto";
    row.error = measureShadowError(scene, method, settings);
  } catch (const std::exception& ex) {
    row.errorMessage = ex.what();
  }
  return row;
}

// Every row's configuration probed once per round, each round a step further down the list
// (round_timing.h), then its rounds combined.
void timeInRounds(std::vector<Row>& rows, const Args& a, const std::string& self) {
  std::vector<std::vector<ProbeResult>> probes(rows.size());
  for (int round = 0; round < a.rounds; ++round) {
    for (size_t k = 0; k < rows.size(); ++k) {
      const size_t i = rotatedIndex(k, rows.size(), round, a.rounds);
      const Experiment& e = rows[i].experiment;
      probes[i].push_back(runProbe(self, ProbeRequest{sceneFile(e, a), e.method, e.overrides, a.threads, a.frames}));
    }
    std::fprintf(stderr, "tradeoffs: timing round %d of %d done\n", round + 1, a.rounds);
  }
  for (size_t i = 0; i < rows.size(); ++i) rows[i].timing = combineRounds(probes[i]);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 2 && std::string(argv[1]) == "--probe") return probeMain(std::vector<std::string>(argv + 2, argv + argc));
  Args args;
  try {
    if (!parseArgs(argc, argv, args)) return 2;
  } catch (const std::exception& e) {
    std::cerr << "tradeoffs: " << e.what() << '\n';
    return 2;
  }
  const auto start = std::chrono::steady_clock::now();
  const std::string self = selfPath();
  RunInfo info;
  info.commit = args.commit;
  info.cpu = firstLine("/proc/cpuinfo", "model name");
  info.cores = static_cast<int>(std::thread::hardware_concurrency());
  info.threads = args.threads;
  info.frames = args.frames;
  info.rounds = args.rounds;
  info.referenceSamples = args.samples;
  info.loadBefore = firstLine("/proc/loadavg");
  info.date = today();
  info.baselineRssKiB = baselineRssKiB(self);

  std::vector<Row> rows;
  const std::vector<Experiment> experiments = allExperiments(info.size);
  for (const Experiment& e : experiments) {
    if (!args.only.empty() && e.group != args.only) continue;
    std::fprintf(stderr, "tradeoffs: %-9s %-10s %-26s %-9s", e.group.c_str(), e.scene.c_str(), e.variant.c_str(),
                 e.method.c_str());
    Row row = measureError(e, args);
    if (row.errorMessage.empty()) std::fprintf(stderr, "  mae %.4f wrong %.4f\n", row.error.mae, row.error.wrong);
    else std::fprintf(stderr, "  error failed: %s\n", row.errorMessage.c_str());
    rows.push_back(std::move(row));
  }
  timeInRounds(rows, args, self);
  for (const Row& row : rows)
    if (!row.timing.ok)
      std::fprintf(stderr, "tradeoffs: %s %s %s: timing failed: %s\n", row.experiment.scene.c_str(),
                   row.experiment.variant.c_str(), row.experiment.method.c_str(), row.timing.error.c_str());
  markParetoFronts(rows);
  info.loadAfter = firstLine("/proc/loadavg");
  info.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  writeCsv(args.csv, info, rows);
  writePlotData(args.plots, rows);
  if (!args.doc.empty()) writeMarkdown(args.doc, info, rows);
  std::fprintf(stderr, "tradeoffs: %zu configurations in %.0f s\n", rows.size(), info.wallSeconds);
  return 0;
}
