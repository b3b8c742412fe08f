// bench/vs-mesa: the same frames through Mesa's software rasterizers (OSMesa, softpipe
// and llvmpipe) and through shadowref, side by side in one run; the ratios, the determinism check
// across thread counts, and the cost against the number of houses and lights.
//
// Every timed run is a child process (this program with --worker): Mesa picks its driver
// (GALLIUM_DRIVER) and llvmpipe its thread count (LP_NUM_THREADS) once per process, and a fresh
// process gives every configuration the same start. Runs alternate between the configurations,
// round by round in A B C … C B A order, because llvmpipe's timings jump between runs; each run
// reports the median of its frames, each configuration the median of its runs. Each round runs
// every compared scene once (each round from another one on), so that a slow stretch of the host
// is shared out among them. The houses and lights series are measured differently: each of
// shadowref's runs renders every point of a series in turn in one process, and a point's figure is
// its share of those cycles (measureSeries); Mesa's, for comparison, are the fastest run a point.
//
// Both run twice over, in two like-for-like pairs: Mesa with GL's fixed-function lighting (per
// vertex) against shadowref with every material switched to Gouraud shading (the same lighting
// equation per vertex, the colour interpolated), and Mesa with a GLSL program that shades per pixel
// with shadowref's Phong model (mesa_frame.h) against shadowref as the scenes are written (per
// pixel). The original reference figures are fixed-function Mesa against per-pixel shadowref,
// unequal work; that ratio is printed too. How close each Mesa frame is to its shadowref partner
// (share of pixels more than 2/255 apart, mean difference) is the last table of a whole run: it is
// what shows the pairs like for like. --agreement prints only that table, --images DIR keeps its
// frames as PNG. Two threads / one is measured on frames at one thread and at two in turn in one
// process, one such process a scene a round (Config::inTurn), since separate processes' figures
// meet different hosts: this one's speed drifts by 10-20 % within minutes. It is printed beside the
// machine's capacity for two busy threads: the 1-thread frame rendered by two processes at once,
// in the same alternating rounds; and the time a cache line takes between the cores, measured
// before every 2-thread run. It is a figure, not a target: on a shared host of two cores the host
// decides it, not the code. What more threads must do is give the same bytes: every buffer of 1,
// 2 and 8 threads is compared, and a difference fails the run. A run ends with the speed targets
// checked against its own figures (speed_targets.h).
//
//   vs_mesa [--rounds N] [--frames N] [--csv FILE] [--quick] [--no-scaling | --series]
//   vs_mesa --agreement [--images DIR]
//   vs_mesa --tally RUN.txt...       (the targets over saved runs: target_tally.h)
#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <optional>
#include <pthread.h>
#include <sched.h>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <unistd.h>
#include <vector>

#include "frames_in_turn.h"
#include "identical_frames.h"
#include "speed_targets.h"
#include "series_stats.h"
#include "target_tally.h"
#include "osmesa/osmesa_harness.h"
#include "image/image_writer.h"
#include "mesa_frame.h"
#include "memory/allocator_tuning.h"
#include "scene/scene_loader.h"
#include "shadow/frame_renderer.h"

