// `render --frames`: numbered files and dumps, the animated GIF and MP4 (decoded back), the
// contact sheet's size, and the usage errors (exit 2, nothing written).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "support/cli_run.h"

namespace fs = std::filesystem;
using shadowref::testing::CliRun;
using shadowref::testing::runShadowref;
using shadowref::testing::runShell;
using shadowref::testing::slurp;
using shadowref::testing::testScratch;
using Catch::Matchers::Contains;

namespace {

// A box under a point light that circles it, 40 x 30 pixels: each frame renders in milliseconds.
const char* kScene =
    "image: {width: 40, height: 30}\n"
    "camera: {eye: [0, 3, 6], target: [0, 0, 0]}\n"
    "lights:\n"
    "  - {name: lamp, position: [3, 4, 0]}\n"
    "meshes:\n"
    "  box: {box: {}}\n"
    "  floor: {plane: {size: [8, 8]}}\n"
    "nodes:\n"
    "  - {name: floor, mesh: floor, translate: [0, -0.5, 0]}\n"
    "  - {name: crate, mesh: box}\n"
    "shadow: {method: zfail}\n"
    "animation:\n"
    "  fps: 2\n"
    "  lights:\n"
    "    lamp: {position: {interpolation: smooth, keys: {0: [3, 4, 0], 1: [0, 4, 3], 2: [-3, 4, 0]}}}\n";

fs::path sceneFile() {
  const fs::path dir = testScratch() / "frames";
  fs::create_directories(dir);
  const fs::path file = dir / "circle.yaml";
  std::ofstream(file) << kScene;
  return file;
}

std::string q(const fs::path& p) { return "'" + p.string() + "'"; }

// The number of images in a GIF: walks the blocks after the header and global colour table
// (GIF89a: image descriptors 0x2C, extensions 0x21, trailer 0x3B).
int gifFrames(const std::string& g, int& width, int& height) {
  if (g.size() < 13 || g.compare(0, 6, "GIF89a") != 0) return -1;
  auto u8 = [&](size_t i) { return size_t(static_cast<unsigned char>(g.at(i))); };
  width = int(u8(6) | u8(7) << 8);
  height = int(u8(8) | u8(9) << 8);
  size_t at = 13;
  if (u8(10) & 0x80) at += 3u << ((u8(10) & 7) + 1);
  auto skipSubBlocks = [&](size_t i) {
    while (u8(i) != 0) i += u8(i) + 1;
    return i + 1;
  };
  int frames = 0;
  while (at < g.size()) {
    const size_t kind = u8(at);
    if (kind == 0x3B) return frames;
    if (kind == 0x21) {
      at = skipSubBlocks(at + 2);
    } else if (kind == 0x2C) {
      ++frames;
      const size_t flags = u8(at + 9);
      at += 10;
      if (flags & 0x80) at += 3u << ((flags & 7) + 1);
      at = skipSubBlocks(at + 1);  // after the LZW minimum code size
    } else {
      return -2;
    }
  }
  return -3;  // no trailer
}

// A PNG's size from its IHDR chunk.
void pngSize(const std::string& png, int& width, int& height) {
  auto be32 = [&](size_t i) {
    return int(uint32_t(static_cast<unsigned char>(png.at(i))) << 24 | uint32_t(static_cast<unsigned char>(png.at(i + 1))) << 16 |
               uint32_t(static_cast<unsigned char>(png.at(i + 2))) << 8 | uint32_t(static_cast<unsigned char>(png.at(i + 3))));
  };
  width = be32(16);
  height = be32(20);
}

bool haveFfmpeg() { return runShell("command -v ffmpeg >/dev/null && command -v ffprobe >/dev/null").status == 0; }

}  // namespace

TEST_CASE("render --frames writes numbered frames and dumps in one process", "[cli][frames]") {
  const fs::path scene = sceneFile();
  const fs::path out = testScratch() / "frames-numbered";
  fs::remove_all(out);
  const CliRun r = runShadowref("render " + q(scene) + " --frames 3..5 -o " + q(out / "f.png") + " -o " +
                                q(out / "f.exr") + " --dump stencil --dump visibility --quiet");
  INFO(r.err);
  REQUIRE(r.status == 0);
  for (const char* n : {"0003", "0004", "0005"}) {
    CHECK(fs::exists(out / ("f." + std::string(n) + ".png")));
    CHECK(fs::exists(out / ("f." + std::string(n) + ".exr")));
    CHECK(fs::exists(out / ("f." + std::string(n) + ".stencil-L0.png")));
    CHECK(fs::exists(out / ("f." + std::string(n) + ".visibility-L0.png")));
  }
  CHECK_FALSE(fs::exists(out / "f.0002.png"));
  CHECK_FALSE(fs::exists(out / "f.0006.png"));
  CHECK_FALSE(fs::exists(out / "f.png"));
  // The light moves: frames differ; --quiet printed nothing.
  CHECK(slurp(out / "f.0003.png") != slurp(out / "f.0005.png"));
  CHECK(r.err.empty());
  // Frame 4 at 2 fps is t = 2 s, the last key: the same picture as the still at that time would
  // be, which a still of the scene with the light at [-3, 4, 0] and no animation gives.
  std::string still = kScene;
  still = still.substr(0, still.find("animation:"));
  still.replace(still.find("position: [3, 4, 0]"), 19, "position: [-3, 4, 0]");
  std::ofstream(out / "still.yaml") << still;
  REQUIRE(runShadowref("render " + q(out / "still.yaml") + " -o " + q(out / "still.png") + " --quiet").status == 0);
  // The files' metadata differ (scene name, frame number), the pixels must not.
  const CliRun cmp = runShadowref("compare " + q(out / "still.png") + " " + q(out / "f.0004.png"));
  INFO(cmp.out << cmp.err);
  CHECK(cmp.status == 0);
}

