// The command line as a user meets it: exit status 0 / 1 / 2, errors as
// file:line:col on stderr, output files complete or absent.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>

namespace fs = std::filesystem;

namespace {

struct Run {
  int status = -1;
  std::string err, out;
};

fs::path scratch() {
  const fs::path dir = fs::temp_directory_path() / ("shadowref-cli-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Runs the shadowref binary with `args` (shell syntax) in the source folder.
Run run(const std::string& args) {
  const fs::path dir = scratch();
  const std::string cmd = std::string("cd '") + SHADOWREF_SOURCE_DIR + "' && '" + SHADOWREF_CLI + "' " + args + " >'" +
                          (dir / "out.txt").string() + "' 2>'" + (dir / "err.txt").string() + "'";
  const int raw = std::system(cmd.c_str());
  Run r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = slurp(dir / "out.txt");
  r.err = slurp(dir / "err.txt");
  return r;
}

std::string writeScene(const std::string& name, const std::string& text) {
  const fs::path p = scratch() / name;
  std::ofstream(p) << text;
  return p.string();
}

}  // namespace

TEST_CASE("render writes the PNG and the EXR it is asked for and exits 0", "[cli]") {
  const fs::path dir = scratch();
  const std::string png = (dir / "m.png").string(), exr = (dir / "m.exr").string();
  fs::remove(png);
  fs::remove(exr);
  const Run r = run("render scenes/minimal.yaml -D image.width=64 -D image.height=48 -o '" + png + "' -o '" + exr +
                    "' --quiet");
  INFO(r.err);
  CHECK(r.status == 0);
  CHECK(fs::file_size(png) > 0);
  CHECK(fs::file_size(exr) > 0);
  CHECK(r.err.empty());
}

TEST_CASE("a malformed scene is reported as file:line:col with exit 2 and no output file", "[cli]") {
  const std::string scene = writeScene("bad.yaml", "image: {width: 64, height: 48}\ncamera: {fov: 60, nera: 1}\n");
  const fs::path png = scratch() / "bad.png";
  fs::remove(png);
  const Run r = run("render '" + scene + "' -o '" + png.string() + "'");
  CHECK(r.status == 2);
  CHECK(r.err.rfind(scene + ":2:", 0) == 0);  // the line of the typo
  CHECK(r.err.find("nera") != std::string::npos);
  CHECK_FALSE(fs::exists(png));
}

TEST_CASE("a scene file that does not exist is bad input (exit 2)", "[cli]") {
  const Run r = run("check scenes/no-such-scene.yaml");
  CHECK(r.status == 2);
  CHECK(r.err.find("no-such-scene.yaml") != std::string::npos);
}

TEST_CASE("check validates without rendering: 0 for a good scene, 2 for a bad one", "[cli]") {
  CHECK(run("check scenes/room.yaml").status == 0);
  const std::string scene = writeScene("nan.yaml", "ambient: [.nan, 0, 0]\n");
  const Run bad = run("check '" + scene + "'");
  CHECK(bad.status == 2);
  CHECK(bad.err.rfind(scene + ":1:", 0) == 0);
}

TEST_CASE("bad flags and values are bad usage (exit 2) and write nothing", "[cli]") {
  const fs::path out = scratch() / "flag.png";
  fs::remove(out);
  CHECK(run("render --no-such-flag").status == 2);
  CHECK(run("render --method zfial -o '" + out.string() + "'").status == 2);
  CHECK(run("render -o '" + (scratch() / "x.jpg").string() + "'").status == 2);
  CHECK(run("render --pixel-history 5 -o '" + out.string() + "'").status == 2);
  CHECK(run("render --dump-region 1,2,0,4 -o '" + out.string() + "'").status == 2);
  CHECK(run("render --threads -1").status == 2);
  CHECK_FALSE(fs::exists(out));
  CHECK_FALSE(fs::exists(scratch() / "x.jpg"));
}

TEST_CASE("compare exits 0 for identical images, 1 when they differ, 2 when one cannot be read", "[cli]") {
  const fs::path dir = scratch();
  const std::string a = (dir / "a.exr").string(), b = (dir / "b.exr").string();
  REQUIRE(run("render scenes/minimal.yaml -D image.width=32 -D image.height=24 -o '" + a + "' --quiet").status == 0);
  REQUIRE(run("render scenes/minimal.yaml -D image.width=32 -D image.height=24 -D ambient=[0.9,0.9,0.9] -o '" + b +
              "' --quiet").status == 0);
  CHECK(run("compare '" + a + "' '" + a + "'").status == 0);
  const Run differ = run("compare '" + a + "' '" + b + "'");
  CHECK(differ.status == 1);
  CHECK(differ.out.find("R") != std::string::npos);
  CHECK(run("compare '" + a + "' '" + (dir / "missing.exr").string() + "'").status == 2);
}

TEST_CASE("bench prints the frame, each pass, and with threads where their time went", "[cli]") {
  const std::string scene = "scenes/minimal.yaml -D image.width=64 -D image.height=48";
  const Run one = run("bench " + scene + " --frames 2 --threads 1");
  CHECK(one.status == 0);
  CHECK(one.out.find("frame (median)") != std::string::npos);
  CHECK(one.out.find("01-ambient") != std::string::npos);
  CHECK(one.out.find("in pool runs") == std::string::npos);  // one thread: no pool
  const Run two = run("bench " + scene + " --frames 2 --threads 2");
  CHECK(two.status == 0);
  CHECK(two.out.find("in pool runs (mean)") != std::string::npos);
  CHECK(two.out.find("the 2 threads busy") != std::string::npos);
  CHECK(two.out.find("outside runs (mean)") != std::string::npos);
  CHECK(run("bench " + scene + " --frames 0").status != 0);
}

TEST_CASE("bench --runs lays out a frame's pool runs, which with the gaps add up to one frame", "[cli]") {
  const std::string scene = "scenes/room.yaml -D image.width=160 -D image.height=128";
  const Run r = run("bench " + scene + " --frames 1 --threads 2 --runs");
  REQUIRE(r.status == 0);
  std::istringstream in(r.out);
  std::string line;
  double frame = -1.0, sum = 0.0, after = -1.0;
  int rows = 0, lastRun = 0;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string first;
    fields >> first;
    if (line.find("frame (median)") != std::string::npos) std::sscanf(line.c_str(), " frame (median) %lf", &frame);
    if (line.find("after the last run") != std::string::npos) std::sscanf(line.c_str(), " after the last run %lf", &after);
    int runNumber = 0, tasks = 0;
    double ms = 0.0, idle = 0.0, before = 0.0;
    if (std::sscanf(line.c_str(), " %d %d %lf %lf %lf", &runNumber, &tasks, &ms, &idle, &before) == 5) {
      CHECK(runNumber == lastRun + 1);  // every run, in order
      lastRun = runNumber;
      CHECK(tasks >= 0);
      CHECK(ms >= 0.0);
      CHECK(idle >= 0.0);
      CHECK(idle <= 100.0);
      sum += ms + before;
      ++rows;
    }
  }
  REQUIRE(frame > 0.0);
  REQUIRE(after >= 0.0);
  CHECK(rows >= 3);  // the room's passes: at least the ambient, stencil and lit bands
  // One frame: its runs, the calling thread's time before each and after the last are the frame,
  // each printed to a microsecond.
  CHECK(std::abs(sum + after - frame) <= 0.0005 * (2 * rows + 2));
  const Run one = run("bench " + scene + " --frames 1 --threads 1 --runs");
  CHECK(one.status == 0);
  CHECK(one.out.find("runs: none") != std::string::npos);
}

TEST_CASE("bench --alternate times one thread and more in turn, its speed-up the medians' quotient", "[cli]") {
  const std::string scene = "scenes/room.yaml -D image.width=160 -D image.height=128";
  const Run r = run("bench " + scene + " --frames 3 --threads 2 --alternate");
  REQUIRE(r.status == 0);
  CHECK(r.out.find("3 frames at 1 thread and 3 at 2 in turn, the workers kept awake") != std::string::npos);
  std::istringstream in(r.out);
  std::string line;
  int rows = 0;
  bool frameRow = false;
  while (std::getline(in, line)) {
    char what[64] = {};
    double one = 0.0, two = 0.0, speedUp = 0.0;
    if (std::sscanf(line.c_str(), " %63s %lf %lf %lf", what, &one, &two, &speedUp) != 4) continue;
    INFO(line);
    CHECK(one > 0.0);
    CHECK(two > 0.0);
    // Each median printed to a microsecond, the quotient to a thousandth.
    const double lo = (one - 0.0005) / (two + 0.0005), hi = (one + 0.0005) / (two - 0.0005);
    CHECK(speedUp >= lo - 0.0005);
    CHECK(speedUp <= hi + 0.0005);
    frameRow = frameRow || std::string(what) == "frame";
    ++rows;
  }
  CHECK(frameRow);
  CHECK(rows == 4);  // the frame and the room's three passes
  const Run oneThread = run("bench " + scene + " --frames 1 --threads 1 --alternate");
  CHECK(oneThread.status == 2);
  CHECK(oneThread.err.find("--threads must be 2 or more") != std::string::npos);
  CHECK(run("bench " + scene + " --frames 1 --threads 2 --alternate --csv").status != 0);
  CHECK(run("bench " + scene + " --frames 1 --threads 2 --alternate --runs").status != 0);
}

TEST_CASE("the --help text lists every subcommand and exits 0", "[cli]") {
  const Run r = run("--help");
  CHECK(r.status == 0);
  for (const char* sub : {"render", "check", "info", "compare", "bench"}) CHECK(r.out.find(sub) != std::string::npos);
}

TEST_CASE("the pixel history (--pixel-history) prints the fragments of the watched pixel in draw order", "[cli]") {
  const Run r = run("render scenes/minimal.yaml -D image.width=64 -D image.height=48 --method zfail --pixel-history "
                    "32,10 -o '" + (scratch() / "h.png").string() + "' --quiet");
  CHECK(r.status == 0);
  CHECK(r.out.find("pixel 32,10") != std::string::npos);
  CHECK(r.out.find("ambient pass") != std::string::npos);
}
