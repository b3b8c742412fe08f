#include "sweep/sweep_run.h"

#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "image/atomic_write.h"
#include "scene/animation.h"
#include "scene/scene_loader.h"
#include "shadow/frame_renderer.h"
#include "shadow/soft_lights.h"
#include "shadow/technique.h"
#include "shadow/technique_registry.h"

namespace shadowref::sweep {

namespace {

using Json = nlohmann::json;

double cpuMs() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n == 0 ? 0.0 : n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// The scene as it stands at `frame` (t = frame / the animation's fps, as render --frames). A scene
// without animation is the same at every frame.
Scene sceneAtFrame(const Scene& scene, int frame) {
  if (!scene.animation) return scene;
  return sceneAt(scene, double(frame) / scene.animation->fps);
}

Json timeFrames(const Scene& scene, const Job& job, const RunOptions& options) {
  FrameOptions frame;
  frame.method = job.method;
  // One maker for the job's frames: its threads start once, as in a program that renders frame
  // after frame.
  const std::unique_ptr<PipelineMaker> pipelines = makePipelineMaker(PipelineKind::Fast, options.threads);
  frame.pipelines = pipelines.get();
  renderFrame(scene, frame);  // warm-up: page in buffers and code
  std::vector<double> wall, cpu;
  for (int i = 0; i < job.repetitions; ++i) {
    const double cpuStart = cpuMs();
    const auto start = std::chrono::steady_clock::now();
    renderFrame(scene, frame);
    wall.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    cpu.push_back(cpuMs() - cpuStart);
  }
  return {{"median_ms", median(wall)},
          {"min_ms", *std::min_element(wall.begin(), wall.end())},
          {"max_ms", *std::max_element(wall.begin(), wall.end())},
          {"cpu_median_ms", median(cpu)},
          {"repetitions", job.repetitions}};
}

}  // namespace

Machine thisMachine() {
  Machine m;
  char host[256] = {};
  m.hostname = gethostname(host, sizeof host - 1) == 0 ? host : "unknown";
  m.cpu = "unknown";
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0 && line.find(':') != std::string::npos) {
      m.cpu = line.substr(line.find(':') + 1);
      m.cpu.erase(0, m.cpu.find_first_not_of(" \t"));
      break;
    }
  return m;
}

std::string recordPath(const std::string& outDir, const Job& job) {
  return (std::filesystem::path(outDir) / (job.id + ".json")).string();
}

bool recordIsComplete(const std::string& file, const Job& job, bool needTime) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return false;
  const Json j = Json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (!j.is_object() || j.value("id", "") != job.id || !j.contains("config") ||
      j["config"] != Json::parse(job.canonical) || !j.contains("lights"))
    return false;
  if (job.record.error && !j.contains("error")) return false;
  if (job.record.counts && !j.contains("counts")) return false;
  if (needTime && job.record.time && !(j.contains("time") && j.contains("machine"))) return false;
  return true;
}

std::string runJob(const Job& job, const RunOptions& options) {
  LoadOptions load;
  std::vector<std::string> keys;
  for (const auto& [key, value] : job.overrides) {
    load.overrides.push_back(key + "=" + value);
    keys.push_back(key);
  }
  Scene loaded;
  try {
    loaded = loadScene(job.scenePath, load);
  } catch (const SceneError& e) {
    // The loader places an error in the i-th override at "<command line>:i:column"; the user
    // wrote it in the sweep file, so the error is reported there.
    const SourceLocation& at = e.where();
    if (at.file == kCommandLineFile && at.line >= 1 && size_t(at.line) <= keys.size()) {
      const auto found = job.overrideAt.find(keys[size_t(at.line - 1)]);
      if (found != job.overrideAt.end())
        throw SceneError(found->second, e.message() + " (in " + job.scene + ")");
    }
    throw;
  }
  const Scene scene = sceneAtFrame(loaded, job.frame);
  const ShadowTechnique* technique = findTechnique(job.method);
  if (!technique) throw std::runtime_error(unknownTechniqueMessage(job.method));

  Json record;
  record["id"] = job.id;
  record["config"] = Json::parse(job.canonical);
  int lights = 0;
  for (const Light& l : scene.lights) lights += static_cast<int>(expandSoftLight(l).size());
  record["lights"] = lights;
  if (job.record.counts) {
    FrameOptions frame;
    frame.method = job.method;
    frame.threads = options.threads;
    const RasterStats s = renderFrame(scene, frame).stats;
    record["counts"] = {{"draw_calls", s.drawCalls},         {"triangles", s.trianglesRasterized},
                        {"fragments", s.fragments},          {"stencil_writes", s.stencilWrites},
                        {"depth_failed", s.depthFailed},     {"stencil_failed", s.stencilFailed},
                        {"color_writes", s.colorWrites}};
  }
  if (job.record.error) {
    ErrorSettings settings;
    settings.reference = job.reference.shape;
    settings.softSpacing = job.reference.size;
    settings.referenceSamples = job.reference.samples;
    settings.threads = options.threads;
    // Shadow volumes render with P_inf ([Kuhn 2016, §3.3]); the oracle's camera then does too.
    settings.forceInfiniteOracle = technique->countsInStencil;
    const ShadowError e = measureShadowError(scene, job.method, settings);
    record["error"] = {{"pixels", e.pixels}, {"mae", e.mae}, {"wrong", e.wrong}, {"wrong_core", e.wrongCore},
                       {"shadowed", e.shadowed}};
  }
  if (job.record.time && options.timing) {
    record["time"] = timeFrames(scene, job, options);
    const Machine m = thisMachine();
    const int threads = options.threads > 0 ? options.threads : std::max(1, int(std::thread::hardware_concurrency()));
    record["machine"] = {{"hostname", m.hostname}, {"cpu", m.cpu}, {"threads", threads}, {"build", options.build}};
  }
  return record.dump() + "\n";
}

RunSummary runJobs(const std::vector<const Job*>& jobs, const RunOptions& options,
                   const std::function<void(const std::string& message)>& report) {
  RunSummary summary;
  std::filesystem::create_directories(options.outDir);
  for (size_t i = 0; i < jobs.size(); ++i) {
    const Job& job = *jobs[i];
    const std::string path = recordPath(options.outDir, job);
    const std::string what = "[" + std::to_string(i + 1) + "/" + std::to_string(jobs.size()) + "] " + job.id + " " +
                             job.scene + " " + job.method + (job.label.empty() ? "" : " " + job.label);
    if (recordIsComplete(path, job, options.timing)) {
      ++summary.skipped;
      continue;
    }
    const auto start = std::chrono::steady_clock::now();
    try {
      const std::string text = runJob(job, options);
      writeFileAtomically(path, [&](const TempFile& temp) { writeAllAt(temp.fd, text.data(), text.size(), 0); });
      ++summary.ran;
      if (options.progress) {
        std::ostringstream line;
        line.precision(1);
        line << std::fixed << what << " ("
             << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() << " s)";
        options.progress(line.str());
      }
    } catch (const SceneError& e) {
      ++summary.badInput;
      report(job.id + ": " + e.what());
    } catch (const std::exception& e) {
      ++summary.failed;
      report(what + ": " + e.what());
    }
  }
  return summary;
}

}  // namespace shadowref::sweep
