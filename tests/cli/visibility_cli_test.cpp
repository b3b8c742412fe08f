// What a user comparing shadows meets on the command line: --dump visibility's EXR channels and
// PNG views with the light names in their metadata, -D removing a light, -D errors (exit 2), and
// -o into folders that do not exist yet.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>

#include "support/cli_run.h"

namespace fs = std::filesystem;
using shadowref::testing::CliRun;
using shadowref::testing::runShadowref;
using shadowref::testing::testScratch;

namespace {

// The box over a plane of tests/shadow/visibility_test.cpp, with a second light.
const std::string kScene =
    "image: {width: 64, height: 64}\n"
    "camera: {eye: [0, 10, 0], target: [0, 0, 0], up: [0, 0, -1], fov: 60}\n"
    "lights:\n"
    "  - {name: sun, type: directional, direction: [1, -1, 0]}\n"
    "  - {name: top, type: directional, direction: [0, -1, 0]}\n"
    "meshes:\n  ground: {plane: {size: [10, 10]}}\n  box: {box: {size: [1, 1, 1]}}\n"
    "nodes:\n  - {name: ground, mesh: ground}\n  - {name: box, mesh: box, translate: [0, 1, 0]}\n"
    "shadow: {method: zfail}\n";

std::string sceneFile() {
  const fs::path p = testScratch() / "box.yaml";
  std::ofstream(p) << kScene;
  return p.string();
}

struct Read {
  std::vector<std::string> channels;
  std::map<std::string, std::string> attributes;
  std::vector<float> pixels;  // every channel as float, top row first
  int width = 0, height = 0;
};

Read readImage(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  REQUIRE(in);
  Read r;
  const OIIO::ImageSpec& spec = in->spec();
  r.channels = spec.channelnames;
  for (const OIIO::ParamValue& p : spec.extra_attribs) {
    const std::string name = p.name().string();
    if (name.rfind("shadowref:", 0) == 0) r.attributes[name] = p.get_string();
  }
  r.width = spec.width;
  r.height = spec.height;
  r.pixels.resize(size_t(spec.width) * size_t(spec.height) * size_t(spec.nchannels));
  REQUIRE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, r.pixels.data()));
  return r;
}

// The value of channel `name` at framebuffer pixel (x, y) (row 0 at the bottom).
float channelAt(const Read& r, const std::string& name, int x, int y) {
  size_t c = 0;
  while (c < r.channels.size() && r.channels[c] != name) ++c;
  REQUIRE(c < r.channels.size());
  const size_t row = size_t(r.height - 1 - y);
  return r.pixels[(row * size_t(r.width) + size_t(x)) * r.channels.size() + c];
}

}  // namespace

TEST_CASE("render --dump visibility: EXR channels per light, named in the metadata, and PNG views", "[cli][visibility]") {
  const fs::path dir = testScratch() / "vis";
  fs::remove_all(dir);
  const std::string scene = sceneFile();
  for (const char* method : {"zpass", "shadowmap"}) {
    INFO(method);
    const std::string exr = (dir / method / "f.exr").string();
    const CliRun r = runShadowref("render '" + scene + "' --method " + method + " --dump visibility --quiet -o '" + exr + "'");
    INFO(r.err);
    REQUIRE(r.status == 0);
    const Read frame = readImage(exr);
    CHECK(std::count(frame.channels.begin(), frame.channels.end(), "visibility.L0") == 1);
    CHECK(std::count(frame.channels.begin(), frame.channels.end(), "visibility.L1") == 1);
    CHECK(frame.attributes.at("shadowref:visibility.L0") == "sun");
    CHECK(frame.attributes.at("shadowref:visibility.L1") == "top");
    // Pixel (39, 32) lies in the sun's shadow, not in the top light's; (24, 32) in neither.
    CHECK(channelAt(frame, "visibility.L0", 39, 32) == 0.0f);
    CHECK(channelAt(frame, "visibility.L1", 39, 32) == 1.0f);
    CHECK(channelAt(frame, "visibility.L0", 24, 32) == 1.0f);
    for (int light = 0; light < 2; ++light) {
      const std::string name = "visibility.L" + std::to_string(light);
      const Read png = readImage((dir / method / ("f.visibility-L" + std::to_string(light) + ".png")).string());
      CHECK(png.attributes.at("shadowref:light") == (light == 0 ? "sun" : "top"));
      CHECK(png.attributes.at("shadowref:content") ==
            "visibility L" + std::to_string(light) + (light == 0 ? " 'sun'" : " 'top'"));
      // The view is the channel: 1 white, 0 black.
      for (int y : {0, 32, 63})
        for (int x : {24, 39, 50}) CHECK(channelAt(png, png.channels[0], x, y) == channelAt(frame, name, x, y));
    }
  }
}

