// series_stats.h: the lines and cycle shares of bench/vs-mesa's series, against values worked
// out by hand.
#include "series_stats.h"

#include <catch2/catch.hpp>

using namespace shadowref::timing;

TEST_CASE("fitLine: points on a line give its slope and intercept with R2 = 1", "[bench]") {
  const LineFit f = fitLine({8, 16, 32, 64, 100}, {5, 9, 17, 33, 51});  // y = 0.5 x + 1
  CHECK(f.slope == Approx(0.5).epsilon(1e-12));
  CHECK(f.intercept == Approx(1.0).epsilon(1e-12));
  CHECK(f.r2 == Approx(1.0).epsilon(1e-12));
}

TEST_CASE("fitLine: R2 by hand for scattered points, and the degenerate inputs", "[bench]") {
  // x = 0 1 2, y = 0 2 1: mean x 1, mean y 1; sxx = 2, sxy = 1, syy = 2; slope 0.5, intercept 0.5,
  // R2 = sxy^2 / (sxx syy) = 1/4.
  const LineFit f = fitLine({0, 1, 2}, {0, 2, 1});
  CHECK(f.slope == Approx(0.5));
  CHECK(f.intercept == Approx(0.5));
  CHECK(f.r2 == Approx(0.25));
  CHECK(fitLine({1}, {1}).r2 == 0.0);          // one point: no line
  CHECK(fitLine({2, 2}, {1, 3}).r2 == 0.0);    // one x: no slope
  CHECK(fitLine({1, 2, 3}, {4, 4, 4}).r2 == 1.0);  // flat: every point on the line y = 4
}

TEST_CASE("cycleShares: a speed that changes from cycle to cycle leaves the shares as they are", "[bench]") {
  // Three scenes of work 1, 2 and 5 (ms at full speed) in five cycles, the host at full speed, 1.5x
  // slower, full, 1.5x slower, 3x slower: every cycle's shares are 1/8, 2/8, 5/8.
  const std::vector<double> slowdown{1.0, 1.5, 1.0, 1.5, 3.0}, work{1.0, 2.0, 5.0};
  std::vector<std::vector<double>> times(3);
  for (size_t i = 0; i < 3; ++i)
    for (double s : slowdown) times[i].push_back(work[i] * s);
  const CycleShares c = cycleShares(times);
  REQUIRE(c.cycles.size() == 5);
  CHECK(c.cycles[0] == 8.0);
  CHECK(c.cycles[1] == 12.0);
  CHECK(c.cycles[4] == 24.0);
  for (size_t i = 0; i < 3; ++i)
    for (double share : c.shares[i]) CHECK(share == Approx(work[i] / 8.0).epsilon(1e-15));
  // The fastest cycle is the one at full speed (8 ms): each scene's own work.
  CHECK(fastestCycleTime(c.shares[0], c.cycles) == Approx(1.0));
  CHECK(fastestCycleTime(c.shares[1], c.cycles) == Approx(2.0));
  CHECK(fastestCycleTime(c.shares[2], c.cycles) == Approx(5.0));
}

TEST_CASE("cycleShares: one slow frame moves one cycle, not the median share", "[bench]") {
  // Work 2 and 2; in cycle 2 the first scene alone is slowed 4x (a hiccup): its share there is 8/10.
  const CycleShares c = cycleShares({{2, 2, 8, 2, 2}, {2, 2, 2, 2, 2}});
  CHECK(c.shares[0][2] == Approx(0.8));
  CHECK(fastestCycleTime(c.shares[0], c.cycles) == Approx(2.0));  // median share 1/2 x fastest cycle 4
  CHECK(fastestCycleTime(c.shares[1], c.cycles) == Approx(2.0));
}

TEST_CASE("cycleShares: no scenes, and scenes with different numbers of cycles", "[bench]") {
  CHECK(cycleShares({}).cycles.empty());
  CHECK(fastestCycleTime({}, {}) == 0.0);
  CHECK_THROWS_AS(cycleShares({{1, 2}, {1}}), std::invalid_argument);
}
