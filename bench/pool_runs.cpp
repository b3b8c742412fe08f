#include "pool_runs.h"

#include <algorithm>
#include <chrono>
#include <thread>

#include "cli/timing_stats.h"

namespace shadowref::bench {

int64_t steadyNanoseconds() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

PoolTimes sumRuns(const std::vector<RunRecord>& records) {
  PoolTimes t;
  int64_t runNanoseconds = 0, taskNanoseconds = 0;
  for (const RunRecord& r : records) {
    t.runs += 1;
    t.tasks += r.tasks;
    runNanoseconds += r.end - r.start;
    taskNanoseconds += r.taskNanoseconds;
  }
  t.runMilliseconds = double(runNanoseconds) * 1e-6;
  t.taskMilliseconds = double(taskNanoseconds) * 1e-6;
  return t;
}

void RunRecorder::runBegins(int tasks) {
  tasksAtStart_ = taskNanoseconds_.load();
  records_.push_back({tasks, steadyNanoseconds(), 0, 0});
}

// Every claim of the run added its time before it counted its tasks done, and the pool saw all of
// them done before it called this: the task time read here is the run's whole.
void RunRecorder::runEnds(int) {
  RunRecord& r = records_.back();
  r.end = steadyNanoseconds();
  r.taskNanoseconds = taskNanoseconds_.load() - tasksAtStart_;
}

int64_t RunRecorder::claimBegins(int) { return steadyNanoseconds(); }

void RunRecorder::claimEnds(int, int64_t fromBegin) {
  taskNanoseconds_.fetch_add(steadyNanoseconds() - fromBegin, std::memory_order_relaxed);
}

void wakeWorkers(ThreadPool& pool) {
  const int threads = pool.threadCount();
  if (threads <= 1) return;
  // A run of one task a thread, each task waiting until every thread holds one: a thread that has
  // taken its task cannot claim another, so each of the pool's threads takes exactly one, and
  // run() returns only after all of them have run.
  std::atomic<int> arrived{0};
  pool.run(threads, [&](int) {
    arrived.fetch_add(1);
    while (arrived.load() < threads) std::this_thread::yield();
  });
}

RunLayout layOutRuns(const std::vector<RunRecord>& records, const std::vector<FrameSpan>& frames, int threads) {
  using timing::median;
  std::vector<std::vector<const RunRecord*>> perFrame(frames.size());
  size_t next = 0;
  for (size_t f = 0; f < frames.size(); ++f) {
    while (next < records.size() && records[next].start < frames[f].start) ++next;
    for (; next < records.size() && records[next].end <= frames[f].end; ++next) perFrame[f].push_back(&records[next]);
  }
  RunLayout layout;
  const size_t runs = perFrame.empty() ? 0 : perFrame.back().size();
  std::vector<size_t> used;
  for (size_t f = 0; f < frames.size(); ++f)
    if (perFrame[f].size() == runs) used.push_back(f);
  layout.framesUsed = used.size();
  const auto ms = [](int64_t ns) { return double(ns) * 1e-6; };
  for (size_t k = 0; k < runs; ++k) {
    std::vector<double> tasks, length, idle, before;
    for (size_t f : used) {
      const RunRecord& r = *perFrame[f][k];
      const int64_t previousEnd = k == 0 ? frames[f].start : perFrame[f][k - 1]->end;
      const double runMs = ms(r.end - r.start);
      tasks.push_back(r.tasks);
      length.push_back(runMs);
      idle.push_back(runMs > 0.0 ? 100.0 * (1.0 - ms(r.taskNanoseconds) / (threads * runMs)) : 0.0);
      before.push_back(ms(r.start - previousEnd));
    }
    layout.rows.push_back({median(tasks), median(length), std::max(0.0, median(idle)), median(before)});
  }
  std::vector<double> after;
  for (size_t f : used) after.push_back(ms(frames[f].end - (runs ? perFrame[f].back()->end : frames[f].start)));
  layout.afterMilliseconds = median(after);
  return layout;
}

}  // namespace shadowref::bench
