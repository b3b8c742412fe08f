// The thread pool under the rasterizer: every task runs exactly once per run, runs follow each
// other without a late worker taking a task of the next one, and a task's exception reaches the
// caller of run() after the other tasks have finished.
#include <sched.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include <catch2/catch.hpp>

#include "exec/fast_pipeline.h"
#include "exec/renderer.h"
#include "exec/thread_pool.h"
#include "support/raster_harness.h"

using namespace shadowref;
using namespace shadowref::testing;

TEST_CASE("every task of every run runs exactly once, for 1, 2 and 8 threads", "[raster][threads]") {
  for (int threads : {1, 2, 8}) {
    ThreadPool pool(threads);
    for (int run = 0; run < 300; ++run) {
      // Small runs are claimed a task at a time, large ones (every tenth here) in shrinking claims.
      const int count = run % 10 == 9 ? 100 + 37 * run : 1 + run % 37;
      std::vector<std::atomic<int>> hits(static_cast<size_t>(count));
      pool.run(count, [&](int i) { hits[size_t(i)].fetch_add(1); });
      int wrong = 0;
      for (const std::atomic<int>& h : hits) wrong += h.load() != 1;
      INFO(threads << " threads, run " << run);
      REQUIRE(wrong == 0);
    }
  }
}

TEST_CASE("claims shrink with the tasks left: large first, single tasks at the end", "[raster][threads]") {
  // Worked out by hand: a claim takes a sixteenth of what is left at two threads (an eighth of a
  // thread's share), a 24th at three, and never less than one task.
  CHECK(ThreadPool::claimSize(129, 2) == 8);
  CHECK(ThreadPool::claimSize(32, 2) == 2);
  CHECK(ThreadPool::claimSize(31, 2) == 1);  // the six bands of a pass: one at a time
  CHECK(ThreadPool::claimSize(1, 2) == 1);
  CHECK(ThreadPool::claimSize(129, 3) == 5);
  CHECK(ThreadPool::claimSize(5000, 8) == 78);
  // Claimed one after another, the claims cover every task once and end in single tasks.
  for (int threads : {2, 3, 8}) {
    for (int count : {1, 31, 129, 1000, 100000}) {
      std::vector<int> claims;
      for (int next = 0; next < count;) {
        claims.push_back(ThreadPool::claimSize(count - next, threads));
        next += claims.back();
      }
      int sum = 0;
      for (int c : claims) sum += c;
      INFO(threads << " threads, " << count << " tasks");
      CHECK(sum == count);
      CHECK(claims.back() == 1);
      CHECK(std::is_sorted(claims.rbegin(), claims.rend()));
      // Each claim at most an eighth of a thread's even share of what was left.
      CHECK(claims.front() <= std::max(1, count / (8 * threads)));
    }
  }
}

TEST_CASE("a task's exception is rethrown by run() once the other tasks are done", "[raster][threads]") {
  for (int threads : {1, 2, 8}) {
    ThreadPool pool(threads);
    std::atomic<int> ran{0};
    CHECK_THROWS_AS(pool.run(16,
                             [&](int i) {
                               ran.fetch_add(1);
                               if (i == 5) throw std::runtime_error("task 5");
                             }),
                    std::runtime_error);
    CHECK(ran.load() == 16);
    // In a run claimed several tasks at a time, the tasks claimed with the throwing one run too.
    ran = 0;
    CHECK_THROWS_AS(pool.run(1000,
                             [&](int i) {
                               ran.fetch_add(1);
                               if (i == 3 || i == 998) throw std::runtime_error("task");
                             }),
                    std::runtime_error);
    CHECK(ran.load() == 1000);
    // The pool is usable afterwards, and the error does not come back.
    std::atomic<int> again{0};
    pool.run(8, [&](int) { again.fetch_add(1); });
    CHECK(again.load() == 8);
  }
}

