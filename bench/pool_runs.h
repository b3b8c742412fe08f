// A thread pool's runs as the benchmarks measure them, through the pool's observer hook
// (exec/thread_pool.h): what each run cost, where a frame's time went run by run, and the pool's
// workers woken before a timed frame. Measurement only: nothing here changes a byte of a frame.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "exec/thread_pool.h"

namespace shadowref::bench {

// steady_clock nanoseconds since that clock's epoch: the time base of the records.
int64_t steadyNanoseconds();

// One run: its tasks, when it began and ended, and the threads' time inside its tasks. Tasks run
// within their run and each thread runs one claim at a time, so the task time is at most the
// pool's threads × the run's length; the rest is time a thread of the run waited — for work to
// start, or for another thread's last task.
struct RunRecord {
  int tasks = 0;
  int64_t start = 0, end = 0, taskNanoseconds = 0;
};

// The records summed.
struct PoolTimes {
  int64_t runs = 0, tasks = 0;
  double runMilliseconds = 0.0, taskMilliseconds = 0.0;
};
PoolTimes sumRuns(const std::vector<RunRecord>& records);

// Records every run of the pool it observes, in order. The run calls come from the pool's calling
// thread, the claim calls from every thread of the pool: the task time is an atomic sum.
class RunRecorder final : public RunObserver {
 public:
  void runBegins(int tasks) override;
  void runEnds(int tasks) override;
  int64_t claimBegins(int tasks) override;
  void claimEnds(int tasks, int64_t fromBegin) override;

  const std::vector<RunRecord>& records() const { return records_; }

 private:
  std::vector<RunRecord> records_;
  int64_t tasksAtStart_ = 0;
  std::atomic<int64_t> taskNanoseconds_{0};
};

// Observes a pool for as long as it lives.
class ObservedPool {
 public:
  ObservedPool(ThreadPool& pool, RunObserver& observer) : pool_(pool) { pool_.setObserver(&observer); }
  ~ObservedPool() { pool_.setObserver(nullptr); }
  ObservedPool(const ObservedPool&) = delete;
  ObservedPool& operator=(const ObservedPool&) = delete;

 private:
  ThreadPool& pool_;
};

// Returns once every thread of the pool has run a task of one run: the workers are then awake and
// spinning, as they are in a stream of frames, and a frame timed right after finds them there
// instead of timing their waking (a frame at one thread in between lets them fall asleep).
void wakeWorkers(ThreadPool& pool);

// Frames of one thread count: when each began and ended, as the records.
struct FrameSpan {
  int64_t start = 0, end = 0;
};

// A frame laid out run by run: for run k of the frames, the medians over the frames of its tasks,
// its length, the share of the threads' time in it that went to no task (per cent, at least 0),
// and the calling thread's time alone before it (from the frame's start or the run before); then
// the median time after the last run. Frames with another number of runs than the last frame are
// left out of the medians (framesUsed counts those kept).
struct RunRow {
  double tasks = 0.0, milliseconds = 0.0, idlePercent = 0.0, beforeMilliseconds = 0.0;
};
struct RunLayout {
  size_t framesUsed = 0;
  std::vector<RunRow> rows;
  double afterMilliseconds = 0.0;
};
RunLayout layOutRuns(const std::vector<RunRecord>& records, const std::vector<FrameSpan>& frames, int threads);

}  // namespace shadowref::bench