namespace shadowref::bench {

using timing::fitLine;
using timing::LineFit;
using timing::median;

namespace {

// ---------------------------------------------------------------------------------------------
// What is measured.

struct SceneCase {
  std::string label;
  std::string file;  // relative to the source tree
  std::vector<std::string> overrides;
  int houses = 0, lights = 0;  // for the scaling sections
};

std::vector<SceneCase> comparedScenes() {
  return {
      {"room", "scenes/room.yaml", {"shadow.method=zfail"}},
      {"pumpkins", "scenes/pumpkins.yaml", {"shadow.method=zfail"}},
      {"city-64", "scenes/city.yaml", {"shadow.method=zfail", "generator.houses=64"}},
      {"outdoor-sm2048", "scenes/outdoor.yaml", {"shadow.method=shadowmap", "shadow.map_size=2048"}},
  };
}

// The city of `houses` houses and `lights` lights; framedHouses > houses puts the camera, the
// lights and the ground where they are for that many houses (generator.framed_houses).
SceneCase cityCase(int houses, int lights, int framedHouses = 0) {
  SceneCase c{"city", "scenes/city.yaml",
              {"shadow.method=zfail", "generator.houses=" + std::to_string(houses),
               "generator.lights=" + std::to_string(lights)}};
  if (framedHouses > houses) c.overrides.push_back("generator.framed_houses=" + std::to_string(framedHouses));
  c.label = "city-h" + std::to_string(houses) + "-l" + std::to_string(lights);
  c.houses = houses;
  c.lights = lights;
  return c;
}

enum class Engine { Shadowref, Llvmpipe, Softpipe };

// Every configuration lights per vertex or per pixel: Mesa with fixed-function lighting or its
// per-pixel program (mesa_frame.h); shadowref with every material Gouraud-shaded or as the scene's
// materials say (per pixel in every compared scene).
struct Config {
  Engine engine;
  int threads;
  MesaLighting lighting = MesaLighting::FixedFunction;
  // Two 1-thread processes at once, each rendering its own frames: what the machine gives two
  // busy threads at that moment (capacity below), the ceiling of any 2-thread speedup.
  bool pair = false;
  // Frames at `threads` and at one thread in turn in one process (renderFramesInTurn): shadowref's
  // own two threads / one, on the same host for both counts (Measured::turnRatios).
  bool inTurn = false;
  std::string name() const { return engineName() + "-" + std::to_string(threads) + "t"; }
  const char* driverName() const {
    if (engine == Engine::Shadowref) return inTurn ? "shadowref-in-turn" : "shadowref";
    return engine == Engine::Llvmpipe ? "llvmpipe" : "softpipe";
  }
  // The CSV's engine column: "llvmpipe-perpixel" for the per-pixel Mesa runs, "shadowref-gouraud"
  // for shadowref per vertex ("shadowref" alone is the scenes' per-pixel shading, as before).
  std::string engineName() const {
    if (engine == Engine::Shadowref)
      return std::string(lighting == MesaLighting::FixedFunction ? "shadowref-gouraud" : "shadowref") +
             (pair ? "-pair" : inTurn ? "-in-turn" : "");
    return std::string(driverName()) + (lighting == MesaLighting::PerPixel ? "-perpixel" : "");
  }
};

// Per vertex for shadowref: every material Gouraud-shaded, the work Mesa's fixed function does.
void shadeGouraud(Scene& scene) {
  for (Material& m : scene.materials) m.shading = ShadingModel::Gouraud;
}

// VS_SHADOWREF_SHADING=gouraud makes a shadowref worker shade per vertex (set by runChild).
bool gouraudFromEnvironment() {
  const char* v = std::getenv("VS_SHADOWREF_SHADING");
  if (!v || std::strcmp(v, "scene") == 0) return false;
  if (std::strcmp(v, "gouraud") == 0) return true;
  throw std::runtime_error(std::string("VS_SHADOWREF_SHADING is scene or gouraud, not ") + v);
}

// VS_MESA_LIGHTING=perpixel selects Mesa's per-pixel program in a worker (set by runChild, or by
// hand with VS_MESA_SNAPSHOT); fixed function otherwise.
MesaLighting lightingFromEnvironment() {
  const char* v = std::getenv("VS_MESA_LIGHTING");
  if (!v || std::strcmp(v, "fixed") == 0) return MesaLighting::FixedFunction;
  if (std::strcmp(v, "perpixel") == 0) return MesaLighting::PerPixel;
  throw std::runtime_error(std::string("VS_MESA_LIGHTING is fixed or perpixel, not ") + v);
}

Scene loadCase(const SceneCase& c) {
  LoadOptions options;
  options.overrides = c.overrides;
  return loadScene(std::string(SHADOWREF_SOURCE_DIR) + "/" + c.file, options);
}

// ---------------------------------------------------------------------------------------------
// The worker: one configuration, one scene or several, warm-up frames and `frames` timed frames of
// each, each time printed in milliseconds on one line.

double cpuMilliseconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

constexpr int kWarmUpFrames = 3;

struct FrameTimes {
  std::vector<double> wallMs, cpuMs;
};

// Times one frame of `frame` into `into`.
template <class Frame>
void timeFrame(Frame&& frame, FrameTimes& into) {
  const double cpu0 = cpuMilliseconds();
  const auto start = std::chrono::steady_clock::now();
  frame();
  into.wallMs.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  into.cpuMs.push_back(cpuMilliseconds() - cpu0);
}

void printTimes(const std::string& renderer, const FrameTimes& t) {
  std::printf("# %s\nW", renderer.c_str());
  for (double m : t.wallMs) std::printf(" %.4f", m);
  std::printf("\nC");
  for (double m : t.cpuMs) std::printf(" %.4f", m);
  std::printf("\n");
}

// Warm-up: page in buffers, JIT llvmpipe's shaders, let the allocator's heaps settle. Three frames,
// every engine alike: shadowref's second and third frames in a fresh process can still be slow
// (pumpkins at 2 threads 14-19 ms, then 10.5-11), llvmpipe's are not; the bench measures the frame
// rate of a renderer that keeps rendering.
int runWorker(const std::string& engine, int threads, int frames, const SceneCase& c) {
  // Mesa keeps its buffers from frame to frame; shadowref allocates them per frame and keeps the
  // freed memory (allocator_tuning.h). Set for both engines, so both run in the same process state.
  keepFreedMemoryForReuse();
  Scene scene = loadCase(c);
  if (engine.rfind("shadowref", 0) == 0 && gouraudFromEnvironment()) shadeGouraud(scene);
  FrameTimes times;
  auto timed = [&](auto&& frame) {
    for (int i = 0; i < kWarmUpFrames; ++i) frame();
    for (int i = 0; i < frames; ++i) timeFrame(frame, times);
  };
  // VS_MESA_SNAPSHOT=file.png: the last frame's colour, to check by eye that both draw the same.
  const char* snapshot = std::getenv("VS_MESA_SNAPSHOT");
  if (engine == "shadowref-in-turn") {
    FrameTimes one, many;
    renderFramesInTurn(scene, FrameOptions{}, {.threads = threads, .warmUp = kWarmUpFrames, .frames = frames},
                       [&](int t, const FrameResult&, double ms) { (t == 1 ? one : many).wallMs.push_back(ms); });
    printTimes("shadowref 1 thread, in turn with " + std::to_string(threads), one);
    printTimes("shadowref " + std::to_string(threads) + " threads, in turn with 1", many);
    return 0;
  }
  if (engine == "shadowref") {
    FrameOptions options;
    options.threads = threads;
    const std::unique_ptr<PipelineMaker> pipelines = makePipelineMaker(PipelineKind::Fast, threads);
    options.pipelines = pipelines.get();  // threads started once, not per frame
    std::optional<FrameResult> last;
    timed([&] {
      last.reset();  // one frame alive at a time, as Mesa keeps one set of buffers
      last = renderFrame(scene, options);
    });
    if (snapshot) writePng(last->framebuffer, snapshot);
    printTimes("shadowref " + std::to_string(threads) + " threads", times);
  } else {
    const MesaLighting lighting = lightingFromEnvironment();
    MesaFrameRenderer mesa(scene, scene.shadow.method, lighting);
    timed([&] { mesa.render(); });
    if (snapshot) writePng(mesa.readColor(), snapshot);
    printTimes(conformance::mesaRenderer(), times);  // the lighting is in the engine's name
  }
  return 0;
}

// A series' points in one shadowref process, their frames interleaved: frame f of every point,
// point after point (each cycle from the next point on), then frame f + 1. The host here changes
// speed by about 1.5x within seconds; one cycle of the points takes a tenth of a second to a
// second, so a change mostly falls between cycles and slows a cycle's frames alike, and the points'
// times keep their proportions however the host goes (measured a process per point, a point whose
// runs all met the slower speed stood 1.5x off the others' line). Prints each point's times in order.
int runSeriesWorker(int threads, int frames, const std::vector<SceneCase>& cases) {
  keepFreedMemoryForReuse();
  std::vector<Scene> scenes;
  for (const SceneCase& c : cases) {
    scenes.push_back(loadCase(c));
    if (gouraudFromEnvironment()) shadeGouraud(scenes.back());
  }
  FrameOptions options;
  options.threads = threads;
  const std::unique_ptr<PipelineMaker> pipelines = makePipelineMaker(PipelineKind::Fast, threads);
  options.pipelines = pipelines.get();  // threads started once, not per frame
  for (const Scene& scene : scenes)
    for (int w = 0; w < kWarmUpFrames; ++w) renderFrame(scene, options);
  std::vector<FrameTimes> times(scenes.size());
  for (int f = 0; f < frames; ++f)
    for (size_t j = 0; j < scenes.size(); ++j) {
      const size_t i = (size_t(f) + j) % scenes.size();
      timeFrame([&] { renderFrame(scenes[i], options); }, times[i]);
    }
  for (const FrameTimes& t : times) printTimes("shadowref " + std::to_string(threads) + " threads", t);
  return 0;
}

// ---------------------------------------------------------------------------------------------
// The driver side.

std::string selfPath() {
  char buf[4096];
  const ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n <= 0) throw std::runtime_error("cannot find /proc/self/exe");
  return std::string(buf, size_t(n));
}

std::string quoted(const std::string& s) {
  std::string q = "'";
  for (char ch : s) q += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return q + "'";
}

struct RunResult {
  std::string renderer;
  std::vector<double> frameMs;  // wall clock
  std::vector<double> cpuMs;    // CPU time of the whole process (all its threads)
};

// How a shadowref worker shades (gouraudFromEnvironment): per vertex against Mesa's fixed function.
std::string shadingVariable(const Config& cfg) {
  return cfg.lighting == MesaLighting::FixedFunction ? "VS_SHADOWREF_SHADING=gouraud " : "VS_SHADOWREF_SHADING=scene ";
}

std::string workerCommand(const Config& cfg, int frames, const SceneCase& c) {
  std::string cmd;
  if (cfg.engine == Engine::Llvmpipe)
    cmd = "GALLIUM_DRIVER=llvmpipe LP_NUM_THREADS=" + std::to_string(cfg.threads) + " ";
  else if (cfg.engine == Engine::Softpipe)
    cmd = "GALLIUM_DRIVER=softpipe ";
  if (cfg.engine != Engine::Shadowref) cmd += std::string("VS_MESA_LIGHTING=") + lightingName(cfg.lighting) + " ";
  else cmd += shadingVariable(cfg);
  cmd += quoted(selfPath()) + " --worker " + cfg.driverName() + " " + std::to_string(cfg.threads) + " " +
         std::to_string(frames) + " " + quoted(c.file);
  for (const std::string& o : c.overrides) cmd += " " + quoted(o);
  return cmd;
}

// A series' points in one shadowref process (runSeriesWorker).
std::string seriesWorkerCommand(const Config& cfg, int frames, const std::vector<SceneCase>& cases) {
  std::string cmd = shadingVariable(cfg);
  cmd += quoted(selfPath()) + " --series-worker " + std::to_string(cfg.threads) + " " + std::to_string(frames);
  for (const SceneCase& c : cases) {
    cmd += " --case " + quoted(c.file);
    for (const std::string& o : c.overrides) cmd += " " + quoted(o);
  }
  return cmd;
}

FILE* startWorker(const std::string& cmd) {
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) throw std::runtime_error("popen failed: " + cmd);
  return pipe;
}

// A worker's output, once it has finished.
std::string workerOutput(FILE* pipe, const std::string& cmd) {
  std::string out;
  char buf[4096];
  while (size_t n = fread(buf, 1, sizeof buf, pipe)) out.append(buf, n);
  if (pclose(pipe) != 0) throw std::runtime_error("worker failed: " + cmd);
  return out;
}

// A worker's runs, one a scene: each starts at its "# renderer" line.
std::vector<RunResult> parseWorkerRuns(const std::string& out, const std::string& cmd) {
  std::vector<RunResult> runs;
  std::istringstream lines(out);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.rfind("# ", 0) == 0) {
      runs.emplace_back().renderer = line.substr(2);
      continue;
    }
    if (runs.empty() || line.empty()) throw std::runtime_error("worker printed times before its renderer: " + cmd);
    std::istringstream values(line.substr(1));
    std::vector<double>& into = line[0] == 'C' ? runs.back().cpuMs : runs.back().frameMs;
    for (double v; values >> v;) into.push_back(v);
  }
  for (const RunResult& r : runs)
    if (r.frameMs.empty()) throw std::runtime_error("worker printed no times: " + cmd);
  return runs;
}

