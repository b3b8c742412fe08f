// tradeoffs/round_timing.h: the trade-off bench's rounds — the order of each round and a
// configuration's probes combined — against figures worked out by hand.
#include "tradeoffs/round_timing.h"

#include <catch2/catch.hpp>

namespace shadowref::bench {
namespace {

ProbeResult probe(double median, double min, double max, long rss, double wall) {
  ProbeResult p;
  p.ok = true;
  p.medianMs = median;
  p.minMs = min;
  p.maxMs = max;
  p.peakRssKiB = rss;
  p.wallMedianMs = wall;
  return p;
}

TEST_CASE("trade-off rounds start a step further down the list each time", "[bench]") {
  // Six configurations in three rounds: the rounds start at 0, 2 and 4 and wrap round.
  const int expected[3][6] = {{0, 1, 2, 3, 4, 5}, {2, 3, 4, 5, 0, 1}, {4, 5, 0, 1, 2, 3}};
  for (int round = 0; round < 3; ++round)
    for (size_t k = 0; k < 6; ++k) CHECK(rotatedIndex(k, 6, round, 3) == size_t(expected[round][k]));
  // Every configuration exactly once in every round, whatever the counts.
  for (size_t count : {1u, 5u, 7u})
    for (int rounds : {1, 3, 5, 9})
      for (int round = 0; round < rounds; ++round) {
        std::vector<int> seen(count);
        for (size_t k = 0; k < count; ++k) ++seen[rotatedIndex(k, count, round, rounds)];
        for (int s : seen) CHECK(s == 1);
      }
  // A configuration's probes about a round apart: of seven in three rounds (starting at 0, 7/3 = 2
  // and 14/3 = 4), the last is probed at place 6 of the first, 4 of the second, 2 of the third —
  // at 6, 7 + 4 and 14 + 2 of the run's 21 probes.
  CHECK(rotatedIndex(6, 7, 0, 3) == 6);
  CHECK(rotatedIndex(4, 7, 1, 3) == 6);
  CHECK(rotatedIndex(2, 7, 2, 3) == 6);
}

TEST_CASE("trade-off rounds: the median of the rounds' medians, the extremes of any frame", "[bench]") {
  // Five rounds, three of them at the host's slower speed (about 1.5x): the time is the median of
  // the rounds' medians, a slow round's here; the fastest round's median beside it.
  const std::vector<ProbeResult> rounds = {probe(15.0, 14.6, 15.4, 9000, 15.6), probe(15.2, 14.9, 15.9, 9100, 15.5),
                                           probe(10.3, 10.0, 10.9, 9000, 10.8), probe(14.8, 14.1, 16.0, 9050, 15.0),
                                           probe(10.1, 9.6, 10.5, 8990, 10.4)};
  const ProbeResult c = combineRounds(rounds);
  REQUIRE(c.ok);
  CHECK(c.medianMs == 14.8);  // sorted 10.1 10.3 14.8 15.0 15.2
  CHECK(c.fastestRoundMs == 10.1);
  CHECK(c.wallMedianMs == 15.0);    // sorted 10.4 10.8 15.0 15.5 15.6
  CHECK(c.minMs == 9.6);
  CHECK(c.maxMs == 16.0);
  CHECK(c.peakRssKiB == 9100);
  // An even count: the median is the mean of the middle two.
  const ProbeResult two = combineRounds(std::vector<ProbeResult>{probe(4.0, 3.5, 4.5, 1, 4.0), probe(6.0, 5.5, 7.0, 2, 8.0)});
  CHECK(two.medianMs == 5.0);
  CHECK(two.fastestRoundMs == 4.0);
  CHECK(two.wallMedianMs == 6.0);
}

TEST_CASE("trade-off rounds: one failed round fails the configuration", "[bench]") {
  ProbeResult failed;
  failed.error = "probe exited with status 9";
  const ProbeResult c = combineRounds(std::vector<ProbeResult>{probe(10.0, 9.0, 11.0, 1, 10.0), failed});
  CHECK_FALSE(c.ok);
  CHECK(c.error == "probe exited with status 9");
  CHECK_FALSE(combineRounds({}).ok);
}

}  // namespace
}  // namespace shadowref::bench
