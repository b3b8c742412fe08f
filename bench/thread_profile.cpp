// thread_profile: where a frame's time goes with threads — the thread pool's runs, observed
// (pool_runs.h), and one thread set against more in turn (frames_in_turn.h). `shadowref bench`
// times frames for users; this is the benchmark that looks inside them.
//
//   thread_profile SCENE [--threads N] [--frames N] [-D key=value ...] [--runs | --alternate]
//
// Default: the median frame and each pass, and the time in and outside the pool's runs with how
// busy the threads were there. --runs adds a frame laid out run by run; --alternate renders frames
// at one thread and at --threads (2 or more) in turn and prints the medians of each and their
// quotient: figures, not verdicts (on a shared host the host decides them).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "cli/timing_stats.h"
#include "exec/fast_pipeline.h"
#include "exec/thread_pool.h"
#include "frames_in_turn.h"
#include "memory/allocator_tuning.h"
#include "pool_runs.h"
#include "scene/scene_loader.h"
#include "shadow/frame_renderer.h"

namespace shadowref::bench {
namespace {

using timing::median;

constexpr const char* kUsage =
    "usage: thread_profile SCENE [--threads N] [--frames N] [-D key=value ...] [--runs | --alternate]\n";

struct Args {
  std::string scene;
  std::vector<std::string> overrides;
  int threads = 2, frames = 5;
  bool runs = false, alternate = false;
};

// Where the threads' time went, per frame on average: inside the pool's runs (and how much of the
// threads' time there went to tasks rather than waiting), and outside them, where the calling
// thread works alone. What keeps more threads from as many times the speed of one, apart from
// each thread running slower when several run (memory, caches, the host).
void printPoolTimes(const PoolTimes& t, int threads, const std::vector<double>& frameMs) {
  const double frames = double(frameMs.size());
  double total = 0.0;
  for (double ms : frameMs) total += ms;
  const double busy = t.runMilliseconds > 0.0 ? 100.0 * t.taskMilliseconds / (threads * t.runMilliseconds) : 0.0;
  std::printf("  in pool runs (mean)       %9.3f ms   %.1f runs a frame; the %d threads busy %.1f %% of it\n",
              t.runMilliseconds / frames, double(t.runs) / frames, threads, busy);
  std::printf("  outside runs (mean)       %9.3f ms   the calling thread alone\n",
              std::max(0.0, total - t.runMilliseconds) / frames);
}

// The pool's runs frame by frame (layOutRuns): long gaps are serial work, a high idle share in a
// long run is its threads' ends apart.
void printRuns(const RunLayout& layout) {
  std::printf("  runs of a frame (medians of %zu frames): tasks, time, the threads' time in it that no task used,\n"
              "  and the calling thread's time alone before it\n", layout.framesUsed);
  std::printf("     run  tasks         ms   idle %%   alone before, ms\n");
  for (size_t k = 0; k < layout.rows.size(); ++k) {
    const RunRow& r = layout.rows[k];
    std::printf("  %6zu %6.0f  %9.3f  %7.1f  %9.3f\n", k + 1, r.tasks, r.milliseconds, r.idlePercent, r.beforeMilliseconds);
  }
  if (layout.framesUsed > 0) std::printf("  after the last run                           %9.3f\n", layout.afterMilliseconds);
}

int profileRuns(const Args& args, const Scene& scene) {
  FrameOptions options;
  options.threads = args.threads;
  const FastPipelineMaker pipelines(args.threads);
  options.pipelines = &pipelines;
  ThreadPool* pool = pipelines.pool();  // the one renderFrame's renderers use
  RunRecorder recorder;
  timing::FrameTimes times;
  std::vector<FrameSpan> spans;
  renderFrame(scene, options);  // warm-up: page in buffers and code
  {
    std::optional<ObservedPool> observed;
    if (pool) observed.emplace(*pool, recorder);
    for (int i = 0; i < args.frames; ++i) {
      const int64_t start = steadyNanoseconds();
      const FrameResult frame = renderFrame(scene, options);
      const int64_t end = steadyNanoseconds();
      times.add(frame, double(end - start) * 1e-6);
      spans.push_back({start, end});
    }
  }
  std::printf("%s, method %s, %dx%d, %d thread%s, %d frames\n", args.scene.c_str(), scene.shadow.method.c_str(),
              scene.width, scene.height, args.threads, args.threads == 1 ? "" : "s", args.frames);
  std::printf("  frame (median)            %9.3f ms\n", median(times.frameMs));
  for (const std::string& pass : times.passOrder)
    std::printf("  %-25s %9.3f ms\n", pass.c_str(), median(times.passMs[pass]));
  if (!pool) {
    std::printf("  pool runs: none (one thread draws without the pool)\n");
    return 0;
  }
  printPoolTimes(sumRuns(recorder.records()), args.threads, times.frameMs);
  if (args.runs) printRuns(layOutRuns(recorder.records(), spans, args.threads));
  return 0;
}

// --alternate: frames at `threads` threads and at one thread in turn (renderFramesInTurn).
int alternate(const Args& args, const Scene& scene) {
  timing::FrameTimes one, many;
  renderFramesInTurn(scene, FrameOptions{}, {.threads = args.threads, .warmUp = 1, .frames = args.frames},
                     [&](int t, const FrameResult& frame, double ms) { (t == 1 ? one : many).add(frame, ms); });
  std::printf("%s, method %s, %dx%d, %d frames at 1 thread and %d at %d in turn, the workers woken before each\n",
              args.scene.c_str(), scene.shadow.method.c_str(), scene.width, scene.height, args.frames, args.frames,
              args.threads);
  std::printf("  median, ms                  1 thread  %2d threads   speed-up\n", args.threads);
  auto line = [](const std::string& what, const std::vector<double>& a, const std::vector<double>& b) {
    const double ma = median(a), mb = median(b);
    std::printf("  %-25s %10.3f  %10.3f  %9.3f\n", what.c_str(), ma, mb, mb > 0.0 ? ma / mb : 0.0);
  };
  line("frame", one.frameMs, many.frameMs);
  for (const std::string& pass : many.passOrder)
    if (one.passMs.count(pass)) line(pass, one.passMs[pass], many.passMs[pass]);
  return 0;
}

// Whole numbers in [lo, hi] only.
bool wholeNumber(const char* text, int lo, int hi, int& out) {
  char* end = nullptr;
  const long v = std::strtol(text, &end, 10);
  if (end == text || *end != '\0' || v < lo || v > hi) return false;
  out = int(v);
  return true;
}

}  // namespace
}  // namespace shadowref::bench