RunResult parseWorker(const std::string& out, const std::string& cmd) {
  std::vector<RunResult> runs = parseWorkerRuns(out, cmd);
  if (runs.size() != 1) throw std::runtime_error("worker printed " + std::to_string(runs.size()) + " runs, not 1: " + cmd);
  return runs.front();
}

// Frames at cfg.threads and at one thread in turn in one worker (Config::inTurn): the one-thread
// run and the cfg.threads run, in that order.
std::vector<RunResult> runInTurnChild(const Config& cfg, int frames, const SceneCase& c) {
  const std::string cmd = workerCommand(cfg, frames, c);
  std::vector<RunResult> runs = parseWorkerRuns(workerOutput(startWorker(cmd), cmd), cmd);
  if (runs.size() != 2) throw std::runtime_error("worker printed " + std::to_string(runs.size()) + " runs, not 2: " + cmd);
  return runs;
}

RunResult runChild(const Config& cfg, int frames, const SceneCase& c) {
  const std::string cmd = workerCommand(cfg, frames, c);
  if (!cfg.pair) return parseWorker(workerOutput(startWorker(cmd), cmd), cmd);
  // Both workers start together; each writes only when done, so reading one after the other
  // cannot block either. The pair's time per frame is that of one engine delivering both
  // processes' frame rates together: 1 / (1/a + 1/b), from each process's median frame. (The
  // faster process ends first and the slower one's last frames run alone; the medians keep to the
  // frames that ran side by side.)
  FILE* a = startWorker(cmd);
  FILE* b = startWorker(cmd);
  const std::string outA = workerOutput(a, cmd), outB = workerOutput(b, cmd);
  const RunResult ra = parseWorker(outA, cmd), rb = parseWorker(outB, cmd);
  RunResult r;
  r.renderer = ra.renderer + ", two processes at once";
  const double ta = median(ra.frameMs), tb = median(rb.frameMs);
  r.frameMs = {1.0 / (1.0 / ta + 1.0 / tb)};
  r.cpuMs = {median(ra.cpuMs) + median(rb.cpuMs)};
  return r;
}

// How long a cache line written on core 0 takes to be seen on core 1, one way, in ns: two threads
// pinned to the two cores pass a counter back and forth (0 when they cannot be pinned). What two
// threads of one frame pay whenever one reads what the other wrote — setups, rows of the buffers.
// The host decides it: on this machine 25-35 ns most of the time, and for minutes at a time about
// 160 ns (the two virtual CPUs then sit on distant cores); two threads of one process then lose a
// quarter or more of their speed-up while two separate processes, sharing nothing, do not.
double crossCoreNs() {
  if (std::thread::hardware_concurrency() < 2) return 0.0;
  alignas(128) static std::atomic<int> turn;
  alignas(128) static std::atomic<bool> unpinned;
  turn.store(0);
  unpinned.store(false);
  constexpr int kRounds = 20000;
  auto pin = [](int core) {
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(core, &set);
    return pthread_setaffinity_np(pthread_self(), sizeof set, &set) == 0;
  };
  double ns = 0.0;
  std::thread([&] {
    if (!pin(0)) return;
    std::thread other([&] {
      if (!pin(1)) {
        unpinned.store(true);
        return;
      }
      for (int i = 0; i < kRounds; ++i) {
        while (turn.load(std::memory_order_acquire) != 2 * i + 1) {}
        turn.store(2 * i + 2, std::memory_order_release);
      }
    });
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < kRounds && !unpinned.load(); ++i) {
      turn.store(2 * i + 1, std::memory_order_release);
      while (turn.load(std::memory_order_acquire) != 2 * i + 2 && !unpinned.load()) {}
    }
    const double elapsed = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count();
    other.join();
    if (!unpinned.load()) ns = elapsed / (2.0 * kRounds);
  }).join();
  return ns;
}

struct Measured {
  std::vector<double> runMedians;
  std::vector<double> cpuRunMedians;
  std::vector<double> crossCore;  // crossCoreNs() right before each run (shadowref's 2-thread runs)
  // Config::inTurn: each run's median one-thread frame over its median frame at more threads (the
  // run medians above are of the latter). The median over runs is the speed-up the tables print.
  std::vector<double> turnRatios;
  std::string renderer;
  // A series' point measured with the others in one process (measureSeriesRun): in each cycle of
  // the points' frames, this point's share of the cycle's time, and the cycles' times (wall, CPU).
  std::vector<double> shares, cpuShares, cycles, cpuCycles;
  // Its time in the fastest cycle: its median share of a cycle times that cycle (fastestCycleTime).
  double seriesMs() const { return timing::fastestCycleTime(shares, cycles); }
  double seriesCpuMs() const { return timing::fastestCycleTime(cpuShares, cpuCycles); }
  double median() const { return timing::median(runMedians); }
  double cpuMedian() const { return timing::median(cpuRunMedians); }
  double min() const { return *std::min_element(runMedians.begin(), runMedians.end()); }
  double cpuMin() const { return *std::min_element(cpuRunMedians.begin(), cpuRunMedians.end()); }
  void add(const Measured& more) {  // another round's runs of the same configuration
    runMedians.insert(runMedians.end(), more.runMedians.begin(), more.runMedians.end());
    cpuRunMedians.insert(cpuRunMedians.end(), more.cpuRunMedians.begin(), more.cpuRunMedians.end());
    crossCore.insert(crossCore.end(), more.crossCore.begin(), more.crossCore.end());
    turnRatios.insert(turnRatios.end(), more.turnRatios.begin(), more.turnRatios.end());
    for (auto [to, from] : {std::pair{&shares, &more.shares}, {&cpuShares, &more.cpuShares}, {&cycles, &more.cycles},
                            {&cpuCycles, &more.cpuCycles}})
      to->insert(to->end(), from->begin(), from->end());
    renderer = more.renderer;
  }
  double max() const { return *std::max_element(runMedians.begin(), runMedians.end()); }
};

struct Settings {
  int rounds = 5;
  int frames = 5;          // per run; softpipe gets fewer (it takes 10x as long)
  std::string csvPath = "vs-mesa.csv";  // in the working directory; the script passes --csv
  bool scaling = true;
  bool quick = false;
  bool agreement = false;  // --agreement: the agreement table only, no timing
  bool seriesOnly = false; // --series: the houses and lights series only
  std::string imageDir;    // --images DIR: the agreement's frames as PNG
};

// One round of alternating runs of a point: A B C … in an even round, … C B A in an odd one, so
// slow drift hits every configuration alike.
std::vector<Measured> measureRound(const SceneCase& c, const std::vector<Config>& configs, const Settings& s,
                                   int round) {
  std::vector<Measured> m(configs.size());
  for (size_t k = 0; k < configs.size(); ++k) {
    const size_t i = round % 2 == 0 ? k : configs.size() - 1 - k;
    const int frames = configs[i].engine == Engine::Softpipe ? std::max(1, s.frames / 3) : s.frames;
    const Config& cfg = configs[i];
    if (cfg.engine == Engine::Shadowref && cfg.threads == 2) m[i].crossCore.push_back(crossCoreNs());
    if (cfg.inTurn) {  // twice the frames of a run at each thread count: a ratio of two medians
      const std::vector<RunResult> r = runInTurnChild(cfg, 2 * frames, c);
      const double one = median(r[0].frameMs), many = median(r[1].frameMs);
      m[i].runMedians.push_back(many);
      m[i].turnRatios.push_back(one / many);
      m[i].renderer = r[1].renderer;
      continue;
    }
    const RunResult r = runChild(cfg, frames, c);
    m[i].runMedians.push_back(median(r.frameMs));
    m[i].cpuRunMedians.push_back(median(r.cpuMs));
    m[i].renderer = r.renderer;
  }
  std::fprintf(stderr, ".");
  return m;
}

std::ofstream openCsv(const std::string& path) {
  std::ofstream csv(path);
  if (!csv) throw std::runtime_error("cannot write " + path);
  csv << "section,scene,houses,lights,engine,threads,runs,median_ms,min_ms,max_ms,cpu_median_ms,renderer\n";
  return csv;
}

void csvRow(std::ofstream& csv, const std::string& section, const SceneCase& c, const Config& cfg, const Measured& m) {
  csv << section << ',' << c.label << ',' << c.houses << ',' << c.lights << ',' << cfg.engineName() << ','
      << cfg.threads << ',' << m.runMedians.size() << ',' << m.median() << ',' << m.min() << ',' << m.max() << ',';
  if (!m.cpuRunMedians.empty()) csv << m.cpuMedian();  // frames in turn are timed by the wall clock only
  csv << ",\"" << m.renderer << "\"\n";
}

