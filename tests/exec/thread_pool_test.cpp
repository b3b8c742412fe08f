// The thread pool under the rasterizer: every task runs exactly once per run, runs follow each
// other without a late worker taking a task of the next one, and a task's exception reaches the
// caller of run() after the other tasks have finished.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include <catch2/catch.hpp>

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

TEST_CASE("a thread keeps one pool per thread count for its renderers, another thread has its own",
          "[raster][threads]") {
  CHECK(threadPoolForThisThread(1) == nullptr);
  ThreadPool* two = threadPoolForThisThread(2);
  REQUIRE(two != nullptr);
  CHECK(two->threadCount() == 2);
  CHECK(threadPoolForThisThread(2) == two);  // kept: no threads started per frame
  CHECK(threadPoolForThisThread(3)->threadCount() == 3);
  ThreadPool* other = nullptr;
  std::thread([&] { other = threadPoolForThisThread(2); }).join();
  CHECK(other != two);  // a pool serves one thread's runs at a time
  Framebuffer fb(8, 8);
  Renderer a(fb, 2), b(fb, 2);
  CHECK(a.threads() == 2);
  CHECK(b.threads() == 2);
}

TEST_CASE("the pool's timers: runs, tasks, and task time within the threads' run time", "[raster][threads]") {
  using namespace std::chrono_literals;
  for (int threads : {1, 2, 3}) {
    INFO(threads << " threads");
    ThreadPool pool(threads);
    pool.run(4, [](int) { std::this_thread::sleep_for(1ms); });  // not timed: timing is off
    CHECK(pool.times().runs == 0);
    pool.timeRuns(true);
    pool.run(6, [](int) { std::this_thread::sleep_for(10ms); });
    pool.run(1, [](int) { std::this_thread::sleep_for(5ms); });  // on the calling thread alone
    const ThreadPool::Times t = pool.times();
    CHECK(t.runs == 2);
    CHECK(t.tasks == 7);
    // Each task slept at least its time; the tasks ran inside their runs, one at a time per thread.
    CHECK(t.taskMilliseconds >= 65.0);
    CHECK(t.taskMilliseconds <= threads * t.runMilliseconds);
    // Six tasks of 10 ms on `threads` threads take at least ceil(6 / threads) × 10 ms, plus 5.
    CHECK(t.runMilliseconds >= 10.0 * ((6 + threads - 1) / threads) + 5.0);
    // The same two runs one by one, in order: each within its time, the first's tasks at least
    // their 60 ms of sleep and at most every thread's time in it.
    const std::vector<ThreadPool::RunRecord>& records = pool.runRecords();
    REQUIRE(records.size() == 2);
    CHECK(records[0].tasks == 6);
    CHECK(records[1].tasks == 1);
    CHECK(records[0].start <= records[0].end);
    CHECK(records[0].end <= records[1].start);
    CHECK(records[0].taskNanoseconds >= 60'000'000);
    CHECK(records[0].taskNanoseconds <= threads * (records[0].end - records[0].start));
    CHECK(records[1].taskNanoseconds >= 5'000'000);
    CHECK(double(records[0].end - records[0].start + records[1].end - records[1].start) * 1e-6 ==
          Approx(t.runMilliseconds).epsilon(1e-9));
    pool.timeRuns(false);
    pool.run(2, [](int) {});
    CHECK(pool.times().runs == 0);  // turned off: started from zero and not counting
    CHECK(pool.runRecords().empty());
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

TEST_CASE("idle workers sleep after their spin, and not while the pool is kept awake", "[raster][threads]") {
  using namespace std::chrono_literals;
  ThreadPool pool(3);
  pool.run(4, [](int) {});
  CHECK(sleepersReach(pool, 2));  // the spin is a few milliseconds
  pool.keepAwake(true);
  pool.run(4, [](int) {});  // wakes them
  REQUIRE(sleepersReach(pool, 0));
  std::this_thread::sleep_for(50ms);  // many spins' time
  CHECK(pool.sleepingWorkers() == 0);
  std::vector<std::atomic<int>> hits(64);
  pool.run(64, [&](int i) { hits[size_t(i)].fetch_add(1); });  // awake workers still take every task once
  for (const std::atomic<int>& h : hits) CHECK(h.load() == 1);
  pool.keepAwake(false);
  CHECK(sleepersReach(pool, 2));
}
