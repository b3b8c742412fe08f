#include "cli/bench_command.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <map>

#include "cli/timing_stats.h"
#include "memory/allocator_tuning.h"
#include "exec/thread_pool.h"
#include "shadow/frame_renderer.h"
#include "shadow/frames_in_turn.h"

namespace shadowref::cli {

namespace {
using timing::median;

// Where the threads' time went, per frame on average: inside the pool's runs (and how much of
// the threads' time there went to tasks rather than waiting), and outside them, where the
// calling thread works alone. What keeps two threads from twice the speed of one, apart from
// each thread running slower when both run (memory, caches, the host).
void printPoolTimes(const ThreadPool::Times& t, int threads, const std::vector<double>& frameMs) {
  const double frames = double(frameMs.size());
  double total = 0.0;
  for (double ms : frameMs) total += ms;
  const double busy = t.runMilliseconds > 0.0 ? 100.0 * t.taskMilliseconds / (threads * t.runMilliseconds) : 0.0;
  std::printf("  in pool runs (mean)       %9.3f ms   %.1f runs a frame; the %d threads busy %.1f %% of it\n",
              t.runMilliseconds / frames, double(t.runs) / frames, threads, busy);
  std::printf("  outside runs (mean)       %9.3f ms   the calling thread alone\n",
              std::max(0.0, total - t.runMilliseconds) / frames);
}
int64_t steadyNanoseconds() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

struct FrameSpan {
  int64_t start = 0, end = 0;  // steady_clock nanoseconds, as the pool's run records
};

// The pool's runs frame by frame, in order: run k of a frame, its tasks, its time, the share of
// the threads' time in it that went to no task (waiting for a task to start or for another
// thread's last), and the calling thread's time alone before it — medians over the frames. Where a
// frame loses against twice the speed of one thread: long gaps are serial work, a high idle share
// in a long run is its threads' ends apart. Frames with another number of runs than the last one
// are left out of the medians.
void printRuns(const std::vector<ThreadPool::RunRecord>& records, const std::vector<FrameSpan>& frames, int threads) {
  std::vector<std::vector<const ThreadPool::RunRecord*>> perFrame(frames.size());
  size_t next = 0;
  for (size_t f = 0; f < frames.size(); ++f) {
    while (next < records.size() && records[next].start < frames[f].start) ++next;
    for (; next < records.size() && records[next].end <= frames[f].end; ++next) perFrame[f].push_back(&records[next]);
  }
  const size_t runs = perFrame.empty() ? 0 : perFrame.back().size();
  std::vector<size_t> used;
  for (size_t f = 0; f < frames.size(); ++f)
    if (perFrame[f].size() == runs) used.push_back(f);
  std::printf("  runs of a frame (medians of %zu frames): tasks, time, the threads' time in it that no task used,\n"
              "  and the calling thread's time alone before it\n", used.size());
  std::printf("     run  tasks         ms   idle %%   alone before, ms\n");
  const auto ms = [](int64_t ns) { return double(ns) * 1e-6; };
  for (size_t k = 0; k < runs; ++k) {
    std::vector<double> tasks, length, idle, before;
    for (size_t f : used) {
      const ThreadPool::RunRecord& r = *perFrame[f][k];
      const int64_t previousEnd = k == 0 ? frames[f].start : perFrame[f][k - 1]->end;
      const double runMs = ms(r.end - r.start);
      tasks.push_back(r.tasks);
      length.push_back(runMs);
      idle.push_back(runMs > 0.0 ? 100.0 * (1.0 - ms(r.taskNanoseconds) / (threads * runMs)) : 0.0);
      before.push_back(ms(r.start - previousEnd));
    }
    std::printf("  %6zu %6.0f  %9.3f  %7.1f  %9.3f\n", k + 1, median(tasks), median(length), std::max(0.0, median(idle)),
                median(before));
  }
  std::vector<double> after;
  for (size_t f : used) after.push_back(ms(frames[f].end - (runs ? perFrame[f].back()->end : frames[f].start)));
  if (!after.empty()) std::printf("  after the last run                           %9.3f\n", median(after));
}
}  // namespace

void addBenchCommand(CLI::App& app, BenchArgs& args) {
  CLI::App* bench = app.add_subcommand("bench", "Render a scene several times; print the median time per frame and pass, and with threads the time in and outside the pool's runs");
  bench->add_option("scene", args.scene.scene, "Scene file (YAML); omitted: the built-in room");
  bench->add_option("--method", args.method, methodHelp());
  bench->add_option("--frames", args.frames, "Frames to time (default 5)")->check(wholeNumberIn(1, 10000));
  bench->add_option("--threads", args.threads, "Worker threads (0: all cores)")->check(wholeNumberIn(0, 256));
  bench->add_option("-D", args.scene.overrides, "Override a scene value, e.g. -D image.width=400");
  CLI::Option* csv =
      bench->add_flag("--csv", args.csv, "One CSV line: scene,method,threads,width,height,frames,median_ms");
  CLI::Option* runs =
      bench->add_flag("--runs", args.runs,
                      "With threads: each run of the thread pool in a frame (tasks, time, idle share, the calling "
                      "thread's time alone before it)");
  bench->add_flag("--alternate", args.alternate,
                  "Frames at one thread and at --threads threads (2 or more) in turn in one process, the workers "
                  "kept awake: medians of each and the speed-up, the host's changes of speed falling on both alike")
      ->excludes(csv)
      ->excludes(runs);
}

namespace {
std::string sceneName(const BenchArgs& args) { return args.scene.scene.empty() ? "<builtin:room>" : args.scene.scene; }

// Frames timed at one thread count: each frame's time and each pass's, the passes in order.
struct FrameTimes {
  std::vector<double> frameMs;
  std::map<std::string, std::vector<double>> passMs;
  std::vector<std::string> passOrder;

