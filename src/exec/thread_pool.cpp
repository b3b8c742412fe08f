#include "exec/thread_pool.h"

#include <sched.h>

#include <algorithm>
#include <chrono>
#include <memory>

namespace shadowref {

namespace {
// How long an idle worker spins before it sleeps: longer than the serial work between two
// rasterizations (building a pass's volumes, setting up its triangles), so that the worker is
// there when the bands are handed out; short enough not to hold a core between frames.
constexpr std::chrono::microseconds kSpinTime{3000};

// Tasks a claim takes: a kClaimShare-th of a thread's share of those left (guided
// self-scheduling). A claim is an atomic operation on a cache line every thread writes — between
// cores 50 to a few hundred nanoseconds — so a run of many small tasks (microseconds each)
// claimed one at a time leaves the threads idle for a large part of it; claimed a share at a time,
// the claims are few. Large claims first, single tasks at the end, so that the threads still
// end together; a run of fewer than 2 x kClaimShare tasks a thread (the bands of a pass, already
// cut into shrinking shares) is claimed one task at a time, as before.
constexpr int kClaimShare = 8;

// One step of a wait loop. The two hardware threads of this machine may be siblings of one core:
// a sibling that waits in sched_yield (a system call a step) takes issue slots from the one that
// works. The x86 PAUSE instruction lets the worker have them; every 16th step still yields, so that
// more threads than cores (the determinism tests run 8 on 2) take turns.
inline void relax(int step) {
#if defined(__x86_64__) || defined(__i386__)
  if ((step & 15) != 15) {
    __builtin_ia32_pause();
    return;
  }
#endif
  (void)step;
  std::this_thread::yield();
}
}  // namespace

std::shared_ptr<ThreadPool> makeThreadPool(int threads) {
  if (threads <= 1) return nullptr;
  return std::make_shared<ThreadPool>(threads);
}

int ThreadPool::claimSize(int left, int threads) { return std::max(1, left / (kClaimShare * threads)); }

int defaultThreadCount() {
  // The processors this process may run on, not the machine's: under `taskset -c 0`, a cgroup's
  // cpuset or a batch system's binding, more threads than those would only take turns on them.
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  if (sched_getaffinity(0, sizeof allowed, &allowed) == 0) {
    const int n = CPU_COUNT(&allowed);
    if (n > 0) return n;
  }
  const unsigned n = std::thread::hardware_concurrency();
  return n == 0 ? 1 : int(n);
}

ThreadPool::ThreadPool(int threads) {
  for (int i = 1; i < threads; ++i) workers_.emplace_back([this, i] { workerLoop(i); });
}

ThreadPool::~ThreadPool() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  for (std::thread& t : workers_) t.join();
}

void ThreadPool::drain(uint32_t generation, int thread) {
  uint64_t ticket = ticket_.load(std::memory_order_acquire);
  for (;;) {
    // count_ may already be the next run's (run() stores it after closing this run's tickets):
    // then the claim below fails, because the acquire load saw that store and so the ticket
    // stored before it. A claim that succeeds therefore saw this run's count.
    const int first = int(ticket & 0xFFFFFFFFu), count = count_.load(std::memory_order_acquire);
    if (uint32_t(ticket >> 32) != generation || first >= count) return;
    const int claimed = claimSize(count - first, threadCount());
    if (!ticket_.compare_exchange_weak(ticket, ticket + uint64_t(claimed), std::memory_order_acq_rel)) continue;
    // The claimed tasks belong to this run, which cannot end before they are done: task_ and
    // observer_ are its.
    if (const std::exception_ptr e = runTasks(*task_.load(std::memory_order_relaxed), first, claimed, thread)) {
      std::lock_guard lock(mutex_);
      if (!error_) error_ = e;
    }
    done_.fetch_add(claimed, std::memory_order_release);
    ticket = ticket_.load(std::memory_order_acquire);
  }
}

uint32_t ThreadPool::waitForWork(uint32_t seen) {
  const auto spinUntil = std::chrono::steady_clock::now() + kSpinTime;
  for (int spins = 0;; ++spins) {
    const uint32_t g = generation_.load(std::memory_order_acquire);
    if (g != seen || stop_.load(std::memory_order_acquire)) return g;
    if ((spins & 63) == 63 && std::chrono::steady_clock::now() > spinUntil)
      break;
    relax(spins);
  }
  // Sleep. sleepers_ is raised before generation_ is read again and run() raises generation_
  // before it reads sleepers_ (both sequentially consistent), so one of the two sees the other.
  std::unique_lock lock(mutex_);
  sleepers_.fetch_add(1);
  wake_.wait(lock, [&] { return stop_.load() || generation_.load() != seen; });
  sleepers_.fetch_sub(1);
  return generation_.load();
}

void ThreadPool::workerLoop(int thread) {
  uint32_t seen = 0;
  for (;;) {
    seen = waitForWork(seen);
    if (stop_.load(std::memory_order_acquire)) return;
    drain(seen, thread);
  }
}

std::exception_ptr ThreadPool::runTasks(const ThreadTask& task, int first, int count, int thread) {
  RunObserver* const observer = observer_.load(std::memory_order_relaxed);
  const int64_t mark = observer ? observer->claimBegins(count) : 0;
  std::exception_ptr error;
  for (int i = first; i < first + count; ++i) {
    try {
      task(i, thread);
    } catch (...) {
      if (!error) error = std::current_exception();
    }
  }
  if (observer) observer->claimEnds(count, mark);
  return error;
}

void ThreadPool::run(int count, const std::function<void(int)>& task) {
  runOnThreads(count, [&task](int i, int) { task(i); });
}

void ThreadPool::runOnThreads(int count, const ThreadTask& task) {
  RunObserver* const observer = observer_.load(std::memory_order_relaxed);
  if (observer) observer->runBegins(count);
  if (workers_.empty() || count <= 1) {
    // The caller's tasks, one after another: one claim.
    const std::exception_ptr error = count > 0 ? runTasks(task, 0, count, 0) : nullptr;
    if (observer) observer->runEnds(count);
    if (error) std::rethrow_exception(error);
    return;
  }
  // The new run's ticket goes first: a worker late from the last run, holding that run's last
  // ticket, could otherwise pair it with this run's count_ and claim (and run) a task of this run
  // that is then claimed again. Workers enter this run's drain only through generation_, whose
  // store publishes task_, count_ and done_.
  const uint32_t generation = generation_.load(std::memory_order_relaxed) + 1;
  ticket_.store(uint64_t(generation) << 32, std::memory_order_relaxed);
  task_.store(&task, std::memory_order_relaxed);
  done_.store(0, std::memory_order_relaxed);
  count_.store(count, std::memory_order_release);  // after the ticket: see drain
  generation_.store(generation);                    // sequentially consistent: see waitForWork
  if (sleepers_.load() > 0) {
    std::lock_guard lock(mutex_);
    wake_.notify_all();
  }
  drain(generation, 0);
  for (int step = 0; done_.load(std::memory_order_acquire) < count; ++step) relax(step);
  // Every claim ended (and told the observer) before it counted its tasks done.
  if (observer) observer->runEnds(count);
  std::exception_ptr error;
  {
    std::lock_guard lock(mutex_);
    std::swap(error, error_);
  }
  if (error) std::rethrow_exception(error);
}

}  // namespace shadowref
