// A sweep file: scenes × -D value grids × methods × frames, and what to record for each job
// (docs/sweeps.md). Parsing expands it into jobs, each named by a stable id: the hash of the job's
// canonical configuration, which does not depend on where or in which order the file lists it.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "scene/scene_error.h"
#include "sweep/shadow_error.h"

namespace shadowref::sweep {

// What a job records besides its configuration.
struct RecordWhat {
  bool time = false;    // time per frame: median of `repetitions` frames after a warm-up frame
  bool error = false;   // shadow error against the ray-cast oracle or an area-light reference
  bool counts = false;  // the frame's pipeline counters (fragments, stencil writes, ...)
};

// The ground truth a job's shadow is compared with.
struct ReferenceSpec {
  Reference shape = Reference::HardLight;
  double size = 0.0;  // square: half the side; sphere: the radius (unused for point)
  int samples = 256;  // shadow rays per pixel of an area-light reference
};

struct Job {
  // The configuration: these fields, and only these, make the id.
  std::string scene;                          // as written in the sweep file
  std::string method;                         // a technique's name
  int frame = 0;                              // frame of the scene's animation (0: a still scene)
  std::map<std::string, std::string> overrides;  // -D key=value, applied in key order
  RecordWhat record;
  ReferenceSpec reference;                    // meaningful when record.error
  int repetitions = 5;                        // timed frames (when record.time)

  std::string id;         // kIdDigits hex digits of the SHA-1 of canonicalJson()
  std::string canonical;  // canonicalJson(): what the id hashes

  // Not configuration: where the job appears in the file and how results name it.
  std::string scenePath;            // the scene file as opened: relative to the sweep file's folder
  std::vector<std::string> groups;  // every group that lists this configuration, sorted
  std::vector<std::string> plots;   // the plots it is a point of, sorted
  std::map<std::string, SourceLocation> overrideAt;  // where the file sets each -D value
  std::string label;                // "map=1024 pcf=3": the group's case and grid values
  size_t order = 0;                 // where the file first lists it: the order of the Markdown table
};

inline constexpr size_t kIdDigits = 16;

struct Spec {
  std::string file;
  int threads = 1;        // render threads when --threads does not say (timings only: bytes do not change)
  std::vector<Job> jobs;  // sorted by id; ids are unique
};

// Reads a sweep file. Throws SceneError ("file:line:col: message") for bad YAML, an unknown key,
// a wrong value, an unknown method or a job that sets the same key twice.
Spec loadSpec(const std::string& path);
Spec parseSpec(const std::string& yaml, const std::string& file);

// The job as one JSON object with sorted keys and no spaces: what the id hashes and `--list` prints.
std::string canonicalJson(const Job& job);

// The jobs shard `k` of `n` (1 <= k <= n) runs: every n-th job in id order, starting at the k-th,
// so that the shards partition the jobs and each gets within one of the same number.
std::vector<const Job*> shardJobs(const Spec& spec, int k, int n);

// "none", "shadow volumes" or "shadow maps": the family a method's points are coloured by.
std::string methodFamily(const std::string& method);

}  // namespace shadowref::sweep