int main(int argc, char** argv) {
  using namespace shadowref;
  using namespace shadowref::bench;
  Args args;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool hasValue = i + 1 < argc;
    if (a == "--threads" && hasValue && wholeNumber(argv[i + 1], 1, 256, args.threads)) ++i;
    else if (a == "--frames" && hasValue && wholeNumber(argv[i + 1], 1, 10000, args.frames)) ++i;
    else if (a == "-D" && hasValue) args.overrides.push_back(argv[++i]);
    else if (a == "--runs") args.runs = true;
    else if (a == "--alternate") args.alternate = true;
    else if (args.scene.empty() && !a.empty() && a[0] != '-') args.scene = a;
    else {
      std::fprintf(stderr, "thread_profile: bad argument %s\n%s", a.c_str(), kUsage);
      return 2;
    }
  }
  if (args.scene.empty() || (args.runs && args.alternate)) {
    std::fprintf(stderr, "%s", kUsage);
    return 2;
  }
  if (args.alternate && args.threads < 2) {
    std::fprintf(stderr, "thread_profile: --alternate sets one thread against more: --threads must be 2 or more\n");
    return 2;
  }
  try {
    keepFreedMemoryForReuse();
    LoadOptions load;
    load.overrides = args.overrides;
    const Scene scene = loadScene(args.scene, load);
    return args.alternate ? alternate(args, scene) : profileRuns(args, scene);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "thread_profile: %s\n", e.what());
    return 2;
  }
}
