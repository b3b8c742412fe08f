// bench/target_tally.h: runs' tables of targets read back and counted over the runs. The tables
// are TargetTable's own text of hand-made figures; the counts are worked out by hand.
#include "target_tally.h"

#include <sstream>

#include <catch2/catch.hpp>

namespace shadowref::bench {
namespace {

// A run's output as vs_mesa prints it: the script's commit line, some of the run, the table last.
std::string runText(const std::string& commit, double twoThreads0, double twoThreads1, double capacity0,
                    double capacity1, double llvmpipe0, double llvmpipe1, bool identical1, double fit) {
  TargetTable t({"room", "city-64"});
  t.atLeast("per vertex, 1 thread: x llvmpipe", 1.0, {1.41, 0.98});
  t.atLeast("per vertex: 2 threads / 1", 1.8, {twoThreads0, twoThreads1});
  t.information("  the host's capacity for two threads", {capacity0, capacity1});
  t.information("  ns for a line between the cores", {52.0, 310.0});
  t.information("  llvmpipe's 2 threads / 1, same runs", {llvmpipe0, llvmpipe1});
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
  const RunTargets run = read(runText("abc1234", 1.85, 1.62, 1.97, 1.55, 1.9, 1.3, false, 0.991));
  CHECK(run.commit == "abc1234");
  CHECK(run.columns == std::vector<std::string>{"room", "city-64"});
  // 1.41 ok, 0.98 SHORT; 1.85 ok, 1.62 SHORT; identical, DIFFERENT; 0.991 ok: 4 of 7.
  CHECK(run.met == 4);
  CHECK(run.checked == 7);
  REQUIRE(run.rows.size() == 8);
  CHECK(run.rows[0].what == "per vertex, 1 thread: x llvmpipe >= 1");
  CHECK(run.rows[0].threshold == 1.0);
  CHECK(run.rows[0].cells == std::vector<std::string>{"1.41 ok", "0.98 SHORT"});
  CHECK(run.rows[1].threshold == 1.8);
  CHECK(run.rows[2].indented);
  CHECK(run.rows[2].what == "the host's capacity for two threads");
  CHECK_FALSE(run.rows[2].threshold.has_value());
  CHECK(run.rows[2].cells == std::vector<std::string>{"1.97", "1.55"});
  CHECK(run.rows[5].cells == std::vector<std::string>{"identical", "DIFFERENT"});
  CHECK(run.rows[6].cells == std::vector<std::string>{"0.991 ok"});
  CHECK(run.rows[6].threshold == 0.95);
  CHECK_FALSE(run.rows[7].indented);
}

TEST_CASE("tally: output without a whole table of targets is no run", "[bench]") {
  std::istringstream none("commit: abc1234\nbench/vs-mesa: shadowref against Mesa through OSMesa\nscene srg-1t\n");
  CHECK_FALSE(readRunTargets(none).has_value());
  std::string whole = runText("abc1234", 1.85, 1.62, 1.97, 1.55, 1.9, 1.3, true, 0.99);
  std::istringstream cut(whole.substr(0, whole.find(" figures at or above")));  // cut in its last line
  CHECK_FALSE(readRunTargets(cut).has_value());
}

TEST_CASE("tally: each figure met in how many runs, two threads / one by the host's capacity", "[bench]") {
  TargetTally tally;
  // Room: 1.85 at capacity 1.97 (met, room), 1.70 at 1.95 (short, room), 1.81 at 1.75 (met, none).
  // City: 1.62 at 1.55 (short, none), 1.92 at 2.01 (met, room), 1.50 at 1.52 (short, none).
  // llvmpipe: room 1.9, 1.79, 1.8 -> 2 of 3; city 1.3, 1.85, 1.1 -> 1 of 3.
  tally.add("a.txt", read(runText("aaaaaaa", 1.85, 1.62, 1.97, 1.55, 1.9, 1.3, true, 0.991)));
  tally.add("b.txt", read(runText("bbbbbbb", 1.70, 1.92, 1.95, 2.01, 1.79, 1.85, false, 0.94)));
  tally.add("c.txt", read(runText("ccccccc", 1.81, 1.50, 1.75, 1.52, 1.8, 1.1, true, 0.97)));
  CHECK(tally.runs() == 3);
  const std::string text = tally.text();
  INFO(text);
  auto row = [&](const std::string& label, const std::string& room, const std::string& city) {
    return targetLine(label, {room, city});
  };
  CHECK(text.find("The speed targets over 3 runs") == 0);
  CHECK(text.find(targetLine("target", {"room", "city-64"})) != std::string::npos);
  CHECK(text.find(row("per vertex, 1 thread: x llvmpipe >= 1", "3/3", "0/3")) != std::string::npos);
  CHECK(text.find(row("per vertex: 2 threads / 1 >= 1.8", "2/3", "1/3")) != std::string::npos);
  CHECK(text.find(row("  where the host's capacity was >= 1.8", "1/2", "1/1")) != std::string::npos);
  CHECK(text.find(row("  where it was below 1.8", "1/1", "0/2")) != std::string::npos);
  CHECK(text.find(row("  llvmpipe's 2 threads / 1 >= 1.8, same runs", "2/3", "1/3")) != std::string::npos);
  CHECK(text.find(row("buffers of 1, 2 and 8 threads", "3/3", "2/3")) != std::string::npos);
  CHECK(text.find(targetLine("linear in houses, 1 thread: R2 >= 0.95", {"2/3"})) != std::string::npos);
  CHECK(text.find("unequal") == std::string::npos);  // information: no verdict to count
  // Every two-thread figure met in one run: shadowref in none (a: city short, b: room short, c:
  // city short); llvmpipe in none either (a: city 1.3, b: room 1.79, c: city 1.1).
  CHECK(text.find("runs with every two-thread figure met: shadowref 0, llvmpipe 0 (of 3)") != std::string::npos);
  // Capacity at or above 1.8 in both cells: b alone (1.95 / 2.01; a's city 1.55, c's 1.75 / 1.52),
  // and b's room was short (1.70).
  CHECK(text.find("runs with the host's capacity for two threads at or above the line in every two-thread cell: 1 "
                  "(every two-thread figure met in 0 of them)") != std::string::npos);
  // Per run: a 1.41/1.85/identical x2/0.991 = 5 of 7; b 1.41/1.92/identical/0.94 short = 3; c 5.
  CHECK(text.find("  5 of 7  a.txt (aaaaaaa)\n  3 of 7  b.txt (bbbbbbb)\n  5 of 7  c.txt (ccccccc)\n") != std::string::npos);
}

TEST_CASE("tally: a run meeting every two-thread figure is counted, for each renderer on its own", "[bench]") {
  TargetTally tally;
  tally.add("a.txt", read(runText("aaaaaaa", 1.85, 1.92, 1.97, 2.01, 1.79, 1.85, true, 0.99)));
  tally.add("b.txt", read(runText("bbbbbbb", 1.85, 1.62, 1.97, 1.55, 1.9, 1.81, true, 0.99)));
  CHECK(tally.text().find("runs with every two-thread figure met: shadowref 1, llvmpipe 1 (of 2)") != std::string::npos);
  // a had room in both cells (1.97 / 2.01) and met both; b's city had none (1.55).
  CHECK(tally.text().find("in every two-thread cell: 1 (every two-thread figure met in 1 of them)") != std::string::npos);
}


TEST_CASE("tally: a target judged in turn counts its separate processes' figure beside it", "[bench]") {
  // Runs from round 34 on judge two threads / one on frames in turn and print the ratio of
  // separate processes under it; a run from before judged the separate processes themselves.
  auto inTurnRun = [](double turn0, double turn1, double separate0, double separate1) {
    TargetTable t({"room", "city-64"});
    t.atLeast("per vertex: in turn, 2 threads / 1", 1.8, {turn0, turn1});
    t.information("  separate processes, 2 threads / 1", {separate0, separate1});
    t.information("  the host's capacity for two threads", {1.97, 1.92});
    return "commit: ddddddd\n\n" + t.text();
  };
  TargetTally tally;
  tally.add("old.txt", read(runText("aaaaaaa", 1.85, 1.62, 1.97, 1.55, 1.9, 1.3, true, 0.991)));
  tally.add("a.txt", read(inTurnRun(1.86, 1.83, 1.79, 1.84)));
  tally.add("b.txt", read(inTurnRun(1.91, 1.78, 1.88, 1.60)));
  const std::string text = tally.text();
  INFO(text);
  auto row = [&](const std::string& label, const std::string& room, const std::string& city) {
    return targetLine(label, {room, city});
  };
  // The old instrument's row and the new one's are counted apart.
  CHECK(text.find(row("per vertex: 2 threads / 1 >= 1.8", "1/1", "0/1")) != std::string::npos);
  CHECK(text.find(row("per vertex: in turn, 2 threads / 1 >= 1.8", "2/2", "1/2")) != std::string::npos);
  // Separate processes: room 1.79, 1.88 -> 1 of 2; city 1.84, 1.60 -> 1 of 2.
  CHECK(text.find(row("  separate processes >= 1.8, same runs", "1/2", "1/2")) != std::string::npos);
  // Capacity 1.97 / 1.92 in both new runs: room met in both, the city in a alone.
  CHECK(text.find(row("  where the host's capacity was >= 1.8", "2/2", "1/2")) != std::string::npos);
  // Every two-thread figure met: a (1.86, 1.83) only.
  CHECK(text.find("runs with every two-thread figure met: shadowref 1, llvmpipe ") != std::string::npos);
}

}  // namespace shadowref::bench
