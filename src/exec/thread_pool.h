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
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace shadowref {

// What a pool's runs look like from outside, for measuring them (bench/pool_runs.h times the runs
// and the threads' time inside tasks with it). An observer only watches: which tasks run, on
// which thread and in what order of claims does not depend on it, and nothing it is told can
// reach a pixel, so the bytes are the same with or without one.
class RunObserver {
 public:
  virtual ~RunObserver() = default;
  // On the thread that called run(): before the first task of a run of `tasks` tasks starts, and
  // after the last one is done (also when a task threw).
  virtual void runBegins(int tasks) = 0;
  virtual void runEnds(int tasks) = 0;
  // On the thread that runs them, around each claim of `tasks` consecutive tasks of a run: on
  // several threads at once. claimEnds is handed what claimBegins returned on that thread.
  virtual int64_t claimBegins(int tasks) = 0;
  virtual void claimEnds(int tasks, int64_t fromBegin) = 0;
};

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
  // The same, telling each task the thread that runs it, in [0, threadCount()) (0: the calling
  // thread). A thread runs one task at a time, so scratch kept per thread number (the renderer's
  // span scratch) has one user at a time; which thread runs which task changes no byte the tasks
  // write when the scratch carries nothing from task to task.
  void runOnThreads(int count, const std::function<void(int task, int thread)>& task);

  // Watches the runs (nullptr: none, the default). Set between runs, from the thread that calls
  // run(); the observer must outlive its time set. It changes nothing the tasks do: the bytes are
  // the same with or without one.
  void setObserver(RunObserver* observer) { observer_.store(observer, std::memory_order_relaxed); }
  // Workers asleep on the condition variable now (at most threadCount() - 1).
  int sleepingWorkers() const { return sleepers_.load(); }

  // How many of a run's `left` unclaimed tasks one claim of `threads` threads takes: one task
  // when a thread's share of them is small, a part of that share when it is large (thread_pool.cpp).
  static int claimSize(int left, int threads);

 private:
  using ThreadTask = std::function<void(int task, int thread)>;
  void workerLoop(int thread);
  // Claims and runs tasks of run number `generation` on thread `thread` until none is left.
  void drain(uint32_t generation, int thread);
  uint32_t waitForWork(uint32_t seen);
  // Runs tasks [first, first + count) on this thread, each whatever the others threw, as one claim
  // the observer sees; returns the first exception thrown (none: null).
  std::exception_ptr runTasks(const ThreadTask& task, int first, int count, int thread);

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::atomic<int> sleepers_{0};
  std::atomic<bool> stop_{false};
  // The current run: its number, and the next task to claim in the low 32 bits of `ticket_`
  // (number in the high bits), so a worker late from an earlier run can never claim a task of
  // this one.
  std::atomic<uint32_t> generation_{0};
  std::atomic<uint64_t> ticket_{0};
  std::atomic<int> done_{0};
  std::atomic<const ThreadTask*> task_{nullptr};
  std::atomic<int> count_{0};
  std::exception_ptr error_;  // the first exception of the current run, under mutex_
  // Read by workers only inside a run (after a claim), which cannot end before they are done, and
  // set only between runs: generation_'s store publishes it to them.
  std::atomic<RunObserver*> observer_{nullptr};
};

// A pool of `threads` threads to own (nullptr for 1 or fewer: everything on the calling thread).
// The executor's pipelines share one (FastPipelineMaker, FastPipeline::forFramebuffer): a frame's
// renderer and its shadow maps' never run at once, and a program rendering frame after frame
// starts no threads per frame (a fresh worker also starts cold: its first bands begin late).
std::shared_ptr<ThreadPool> makeThreadPool(int threads);

// The number of threads "0 = all cores" means: the processors in this process's affinity mask
// (sched_getaffinity), e.g. 1 under `taskset -c 0`; the machine's count if the mask is unknown.
int defaultThreadCount();

}  // namespace shadowref
