// frame_profile: renders one scene's frames and nothing else, for a profiler.
//
//   frame_profile SCENE [--frames N] [--threads N] [-D key=value ...]
//
// `valgrind --tool=callgrind --toggle-collect='shadowref::renderFrame*' build/bench/frame_profile
// scenes/room.yaml -D shadow.method=zfail` counts the instructions of the frames alone. It links
// no image library: the CLI's OpenImageIO pulls in libhwy, whose start-up code uses an
// instruction valgrind does not know on this machine's CPU, so `shadowref bench` cannot run
// under valgrind here. The first frame warms up (pages in buffers), like `shadowref bench`.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "memory/allocator_tuning.h"
#include "scene/scene_loader.h"
#include "shadow/frame_renderer.h"

int main(int argc, char** argv) {
  using namespace shadowref;
  std::string file;
  int frames = 1, threads = 1;
  LoadOptions options;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "frame_profile: %s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--frames") frames = std::atoi(value().c_str());
    else if (a == "--threads") threads = std::atoi(value().c_str());
    else if (a == "-D") options.overrides.push_back(value());
    else if (file.empty() && a[0] != '-') file = a;
    else {
      std::fprintf(stderr, "usage: frame_profile SCENE [--frames N] [--threads N] [-D key=value ...]\n");
      return 2;
    }
  }
  if (file.empty() || frames < 1 || threads < 0) {
    std::fprintf(stderr, "usage: frame_profile SCENE [--frames N] [--threads N] [-D key=value ...]\n");
    return 2;
  }
  try {
    keepFreedMemoryForReuse();
    const Scene scene = loadScene(file, options);
    FrameOptions frame;
    frame.threads = threads;
    const std::unique_ptr<PipelineMaker> pipelines = makePipelineMaker(frame.pipeline, threads);
    frame.pipelines = pipelines.get();  // threads started once, not per frame
    uint64_t fragments = 0;
    for (int i = 0; i <= frames; ++i) fragments = renderFrame(scene, frame).stats.fragments;
    std::printf("%s: %d+1 frames, %llu fragments per frame\n", file.c_str(), frames, (unsigned long long)fragments);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
  return 0;
}