TEST_CASE("render -D lights.NAME=off renders the scene without that light", "[cli][visibility]") {
  const std::string scene = sceneFile();
  const fs::path dir = testScratch();
  std::string one = kScene;
  one.erase(one.find("  - {name: top"), one.find("meshes:") - one.find("  - {name: top"));
  const fs::path oneFile = dir / "one.yaml";
  std::ofstream(oneFile) << one;
  const std::string a = (dir / "removed.exr").string(), b = (dir / "one.exr").string();
  REQUIRE(runShadowref("render '" + scene + "' -D lights.top=off --dump visibility --quiet -o '" + a + "'").status == 0);
  REQUIRE(runShadowref("render '" + oneFile.string() + "' --dump visibility --quiet -o '" + b + "'").status == 0);
  const Read ra = readImage(a), rb = readImage(b);
  CHECK(ra.channels == rb.channels);  // R, G, B, A, Z, stencil, visibility.L0: one light
  CHECK(ra.pixels == rb.pixels);
  CHECK(ra.attributes.at("shadowref:visibility.L0") == "sun");
}

TEST_CASE("render and check with -D naming an unknown light or node exit 2 with the place on the command line", "[cli][visibility]") {
  const std::string scene = sceneFile();
  const fs::path out = testScratch() / "never.png";
  CliRun r = runShadowref("render '" + scene + "' -D lights.son=off -o '" + out.string() + "'");
  CHECK(r.status == 2);
  CHECK(r.err == "<command line>:1:8: lights.son: no light named 'son'; did you mean 'sun'?\n");
  r = runShadowref("check '" + scene + "' -D camera.fov=40 -D nodes.bx.cast_shadows=false");
  CHECK(r.status == 2);
  CHECK(r.err == "<command line>:2:7: nodes.bx: no node with the path 'bx'; did you mean 'box'?\n");
  CHECK_FALSE(fs::exists(out));
}

TEST_CASE("render -o into folders that do not exist makes them, and a failed write leaves none behind", "[cli][visibility]") {
  const fs::path dir = testScratch() / "folders";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string scene = sceneFile();
  const fs::path nested = dir / "a" / "b" / "f.png";
  CliRun r = runShadowref("render '" + scene + "' --quiet -o '" + nested.string() + "'");
  CHECK(r.status == 0);
  CHECK(fs::is_regular_file(nested));

  // A part of the path is a file: refused before rendering (exit 2), nothing made.
  std::ofstream(dir / "file") << "x";
  r = runShadowref("render '" + scene + "' --quiet -o '" + (dir / "file" / "c" / "f.png").string() + "'");
  CHECK(r.status == 2);
  CHECK(r.err.find("is not a folder") != std::string::npos);

  // The folders are made, then the file cannot be (its name is longer than any file system allows):
  // the render fails and takes away the folders it made.
  const std::string tooLong((dir / "new" / "deeper" / (std::string(300, 'n') + ".png")).string());
  r = runShadowref("render '" + scene + "' --quiet -o '" + tooLong + "'");
  CHECK(r.status == 1);
  CHECK_FALSE(fs::exists(dir / "new"));
  std::vector<std::string> left;
  for (const auto& e : fs::directory_iterator(dir)) left.push_back(e.path().filename().string());
  std::sort(left.begin(), left.end());
  CHECK(left == std::vector<std::string>{"a", "file"});
}

TEST_CASE("render --help names the visibility dump", "[cli][visibility]") {
  const CliRun r = runShadowref("render --help");
  CHECK(r.status == 0);
  CHECK(r.out.find("'visibility'") != std::string::npos);
}
