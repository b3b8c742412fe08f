// The registry of shadow techniques: the one list behind shadow.method, --method, --help and
// `shadowref info`, and the dispatch renderFrame makes through it — for the built-in techniques
// and for one defined here, as a new technique's file would define it.
#include <catch2/catch.hpp>

#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "scene/scene_loader.h"
#include "shadow/frame_renderer.h"
#include "shadow/technique_registry.h"
#include "support/errors.h"

using namespace shadowref;
using shadowref::testing::messageOf;
using Catch::Matchers::Contains;

namespace {

const std::string kEveryName = "none, zpass, zfail, auto, shadowmap, tsm";

// A box on a ground plane under one point light, small enough to render every technique quickly.
Scene smallScene(const std::string& method) {
  LoadOptions o;
  o.overrides = {"image.width=40", "image.height=30", "shadow.map_size=64", "shadow.method=" + method};
  return loadScene(std::string(SHADOWREF_SOURCE_DIR) + "/scenes/minimal.yaml", o);
}

// A technique defined only here, as a new technique's file defines one: it fills the colour
// buffer with one colour and reports one pass. It reads no shadow settings.
constexpr glm::vec4 kFlatColor{0.25f, 0.5f, 0.75f, 1.0f};

void renderFlat(const Scene& scene, const FrameOptions& options, FrameResult& result, Pipeline& pipeline) {
  RenderState state;
  state.viewport = {0, 0, scene.width, scene.height};
  pipeline.clear({.state = state, .color = kFlatColor, .depth = 1.0});
  result.notes.push_back("flat");
  if (options.onPass) options.onPass("01-flat", pipeline.framebuffer());
}

const ShadowTechnique kFlatTechnique{
    .name = "flat",
    .summary = "one colour everywhere: a technique defined by a test",
    .settings = {},
    .countsInStencil = false,
    .render = renderFlat,
    .describe = nullptr,
};

// The built-in techniques and the test's, as a registry with one more line would list them.
std::vector<const ShadowTechnique*> withFlat() {
  std::vector<const ShadowTechnique*> list(techniques().begin(), techniques().end());
  list.push_back(&kFlatTechnique);
  return list;
}

}  // namespace

TEST_CASE("every built-in technique has a unique name, a summary, a renderer, and is found by its name",
          "[shadow][registry]") {
  CHECK(techniqueNames() == kEveryName);  // the order of --help and of the messages
  std::set<std::string_view> names;
  for (const ShadowTechnique* t : techniques()) {
    INFO(t->name);
    CHECK(!t->name.empty());
    CHECK(names.insert(t->name).second);
    CHECK(!t->summary.empty());
    CHECK(t->render != nullptr);
    CHECK(findTechnique(t->name) == t);
    ShadowSettings settings;
    settings.method = std::string(t->name);
    CHECK(&techniqueOf(settings) == t);
  }
  CHECK(findTechnique("zfial") == nullptr);
  CHECK(findTechnique("") == nullptr);
  CHECK(findTechnique("ZFAIL") == nullptr);  // names are matched exactly, as the scene file's keys
}

TEST_CASE("an unknown technique is reported where the file or the -D wrote it, with every name", "[shadow][registry]") {
  const Scene file = loadSceneFromString("shadow:\n  method: zfial\n", "t.yaml");
  const std::string expected =
      "t.yaml:2:11: shadow.method: 'zfial' is not one of " + kEveryName + "; did you mean 'zfail'?";
  CHECK(messageOf([&] { techniqueOf(file.shadow); }) == expected);
  // Rendering reports the same: no path renders a name the registry does not know.
  CHECK(messageOf([&] { renderFrame(file); }) == expected);

  // 'z' is character 18 of the second -D, "shadow.method=\n  zfial".
  LoadOptions o;
  o.overrides = {"camera.near=0.5", "shadow.method=\n  zfial"};
  const Scene overridden = loadSceneFromString("meshes:\n  box: {box: {}}\n", "t.yaml", o);
  CHECK(messageOf([&] { techniqueOf(overridden.shadow); }) ==
        "<command line>:2:18: shadow.method: 'zfial' is not one of " + kEveryName + "; did you mean 'zfail'?");

  // No suggestion when no name is close.
  CHECK(unknownTechniqueMessage("penumbra-wedges") == "'penumbra-wedges' is not one of " + kEveryName);

  // FrameOptions::method (--method) has no place in a file.
  FrameOptions options;
  options.method = "shadowmapp";
  CHECK(messageOf([&] { renderFrame(smallScene("none"), options); }) ==
        "shadow method 'shadowmapp' is not one of " + kEveryName + "; did you mean 'shadowmap'?");
}