// ---------------------------------------------------------------------------------------------
// Determinism: every buffer byte-identical for 1, 2 and 8 threads.

// Per scene: whether 2 and 8 threads gave 1 thread's bytes.
std::vector<bool> checkDeterminism(const std::vector<SceneCase>& cases, std::ofstream& csv) {
  std::printf("\nDeterminism: every buffer (colour, depth, stencil, accumulation) of 2 and 8 threads against 1\n");
  std::vector<bool> identical;
  for (const SceneCase& c : cases) {
    bool all = true;
    const Scene scene = loadCase(c);
    FrameOptions options;
    options.threads = 1;
    const FrameResult one = renderFrame(scene, options);
    std::printf("  %-16s", c.label.c_str());
    for (int threads : {2, 8}) {
      options.threads = threads;
      const bool same = identicalFrames(one.framebuffer, renderFrame(scene, options).framebuffer);
      all = all && same;
      std::printf("  %d threads: %s", threads, same ? "identical" : "DIFFERENT");
      csv << "determinism," << c.label << ',' << c.houses << ',' << c.lights << ",shadowref," << threads << ",1,"
          << (same ? "identical" : "different") << ",,,,\n";
    }
    std::printf("\n");
    identical.push_back(all);
  }
  return identical;
}

// ---------------------------------------------------------------------------------------------
// Agreement (--agreement): how far Mesa's frame is from its shadowref partner, per lighting, in
// the 8-bit colour both end in: fixed function against shadowref Gouraud, the per-pixel program
// against shadowref per pixel. What is left is float against double (per vertex: Mesa lights in
// eye space, shadowref in world space), the rasterization of shared edges and the shadow-map texel
// ties; fixed function adds a compare-fail value of 0.

// A colour channel as an 8-bit GL colour buffer holds it (writePng's rounding).
int toByte(float c) { return c <= 0.0f ? 0 : c >= 1.0f ? 255 : int(std::round(double(c) * 255.0)); }

struct Agreement {
  double over2 = 0.0;    // share of the pixels with a channel more than 2/255 apart
  size_t over2Pixels = 0;
  double meanAbs = 0.0;  // mean |difference| over the R, G and B of every pixel, in 1/255
  int maxAbs = 0;        // in 1/255
};

Agreement agreement(const Framebuffer& a, const Framebuffer& b) {
  const PixelVector<glm::vec4>& ca = a.color();
  const PixelVector<glm::vec4>& cb = b.color();
  if (ca.size() != cb.size()) throw std::runtime_error("agreement: frames of different sizes");
  Agreement r;
  size_t over = 0;
  double sum = 0.0;
  for (size_t i = 0; i < ca.size(); ++i) {
    int worst = 0;
    for (int k = 0; k < 3; ++k) {
      const int d = std::abs(toByte(ca[i][k]) - toByte(cb[i][k]));
      sum += d;
      worst = std::max(worst, d);
    }
    over += worst > 2 ? 1 : 0;
    r.maxAbs = std::max(r.maxAbs, worst);
  }
  r.over2Pixels = over;
  r.over2 = ca.empty() ? 0.0 : double(over) / double(ca.size());
  r.meanAbs = ca.empty() ? 0.0 : sum / double(3 * ca.size());
  return r;
}

// Where two frames are more than 2/255 apart: red on a dimmed grey copy of `a`, to find the few.
Framebuffer differenceImage(const Framebuffer& a, const Framebuffer& b) {
  Framebuffer out = a;
  for (size_t i = 0; i < out.color().size(); ++i) {
    int worst = 0;
    for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(toByte(a.color()[i][k]) - toByte(b.color()[i][k])));
    const float grey = 0.25f * (a.color()[i].r + a.color()[i].g + a.color()[i].b) / 3.0f;
    out.color()[i] = worst > 2 ? glm::vec4(1.0f, 0.0f, 0.0f, 1.0f) : glm::vec4(grey, grey, grey, 1.0f);
  }
  return out;
}

// In this process: the Mesa driver is GALLIUM_DRIVER's (llvmpipe unless set), one context for all.
// The driver runs it last, after every timed child, so its context's idle threads time nothing.
// CSV rows (when given a file): the share in median_ms, the mean in min_ms, the largest in max_ms,
// threads 0 (the driver picks its own).
void agreementTable(const std::string& imageDir, std::ofstream* csv) {
  setenv("GALLIUM_DRIVER", "llvmpipe", 0);
  std::printf("\nAgreement with shadowref at 800x640: share of pixels with an RGB channel more than 2/255 apart,\n"
              "mean and largest |difference| in 1/255; Mesa fixed function against shadowref Gouraud, Mesa per\n"
              "pixel against shadowref per pixel\n\n");
  std::printf("%-15s | %17s %6s %4s | %17s %6s %4s\n", "scene", "fixed: >2/255", "mean", "max", "per pixel: >2/255",
              "mean", "max");
  std::string renderer;
  for (const SceneCase& c : comparedScenes()) {
    const Scene scene = loadCase(c);
    Scene gouraud = scene;
    shadeGouraud(gouraud);
    FrameOptions options;
    options.threads = 2;  // the same bits for every thread count
    std::printf("%-15s", c.label.c_str());
    for (MesaLighting lighting : {MesaLighting::FixedFunction, MesaLighting::PerPixel}) {
      const bool perVertex = lighting == MesaLighting::FixedFunction;
      const FrameResult reference = renderFrame(perVertex ? gouraud : scene, options);
      if (!imageDir.empty())
        writePng(reference.framebuffer, imageDir + "/" + c.label + (perVertex ? "-shadowref-gouraud.png" : "-shadowref.png"));
      MesaFrameRenderer mesa(scene, scene.shadow.method, lighting);
      mesa.render();
      const Framebuffer frame = mesa.readColor();
      if (!imageDir.empty()) {
        const std::string stem = imageDir + "/" + c.label + "-mesa-" + lightingName(lighting);
        writePng(frame, stem + ".png");
        writePng(differenceImage(reference.framebuffer, frame), stem + "-diff.png");
      }
      const Agreement a = agreement(reference.framebuffer, frame);
      if (csv)
        *csv << "agreement," << c.label << ',' << c.houses << ',' << c.lights << ','
             << Config{Engine::Llvmpipe, 1, lighting}.engineName() << ",0,1," << a.over2 << ',' << a.meanAbs << ','
             << a.maxAbs << ",,\"share > 2/255; mean, max |difference| in 1/255: " << conformance::mesaRenderer()
             << "\"\n";
      std::printf(" | %7.3f%% %8zu %6.3f %4d", 100.0 * a.over2, a.over2Pixels, a.meanAbs, a.maxAbs);
    }
    std::printf("\n");
    std::fflush(stdout);
    renderer = conformance::mesaRenderer();
  }
  std::printf("Mesa: %s\n", renderer.c_str());
  if (!imageDir.empty())
    std::printf("images: %s/<scene>-{shadowref,shadowref-gouraud,mesa-fixed,mesa-perpixel}.png, and -diff.png: red\n"
                "where > 2/255\n",
                imageDir.c_str());
}

// ---------------------------------------------------------------------------------------------
// Reports.

std::string cpuModel() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown";
}

std::string range(const Measured& m) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.0f-%.0f", m.min(), m.max());
  return buf;
}

std::string loadAverage() {
  std::ifstream in("/proc/loadavg");
  std::string one, five, fifteen;
  in >> one >> five >> fifteen;
  return one + " " + five + " " + fifteen;
}

// The configurations of compareScenes, in the order of its columns.
enum Column { kSr1, kSr2, kLl1, kLl2, kSoft, kLp1, kLp2, kSopp, kSrg1, kSrg2, kSrPair, kSrgPair, kSrTurn, kSrgTurn, kColumns };

