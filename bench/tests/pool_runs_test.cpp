// pool_runs.h: a pool's runs recorded through its observer, laid out frame by frame, and its
// workers woken — against sleeps of known length and records worked out by hand.
#include "pool_runs.h"

#include <catch2/catch.hpp>

#include <chrono>
#include <mutex>
#include <set>
#include <thread>

namespace shadowref::bench {
namespace {

TEST_CASE("recorded runs: tasks, and task time within the threads' run time", "[bench]") {
  using namespace std::chrono_literals;
  for (int threads : {1, 2, 3}) {
    INFO(threads << " threads");
    ThreadPool pool(threads);
    RunRecorder recorder;
    pool.run(4, [](int) { std::this_thread::sleep_for(1ms); });  // not recorded: no observer yet
    {
      const ObservedPool observed(pool, recorder);
      pool.run(6, [](int) { std::this_thread::sleep_for(10ms); });
      pool.run(1, [](int) { std::this_thread::sleep_for(5ms); });  // on the calling thread alone
    }
    pool.run(2, [](int) {});  // not recorded: the observer is gone
    const PoolTimes t = sumRuns(recorder.records());
    CHECK(t.runs == 2);
    CHECK(t.tasks == 7);
    // Each task slept at least its time; the tasks ran inside their runs, one at a time per thread.
    CHECK(t.taskMilliseconds >= 65.0);
    CHECK(t.taskMilliseconds <= threads * t.runMilliseconds);
    // Six tasks of 10 ms on `threads` threads take at least ceil(6 / threads) × 10 ms, plus 5.
    CHECK(t.runMilliseconds >= 10.0 * ((6 + threads - 1) / threads) + 5.0);
    // The same two runs one by one, in order: each within its time, the first's tasks at least
    // their 60 ms of sleep and at most every thread's time in it.
    const std::vector<RunRecord>& records = recorder.records();
    REQUIRE(records.size() == 2);
    CHECK(records[0].tasks == 6);
    CHECK(records[1].tasks == 1);
    CHECK(records[0].start <= records[0].end);
    CHECK(records[0].end <= records[1].start);
    CHECK(records[0].taskNanoseconds >= 60'000'000);
    CHECK(records[0].taskNanoseconds <= threads * (records[0].end - records[0].start));
    CHECK(records[1].taskNanoseconds >= 5'000'000);
  }
}

TEST_CASE("runs laid out by frame: medians per run, the gaps before, the time after", "[bench]") {
  // Two frames of two runs each on two threads, in nanoseconds. Frame 1: 0 to 10 ms, runs at 1-3 ms
  // (4 tasks, 3 ms of task time: 25 % idle) and 5-9 ms (2 tasks, 8 ms: 0 % idle). Frame 2: 20 to
  // 34 ms, runs at 23-25 ms (4 tasks, 4 ms: 0 %) and 26-32 ms (2 tasks, 6 ms: 50 %).
  // A third frame with one run only is left out of the medians.
  const int64_t ms = 1'000'000;
  const std::vector<RunRecord> records{{4, 1 * ms, 3 * ms, 3 * ms},   {2, 5 * ms, 9 * ms, 8 * ms},
                                       {4, 23 * ms, 25 * ms, 4 * ms}, {2, 26 * ms, 32 * ms, 6 * ms},
                                       {9, 41 * ms, 42 * ms, 2 * ms}};
  const std::vector<FrameSpan> frames{{0, 10 * ms}, {20 * ms, 34 * ms}, {40 * ms, 43 * ms}};
  // The last frame decides the number of runs: with it, one run a frame and only it kept.
  const RunLayout withLast = layOutRuns(records, frames, 2);
  CHECK(withLast.framesUsed == 1);
  REQUIRE(withLast.rows.size() == 1);
  CHECK(withLast.rows[0].tasks == 9.0);
  CHECK(withLast.rows[0].milliseconds == Approx(1.0));
  CHECK(withLast.rows[0].idlePercent == Approx(0.0));  // 2 ms of tasks in 1 ms of 2 threads: none idle
  CHECK(withLast.rows[0].beforeMilliseconds == Approx(1.0));
  CHECK(withLast.afterMilliseconds == Approx(1.0));
  const RunLayout layout = layOutRuns({records.begin(), records.begin() + 4}, {frames.begin(), frames.begin() + 2}, 2);
  CHECK(layout.framesUsed == 2);
  REQUIRE(layout.rows.size() == 2);
  CHECK(layout.rows[0].tasks == 4.0);
  CHECK(layout.rows[0].milliseconds == Approx(2.0));        // 2 and 2
  CHECK(layout.rows[0].idlePercent == Approx(12.5));        // 25 and 0
  CHECK(layout.rows[0].beforeMilliseconds == Approx(2.0));  // 1 and 3
  CHECK(layout.rows[1].tasks == 2.0);
  CHECK(layout.rows[1].milliseconds == Approx(5.0));        // 4 and 6
  CHECK(layout.rows[1].idlePercent == Approx(25.0));        // 0 and 50
  CHECK(layout.rows[1].beforeMilliseconds == Approx(1.5));  // 2 and 1
  CHECK(layout.afterMilliseconds == Approx(1.5));           // 1 and 2
}

TEST_CASE("a recorded frame's runs, the gaps before them and the time after add up to the frame", "[bench]") {
  ThreadPool pool(2);
  RunRecorder recorder;
  FrameSpan frame;
  {
    const ObservedPool observed(pool, recorder);
    frame.start = steadyNanoseconds();
    for (int run = 0; run < 5; ++run) pool.run(8 + run, [](int) { std::this_thread::yield(); });
    frame.end = steadyNanoseconds();
  }
  const RunLayout layout = layOutRuns(recorder.records(), {frame}, 2);
  REQUIRE(layout.rows.size() == 5);
  double sum = layout.afterMilliseconds;
  for (size_t k = 0; k < layout.rows.size(); ++k) {
    CHECK(layout.rows[k].tasks == double(8 + k));
    CHECK(layout.rows[k].idlePercent >= 0.0);
    CHECK(layout.rows[k].idlePercent <= 100.0);
    sum += layout.rows[k].milliseconds + layout.rows[k].beforeMilliseconds;
  }
  CHECK(sum == Approx(double(frame.end - frame.start) * 1e-6).epsilon(1e-9));
}

// Counts the threads that ran a claim.
class ClaimThreads final : public RunObserver {
 public:
  void runBegins(int) override {}
  void runEnds(int) override {}
  int64_t claimBegins(int) override {
    const std::lock_guard lock(mutex_);
    threads_.insert(std::this_thread::get_id());
    return 0;
  }
  void claimEnds(int, int64_t) override {}
  size_t threads() const { return threads_.size(); }

 private:
  std::mutex mutex_;
  std::set<std::thread::id> threads_;
};

TEST_CASE("waking the workers runs a task on every thread of the pool", "[bench]") {
  for (int threads : {2, 3, 8}) {
    ThreadPool pool(threads);
    for (int round = 0; round < 3; ++round) {
      if (round > 0) std::this_thread::sleep_for(std::chrono::milliseconds(20));  // workers fall asleep after their spin
      ClaimThreads seen;
      {
        const ObservedPool observed(pool, seen);
        wakeWorkers(pool);
      }
      INFO(threads << " threads, round " << round);
      CHECK(seen.threads() == size_t(threads));
    }
  }
}

}  // namespace
}  // namespace shadowref::bench
