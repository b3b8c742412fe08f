#include "cli/bench_command.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <map>

#include "cli/timing_stats.h"
#include "memory/allocator_tuning.h"
#include "shadow/frame_renderer.h"

namespace shadowref::cli {

namespace {
using timing::median;
}  // namespace

void addBenchCommand(CLI::App& app, BenchArgs& args) {
  CLI::App* bench = app.add_subcommand("bench", "Render a scene several times; print the median time per frame and per pass");
  bench->add_option("scene", args.scene.scene, "Scene file (YAML); omitted: the built-in room");
  bench->add_option("--method", args.method, methodHelp());
  bench->add_option("--frames", args.frames, "Frames to time (default 5)")->check(wholeNumberIn(1, 10000));
  bench->add_option("--threads", args.threads, "Worker threads (0: one per CPU this process may run on)")->check(wholeNumberIn(0, 256));
  bench->add_option("--pipeline", args.pipeline, "'fast' (default) or 'reference'")
      ->check(CLI::IsMember({"reference", "fast"}));
  bench->add_option("-D", args.scene.overrides, "Override a scene value, e.g. -D image.width=400")
      ->take_all()
      ->allow_extra_args(false);
  bench->add_flag("--csv", args.csv, "One CSV line: scene,method,threads,width,height,frames,median_ms");
}

namespace {
std::string sceneName(const BenchArgs& args) { return args.scene.scene.empty() ? "<builtin:room>" : args.scene.scene; }

}  // namespace

int runBench(const BenchArgs& args) {
  keepFreedMemoryForReuse();
  const std::optional<Scene> scene = loadSceneOrReport(args.scene);
  if (!scene) return kBadInput;
  FrameOptions options;
  options.threads = args.threads;
  options.pipeline = args.pipeline == "reference" ? PipelineKind::Reference : PipelineKind::Fast;
  if (!checkMethodOrReport(args.method)) return kBadInput;
  options.method = args.method;
  const char* const method = options.method.empty() ? scene->shadow.method.c_str() : options.method.c_str();
  timing::FrameTimes times;
  const int threads = pipelineThreads(options.pipeline, args.threads);
  // One maker for every frame: its threads start once, as in a program that renders frame after
  // frame, not per frame.
  const std::unique_ptr<PipelineMaker> pipelines = makePipelineMaker(options.pipeline, args.threads);
  options.pipelines = pipelines.get();
  try {
    renderFrame(*scene, options);  // warm-up: page in buffers and code
    for (int i = 0; i < args.frames; ++i) {
      const auto start = std::chrono::steady_clock::now();
      const FrameResult frame = renderFrame(*scene, options);
      times.add(frame, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
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
  return kSuccess;
}

}  // namespace shadowref::cli