std::vector<Config> comparedConfigs() {
  const MesaLighting pp = MesaLighting::PerPixel, fixed = MesaLighting::FixedFunction;
  return {{Engine::Shadowref, 1, pp}, {Engine::Shadowref, 2, pp}, {Engine::Llvmpipe, 1, fixed},
          {Engine::Llvmpipe, 2, fixed}, {Engine::Softpipe, 1, fixed}, {Engine::Llvmpipe, 1, pp},
          {Engine::Llvmpipe, 2, pp}, {Engine::Softpipe, 1, pp}, {Engine::Shadowref, 1, fixed},
          {Engine::Shadowref, 2, fixed}, {Engine::Shadowref, 1, pp, true}, {Engine::Shadowref, 1, fixed, true},
          {Engine::Shadowref, 2, pp, false, true}, {Engine::Shadowref, 2, fixed, false, true}};
}

// Two threads against what the machine gives two threads: the 1-thread frame rendered by two
// processes at once (Config::pair). On an idle machine with two equal cores the pair delivers
// twice the frames of one process (capacity 2); on a shared host a core can slow down while the
// other is busy (seen here at times: one virtual CPU 30-40 % slower whenever the other ran
// anything, even a spin loop), and no 2-thread frame can then be faster than 1-thread time /
// capacity. The spin-loop probe (probeMachine) does not see that; this does, per scene and round.
void printCapacityTable(const std::vector<SceneCase>& cases, const std::vector<std::vector<Measured>>& all) {
  std::printf("\nTwo threads against the machine's capacity for two busy threads: the 1-thread frame rendered by\n"
              "two processes at once (pair: time per frame of the two together); capacity = 1t / pair, 2 on an\n"
              "idle machine of two equal cores, the ceiling of 2t/1t; share = (1t / 2t) / capacity; xcore: ns\n"
              "for a cache line to pass between the cores, measured before each 2-thread run (median/largest);\n"
              "turn: 2t/1t of frames at two threads and one in turn in one process, the median over its runs\n");
  std::printf("%-15s %7s %7s %7s %6s %6s %6s %7s %6s | %7s %7s %7s %6s %6s %6s %7s %6s\n", "scene", "srg-1t", "srg-2t",
              "pair", "2t/1t", "capac", "share", "xcore", "turn", "sr-1t", "sr-2t", "pair", "2t/1t", "capac", "share",
              "xcore", "turn");
  for (size_t k = 0; k < all.size(); ++k) {
    std::printf("%-15s", cases[k].label.c_str());
    const auto row = [&](Column one, Column two, Column pair, Column turn) {
      const double t1 = all[k][size_t(one)].median(), t2 = all[k][size_t(two)].median(), tp = all[k][size_t(pair)].median();
      const std::vector<double>& x = all[k][size_t(two)].crossCore;
      const std::string xcore = x.empty() ? "-" : std::to_string(int(median(x))) + "/" + std::to_string(int(*std::max_element(x.begin(), x.end())));
      std::printf(" %7.2f %7.2f %7.2f %6.2f %6.2f %6.2f %7s %6.2f", t1, t2, tp, t1 / t2, t1 / tp, (t1 / t2) / (t1 / tp),
                  xcore.c_str(), median(all[k][size_t(turn)].turnRatios));
    };
    row(kSrg1, kSrg2, kSrgPair, kSrgTurn);
    std::printf(" |");
    row(kSr1, kSr2, kSrPair, kSrTurn);
    std::printf("\n");
  }
}

// One like-for-like pair of a table: shadowref's 1- and 2-thread columns, Mesa's llvmpipe 1 and 2
// threads and softpipe. Times are the medians of the runs, wall clock or CPU.
struct PairColumns {
  const char* title;
  const char* names[5];
  Column columns[5];
  const char* ratios[3];  // llvmpipe 1 thread, 2 threads, softpipe against shadowref
};

void printPairTable(const PairColumns& p, const std::vector<SceneCase>& cases, const std::vector<std::vector<Measured>>& all,
                    bool cpu) {
  // CPU time: the 1-thread ratios only (a 2-thread process's CPU time includes its waiting threads).
  std::printf("\n%s\n", p.title);
  std::printf("%-15s %7s %7s %7s %7s %8s | %6s %6s %6s", "scene", p.names[0], p.names[1], p.names[2], p.names[3],
              p.names[4], p.ratios[0], cpu ? "" : p.ratios[1], p.ratios[2]);
  std::printf(cpu ? "\n" : " %6s\n", "sr2/1");
  for (size_t k = 0; k < all.size(); ++k) {
    double t[5];
    for (int i = 0; i < 5; ++i) {
      const Measured& m = all[k][size_t(p.columns[i])];
      t[i] = cpu ? m.cpuMedian() : m.median();
    }
    std::printf("%-15s %7.2f %7.2f %7.2f %7.2f %8.1f | %6.3f ", cases[k].label.c_str(), t[0], t[1], t[2], t[3], t[4],
                t[2] / t[0]);
    if (cpu) {
      std::printf("%6s %6.2f\n", "", t[4] / t[0]);
      continue;
    }
    std::printf("%6.3f %6.2f %6.2f\n", t[3] / t[1], t[4] / t[0], t[0] / t[1]);
    std::printf("%-15s", "");
    for (int i = 0; i < 5; ++i) std::printf(" %*s", i == 4 ? 8 : 7, range(all[k][size_t(p.columns[i])]).c_str());
    std::printf("   (lowest-highest run median)\n");
  }
}

// Points — the compared scenes, or a series' numbers of houses or lights — measured round by
// round, each round every point once, and within a point the configurations alternating as in
// measureRound(). Round r starts r/rounds of the way along the points and wraps around, so that
// every point's runs lie about a round apart: a slow stretch of the host (minutes at a time here)
// then falls on different points in different rounds instead of on every run of the points it meets.
// (Rounds that went 1 … n, then n … 1, ran the end points twice in a row at each turn: in run AH
// the 8-house point's fastest of five runs met a slow stretch.)
std::vector<std::vector<Measured>> measureInRounds(const std::vector<SceneCase>& cases, const std::vector<Config>& configs,
                                                   const Settings& s) {
  std::vector<std::vector<Measured>> m(cases.size(), std::vector<Measured>(configs.size()));
  const size_t n = cases.size();
  for (int round = 0; round < s.rounds; ++round) {
    const size_t start = size_t(round) * n / size_t(s.rounds);
    for (size_t j = 0; j < n; ++j) {
      const size_t i = (start + j) % n;
      const std::vector<Measured> r = measureRound(cases[i], configs, s, round);
      for (size_t k = 0; k < configs.size(); ++k) m[i][k].add(r[k]);
    }
  }
  return m;
}

// One run of each point of a series in one shadowref process (runSeriesWorker): a Measured per point.
std::vector<Measured> measureSeriesRun(const std::vector<SceneCase>& cases, const Config& cfg, const Settings& s) {
  std::vector<Measured> m(cases.size());
  const double crossCore = cfg.threads == 2 ? crossCoreNs() : 0.0;
  const std::string cmd = seriesWorkerCommand(cfg, s.frames, cases);
  const std::vector<RunResult> runs = parseWorkerRuns(workerOutput(startWorker(cmd), cmd), cmd);
  if (runs.size() != cases.size()) throw std::runtime_error("series worker printed " + std::to_string(runs.size()) + " runs: " + cmd);
  for (size_t i = 0; i < cases.size(); ++i) {
    m[i].runMedians.push_back(median(runs[i].frameMs));
    m[i].cpuRunMedians.push_back(median(runs[i].cpuMs));
    m[i].renderer = runs[i].renderer;
    if (cfg.threads == 2) m[i].crossCore.push_back(crossCore);
  }
  // Frame f of every point makes cycle f (runSeriesWorker): a tenth of a second to a second, in
  // which the host's speed seldom changes, so a point's share of it is its share of the work.
  auto addShares = [&](std::vector<double> RunResult::*times, std::vector<double> Measured::*shares,
                       std::vector<double> Measured::*cycles) {
    std::vector<std::vector<double>> t;
    for (const RunResult& r : runs) t.push_back(r.*times);
    const timing::CycleShares c = timing::cycleShares(t);
    for (size_t i = 0; i < cases.size(); ++i) {
      (m[i].*shares).insert((m[i].*shares).end(), c.shares[i].begin(), c.shares[i].end());
      (m[i].*cycles).insert((m[i].*cycles).end(), c.cycles.begin(), c.cycles.end());
    }
  };
  addShares(&RunResult::frameMs, &Measured::shares, &Measured::cycles);
  addShares(&RunResult::cpuMs, &Measured::cpuShares, &Measured::cpuCycles);
  return m;
}

