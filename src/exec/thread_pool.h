// A small pool of persistent worker threads for the rasterizer. Work is handed out as numbered
// tasks (bands of rows, chunks of triangles); which thread runs which task varies, but tasks touch
// disjoint pixels and each runs its triangles in submission order, so the buffers come out
// byte-identical for any thread count (llvmpipe's idea: each tile owned by one
// thread, replayed in order) — or, where the order cannot matter (stencil counts, which only add
// modulo 256: counting_flush.cpp), each writes a buffer of its own that is summed after.
//
// A frame is hundreds of draws, each a few hundred microseconds or less, so waking a sleeping
// thread per draw (tens of microseconds) would eat the gain. Idle workers therefore spin, yielding
// the core, for a while before they sleep on the condition variable: a draw that follows soon
// starts on every thread within a microsecond or so.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace shadowref {

class ThreadPool {
 public:
  // threads <= 1: everything runs on the calling thread.
  explicit ThreadPool(int threads);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  int threadCount() const { return int(workers_.size()) + 1; }

  // Runs task(i) for i in [0, count), on the workers and the calling thread; returns when all
  // are done, rethrowing the first exception a task threw (the other tasks still run). Not
  // reentrant: one run at a time, from one thread.
  void run(int count, const std::function<void(int)>& task);

  // What the runs cost while timing is on: the caller's time inside run() and the threads' time
  // inside tasks. Tasks run within their run and each thread runs one at a time, so task time is
  // at most threadCount() × run time; the rest is time a thread of a run waited — for work to
  // start, or for the last task of another thread (`shadowref bench` prints the share). Off by
  // default: two clock reads a task.
  struct Times {
    int64_t runs = 0, tasks = 0;
    double runMilliseconds = 0.0, taskMilliseconds = 0.0;
  };
  void timeRuns(bool on);  // and starts the times from zero
  Times times() const;
  // Each run while timing is on, in order: its tasks, when it began and ended (steady_clock
  // nanoseconds since that clock's epoch) and the threads' time inside its tasks. What
  // `shadowref bench --runs` lays out run by run. Started again by timeRuns.
  struct RunRecord {
    int tasks = 0;
    int64_t start = 0, end = 0, taskNanoseconds = 0;
  };
  const std::vector<RunRecord>& runRecords() const { return records_; }

  // While on, idle workers spin without end instead of sleeping after a while: a run after a long
  // pause (a frame drawn on one thread in between, `shadowref bench --alternate`) finds them awake,
  // as a run does in a stream of frames. Off by default: a pool between frames holds no core.
  void keepAwake(bool on);
  // Workers asleep on the condition variable now (at most threadCount() - 1).
  int sleepingWorkers() const { return sleepers_.load(); }

  // How many of a run's `left` unclaimed tasks one claim of `threads` threads takes: one task
  // when a thread's share of them is small, a part of that share when it is large (thread_pool.cpp).
  static int claimSize(int left, int threads);

 private:
  void workerLoop();
  // Claims and runs tasks of run number `generation` until none is left.
  void drain(uint32_t generation);
  uint32_t waitForWork(uint32_t seen);
  // Adds a run of `tasks` that began at `start` (nanoseconds), when the task time stood at
  // `tasksBefore`, to the times.
  void recordRun(int tasks, int64_t start, int64_t tasksBefore);

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::atomic<int> sleepers_{0};
  std::atomic<bool> stop_{false};
  std::atomic<bool> awake_{false};  // keepAwake
  // The current run: its number, and the next task to claim in the low 32 bits of `ticket_`
  // (number in the high bits), so a worker late from an earlier run can never claim a task of
  // this one.
  std::atomic<uint32_t> generation_{0};
  std::atomic<uint64_t> ticket_{0};
  std::atomic<int> done_{0};
  std::atomic<const std::function<void(int)>*> task_{nullptr};
  std::atomic<int> count_{0};
  std::exception_ptr error_;  // the first exception of the current run, under mutex_
  std::atomic<bool> timing_{false};
  std::atomic<int64_t> taskNanoseconds_{0};  // every thread's, added per claim
  std::vector<RunRecord> records_;  // written by the calling thread only, at each run's end: times() sums them
};

// The pool of `threads` threads that the calling thread keeps for its renderers (nullptr for 1):
// made at the first call and kept until the calling thread ends, so that a program rendering frame
// after frame — each frame a Renderer, each shadow map another — starts no threads per frame (a
// fresh worker also starts cold: its first bands begin late). One per calling thread, because a
// pool serves one run at a time from one thread; renderers of one thread never run at once.
ThreadPool* threadPoolForThisThread(int threads);

// The number of threads "0 = all cores" means.
int defaultThreadCount();

}  // namespace shadowref