TEST_CASE("a vertex index out of range is an error with threads too, and nothing is drawn", "[raster][threads]") {
  Framebuffer fb(64, 64);
  Renderer renderer(fb, 2);
  const RenderState s = coverageCountingState(fb);
  std::vector<ClipVertex> vertices = windowRect(s.viewport, 2, 2, 60, 60);
  std::vector<uint32_t> indices;
  for (uint32_t i = 0; i < 600; ++i) indices.insert(indices.end(), {0, 1, 2});  // chunks on both threads
  indices.push_back(0);
  indices.push_back(1);
  indices.push_back(99);  // out of range, in the last chunk
  DrawCall call;
  call.state = &s;
  call.vertices = vertices;
  call.indices = indices;
  CHECK_THROWS_AS(renderer.draw(call), std::out_of_range);
  for (uint8_t v : fb.stencil()) REQUIRE(v == 0);
}

TEST_CASE("a maker's pipelines share its pool, and a renderer made with a count has a pool of its own",
          "[raster][threads]") {
  CHECK(makeThreadPool(1) == nullptr);
  const FastPipelineMaker one(1);
  CHECK(one.pool() == nullptr);
  CHECK(one.threads() == 1);
  const FastPipelineMaker maker(2);
  ThreadPool* const pool = maker.pool();
  REQUIRE(pool != nullptr);
  CHECK(pool->threadCount() == 2);
  Framebuffer fb(8, 8), map(4, 4);
  const std::unique_ptr<Pipeline> frame = maker.make(fb);
  auto& fast = dynamic_cast<FastPipeline&>(*frame);
  CHECK(fast.renderer().pool().get() == pool);  // kept: no threads started per frame
  const std::unique_ptr<Pipeline> shadowMap = frame->forFramebuffer(map);
  CHECK(dynamic_cast<FastPipeline&>(*shadowMap).renderer().pool().get() == pool);
  CHECK(shadowMap->threads() == 2);
  Renderer a(fb, 2), b(fb, 2);
  CHECK(a.threads() == 2);
  CHECK(b.threads() == 2);
  CHECK(a.pool() != b.pool());
  CHECK(a.pool() != nullptr);
}

TEST_CASE("runOnThreads names each task's thread, and a thread runs one task at a time", "[raster][threads]") {
  for (const int threads : {1, 2, 3}) {
    ThreadPool pool(threads);
    constexpr int kTasks = 200;
    std::vector<int> threadOf(kTasks, -1);
    // One flag per thread: a task that finds its thread's flag raised would share that thread
    // with a task still running.
    std::vector<std::atomic<int>> busy(static_cast<size_t>(threads));
    std::atomic<int> overlaps{0};
    pool.runOnThreads(kTasks, [&](int task, int thread) {
      threadOf[size_t(task)] = thread;
      if (thread < 0 || thread >= threads) return;
      if (busy[size_t(thread)].exchange(1) != 0) ++overlaps;
      std::this_thread::yield();  // long enough for another thread to claim a task meanwhile
      busy[size_t(thread)].store(0);
    });
    CHECK(overlaps == 0);
    for (const int t : threadOf) {
      REQUIRE(t >= 0);
      REQUIRE(t < threads);
    }
  }
}

namespace {
// What an observer is told, checked as it is told: run calls on the calling thread, paired and in
// order; every claim inside a run, on any thread, its tasks adding up to the run's.
class CheckingObserver final : public RunObserver {
 public:
  void runBegins(int tasks) override {
    callingThreadOnly();
    if (inRun_) ++errors_;
    inRun_ = true;
    claimed_ = 0;
    runTasks_ = tasks;
    ++runs_;
  }
  void runEnds(int tasks) override {
    callingThreadOnly();
    if (!inRun_ || tasks != runTasks_ || claimed_.load() != tasks || open_.load() != 0) ++errors_;
    inRun_ = false;
  }
  int64_t claimBegins(int tasks) override {
    if (!inRun_ || tasks < 1) ++errors_;
    open_.fetch_add(1);
    return tasks * 1000 + 7;  // handed back to claimEnds on this thread
  }
  void claimEnds(int tasks, int64_t fromBegin) override {
    if (fromBegin != tasks * 1000 + 7) ++errors_;
    claimed_.fetch_add(tasks);
    open_.fetch_sub(1);
  }
  int errors() const { return errors_.load(); }
  int runs() const { return runs_; }