// A series' points round by round: each round shadowref's configurations each in one process that
// interleaves the points' frames (measureSeriesRun), and Mesa's a process per point and
// configuration as in measureInRounds (Mesa's driver and its threads are set per process, and its
// figures here are for comparison only) — shadowref first in even rounds, Mesa first in odd ones.
std::vector<std::vector<Measured>> measureSeries(const std::vector<SceneCase>& cases, const std::vector<Config>& configs,
                                                 const Settings& s, const Settings& mesaSettings) {
  std::vector<std::vector<Measured>> m(cases.size(), std::vector<Measured>(configs.size()));
  std::vector<size_t> ours, mesa;
  for (size_t k = 0; k < configs.size(); ++k) (configs[k].engine == Engine::Shadowref ? ours : mesa).push_back(k);
  std::vector<Config> mesaConfigs;
  for (size_t k : mesa) mesaConfigs.push_back(configs[k]);
  const size_t n = cases.size();
  for (int round = 0; round < s.rounds; ++round) {
    auto runOurs = [&] {
      for (size_t j = 0; j < ours.size(); ++j) {
        const size_t k = ours[round % 2 == 0 ? j : ours.size() - 1 - j];
        const std::vector<Measured> r = measureSeriesRun(cases, configs[k], s);
        for (size_t i = 0; i < n; ++i) m[i][k].add(r[i]);
      }
      std::fprintf(stderr, ":");
    };
    auto runMesa = [&] {
      if (mesaConfigs.empty()) return;
      const size_t start = size_t(round) * n / size_t(s.rounds);
      for (size_t j = 0; j < n; ++j) {
        const size_t i = (start + j) % n;
        const std::vector<Measured> r = measureRound(cases[i], mesaConfigs, mesaSettings, round);
        for (size_t q = 0; q < mesa.size(); ++q) m[i][mesa[q]].add(r[q]);
      }
    };
    if (round % 2 == 0) {
      runOurs();
      runMesa();
    } else {
      runMesa();
      runOurs();
    }
  }
  return m;
}

// The compared scenes' tables; returns every configuration's figures, per scene in comparedConfigs' order.
std::vector<std::vector<Measured>> compareScenes(const Settings& s, std::ofstream& csv) {
  const std::vector<Config> configs = comparedConfigs();
  const std::vector<SceneCase> cases = comparedScenes();
  std::fprintf(stderr, "comparing");
  // Round by round, as the series go (measured scene after scene, a slow stretch of the host
  // covered most runs of one scene: run AT's outdoor frame at two threads, 6-10 ms against 5.9).
  const std::vector<std::vector<Measured>> all = measureInRounds(cases, configs, s);
  for (size_t k = 0; k < cases.size(); ++k) {
    const SceneCase& c = cases[k];
    for (size_t i = 0; i < configs.size(); ++i) {
      csvRow(csv, "compare", c, configs[i], all[k][i]);
      const std::vector<double>& x = all[k][i].crossCore;
      if (!x.empty())
        csv << "cross-core," << c.label << ',' << c.houses << ',' << c.lights << ',' << configs[i].engineName() << ','
            << configs[i].threads << ',' << x.size() << ',' << median(x) << ',' << *std::min_element(x.begin(), x.end())
            << ',' << *std::max_element(x.begin(), x.end()) << ",,\"ns for a cache line to pass between the cores, before each run\"\n";
      const std::vector<double>& turn = all[k][i].turnRatios;
      if (!turn.empty())
        csv << "in-turn," << c.label << ',' << c.houses << ',' << c.lights << ',' << configs[i].engineName() << ','
            << configs[i].threads << ',' << turn.size() << ',' << median(turn) << ',' << *std::min_element(turn.begin(), turn.end())
            << ',' << *std::max_element(turn.begin(), turn.end())
            << ",,\"2 threads / 1 of frames in turn in one process: each run's one-thread median / its two-thread median\"\n";
    }
  }
  std::fprintf(stderr, "\n");
  std::printf("\nTime per frame at 800x640, median of %d alternating runs of %d frames (softpipe %d), in ms;\n"
              "ratios are speed ratios (Mesa's time / shadowref's time: above 1 shadowref is faster).\n",
              s.rounds, s.frames, std::max(1, s.frames / 3));
  const PairColumns perVertex{"Per vertex, like for like: shadowref with every material Gouraud-shaded (srg) against Mesa's\n"
                              "fixed-function lighting (llvm, soft)",
                              {"srg-1t", "srg-2t", "llvm-1t", "llvm-2t", "softpipe"},
                              {kSrg1, kSrg2, kLl1, kLl2, kSoft},
                              {"vsLl1", "vsLl2", "vsSoft"}};
  const PairColumns perPixel{"Per pixel, like for like: shadowref as the scenes are written (sr) against Mesa's per-pixel\n"
                             "program (llpp, sopp)",
                             {"sr-1t", "sr-2t", "llpp-1t", "llpp-2t", "sopp"},
                             {kSr1, kSr2, kLp1, kLp2, kSopp},
                             {"vsLp1", "vsLp2", "vsSopp"}};
  const PairColumns unequal{"Unequal work, the original reference figures: shadowref per pixel (sr) against Mesa's fixed\n"
                            "function (per vertex: less work per fragment)",
                            {"sr-1t", "sr-2t", "llvm-1t", "llvm-2t", "softpipe"},
                            {kSr1, kSr2, kLl1, kLl2, kSoft},
                            {"vsLl1", "vsLl2", "vsSoft"}};
  for (const PairColumns* p : {&perVertex, &perPixel, &unequal}) printPairTable(*p, cases, all, false);
  std::printf("Mesa: %s; %s\n", all.front()[kLl1].renderer.c_str(), all.front()[kSoft].renderer.c_str());
  printCapacityTable(cases, all);
  // On a shared machine the wall clock carries other processes' load; the process CPU time of the
  // single-threaded runs does not (much), so it is the steadier comparison of work per frame (the
  // 2-thread columns' CPU time includes the workers' waiting).
  std::printf("\nCPU time per frame (whole process, all threads), ms; the 1-thread ratios are the steadier ones\n");
  for (const PairColumns* p : {&perVertex, &perPixel}) printPairTable(*p, cases, all, true);
  std::printf("load average after the runs: %s\n", loadAverage().c_str());
  return all;
}

// R² of the least-squares lines through shadowref's times, 1 and 2 threads, against houses and lights.
struct ScalingFits {
  double houses1 = 0.0, houses2 = 0.0, lights1 = 0.0, lights2 = 0.0;
};

