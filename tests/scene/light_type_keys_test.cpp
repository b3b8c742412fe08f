// A light key that its type does not read is an error at the key, as an unknown key is: a
// directional light has no position, a point light no direction, only a spot light a cone.
#include <catch2/catch.hpp>

#include <string>

#include "scene/scene_loader.h"

using namespace shadowref;
using Catch::Matchers::StartsWith;

namespace {

std::string errorOf(const std::string& light, std::vector<std::string> overrides = {}) {
  try {
    LoadOptions options;
    options.overrides = std::move(overrides);
    loadSceneFromString("lights:\n  - " + light + "\n", "t.yaml", options);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST_CASE("light keys: each type takes its own keys", "[loader][lights]") {
  CHECK(errorOf("{type: point, position: [0, 3, 0], range: 5}") == "(no error)");
  CHECK(errorOf("{type: directional, direction: [0, -1, 0], color: 0.5}") == "(no error)");
  CHECK(errorOf("{type: spot, position: [0, 3, 0], direction: [0, -1, 0], spot_cutoff: 30, spot_exponent: 2}") ==
        "(no error)");
  CHECK(errorOf("{position: [0, 3, 0]}") == "(no error)");  // a point light by default
}

TEST_CASE("light keys: a key of another type is an error naming it, at its place", "[loader][lights]") {
  // "  - {type: directional, position: ...": the key starts in column 25 of line 2.
  CHECK(errorOf("{type: directional, position: [0, 3, 0]}") ==
        "t.yaml:2:25: key 'position' does not apply to the directional light lights.0 (keys of a directional "
        "light: name, type, direction, color, range, attenuation, soft)");
  CHECK_THAT(errorOf("{type: point, direction: [0, -1, 0]}"),
             StartsWith("t.yaml:2:19: key 'direction' does not apply to the point light lights.0"));
  CHECK_THAT(errorOf("{spot_cutoff: 30}"), StartsWith("t.yaml:2:6: key 'spot_cutoff' does not apply to the point light"));
  CHECK_THAT(errorOf("{type: directional, spot_exponent: 4}"),
             StartsWith("t.yaml:2:25: key 'spot_exponent' does not apply to the directional light"));
  // The type may come after the key: the light's type decides.
  CHECK_THAT(errorOf("{position: [0, 3, 0], type: directional}"),
             StartsWith("t.yaml:2:6: key 'position' does not apply to the directional light"));
  // On the command line too.
  CHECK_THAT(errorOf("{name: sun, type: directional}", {"lights.sun.position=[1, 2, 3]"}),
             StartsWith("<command line>:1:12: key 'position' does not apply to the directional light lights.0"));
  CHECK_THAT(errorOf("{name: bulb}", {"lights.bulb.spot_cutoff=20"}),
             StartsWith("<command line>:1:13: key 'spot_cutoff' does not apply to the point light lights.0"));
}