  void add(const FrameResult& frame, double ms) {
    frameMs.push_back(ms);
    for (const PassTiming& t : frame.timings) {
      if (!passMs.count(t.pass)) passOrder.push_back(t.pass);
      passMs[t.pass].push_back(t.milliseconds);
    }
  }
};

// `bench --alternate`: frames at `threads` threads and at one thread in turn (renderFramesInTurn).
int runAlternating(const BenchArgs& args, const Scene& scene, const FrameOptions& options, int threads, const char* method) {
  FrameTimes one, many;
  try {
    renderFramesInTurn(scene, options, {.threads = threads, .warmUp = 1, .frames = args.frames},
                       [&](int t, const FrameResult& frame, double ms) { (t == 1 ? one : many).add(frame, ms); });
  } catch (const std::exception& e) {
    std::cerr << "bench: " << e.what() << '\n';
    return kFailed;
  }
  const std::string name = sceneName(args);
  std::printf("%s, method %s, %dx%d, %d frames at 1 thread and %d at %d in turn, the workers kept awake\n",
              name.c_str(), method, scene.width, scene.height, args.frames, args.frames, threads);
  std::printf("  median, ms                  1 thread  %2d threads   speed-up\n", threads);
  auto line = [](const std::string& what, const std::vector<double>& a, const std::vector<double>& b) {
    const double ma = median(a), mb = median(b);
    std::printf("  %-25s %10.3f  %10.3f  %9.3f\n", what.c_str(), ma, mb, mb > 0.0 ? ma / mb : 0.0);
  };
  line("frame", one.frameMs, many.frameMs);
  for (const std::string& pass : many.passOrder)
    if (one.passMs.count(pass)) line(pass, one.passMs[pass], many.passMs[pass]);
  return kSuccess;
}
}  // namespace

int runBench(const BenchArgs& args) {
  keepFreedMemoryForReuse();
  const std::optional<Scene> scene = loadSceneOrReport(args.scene);
  if (!scene) return kBadInput;
  FrameOptions options;
  options.threads = args.threads;
  if (!checkMethodOrReport(args.method)) return kBadInput;
  options.method = args.method;
  const char* const method = options.method.empty() ? scene->shadow.method.c_str() : options.method.c_str();
  FrameTimes times;
  const int threads = args.threads == 0 ? defaultThreadCount() : args.threads;
  if (args.alternate) {
    if (threads < 2) {
      std::cerr << "bench: --alternate sets one thread against more: --threads must be 2 or more"
                << (args.threads == 0 ? " (0 means this machine's one core)" : "") << '\n';
      return kBadInput;
    }
    return runAlternating(args, *scene, options, threads, method);
  }
  ThreadPool* pool = threadPoolForThisThread(threads);  // the one renderFrame's renderers use
  ThreadPool::Times poolTimes;
  std::vector<ThreadPool::RunRecord> runRecords;
  std::vector<FrameSpan> frameSpans;
  try {
    renderFrame(*scene, options);  // warm-up: page in buffers and code
    if (pool) pool->timeRuns(true);
    for (int i = 0; i < args.frames; ++i) {
      const int64_t start = steadyNanoseconds();
      const FrameResult frame = renderFrame(*scene, options);
      const int64_t end = steadyNanoseconds();
      times.add(frame, double(end - start) * 1e-6);
      frameSpans.push_back({start, end});
    }
    if (pool) {
      poolTimes = pool->times();
      runRecords = pool->runRecords();
      pool->timeRuns(false);
    }
  } catch (const std::exception& e) {
    std::cerr << "bench: " << e.what() << '\n';
    return kFailed;
  }
  const std::string name = sceneName(args);
  if (args.csv) {
    std::printf("%s,%s,%d,%d,%d,%d,%.3f\n", name.c_str(), method, threads, scene->width, scene->height,
                args.frames, median(times.frameMs));
    return kSuccess;
  }
  std::printf("%s, method %s, %dx%d, %d thread%s, %d frames\n", name.c_str(), method, scene->width,
              scene->height, threads, threads == 1 ? "" : "s", args.frames);
  std::printf("  frame (median)            %9.3f ms\n", median(times.frameMs));
  for (const std::string& pass : times.passOrder)
    std::printf("  %-25s %9.3f ms\n", pass.c_str(), median(times.passMs[pass]));
  if (pool) printPoolTimes(poolTimes, threads, times.frameMs);
  if (args.runs) {
    if (pool) printRuns(runRecords, frameSpans, threads);
    else std::printf("  runs: none (one thread draws without the pool)\n");
  }
  return kSuccess;
}

}  // namespace shadowref::cli