ScalingFits scaling(const Settings& s, std::ofstream& csv) {
  ScalingFits fits;
  // llvmpipe both ways: per-pixel lighting costs per light and fragment, as shadowref's does.
  const MesaLighting pp = MesaLighting::PerPixel;
  const std::vector<Config> configs = {{Engine::Shadowref, 1, pp}, {Engine::Shadowref, 2, pp}, {Engine::Llvmpipe, 1},
                                       {Engine::Llvmpipe, 1, pp}};
  // Mesa's runs, a process per point, take fewer frames (its figures here are for comparison);
  // shadowref's, all points in one process, the full number, which costs a second or two a round.
  Settings fewer = s;
  fewer.frames = std::max(1, s.frames / 2 + 1);
  struct Series {
    std::string title, axis;
    std::vector<SceneCase> cases;
    std::vector<double> x;
  };
  std::vector<Series> series(2);
  series[0] = {"Houses (city, z-fail, 1 light, camera and light as for 100 houses)", "houses", {}, {}};
  const std::vector<int> houses = s.quick ? std::vector<int>{8, 32, 100} : std::vector<int>{8, 16, 32, 48, 64, 80, 100};
  for (int h : houses) {
    // Only the houses change from point to point: the camera, the light and the ground stay those
    // of the largest city. Framed for each city in turn, the camera backs away as the city grows
    // and each house covers fewer pixels (8 houses fill half the view of 16): then the work per
    // house is not the same from point to point, whatever the renderer (frame_profile under
    // callgrind, instructions a frame: R2 0.981 framed for each city, 0.990 framed for 100).
    series[0].cases.push_back(cityCase(h, 1, houses.back()));
    series[0].x.push_back(h);
  }
  series[1] = {"Lights (city-64, z-fail)", "lights", {}, {}};
  for (int l : s.quick ? std::vector<int>{1, 4, 9} : std::vector<int>{1, 2, 3, 4, 5, 6, 7, 8, 9}) {
    series[1].cases.push_back(cityCase(64, l));
    series[1].x.push_back(l);
  }
  for (const Series& ser : series) {
    // shadowref: every point's frames interleaved in one process, so the host's changes of speed
    // fall on all points alike and each point's share of a cycle of them is its share of the work.
    // Mesa, a process per point: the fastest of a point's runs, the one the host slowed least
    // (the CSV keeps the median and the slowest too).
    std::printf("\n%s: ms per frame.\n"
                "shadowref: %d runs, each a process rendering every point's frames in turn, %d cycles of one frame\n"
                "a point; a point's figure is its median share of a cycle times the fastest cycle. Mesa: the fastest\n"
                "of %d runs of %d frames, a process per point.\n",
                ser.title.c_str(), s.rounds, s.frames, fewer.rounds, fewer.frames);
    std::printf("%8s %9s %9s %9s %9s   %3s %9s %9s %9s %9s\n", ser.axis.c_str(), "sr-1t", "sr-2t", "llvm-1t", "llpp-1t",
                "", "sr-1t", "sr-2t", "llvm-1t", "llpp-1t");
    std::vector<std::vector<double>> y(configs.size()), yCpu(configs.size());
    const std::vector<std::vector<Measured>> all = measureSeries(ser.cases, configs, s, fewer);
    for (size_t i = 0; i < ser.cases.size(); ++i) {
      const std::vector<Measured>& m = all[i];
      for (size_t k = 0; k < configs.size(); ++k) {
        csvRow(csv, ser.axis, ser.cases[i], configs[k], m[k]);
        const bool interleaved = configs[k].engine == Engine::Shadowref;
        if (interleaved)  // the figure the line is fitted to (the row above: the runs' medians)
          csv << ser.axis << "-share," << ser.cases[i].label << ',' << ser.cases[i].houses << ',' << ser.cases[i].lights
              << ',' << configs[k].engineName() << ',' << configs[k].threads << ',' << m[k].shares.size() << ','
              << m[k].seriesMs() << ",,," << m[k].seriesCpuMs()
              << ",\"median share of a cycle of every point's frames x the fastest cycle\"\n";
        y[k].push_back(interleaved ? m[k].seriesMs() : m[k].min());
        yCpu[k].push_back(interleaved ? m[k].seriesCpuMs() : m[k].cpuMin());
      }
      std::printf("\r%8g %9.2f %9.2f %9.2f %9.2f   cpu %9.2f %9.2f %9.2f %9.2f\n", ser.x[i], y[0].back(), y[1].back(),
                  y[2].back(), y[3].back(), yCpu[0].back(), yCpu[1].back(), yCpu[2].back(), yCpu[3].back());
    }
    std::fflush(stdout);
    // Least-squares lines: R2 near 1 means the cost grows linearly.
    (ser.axis == "houses" ? fits.houses1 : fits.lights1) = fitLine(ser.x, y[0]).r2;
    (ser.axis == "houses" ? fits.houses2 : fits.lights2) = fitLine(ser.x, y[1]).r2;
    for (const auto* ys : {&y, &yCpu}) {
      std::printf("%8s", ys == &y ? "fit" : "cpu fit");
      for (size_t k = 0; k < configs.size(); ++k) {
        const LineFit f = fitLine(ser.x, (*ys)[k]);
        std::printf("  %s: %.1f + %.2f/%s R2 %.3f", configs[k].name().c_str(), f.intercept, f.slope,
                    ser.axis == "houses" ? "house" : "light", f.r2);
      }
      std::printf("\n");
    }
  }
  return fits;
}

// How much of the machine this process gets: the same spin loop on 1 thread, then on 2 threads
// at once. On an idle 2-core machine both take the same time (parallelism 2); when other
// processes keep the cores busy, 2 threads take longer and no renderer can show a 2-thread speedup.
struct MachineShare {
  double parallelism = 0.0;  // 2 * t(1 thread) / t(2 threads), 2 at best
  double cpuShare = 0.0;     // CPU time / wall time of the 1-thread spin, 1 at best
};

// The probes' unit of work: a dependent chain of additions, the same on every core.
void spin() {
  volatile double x = 0.0;
  for (long i = 0; i < 100'000'000; ++i) x = x + 1e-9;
}

MachineShare probeMachine() {
  auto wallOf = [&](int threads, double* cpu) {
    const double cpu0 = cpuMilliseconds();
    const auto start = std::chrono::steady_clock::now();
    std::vector<std::thread> pool;
    for (int i = 0; i < threads; ++i) pool.emplace_back(spin);
    for (std::thread& t : pool) t.join();
    if (cpu) *cpu = cpuMilliseconds() - cpu0;
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  };
  double cpu1 = 0.0;
  const double t1 = wallOf(1, &cpu1);
  const double t2 = wallOf(2, nullptr);
  return {2.0 * t1 / t2, cpu1 / t1};
}

// Each core's speed for one busy thread, as a fraction of the fastest core's (0 where the thread
// could not be pinned). The host need not give a virtual machine's cores equal shares: this
// machine's two have run 1.5x apart for minutes at a time. Then two threads can gain at most
// 1 + slower/faster over one thread on the faster core, and a 1-thread time depends on the core it
// ran on.
std::vector<double> coreSpeeds() {
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  std::vector<double> ms(cores, 0.0);
  for (unsigned c = 0; c < cores; ++c) {
    std::thread([&ms, c] {
      cpu_set_t set;
      CPU_ZERO(&set);
      CPU_SET(c, &set);
      if (pthread_setaffinity_np(pthread_self(), sizeof set, &set) != 0) return;
      const auto start = std::chrono::steady_clock::now();
      spin();
      ms[c] = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    }).join();
  }
  double fastest = 0.0;
  for (const double t : ms)
    if (t > 0.0 && (fastest == 0.0 || t < fastest)) fastest = t;
  std::vector<double> speeds;
  for (const double t : ms) speeds.push_back(t > 0.0 ? fastest / t : 0.0);
  return speeds;
}

void printCoreSpeeds(const char* when, std::ofstream& csv) {
  const std::vector<double> speeds = coreSpeeds();
  std::printf("cores%s: one busy thread pinned to each runs at", when);
  for (size_t c = 0; c < speeds.size(); ++c) {
    std::printf(" %.2f", speeds[c]);
    csv << "probe,core" << c << (*when ? "-end" : "") << ",0,0,machine,1,1," << speeds[c]
        << ",,,,\"speed of one thread pinned to this core / the fastest core's\"\n";
  }
  std::printf(" of the fastest core's speed\n");
}

void printCrossCore(const char* when, std::ofstream& csv) {
  const double ns = crossCoreNs();
  std::printf("cores%s: a cache line written on one core is read on the other after %.0f ns (25-35 on most\n"
              "days here; about 160 while the host keeps the two virtual CPUs far apart, and then two threads\n"
              "of one frame gain less)\n",
              when, ns);
  csv << "probe,cross-core" << (*when ? "-end" : "") << ",0,0,machine,2,1," << ns
      << ",,,,\"ns for a cache line to pass from one core to the other\"\n";
}

// The speed targets against this run's figures (speed_targets.h), like for like: shadowref at
// least as fast as llvmpipe at the same thread count and at least 10x softpipe, in both lighting
// pairs; identical buffers; cost linear in houses and lights, read as a
// least-squares line with R² of at least kLinearR2. The unequal pairing is shown, not
// judged: per-pixel Phong in double against per-vertex lighting is not the same passes' work. Nor
// is two threads against one, measured on frames in turn (Config::inTurn: the same host for both
// counts) and shown with the same ratio from separate processes, the host's capacity for two
// threads (the ceiling no renderer passes) and llvmpipe's own ratio beside it.
constexpr double kLinearR2 = 0.95;

