// TwoEndedClaims: one owner claiming from the front and thieves from the back get every item
// exactly once — on one thread against a hand-worked sequence, and on threads against a count of
// who took what.
#include <atomic>
#include <thread>
#include <vector>

#include <catch2/catch.hpp>

#include "exec/two_ended_claims.h"

using namespace shadowref;

TEST_CASE("claims from both ends take the items in chunks, each once, until none is left", "[raster][threads]") {
  TwoEndedClaims c;
  uint32_t first = 0, last = 0;
  CHECK(c.left() == 0);
  CHECK_FALSE(c.claimFront(4, first, last));  // not opened: nothing to claim
  c.open(10);
  CHECK(c.left() == 10);
  REQUIRE(c.claimFront(3, first, last));
  CHECK((first == 0 && last == 3));
  REQUIRE(c.claimBack(4, first, last));
  CHECK((first == 6 && last == 10));
  REQUIRE(c.claimFront(0, first, last));  // at least one
  CHECK((first == 3 && last == 4));
  CHECK(c.left() == 2);
  REQUIRE(c.claimBack(5, first, last));  // no more than are left
  CHECK((first == 4 && last == 6));
  CHECK(c.left() == 0);
  CHECK_FALSE(c.claimFront(1, first, last));
  CHECK_FALSE(c.claimBack(1, first, last));
  c.open(2);  // opened again for the next flush
  REQUIRE(c.claimBack(1, first, last));
  CHECK((first == 1 && last == 2));
  c.close();
  CHECK_FALSE(c.claimFront(1, first, last));
}

TEST_CASE("an owner and three thieves on threads claim every item exactly once", "[raster][threads]") {
  constexpr uint32_t kItems = 200000;
  for (int round = 0; round < 5; ++round) {
    TwoEndedClaims c;
    std::vector<std::atomic<int>> taken(kItems);
    c.open(kItems);
    auto work = [&](bool owner, uint32_t chunk) {
      for (uint32_t first, last; owner ? c.claimFront(chunk, first, last) : c.claimBack(chunk, first, last);)
        for (uint32_t i = first; i < last; ++i) taken[i].fetch_add(1, std::memory_order_relaxed);
    };
    std::vector<std::thread> threads;
    threads.emplace_back(work, true, 7);
    for (uint32_t t = 0; t < 3; ++t) threads.emplace_back(work, false, 1 + t * 5);
    for (std::thread& t : threads) t.join();
    int wrong = 0;
    for (const std::atomic<int>& n : taken) wrong += n.load() != 1;
    CHECK(wrong == 0);
    CHECK(c.left() == 0);
  }
}
