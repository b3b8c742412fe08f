// bench/speed_targets.h: the verdict vs_mesa prints last. Hand-made figures, hand-checked cells.
#include "speed_targets.h"

#include <catch2/catch.hpp>

namespace shadowref::bench {

TEST_CASE("targets: a figure meets its threshold at or above it, and is shown cut, never rounded up", "[bench]") {
  TargetTable t({"room", "city"});
  t.atLeast("a ratio", 1.8, {1.8, 1.797});
  t.atLeast("x softpipe", 10.0, {9.999, 25.18});
  const std::string text = t.text();
  CHECK(text.find("1.80 ok") != std::string::npos);
  CHECK(text.find("1.79 SHORT") != std::string::npos);   // 1.797 would round to 1.80
  CHECK(text.find("9.99 SHORT") != std::string::npos);   // 9.999 would round to 10.00
  CHECK(text.find("25.18 ok") != std::string::npos);
  CHECK(t.checked() == 4);
  CHECK(t.shortOf() == 2);
  CHECK(text.find("2 of 4 figures at or above their targets") != std::string::npos);
  CHECK(text.find("a ratio >= 1.8 ") != std::string::npos);
  CHECK(text.find("x softpipe >= 10 ") != std::string::npos);
}

TEST_CASE("targets: information rows carry no verdict and are not counted", "[bench]") {
  TargetTable t({"room"});
  t.information("capacity", {1.5});
  t.information("unequal pairing", {0.84});
  CHECK(t.checked() == 0);
  CHECK(t.shortOf() == 0);
  const std::string text = t.text();
  CHECK(text.find("0.84") != std::string::npos);
  CHECK(text.find("SHORT") == std::string::npos);
  CHECK(text.find(" ok") == std::string::npos);
}

TEST_CASE("targets: flags and single figures are targets too", "[bench]") {
  TargetTable t({"room", "city"});
  t.holds("buffers identical", {true, false}, "identical", "DIFFERENT");
  t.single("linear: R2", 0.9812, 0.95);
  t.single("linear: R2", 0.9499, 0.95);
  CHECK(t.checked() == 4);
  CHECK(t.shortOf() == 2);
  const std::string text = t.text();
  CHECK(text.find("identical") != std::string::npos);
  CHECK(text.find("DIFFERENT") != std::string::npos);
  CHECK(text.find("0.981 ok") != std::string::npos);
  CHECK(text.find("0.949 SHORT") != std::string::npos);
  CHECK(text.find("linear: R2 >= 0.95 ") != std::string::npos);
}

TEST_CASE("targets: one line per row, the scenes as column titles", "[bench]") {
  TargetTable t({"room", "pumpkins"});
  t.atLeast("x llvmpipe", 1.0, {1.41, 0.99});
  const std::string text = t.text();
  const size_t firstLineEnd = text.find('\n');
  const std::string header = text.substr(0, firstLineEnd);
  CHECK(header.find("room") != std::string::npos);
  CHECK(header.find("pumpkins") != std::string::npos);
  const std::string row = text.substr(firstLineEnd + 1, text.find('\n', firstLineEnd + 1) - firstLineEnd - 1);
  CHECK(row.find("x llvmpipe >= 1 ") == 0);  // the label, with the threshold made from the number
  CHECK(row.find("1.41 ok") < row.find("0.99 SHORT"));
}

}  // namespace shadowref::bench