void printTargets(const std::vector<SceneCase>& cases, const std::vector<std::vector<Measured>>& all,
                  const std::vector<bool>& identical, const std::optional<ScalingFits>& fits) {
  std::vector<std::string> labels;
  for (const SceneCase& c : cases) labels.push_back(c.label);
  TargetTable table(labels);
  const auto ratio = [&](Column numerator, Column denominator) {
    std::vector<double> v;
    for (const std::vector<Measured>& m : all) v.push_back(m[size_t(numerator)].median() / m[size_t(denominator)].median());
    return v;
  };
  table.atLeast("per vertex, 1 thread: x llvmpipe", 1.0, ratio(kLl1, kSrg1));
  table.atLeast("per vertex, 2 threads: x llvmpipe", 1.0, ratio(kLl2, kSrg2));
  table.atLeast("per vertex: x softpipe", 10.0, ratio(kSoft, kSrg1));
  table.atLeast("per pixel, 1 thread: x llvmpipe", 1.0, ratio(kLp1, kSr1));
  table.atLeast("per pixel, 2 threads: x llvmpipe", 1.0, ratio(kLp2, kSr2));
  table.atLeast("per pixel: x softpipe", 10.0, ratio(kSopp, kSr1));
  // Per scene, the median of one of a configuration's lists over its runs.
  const auto medianOf = [&](Column c, std::vector<double> Measured::*list) {
    std::vector<double> v;
    for (const std::vector<Measured>& m : all) v.push_back(median(m[size_t(c)].*list));
    return v;
  };
  const auto crossCore = [&](Column c) { return medianOf(c, &Measured::crossCore); };
  const auto inTurn = [&](Column c) { return medianOf(c, &Measured::turnRatios); };
  table.information("per vertex: in turn, 2 threads / 1", inTurn(kSrgTurn));
  table.information("  separate processes, 2 threads / 1", ratio(kSrg1, kSrg2));
  table.information("  the host's capacity for two threads", ratio(kSrg1, kSrgPair));
  table.information("  ns for a line between the cores", crossCore(kSrg2));
  table.information("  llvmpipe's 2 threads / 1, same runs", ratio(kLl1, kLl2));
  table.information("per pixel: in turn, 2 threads / 1", inTurn(kSrTurn));
  table.information("  separate processes, 2 threads / 1", ratio(kSr1, kSr2));
  table.information("  the host's capacity for two threads", ratio(kSr1, kSrPair));
  table.information("  ns for a line between the cores", crossCore(kSr2));
  table.information("  llvmpipe's 2 threads / 1, same runs", ratio(kLp1, kLp2));
  table.holds("buffers of 1, 2 and 8 threads", identical, "identical", "DIFFERENT");
  if (fits) {
    table.single("linear in houses, 1 thread: R2", fits->houses1, kLinearR2);
    table.single("linear in houses, 2 threads: R2", fits->houses2, kLinearR2);
    table.single("linear in lights, 1 thread: R2", fits->lights1, kLinearR2);
    table.single("linear in lights, 2 threads: R2", fits->lights2, kLinearR2);
  }
  table.information("unequal: per pixel, x llvmpipe fixed 1t", ratio(kLl1, kSr1));
  table.information("unequal: per pixel, x softpipe fixed", ratio(kSoft, kSr1));
  std::printf("\nThe speed targets in this run, like for like (figures cut to the decimals shown; rows\n"
              "without a verdict are information)%s\n%s",
              fits ? "" : "; cost against houses and lights not measured (--no-scaling)", table.text().c_str());
}

int runDriver(const Settings& s) {
  std::printf("bench/vs-mesa: shadowref against Mesa through OSMesa\n");
  std::printf("machine: %u hardware threads, %s; load average %s\n", std::thread::hardware_concurrency(),
              cpuModel().c_str(), loadAverage().c_str());
  const MachineShare before = probeMachine();
  std::printf("available: parallelism %.2f of 2, CPU share of one thread %.2f (spin-loop probe; 2 and 1.00 on an idle\n"
              "machine; below that, other processes compete and wall-clock times and thread speedups suffer)\n",
              before.parallelism, before.cpuShare);
  std::ofstream csv = openCsv(s.csvPath);
  csv << "probe,before,0,0,machine,2,1," << before.parallelism << ",,," << before.cpuShare << ",\"parallelism; cpu share\"\n";
  printCoreSpeeds("", csv);
  printCrossCore("", csv);
  if (s.seriesOnly) {
    const ScalingFits f = scaling(s, csv);
    std::printf("\nR2 of the lines, shadowref: houses %.3f (1 thread) %.3f (2 threads), lights %.3f %.3f (target: %.2f)\n",
                f.houses1, f.houses2, f.lights1, f.lights2, kLinearR2);
    std::printf("\nCSV: %s\n", s.csvPath.c_str());
    return 0;
  }
  const std::vector<std::vector<Measured>> compared = compareScenes(s, csv);
  const std::vector<bool> identical = checkDeterminism(comparedScenes(), csv);
  std::optional<ScalingFits> fits;
  if (s.scaling) fits = scaling(s, csv);
  const MachineShare after = probeMachine();
  std::printf("\navailable at the end: parallelism %.2f of 2, CPU share %.2f; load average %s\n", after.parallelism,
              after.cpuShare, loadAverage().c_str());
  csv << "probe,after,0,0,machine,2,1," << after.parallelism << ",,," << after.cpuShare << ",\"parallelism; cpu share\"\n";
  printCoreSpeeds(" at the end", csv);
  printCrossCore(" at the end", csv);
  agreementTable("", &csv);
  printTargets(comparedScenes(), compared, identical, fits);
  std::printf("\nCSV: %s\n", s.csvPath.c_str());
  return std::find(identical.begin(), identical.end(), false) == identical.end() ? 0 : 1;
}

// --tally: the tables of targets of runs saved before (each the whole output of a run, as
// scripts/bench-vs-mesa.sh writes build/bench-results/vs-mesa.txt), figure by figure over the runs.
int tallyRuns(const std::vector<std::string>& files) {
  if (files.empty()) throw std::runtime_error("--tally needs the saved output of at least one run");
  TargetTally tally;
  for (const std::string& file : files) {
    std::ifstream in(file);
    if (!in) throw std::runtime_error(file + ": cannot be read");
    const std::optional<RunTargets> run = readRunTargets(in);
    if (!run) {
      std::fprintf(stderr, "vs_mesa: %s: no table of targets (from before the bench printed one, or cut short); left out\n",
                   file.c_str());
      continue;
    }
    tally.add(file, *run);
  }
  if (tally.runs() == 0) throw std::runtime_error("--tally: none of the files holds a table of targets");
  std::printf("%s", tally.text().c_str());
  return 0;
}

}  // namespace

}  // namespace shadowref::bench

int main(int argc, char** argv) {
  using namespace shadowref::bench;
  try {
    if (argc >= 6 && std::strcmp(argv[1], "--worker") == 0) {
      SceneCase c{"worker", argv[5], {}};
      for (int i = 6; i < argc; ++i) c.overrides.push_back(argv[i]);
      return runWorker(argv[2], std::atoi(argv[3]), std::atoi(argv[4]), c);
    }
    if (argc >= 6 && std::strcmp(argv[1], "--series-worker") == 0) {  // THREADS FRAMES (--case FILE OVERRIDE...)...
      std::vector<SceneCase> cases;
      for (int i = 4; i < argc; ++i) {
        if (std::strcmp(argv[i], "--case") == 0 && i + 1 < argc) cases.push_back({"worker", argv[++i], {}});
        else if (!cases.empty()) cases.back().overrides.push_back(argv[i]);
        else throw std::runtime_error("--series-worker: --case FILE first");
      }
      return runSeriesWorker(std::atoi(argv[2]), std::atoi(argv[3]), cases);
    }
    if (argc >= 2 && std::strcmp(argv[1], "--tally") == 0) return tallyRuns(std::vector<std::string>(argv + 2, argv + argc));
    Settings s;
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      auto next = [&]() -> std::string {
        if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
        return argv[++i];
      };
      if (a == "--rounds") s.rounds = std::max(1, std::stoi(next()));
      else if (a == "--frames") s.frames = std::max(1, std::stoi(next()));
      else if (a == "--csv") s.csvPath = next();
      else if (a == "--no-scaling") s.scaling = false;
      else if (a == "--quick") s.quick = true;
      else if (a == "--series") s.seriesOnly = true;
      else if (a == "--agreement") s.agreement = true;
      else if (a == "--images") s.imageDir = next();
      else {
        std::fprintf(stderr, "usage: vs_mesa [--rounds N] [--frames N] [--csv FILE] [--quick] [--no-scaling | --series]\n"
                             "       vs_mesa --agreement [--images DIR]\n"
                             "       vs_mesa --tally RUN.txt...\n");
        return 2;
      }
    }
    if (s.agreement) {
      agreementTable(s.imageDir, nullptr);
      return 0;
    }
    return runDriver(s);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vs_mesa: %s\n", e.what());
    return 1;
  }
}