TEST_CASE("render --frames: bad ranges and flags exit 2 and write nothing", "[cli][frames]") {
  const fs::path scene = sceneFile();
  const fs::path out = testScratch() / "frames-bad";
  fs::remove_all(out);
  const std::string o = " -o " + q(out / "f.png");
  struct Case {
    std::string args, message;
  };
  for (const Case& c : std::vector<Case>{
           {"--frames 5..2", "is empty"},
           {"--frames a..b", "expected A..B"},
           {"--frames 1..", "expected A..B"},
           {"--frames -3..2", "expected A..B"},
           {"--frames 0..10000000", "expected A..B"},
           {"--frames 0..200000", "more than the 100000"},
           {"--frames 0..2 --fps 0", "--fps"},
           {"--frames 0..2 --fps 5000", "--fps"},
           {"--frames 0..2 --fps fast", "--fps"},
           {"--gif " + q(out / "a.gif"), "need --frames"},
           {"--frames 0..2 --gif " + q(out / "a.png"), "ending in .gif"},
           {"--frames 0..2 --movie " + q(out / "a.avi"), ".gif or .mp4"},
           {"--frames 0..2 --contact-sheet " + q(out / "s.jpg"), "ending in .png"},
       }) {
    const CliRun r = runShadowref("render " + q(scene) + o + " " + c.args);
    INFO(c.args << "\n" << r.err);
    CHECK(r.status == 2);
    CHECK_THAT(r.err, Contains(c.message));
    CHECK_FALSE(fs::exists(out));
  }
}

TEST_CASE("render --gif without ffmpeg on PATH is a clear usage error", "[cli][frames]") {
  const fs::path scene = sceneFile();
  const fs::path out = testScratch() / "frames-noffmpeg";
  fs::remove_all(out);
  const CliRun r = runShell("PATH=/nonexistent '" + std::string(SHADOWREF_CLI) + "' render " + q(scene) +
                            " --frames 0..1 -o " + q(out / "f.png") + " --gif " + q(out / "a.gif"));
  CHECK(r.status == 2);
  CHECK_THAT(r.err, Contains("ffmpeg") && Contains("apt-get install ffmpeg"));
  CHECK_FALSE(fs::exists(out));
}

TEST_CASE("render --gif, --mp4 and --contact-sheet hold every frame", "[cli][frames]") {
  if (!haveFfmpeg()) {
    WARN("ffmpeg/ffprobe not installed (scripts/setup.sh --role test): the movie checks are skipped");
    return;
  }
  const fs::path scene = sceneFile();
  const fs::path out = testScratch() / "frames-movies";
  fs::remove_all(out);
  const CliRun r = runShadowref("render " + q(scene) + " --frames 0..4 -o " + q(out / "f.png") + " --gif " +
                                q(out / "m.gif") + " --mp4 " + q(out / "m.mp4") + " --contact-sheet " +
                                q(out / "sheet.png") + " --quiet");
  INFO(r.err);
  REQUIRE(r.status == 0);
  int w = 0, h = 0;
  CHECK(gifFrames(slurp(out / "m.gif"), w, h) == 5);
  CHECK(w == 40);
  CHECK(h == 30);
  const CliRun probe = runShell("ffprobe -v error -count_frames -select_streams v:0 -show_entries "
                                "stream=nb_read_frames,width,height,codec_name -of csv=p=0 " + q(out / "m.mp4"));
  INFO(probe.err);
  CHECK(probe.status == 0);
  CHECK(probe.out == "h264,40,30,5\n");
  // 5 tiles of 40 x 30 in 3 columns and 2 rows: 4 + 3 (40 + 4) wide, 4 + 2 (30 + 18) high.
  pngSize(slurp(out / "sheet.png"), w, h);
  CHECK(w == 136);
  CHECK(h == 100);
  // No temporary file is left beside them.
  for (const auto& e : fs::directory_iterator(out)) CHECK(e.path().string().find(".tmp-") == std::string::npos);
}
