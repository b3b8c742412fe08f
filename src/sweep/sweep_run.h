// Running a sweep's jobs: each job's frame timed, compared with the ray-cast oracle and counted,
// and its record written atomically to OUTDIR/<id>.json. A job whose complete record is there
// already is skipped, so that a shard run again after a crash finishes what is missing.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "sweep/sweep_spec.h"

namespace shadowref::sweep {

struct Machine {
  std::string hostname;
  std::string cpu;  // /proc/cpuinfo's "model name", or "unknown"
};
Machine thisMachine();

struct RunOptions {
  std::string outDir;
  int threads = 1;       // render threads (0: one per CPU); the bytes, errors and counts do not depend on it
  bool timing = true;    // false (--no-timing): no job is timed, and records name no machine
  std::string build;     // the program's version and revision, kept with the times
  std::function<void(const std::string& line)> progress;  // one line per job; may be empty
};

// OUTDIR/<id>.json
std::string recordPath(const std::string& outDir, const Job& job);

// True when `file` holds a complete record of `job`: valid JSON, the job's id and configuration,
// every part the job records (its time only when `needTime`). Missing, truncated or foreign files
// are not complete.
bool recordIsComplete(const std::string& file, const Job& job, bool needTime);

// The job's record as JSON text (sorted keys, one line, a final newline). Throws SceneError for a
// scene the overrides make invalid, std::runtime_error when the frame cannot be rendered.
std::string runJob(const Job& job, const RunOptions& options);

struct RunSummary {
  int ran = 0, skipped = 0, failed = 0, badInput = 0;
};

// Runs every job without a complete record, in order, writing each record as it finishes. A failed
// job is reported through `report` and the others still run.
RunSummary runJobs(const std::vector<const Job*>& jobs, const RunOptions& options,
                   const std::function<void(const std::string& message)>& report);

}  // namespace shadowref::sweep
