// The median `shadowref bench` and the benchmarks report timings with, against values worked out
// by hand.
#include <catch2/catch.hpp>

#include "cli/timing_stats.h"

using namespace shadowref::timing;

TEST_CASE("median: the middle value, the mean of the middle two, unsorted input", "[timing]") {
  CHECK(median({7.0}) == 7.0);
  CHECK(median({3.0, 1.0, 2.0}) == 2.0);
  CHECK(median({4.0, 1.0, 3.0, 2.0}) == 2.5);
  // One slow run moves the mean, not the median: what the timings are reported with.
  CHECK(median({10.0, 10.5, 9.5, 10.0, 90.0}) == 10.0);
  CHECK(median({}) == 0.0);
}