TEST_CASE("the keys a technique reads are keys of the scene's shadow section", "[shadow][registry]") {
  // The loader names its shadow keys in the message for an unknown one.
  const std::string message = messageOf([] { loadSceneFromString("shadow: {no_such_key: 1}\n", "t.yaml"); });
  REQUIRE_THAT(message, Contains("(allowed: method, "));
  for (const ShadowTechnique* t : techniques())
    for (const TechniqueSetting& s : t->settings) {
      INFO(t->name << "." << s.key);
      CHECK_THAT(message, Contains(" " + std::string(s.key) + ",") || Contains(" " + std::string(s.key) + ")"));
      CHECK(!s.range.empty());
    }
}

TEST_CASE("TSM reads the shadow map's settings but its fit, in their order, and the focus region", "[shadow][registry]") {
  auto keys = [](const char* name) {
    const ShadowTechnique* t = findTechnique(name);
    REQUIRE(t != nullptr);
    std::vector<std::string> out;
    for (const TechniqueSetting& s : t->settings) out.emplace_back(s.key);
    return out;
  };
  const std::vector<std::string> common = {"map_size", "offset_factor", "offset_units", "bias", "back_faces_only",
                                           "pcf", "receiver_plane_bias", "compare_fail"};
  std::vector<std::string> map = common;
  map.push_back("fit");
  CHECK(keys("shadowmap") == map);
  std::vector<std::string> tsm = common;
  tsm.push_back("focus_region");
  CHECK(keys("tsm") == tsm);
}

TEST_CASE("`info` describes the settings the scene's technique reads", "[shadow][registry]") {
  ShadowSettings s;  // the defaults of docs/scene-format.md
  s.method = "none";
  CHECK(describeShadowSettings(s).empty());
  for (const char* volumes : {"zpass", "zfail", "auto"}) {
    s.method = volumes;
    CHECK(describeShadowSettings(s) == "silhouette kuhn, two-sided stencil, wrapping stencil ops");
  }
  s.method = "shadowmap";
  CHECK(describeShadowSettings(s) == "map 1024 x 1024, offset 1.1 / 4, bias 0, pcf 1, compare fail 0.4, fit casters");
  s.method = "tsm";
  s.mapSize = 256;
  s.backFacesOnly = true;
  s.focusRegion = 0.25;
  CHECK(describeShadowSettings(s) ==
        "map 256 x 256, offset 1.1 / 4, bias 0, back faces only, pcf 1, compare fail 0.4, focus region 0.25");
  s.method = "zfial";
  CHECK(describeShadowSettings(s).empty());
}

TEST_CASE("a technique counts in the stencil buffer exactly when its entry says so", "[shadow][registry]") {
  for (const ShadowTechnique* t : techniques()) {
    INFO(t->name);
    FrameOptions options;
    options.keepStencil = true;
    const FrameResult frame = renderFrame(smallScene(std::string(t->name)), options);
    CHECK(frame.stencilPerLight.size() == (t->countsInStencil ? 1u : 0u));  // one light
  }
}

TEST_CASE("a technique defined outside the registry's file is found and rendered through the same dispatch",
          "[shadow][registry]") {
  const std::vector<const ShadowTechnique*> list = withFlat();
  FrameOptions options;
  options.techniques = list;
  std::vector<std::string> passes;
  options.onPass = [&](const std::string& pass, const Framebuffer&) { passes.push_back(pass); };

  CHECK(techniqueNames(list) == kEveryName + ", flat");
  CHECK(findTechnique("flat", list) == &kFlatTechnique);
  CHECK(findTechnique("flat") == nullptr);  // not a built-in

  // By the scene's shadow.method, as a file would name it.
  const FrameResult frame = renderFrame(smallScene("flat"), options);
  REQUIRE(frame.framebuffer.hasColor());
  for (int y = 0; y < frame.framebuffer.height(); ++y)
    for (int x = 0; x < frame.framebuffer.width(); ++x) REQUIRE(frame.framebuffer.colorAt(x, y) == kFlatColor);
  CHECK(passes == std::vector<std::string>{"01-flat"});
  CHECK(frame.notes == std::vector<std::string>{"flat"});

  // By FrameOptions::method, as --method names it, over a scene that names another.
  passes.clear();
  options.method = "flat";
  const FrameResult overridden = renderFrame(smallScene("zfail"), options);
  CHECK(overridden.framebuffer.colorAt(0, 0) == kFlatColor);
  CHECK(passes == std::vector<std::string>{"01-flat"});

  // The built-in ones are dispatched the same way from the longer list: the same bytes.
  options.method.clear();
  options.onPass = nullptr;
  for (const ShadowTechnique* t : techniques()) {
    INFO(t->name);
    const Scene scene = smallScene(std::string(t->name));
    const FrameResult viaList = renderFrame(scene, options);
    const FrameResult builtIn = renderFrame(scene);
    CHECK(viaList.framebuffer.color() == builtIn.framebuffer.color());
  }

  // Without the test's list, the name is unknown, and the message lists the built-in names.
  CHECK_THAT(messageOf([] { renderFrame(smallScene("flat")); }), Contains("'flat' is not one of " + kEveryName));
}
