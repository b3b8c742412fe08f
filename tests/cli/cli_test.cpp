// The command line as a user meets it: exit status 0 / 1 / 2, errors as
// file:line:col on stderr, output files complete or absent.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <csignal>
#include <cstring>
#include <string>
#include <vector>

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "support/cli_run.h"

namespace fs = std::filesystem;
using shadowref::testing::CliRun;
using shadowref::testing::runShadowref;
using shadowref::testing::slurp;

namespace {

fs::path scratch() {
  const fs::path dir = fs::temp_directory_path() / ("shadowref-cli-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

std::string writeScene(const std::string& name, const std::string& text) {
  const fs::path p = scratch() / name;
  std::ofstream(p) << text;
  return p.string();
}

// Every entry's file name in dir, sorted.
std::vector<std::string> entries(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

fs::path freshDir(const std::string& name) {
  const fs::path dir = scratch() / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Starts the CLI with argv (no shell), stderr to errFile, in the source folder. In the child:
// fileSizeLimit > 0 sets RLIMIT_FSIZE (SIGXFSZ ignored, so a write beyond it fails with EFBIG as
// on a full disk); holdTemp sets the writer's test hook (atomic_write.h).
pid_t spawn(const std::vector<std::string>& args, const fs::path& errFile, long fileSizeLimit, bool holdTemp) {
  const pid_t pid = ::fork();
  if (pid != 0) return pid;
  if (::chdir(SHADOWREF_SOURCE_DIR) != 0) ::_exit(126);
  const int err = ::open(errFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (err < 0 || ::dup2(err, 2) < 0) ::_exit(126);
  const int null = ::open("/dev/null", O_WRONLY);
  if (null < 0 || ::dup2(null, 1) < 0) ::_exit(126);
  if (holdTemp) ::setenv("SHADOWREF_TEST_HOLD_TEMP_FILE", "1", 1);
  if (fileSizeLimit > 0) {
    ::signal(SIGXFSZ, SIG_IGN);  // stays ignored across exec
    const rlimit limit{rlim_t(fileSizeLimit), rlim_t(fileSizeLimit)};
    if (::setrlimit(RLIMIT_FSIZE, &limit) != 0) ::_exit(126);
  }
  std::vector<char*> argv{const_cast<char*>(SHADOWREF_CLI)};
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  ::execv(SHADOWREF_CLI, argv.data());
  ::_exit(127);
}

// Writes a PNG whose header declares width x height grey pixels but whose data is one empty row:
// what a hostile file looks like to a reader that trusts the header. CRCs are computed, so only the
// sizes are false.
void writeLyingPng(const fs::path& path, uint32_t width, uint32_t height) {
  auto crc32 = [](const std::string& bytes) {
    uint32_t crc = 0xFFFFFFFFu;
    for (unsigned char c : bytes) {
      crc ^= c;
      for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    return crc ^ 0xFFFFFFFFu;
  };
  auto be32 = [](uint32_t v) {
    return std::string{char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
  };
  auto chunk = [&](const std::string& type, const std::string& data) {
    return be32(uint32_t(data.size())) + type + data + be32(crc32(type + data));
  };
  const std::string ihdr = be32(width) + be32(height) + std::string{8, 0, 0, 0, 0};  // 8-bit grey
  // zlib stream of one byte (filter 0), stored block: 78 01, 01 0001 fffe, 00, adler32 = 00010001.
  const std::string idat{'\x78', '\x01', '\x01', '\x01', '\x00', '\xfe', '\xff', '\x00', '\x00', '\x01', '\x00', '\x01'};
  std::ofstream(path, std::ios::binary) << std::string("\x89PNG\r\n\x1a\n", 8) << chunk("IHDR", ihdr)
                                        << chunk("IDAT", idat) << chunk("IEND", "");
}

}  // namespace

TEST_CASE("render writes the PNG and the EXR it is asked for and exits 0", "[cli]") {
  const fs::path dir = scratch();
  const std::string png = (dir / "m.png").string(), exr = (dir / "m.exr").string();
  fs::remove(png);
  fs::remove(exr);
  const CliRun r = runShadowref("render scenes/minimal.yaml -D image.width=64 -D image.height=48 -o '" + png + "' -o '" + exr +
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
  const CliRun r = runShadowref("render '" + scene + "' -o '" + png.string() + "'");
  CHECK(r.status == 2);
  CHECK(r.err.rfind(scene + ":2:", 0) == 0);  // the line of the typo
  CHECK(r.err.find("nera") != std::string::npos);
  CHECK_FALSE(fs::exists(png));
}

TEST_CASE("a scene file that does not exist is bad input (exit 2)", "[cli]") {
  const CliRun r = runShadowref("check scenes/no-such-scene.yaml");
  CHECK(r.status == 2);
  CHECK(r.err.find("no-such-scene.yaml") != std::string::npos);
}

TEST_CASE("check validates without rendering: 0 for a good scene, 2 for a bad one", "[cli]") {
  CHECK(runShadowref("check scenes/room.yaml").status == 0);
  const std::string scene = writeScene("nan.yaml", "ambient: [.nan, 0, 0]\n");
  const CliRun bad = runShadowref("check '" + scene + "'");
  CHECK(bad.status == 2);
  CHECK(bad.err.rfind(scene + ":1:", 0) == 0);
}

TEST_CASE("bad flags and values are bad usage (exit 2) and write nothing", "[cli]") {
  const fs::path out = scratch() / "flag.png";
  fs::remove(out);
  CHECK(runShadowref("render --no-such-flag").status == 2);
  CHECK(runShadowref("render --method zfial -o '" + out.string() + "'").status == 2);
  CHECK(runShadowref("render -o '" + (scratch() / "x.jpg").string() + "'").status == 2);
  CHECK(runShadowref("render --pixel-history 5 -o '" + out.string() + "'").status == 2);
  CHECK(runShadowref("render --dump-region 1,2,0,4 -o '" + out.string() + "'").status == 2);
  CHECK(runShadowref("render --threads -1").status == 2);
  CHECK_FALSE(fs::exists(out));
  CHECK_FALSE(fs::exists(scratch() / "x.jpg"));
}

TEST_CASE("compare exits 0 for identical images, 2 (FAILURE) when they differ, 4 when one cannot be read", "[cli]") {
  const fs::path dir = scratch();
  const std::string a = (dir / "a.exr").string(), b = (dir / "b.exr").string();
  REQUIRE(runShadowref("render scenes/minimal.yaml -D image.width=32 -D image.height=24 -o '" + a + "' --quiet").status == 0);
  REQUIRE(runShadowref("render scenes/minimal.yaml -D image.width=32 -D image.height=24 -D ambient=[0.9,0.9,0.9] -o '" + b +
              "' --quiet").status == 0);
  CHECK(runShadowref("compare '" + a + "' '" + a + "'").status == 0);
  const CliRun differ = runShadowref("compare '" + a + "' '" + b + "'");
  CHECK(differ.status == 2);
  CHECK(differ.out.find("R") != std::string::npos);
  CHECK(runShadowref("compare '" + a + "' '" + (dir / "missing.exr").string() + "'").status == 4);
}

TEST_CASE("bench prints the median frame and each pass, at any thread count, and judges none", "[cli]") {
  const std::string scene = "scenes/minimal.yaml -D image.width=64 -D image.height=48";
  for (const char* threads : {"1", "2"}) {
    const CliRun r = runShadowref("bench " + scene + " --frames 2 --threads " + threads);
    INFO(r.out);
    CHECK(r.status == 0);
    CHECK(r.out.find(std::string(", ") + threads + " thread") != std::string::npos);
    CHECK(r.out.find("frame (median)") != std::string::npos);
    CHECK(r.out.find("01-ambient") != std::string::npos);
  }
  // The CSV line: scene, method, threads, width, height, frames, median ms.
  const CliRun csv = runShadowref("bench " + scene + " --frames 2 --threads 2 --csv");
  CHECK(csv.status == 0);
  char method[32] = {};
  int threads = 0, width = 0, height = 0, frames = 0;
  double ms = -1.0;
  CHECK(std::sscanf(csv.out.c_str(), "scenes/minimal.yaml,%31[^,],%d,%d,%d,%d,%lf", method, &threads, &width, &height,
                    &frames, &ms) == 6);
  CHECK(threads == 2);
  CHECK(width == 64);
  CHECK(height == 48);
  CHECK(frames == 2);
  CHECK(ms > 0.0);
  CHECK(runShadowref("bench " + scene + " --frames 0").status != 0);
}

TEST_CASE("the --help text lists every subcommand and exits 0", "[cli]") {
  const CliRun r = runShadowref("--help");
  CHECK(r.status == 0);
  for (const char* sub : {"render", "check", "info", "compare", "bench", "sweep"}) CHECK(r.out.find(sub) != std::string::npos);
}

TEST_CASE("the pixel history (--pixel-history) prints the fragments of the watched pixel in draw order", "[cli]") {
  const CliRun r = runShadowref("render scenes/minimal.yaml -D image.width=64 -D image.height=48 --method zfail --pixel-history "
                    "32,10 -o '" + (scratch() / "h.png").string() + "' --quiet");
  CHECK(r.status == 0);
  CHECK(r.out.find("pixel 32,10") != std::string::npos);
  CHECK(r.out.find("ambient pass") != std::string::npos);
}

TEST_CASE("a write that fails half-way (file-size limit) exits 1 naming the file, leaving no file", "[cli][hostile]") {
  for (const char* name : {"full.png", "full.exr"}) {
    const fs::path dir = freshDir("fsize");
    const fs::path out = dir / name, err = scratch() / "fsize-err.txt";
    // 400x300 of the room is tens of kilobytes in either format; the limit lets 4 KiB through.
    const pid_t pid = spawn({"render", "scenes/room.yaml", "-D", "image.width=400", "-D", "image.height=300", "-o",
                             out.string()},
                            err, 4096, false);
    int status = 0;
    REQUIRE(::waitpid(pid, &status, 0) == pid);
    const std::string message = slurp(err);
    INFO(message);
    CHECK(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == 1);
    CHECK(message.find("cannot write '" + out.string() + "'") != std::string::npos);
    CHECK(message.find(std::strerror(EFBIG)) != std::string::npos);
    CHECK(entries(dir).empty());  // neither the target nor a temporary file
  }
}

TEST_CASE("SIGTERM or SIGINT while an output is written ends the CLI by that signal and removes the temporary file",
          "[cli][hostile]") {
  for (const int sig : {SIGTERM, SIGINT}) {
    const fs::path dir = freshDir("signal");
    const fs::path out = dir / "out.png", err = scratch() / "signal-err.txt";
    const pid_t pid = spawn({"render", "scenes/minimal.yaml", "-D", "image.width=32", "-D", "image.height=24", "-o",
                             out.string()},
                            err, 0, true);
    // The hook holds the writer right after it created "out.png.tmp-<pid>-<n>": wait for that file.
    bool sawTemp = false;
    for (int i = 0; i < 3000 && !sawTemp; ++i) {
      for (const std::string& name : entries(dir)) sawTemp = sawTemp || name.rfind("out.png.tmp-", 0) == 0;
      if (!sawTemp) ::usleep(10000);
    }
    CHECK(sawTemp);
    ::kill(pid, sig);
    int status = 0;
    REQUIRE(::waitpid(pid, &status, 0) == pid);
    CHECK(WIFSIGNALED(status));  // a shell reports 128 + sig: 143, 130
    CHECK((WIFSIGNALED(status) ? WTERMSIG(status) : 0) == sig);
    CHECK(entries(dir).empty());
  }
}

TEST_CASE("render -o onto the scene file itself is refused with exit 2 and the scene kept", "[cli][hostile]") {
  const fs::path dir = freshDir("self");
  const fs::path scene = dir / "scene.png";  // a YAML scene under an image name: -o would overwrite it
  const std::string text = "image: {width: 16, height: 12}\n";
  std::ofstream(scene) << text;
  const CliRun r = runShadowref("render '" + scene.string() + "' -o '" + scene.string() + "'");
  CHECK(r.status == 2);
  CHECK(r.err.find("the scene file itself") != std::string::npos);
  CHECK(slurp(scene) == text);
  // Through another spelling of the same path, too.
  const CliRun dotted = runShadowref("render '" + scene.string() + "' -o '" + (dir / "." / "scene.png").string() + "'");
  CHECK(dotted.status == 2);
  CHECK(slurp(scene) == text);
  CHECK(entries(dir) == std::vector<std::string>{"scene.png"});
}

TEST_CASE("compare refuses an image whose header declares more pixels than its file holds, before allocating",
          "[cli][hostile]") {
  const fs::path dir = freshDir("lying");
  const fs::path png = dir / "huge.png";
  // 30000^2 values are more than the 2^29 any image may have.
  writeLyingPng(png, 30000, 30000);
  REQUIRE(fs::file_size(png) < 100);
  const CliRun r = runShadowref("compare '" + png.string() + "' '" + png.string() + "'");
  CHECK(r.status == 4);
  CHECK(r.err.find("cannot read '" + png.string() + "'") != std::string::npos);
  CHECK(r.err.find("30000x30000 pixels with 1 channels, more than the limit of 536870912") != std::string::npos);
  // 20000^2 are within it, but 4e8 bytes of pixels do not fit in 1032 times the file's bytes.
  writeLyingPng(png, 20000, 20000);
  const CliRun small = runShadowref("compare '" + png.string() + "' '" + png.string() + "'");
  CHECK(small.status == 4);
  CHECK(small.err.find("20000x20000 pixels with 1 channels (400000000 bytes of pixels), more than its") !=
        std::string::npos);
  CHECK(small.err.find("file can hold") != std::string::npos);
}

TEST_CASE("render --dump-region is checked before rendering: extreme or outside regions exit 2 with nothing written",
          "[cli][hostile]") {
  const fs::path dir = freshDir("region");
  const std::string out = (dir / "r.png").string();
  const std::string scene = "scenes/minimal.yaml -D image.width=64 -D image.height=48 --method zfail -o '" + out + "'";
  for (const char* region : {"2147483647,0,2147483647,1", "0,2147483647,1,2147483647", "-2147483648,0,2147483647,1",
                             "64,0,4,4", "0,48,4,4", "-4,0,4,4", "0,0,99999999999,1", "1,2,3", "a,b,c,d"}) {
    INFO(region);
    const CliRun r = runShadowref("render " + scene + " --dump-region " + region);
    CHECK(r.status == 2);
    CHECK(r.err.find("--dump-region") != std::string::npos);
    CHECK(entries(dir).empty());
  }
  // A region reaching past the image is clipped; its ends do not overflow.
  const CliRun clipped = runShadowref("render " + scene + " --dump-region 60,0,2147483647,2 --quiet");
  CHECK(clipped.status == 0);
  CHECK(clipped.out.find("stencil x 60..63, y 0..1") != std::string::npos);
  CHECK(clipped.out.find("clipped") != std::string::npos);
}

TEST_CASE("render --dump stencil writes each light's picture as its pass ends and bounds what an EXR keeps",
          "[cli][hostile]") {
  const std::string scene = writeScene("three.yaml",
                                       "image: {width: 64, height: 48}\n"
                                       "lights:\n  - {position: [-2, 4, 1]}\n  - {position: [2, 4, 1]}\n"
                                       "  - {position: [0, 4, -2]}\n"
                                       "meshes: {ground: {plane: {size: [8, 8]}}, box: {box: {size: [1, 1, 1]}}}\n"
                                       "nodes: [{mesh: ground}, {mesh: box, translate: [0, 0.5, 0]}]\n"
                                       "shadow: {method: zfail}\n");
  const fs::path dir = freshDir("stencil");
  const CliRun r = runShadowref("render '" + scene + "' -o '" + (dir / "s.png").string() + "' --dump stencil --quiet");
  CHECK(r.status == 0);
  CHECK(entries(dir) == std::vector<std::string>{"s.png", "s.stencil-L0.png", "s.stencil-L1.png", "s.stencil-L2.png"});
  // 3 lights x 8192 x 8192 counts = 3 * 2^26 > 2^27: refused before rendering, nothing written.
  const fs::path big = freshDir("stencil-big");
  const CliRun refused = runShadowref("render '" + scene + "' -D image.width=8192 -D image.height=8192 -o '" +
                          (big / "s.exr").string() + "' --dump stencil");
  CHECK(refused.status == 2);
  CHECK(refused.err.find("134217728") != std::string::npos);
  CHECK(entries(big).empty());
}

TEST_CASE("flag messages say what is wrong: not a number, an unknown subcommand, any-case extensions",
          "[cli][hostile]") {
  const CliRun letters = runShadowref("render --threads abc");
  CHECK(letters.status == 2);
  CHECK(letters.err.find("'abc' is not a whole number (allowed: 0 to 256)") != std::string::npos);
  const CliRun large = runShadowref("render --threads 257");
  CHECK(large.status == 2);
  CHECK(large.err.find("257 is outside the allowed range 0 to 256") != std::string::npos);
  const CliRun typo = runShadowref("rendr scenes/minimal.yaml");
  CHECK(typo.status == 2);
  CHECK(typo.err.find("unknown subcommand 'rendr' (did you mean 'render'?)") != std::string::npos);
  const CliRun far = runShadowref("xyzzy");
  CHECK(far.status == 2);
  CHECK(far.err.find("unknown subcommand 'xyzzy'; the subcommands are") != std::string::npos);
  const fs::path dir = freshDir("case");
  const CliRun mixed = runShadowref("render scenes/minimal.yaml -D image.width=16 -D image.height=12 -o '" + (dir / "a.Png").string() +
                        "' -o '" + (dir / "b.eXr").string() + "' --quiet");
  CHECK(mixed.status == 0);
  CHECK(entries(dir) == std::vector<std::string>{"a.Png", "b.eXr"});
}

TEST_CASE("a range message shows the value as written, not rounded into the range", "[cli][hostile]") {
  // %g printed 90.0000001 as "90 is outside the allowed range [0, 90]".
  const std::string scene = writeScene("cutoff.yaml", "lights: [{type: spot, position: [0, 4, 0], spot_cutoff: 90.0000001}]\n");
  const CliRun r = runShadowref("check '" + scene + "'");
  CHECK(r.status == 2);
  CHECK(r.err.find("spot_cutoff: 90.0000001 is outside the allowed range [0, 90]") != std::string::npos);
}

TEST_CASE("render with the reference and the fast pipeline writes the same pixels, another name is bad usage", "[cli]") {
  const fs::path dir = freshDir("pipelines");
  const std::string ref = (dir / "ref.exr").string(), fast = (dir / "fast.exr").string();
  const std::string scene = "render scenes/minimal.yaml -D image.width=48 -D image.height=36 --method zfail --quiet ";
  const CliRun a = runShadowref(scene + "--pipeline reference -o '" + ref + "'");
  const CliRun b = runShadowref(scene + "--pipeline fast --threads 3 -o '" + fast + "'");
  INFO(a.err << b.err);
  REQUIRE(a.status == 0);
  REQUIRE(b.status == 0);
  // Every channel (R, G, B, A, Z, stencil) exactly: the reference defines the bytes.
  const CliRun same = runShadowref("compare '" + ref + "' '" + fast + "'");  // tolerance 0
  INFO(same.out << same.err);
  CHECK(same.status == 0);
  const CliRun bad = runShadowref(scene + "--pipeline softpipe -o '" + (dir / "x.exr").string() + "'");
  CHECK(bad.status == 2);
  CHECK(bad.err.find("--pipeline") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "x.exr"));
}

TEST_CASE("render warns once per open, non-manifold, inconsistently wound or inside-out mesh, naming it and what "
          "it does, and a closed scene gets no warning", "[cli]") {
  const std::string png = (scratch() / "irregular.png").string();
  const CliRun r = runShadowref("render scenes/irregular.yaml -D image.width=64 -D image.height=48 -o '" + png + "'");
  INFO(r.err);
  CHECK(r.status == 0);
  auto lines = [&](const std::string& needle) {
    size_t n = 0;
    for (size_t at = r.err.find(needle); at != std::string::npos; at = r.err.find(needle, at + 1)) ++n;
    return n;
  };
  CHECK(lines("warning: ") == 5);
  CHECK(lines("warning: mesh 'triangle' is open (3 edges with one triangle); it casts its shadow as a two-sided "
              "surface") == 1);
  CHECK(lines("warning: mesh 'fins' is open (6 edges with one triangle), non-manifold (1 edges with three or more "
              "triangles)") == 1);
  CHECK(lines("warning: mesh 'inside_out_cube' is inside out (closed, but it encloses a negative volume, -1") == 1);
  CHECK(lines("the shadow volumes take its winding as reversed") == 1);
  CHECK(lines("warning: mesh 'flipped_face_cube' is inconsistently wound (4 edges whose two triangles run them the "
              "same way)") == 1);
  CHECK(lines("warning: mesh 'mixed_cubes' is partly inside out (1 of its 2 closed parts enclose a negative volume "
              "outside every other part); it casts its shadow as a two-sided surface") == 1);
  // The tent under two lights: one warning, not one per light.
  const CliRun tent = runShadowref("render scenes/tent.yaml -D image.width=64 -D image.height=48 -o '" + png + "'");
  CHECK(tent.status == 0);
  CHECK(tent.err.find("warning: mesh 'tent' is open (5 edges with one triangle)") != std::string::npos);
  CHECK(tent.err.find("warning: ") == tent.err.rfind("warning: "));
  // --quiet prints nothing but errors; a scene of closed outward meshes has nothing to warn about.
  CHECK(runShadowref("render scenes/tent.yaml -D image.width=64 -D image.height=48 --quiet -o '" + png + "'").err.empty());
  CHECK(runShadowref("render scenes/minimal.yaml -D image.width=64 -D image.height=48 -o '" + png + "'").err.find("warning") ==
        std::string::npos);
}

TEST_CASE("info reports an inside-out closed mesh by the sign of the volume it encloses", "[cli]") {
  const CliRun r = runShadowref("info scenes/irregular.yaml");
  INFO(r.err);
  CHECK(r.status == 0);
  CHECK(r.out.find("inside_out_cube: 12 triangles, 8 welded vertices, 18 edges, closed (0 open, 0 non-manifold "
                   "edges), encloses volume -1 (negative: inside out, every triangle wound clockwise seen from "
                   "outside)") != std::string::npos);
  CHECK(r.out.find("flipped_face_cube: 12 triangles, 8 welded vertices, 18 edges, closed (0 open, 0 non-manifold "
                   "edges), inconsistently wound (4 edges whose two triangles run them the same way)") !=
        std::string::npos);
  CHECK(r.out.find("triangle: 1 triangles, 3 welded vertices, 3 edges, open (3 open, 0 non-manifold edges), bounds") !=
        std::string::npos);
  // 0.8³ − 0.5³ = 0.387: positive, yet one of its two cubes is wound inside out.
  CHECK(r.out.find("mixed_cubes: 24 triangles, 16 welded vertices, 36 edges, closed (0 open, 0 non-manifold edges), "
                   "encloses volume 0.387 (partly inside out: 1 of its 2 closed parts enclose a negative volume "
                   "outside every other part)") != std::string::npos);
  // A unit cube wound the right way encloses +1 and is not called inside out.
  const CliRun minimal = runShadowref("info scenes/minimal.yaml");
  CHECK(minimal.out.find("inside out") == std::string::npos);
  CHECK(minimal.out.find("encloses volume ") != std::string::npos);
}

TEST_CASE("every subcommand that reads a scene takes -D before or after it", "[cli]") {
  const fs::path dir = freshDir("d-order");
  for (const bool before : {true, false}) {
    INFO((before ? "-D before the scene" : "-D after the scene"));
    const auto with = [&](const std::string& command, const std::string& d, const std::string& rest = "") {
      const std::string scene = "scenes/minimal.yaml";
      return runShadowref(command + " " + (before ? d + " " + scene : scene + " " + d) + " " + rest);
    };
    // info prints the size the override set; check refuses an override the scene rejects.
    const CliRun info = with("info", "-D image.width=37 -D image.height=29");
    INFO(info.err);
    CHECK(info.status == 0);
    CHECK(info.out.find("image: 37 x 29") != std::string::npos);
    CHECK(with("check", "-D image.width=37").status == 0);
    const CliRun bad = with("check", "-D shadow.method=nosuchmethod");
    CHECK(bad.status == 2);
    CHECK(bad.err.find("nosuchmethod") != std::string::npos);
    const CliRun bench = with("bench", "-D image.width=24 -D image.height=16", "--frames 1 --csv");
    INFO(bench.err);
    CHECK(bench.status == 0);
    CHECK(bench.out.find(",24,16,1,") != std::string::npos);
    const std::string png = (dir / (before ? "before.png" : "after.png")).string();
    const CliRun render = with("render", "-D image.width=24 -D image.height=16", "--quiet -o '" + png + "'");
    INFO(render.err);
    CHECK(render.status == 0);
    CHECK(fs::exists(png));
  }
}

TEST_CASE("under taskset -c 0 a render uses one thread by default, as its metadata says", "[cli][threads]") {
  if (std::system("command -v taskset >/dev/null 2>&1") != 0) {
    WARN("taskset (util-linux) is not installed");
    return;
  }
  const fs::path dir = freshDir("taskset");
  const std::string png = (dir / "one.png").string();
  // The CLI's own process under the mask: taskset runs it on CPU 0 only.
  const std::string cli = std::string("'") + SHADOWREF_CLI + "'";
  const std::string cmd = std::string("cd '") + SHADOWREF_SOURCE_DIR + "' && taskset -c 0 " + cli +
                          " render scenes/minimal.yaml -D image.width=32 -D image.height=24 --quiet -o '" + png + "'";
  REQUIRE(std::system(cmd.c_str()) == 0);
  // The PNG's tEXt chunk "shadowref:threads" holds the thread count the frame ran on: a chunk is
  // a 4-byte big-endian length, "tEXt", then keyword NUL value.
  const std::string bytes = slurp(png);
  const std::string key = std::string("tEXtshadowref:threads") + '\0';
  const size_t at = bytes.find(key);
  REQUIRE(at != std::string::npos);
  REQUIRE(at >= 4);
  uint32_t length = 0;
  for (size_t i = at - 4; i < at; ++i) length = length << 8 | uint8_t(bytes[i]);
  REQUIRE(length > key.size() - 5);
  CHECK(bytes.substr(at + key.size(), length - (key.size() - 4)) == "1");
}
