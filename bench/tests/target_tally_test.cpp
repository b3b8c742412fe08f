// bench/target_tally.h: runs' tables of targets read back and counted over the runs. The tables
// are TargetTable's own text of hand-made figures; the counts are worked out by hand.
#include "target_tally.h"

#include <sstream>

#include <catch2/catch.hpp>

namespace shadowref::bench {
namespace {

// A run's output as vs_mesa prints it: the script's commit line, some of the run, the table last.
// The two-thread figures are information, as vs_mesa prints them.
std::string runText(const std::string& commit, double llvmpipe0, double llvmpipe1, double twoThreads0,
                    double twoThreads1, bool identical1, double fit) {
  TargetTable t({"room", "city-64"});
  t.atLeast("per vertex, 1 thread: x llvmpipe", 1.0, {llvmpipe0, llvmpipe1});
  t.information("per vertex: in turn, 2 threads / 1", {twoThreads0, twoThreads1});
  t.information("  the host's capacity for two threads", {1.97, 1.55});
  t.holds("buffers of 1, 2 and 8 threads", {true, identical1}, "identical", "DIFFERENT");
  t.single("linear in houses, 1 thread: R2", fit, 0.95);
  t.information("unequal: per pixel, x llvmpipe fixed 1t", {0.91, 2.3});
  return "commit: " + commit + "\nnproc: 2\nbench/vs-mesa: shadowref against Mesa through OSMesa\n\nThe speed targets\n" +
         t.text() + "\nCSV: bench/results/vs-mesa.csv\n";
}

RunTargets read(const std::string& text) {
  std::istringstream in(text);
  const std::optional<RunTargets> run = readRunTargets(in);
  REQUIRE(run.has_value());
  return *run;
}

}  // namespace

TEST_CASE("tally: a run's table is read back row by row, cell by cell", "[bench]") {
  const RunTargets run = read(runText("abc1234", 1.41, 0.98, 1.85, 1.62, false, 0.991));
  CHECK(run.commit == "abc1234");
  CHECK(run.columns == std::vector<std::string>{"room", "city-64"});
  // 1.41 ok, 0.98 SHORT; identical, DIFFERENT; 0.991 ok: 3 of 5 (the two-thread row is information).
  CHECK(run.met == 3);
  CHECK(run.checked == 5);
  REQUIRE(run.rows.size() == 6);
  CHECK(run.rows[0].what == "per vertex, 1 thread: x llvmpipe >= 1");
  CHECK(run.rows[0].threshold == 1.0);
  CHECK(run.rows[0].cells == std::vector<std::string>{"1.41 ok", "0.98 SHORT"});
  CHECK_FALSE(run.rows[1].threshold.has_value());
  CHECK(run.rows[1].cells == std::vector<std::string>{"1.85", "1.62"});
  CHECK(run.rows[2].indented);
  CHECK(run.rows[2].what == "the host's capacity for two threads");
  CHECK(run.rows[3].cells == std::vector<std::string>{"identical", "DIFFERENT"});
  CHECK(run.rows[4].cells == std::vector<std::string>{"0.991 ok"});
  CHECK(run.rows[4].threshold == 0.95);
  CHECK_FALSE(run.rows[5].indented);
}

TEST_CASE("tally: output without a whole table of targets is no run", "[bench]") {
  std::istringstream none("commit: abc1234\nbench/vs-mesa: shadowref against Mesa through OSMesa\nscene srg-1t\n");
  CHECK_FALSE(readRunTargets(none).has_value());
  std::string whole = runText("abc1234", 1.41, 0.98, 1.85, 1.62, true, 0.99);
  std::istringstream cut(whole.substr(0, whole.find(" figures at or above")));  // cut in its last line
  CHECK_FALSE(readRunTargets(cut).has_value());
}

TEST_CASE("tally: each target met in how many runs, figures without a verdict not counted", "[bench]") {
  TargetTally tally;
  // x llvmpipe: room 1.41, 0.97, 1.2 -> 2 of 3; city 0.98, 1.05, 1.0 -> 2 of 3 (1.0 meets >= 1).
  tally.add("a.txt", read(runText("aaaaaaa", 1.41, 0.98, 1.85, 1.62, true, 0.991)));
  tally.add("b.txt", read(runText("bbbbbbb", 0.97, 1.05, 1.70, 1.92, false, 0.94)));
  tally.add("c.txt", read(runText("ccccccc", 1.2, 1.0, 1.81, 1.50, true, 0.97)));
  CHECK(tally.runs() == 3);
  const std::string text = tally.text();
  INFO(text);
  auto row = [&](const std::string& label, const std::string& room, const std::string& city) {
    return targetLine(label, {room, city});
  };
  CHECK(text.find("The speed targets over 3 runs") == 0);
  CHECK(text.find(targetLine("target", {"room", "city-64"})) != std::string::npos);
  CHECK(text.find(row("per vertex, 1 thread: x llvmpipe >= 1", "2/3", "2/3")) != std::string::npos);
  CHECK(text.find(row("buffers of 1, 2 and 8 threads", "3/3", "2/3")) != std::string::npos);
  CHECK(text.find(targetLine("linear in houses, 1 thread: R2 >= 0.95", {"2/3"})) != std::string::npos);
  CHECK(text.find("2 threads / 1") == std::string::npos);  // information: no verdict to count
  CHECK(text.find("capacity") == std::string::npos);
  CHECK(text.find("unequal") == std::string::npos);
  // Per run: a 1.41/identical x2/0.991 = 4 of 5; b 1.05/identical/(0.94 short) = 2; c 1.2/1.0/identical x2/0.97 = 5.
  CHECK(text.find("  4 of 5  a.txt (aaaaaaa)\n  2 of 5  b.txt (bbbbbbb)\n  5 of 5  c.txt (ccccccc)\n") != std::string::npos);
}

TEST_CASE("tally: a saved run that still judged two threads / one is counted without that row", "[bench]") {
  // Runs saved before the two-thread verdict was retired carry it as a target ("... >= 1.8").
  TargetTable old({"room", "city-64"});
  old.atLeast("per vertex, 1 thread: x llvmpipe", 1.0, {1.3, 1.1});
  old.atLeast("per vertex: in turn, 2 threads / 1", 1.8, {1.84, 1.62});
  old.holds("buffers of 1, 2 and 8 threads", {true, true}, "identical", "identical");
  TargetTally tally;
  tally.add("old.txt", read("commit: ddddddd\n\n" + old.text()));
  tally.add("a.txt", read(runText("aaaaaaa", 1.41, 0.98, 1.85, 1.62, true, 0.991)));
  const std::string text = tally.text();
  INFO(text);
  CHECK(text.find("2 threads / 1") == std::string::npos);
  CHECK(text.find(targetLine("per vertex, 1 thread: x llvmpipe >= 1", {"2/2", "1/2"})) != std::string::npos);
  CHECK(text.find(targetLine("buffers of 1, 2 and 8 threads", {"2/2", "2/2"})) != std::string::npos);
  // The run's own count line is printed as the run printed it: the old run judged 6 figures.
  CHECK(text.find("  5 of 6  old.txt (ddddddd)\n") != std::string::npos);
}

}  // namespace shadowref::bench
