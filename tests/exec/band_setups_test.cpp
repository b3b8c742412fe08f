// BandSetups against a plain filter of the same lists: the setups whose rows meet the band's, in
// order, each once — whatever the prefetching ahead of them (which must neither skip nor repeat
// one, nor read past the lists: the sanitizer build runs this too).
#include <random>
#include <vector>

#include <catch2/catch.hpp>

#include "exec/band_setups.h"

using namespace shadowref;

namespace {
std::vector<size_t> collect(const std::vector<SetupBounds>& bounds, const std::vector<const TriangleSetup*>& setups,
                            int first, int last, bool cut = true) {
  BandSetups band(bounds, setups, first, last, cut);
  std::vector<size_t> got;
  for (size_t i; band.next(i);) got.push_back(i);
  size_t i = 0;
  CHECK_FALSE(band.next(i));  // the end stays the end
  return got;
}

std::vector<size_t> filtered(const std::vector<SetupBounds>& bounds, int first, int last) {
  std::vector<size_t> expect;
  for (size_t i = 0; i < bounds.size(); ++i)
    if (bounds[i].maxY >= first && bounds[i].minY <= last) expect.push_back(i);
  return expect;
}
}  // namespace

TEST_CASE("a band's setups: those whose rows meet the band's, in order, touching rows counted", "[raster][bands]") {
  const std::vector<TriangleSetup> storage(6);
  std::vector<const TriangleSetup*> setups;
  for (const TriangleSetup& t : storage) setups.push_back(&t);
  // Rows 10 … 19: the second ends on row 10, the fourth starts on 19, the fifth spans the band.
  const std::vector<SetupBounds> bounds = {
      {0, 0, 5, 9}, {0, 5, 5, 10}, {0, 12, 5, 14}, {0, 19, 5, 30}, {0, 0, 5, 40}, {0, 20, 5, 25}};
  CHECK(collect(bounds, setups, 10, 19) == std::vector<size_t>{1, 2, 3, 4});
  CHECK(collect(bounds, setups, 41, 50).empty());
  CHECK(collect(bounds, setups, 0, 40) == std::vector<size_t>{0, 1, 2, 3, 4, 5});
  CHECK(collect({}, {}, 0, 100).empty());
}

TEST_CASE("a band's setups match a plain filter for any lists and rows", "[raster][bands]") {
  std::mt19937 random(20261128);
  std::uniform_int_distribution<int> row(0, 199), height(0, 60);
  for (int round = 0; round < 200; ++round) {
    const size_t count = size_t(round % 40);  // fewer than, as many as and more than kAhead
    std::vector<TriangleSetup> storage(count);
    std::vector<const TriangleSetup*> setups;
    std::vector<SetupBounds> bounds;
    for (size_t i = 0; i < count; ++i) {
      setups.push_back(&storage[i]);
      const int minY = row(random);
      bounds.push_back({0, minY, 10, minY + height(random)});
    }
    const int first = row(random), last = first + height(random);
    INFO("round " << round);
    CHECK(collect(bounds, setups, first, last) == filtered(bounds, first, last));
    CHECK(collect(bounds, setups, first, last, false) == filtered(bounds, first, last));  // nothing fetched ahead
  }
}
