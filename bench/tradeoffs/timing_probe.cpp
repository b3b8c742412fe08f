#include "tradeoffs/timing_probe.h"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

#include "cli/timing_stats.h"
#include "scene/scene_loader.h"
#include "shadow/frame_renderer.h"
#include "shadow/technique_registry.h"

namespace shadowref::bench {

namespace {
using timing::median;

// The peak resident set of this process image: VmHWM of /proc/self/status. Not getrusage's
// ru_maxrss: Linux carries the forking parent's peak over fork and exec into the child's ru_maxrss,
// so every child would report at least the bench's own (oracle-sized) peak.
long ownPeakRssKiB() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::stol(line.substr(6));  // "VmHWM:   12345 kB"
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss;
}

// fork + exec, the child's stdout read through a pipe; no shell, so no quoting.
std::string runChild(const std::string& self, const std::vector<std::string>& args, int& status) {
  int fds[2];
  if (pipe(fds) != 0) {
    status = -1;
    return "error pipe failed";
  }
  const pid_t pid = fork();
  if (pid == 0) {
    dup2(fds[1], STDOUT_FILENO);
    close(fds[0]);
    close(fds[1]);
    std::vector<char*> argv;
    argv.push_back(const_cast<char*>(self.c_str()));
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(self.c_str(), argv.data());
    _exit(127);
  }
  close(fds[1]);
  std::string out;
  char buffer[4096];
  ssize_t n;
  while ((n = read(fds[0], buffer, sizeof buffer)) > 0) out.append(buffer, static_cast<size_t>(n));
  close(fds[0]);
  waitpid(pid, &status, 0);
  return out;
}

double processCpuMs() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

}  // namespace

ProbeResult runProbe(const std::string& self, const ProbeRequest& request) {
  std::vector<std::string> args = {"--probe", request.sceneFile, request.method, std::to_string(request.threads),
                                   std::to_string(request.frames)};
  args.insert(args.end(), request.overrides.begin(), request.overrides.end());
  int status = 0;
  const std::string out = runChild(self, args, status);
  ProbeResult result;
  std::istringstream line(out);
  std::string word;
  line >> word;
  if (word == "ok" && line >> result.medianMs >> result.minMs >> result.maxMs >> result.peakRssKiB >> result.wallMedianMs) {
    result.ok = true;
    return result;
  }
  result.error = out.empty() ? "probe exited with status " + std::to_string(status) : out;
  while (!result.error.empty() && result.error.back() == '\n') result.error.pop_back();
  return result;
}

int probeMain(const std::vector<std::string>& args) {
  if (args.size() == 1 && args[0] == "baseline") {
    std::printf("ok 0 0 0 %ld 0\n", ownPeakRssKiB());
    return 0;
  }
  if (args.size() < 4) {
    std::printf("error usage: --probe SCENE METHOD THREADS FRAMES [overrides...]\n");
    return 2;
  }
  try {
    LoadOptions load;
    load.overrides.assign(args.begin() + 4, args.end());
    const Scene scene = loadScene(args[0], load);
    FrameOptions options;
    if (!findTechnique(args[1])) throw std::runtime_error("unknown method " + args[1]);
    options.method = args[1];
    options.threads = std::stoi(args[2]);
    const int frames = std::stoi(args[3]);
    const std::unique_ptr<PipelineMaker> pipelines = makePipelineMaker(options.pipeline, options.threads);
    options.pipelines = pipelines.get();  // threads started once, not per frame
    renderFrame(scene, options);  // warm-up: page in buffers and code
    std::vector<double> cpu, wall;
    for (int i = 0; i < frames; ++i) {
      const double cpuStart = processCpuMs();
      const auto start = std::chrono::steady_clock::now();
      const FrameResult frame = renderFrame(scene, options);
      wall.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
      cpu.push_back(processCpuMs() - cpuStart);
    }
    std::printf("ok %.4f %.4f %.4f %ld %.4f\n", median(cpu), *std::min_element(cpu.begin(), cpu.end()),
                *std::max_element(cpu.begin(), cpu.end()), ownPeakRssKiB(), median(wall));
    return 0;
  } catch (const std::exception& e) {
    std::string message = e.what();
    std::replace(message.begin(), message.end(), '\n', ' ');
    std::printf("error %s\n", message.c_str());
    return 1;
  }
}

long baselineRssKiB(const std::string& self) {
  int status = 0;
  const std::string out = runChild(self, {"--probe", "baseline"}, status);
  std::istringstream line(out);
  std::string word;
  double a, b, c;
  long rss = 0;
  line >> word >> a >> b >> c >> rss;
  return rss;
}

}  // namespace shadowref::bench