 private:
  void callingThreadOnly() {
    if (caller_ == std::thread::id()) caller_ = std::this_thread::get_id();
    if (caller_ != std::this_thread::get_id()) ++errors_;
  }
  std::thread::id caller_;
  std::atomic<bool> inRun_{false};
  std::atomic<int> claimed_{0}, open_{0}, errors_{0};
  int runTasks_ = 0, runs_ = 0;
};
}  // namespace

TEST_CASE("an observer sees each run begin and end around claims that cover its tasks, and changes no task",
          "[raster][threads]") {
  for (int threads : {1, 2, 3, 8}) {
    INFO(threads << " threads");
    ThreadPool pool(threads);
    CheckingObserver observer;
    pool.setObserver(&observer);
    int expectedRuns = 0;
    for (int run = 0; run < 60; ++run) {
      const int count = run % 10 == 9 ? 500 + run : run % 7;  // empty, single, small and claimed-in-shares runs
      std::vector<std::atomic<int>> hits(static_cast<size_t>(count));
      pool.run(count, [&](int i) { hits[size_t(i)].fetch_add(1); });
      ++expectedRuns;
      int wrong = 0;
      for (const std::atomic<int>& h : hits) wrong += h.load() != 1;
      REQUIRE(wrong == 0);
    }
    // A run whose task throws still ends for the observer before run() rethrows.
    CHECK_THROWS_AS(pool.run(16, [](int i) { if (i == 3) throw std::runtime_error("task 3"); }), std::runtime_error);
    ++expectedRuns;
    pool.setObserver(nullptr);
    pool.run(4, [](int) {});  // unobserved
    CHECK(observer.runs() == expectedRuns);
    CHECK(observer.errors() == 0);
  }
}

namespace {
// Waits up to two seconds for `count` workers asleep; true when they were.
bool sleepersReach(const ThreadPool& pool, int count) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(2);
  while (pool.sleepingWorkers() != count) {
    if (std::chrono::steady_clock::now() > until) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return true;
}
}  // namespace

TEST_CASE("idle workers sleep after their spin, and a run wakes them", "[raster][threads]") {
  ThreadPool pool(3);
  pool.run(4, [](int) {});
  CHECK(sleepersReach(pool, 2));  // the spin is a few milliseconds
  std::vector<std::atomic<int>> hits(64);
  pool.run(64, [&](int i) { hits[size_t(i)].fetch_add(1); });  // sleeping workers are woken: every task once
  for (const std::atomic<int>& h : hits) CHECK(h.load() == 1);
  CHECK(sleepersReach(pool, 2));
}

TEST_CASE("the default thread count is the number of CPUs in the affinity mask", "[raster][threads]") {
  // On a thread of its own, so that narrowing its mask leaves the test runner's threads alone.
  // Catch's assertions are made on the test's thread, after the probe has ended.
  int full = 0, narrowed = 0, expectedFull = 0;
  bool maskRead = false, maskSet = false;
  std::thread probe([&] {
    cpu_set_t mask;
    CPU_ZERO(&mask);
    maskRead = sched_getaffinity(0, sizeof mask, &mask) == 0;
    if (!maskRead) return;
    expectedFull = CPU_COUNT(&mask);
    full = defaultThreadCount();
    int first = 0;
    while (!CPU_ISSET(first, &mask)) ++first;
    cpu_set_t one;
    CPU_ZERO(&one);
    CPU_SET(first, &one);
    maskSet = sched_setaffinity(0, sizeof one, &one) == 0;
    narrowed = defaultThreadCount();
  });
  probe.join();
  REQUIRE(maskRead);
  REQUIRE(maskSet);
  CHECK(full == expectedFull);
  CHECK(narrowed == 1);
}
