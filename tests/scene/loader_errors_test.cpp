// Every malformed scene is rejected with "file:line:column: message" (1-based), pointing at the
// key or value that is wrong — one test per kind of error.
#include <catch2/catch.hpp>

#include "scene/scene_loader.h"
#include "scene/input_file.h"
#include "support/errors.h"

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

using namespace shadowref;
using shadowref::testing::yamlErrorOf;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

namespace {

std::string fileErrorOf(const std::string& name, const LoadOptions& options = {}) {
  try {
    loadScene(std::string(SHADOWREF_SOURCE_DIR) + "/tests/data/scenes/" + name, options);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(no error)";
}

const std::string kData = std::string(SHADOWREF_SOURCE_DIR) + "/tests/data/scenes/";

// A valid scene body to which a test adds one broken section.
const std::string kBoxScene =
    "meshes:\n"
    "  box: {box: {}}\n"
    "nodes:\n"
    "  - {mesh: box}\n";

}  // namespace

TEST_CASE("a valid scene loads without error", "[loader]") {
  CHECK(yamlErrorOf(kBoxScene) == "(no error)");
}

TEST_CASE("a YAML syntax error is reported at yaml-cpp's mark, 1-based", "[loader]") {
  // "camera: b: c": the second ':' on line 2, column 10, is an illegal map value.
  CHECK_THAT(yamlErrorOf("# comment\ncamera: b: c\n"), StartsWith("t.yaml:2:10: YAML syntax error: illegal map value"));
  // yaml-cpp notices the unclosed flow list of line 4 only at the end of the file (line 6).
  CHECK_THAT(fileErrorOf("bad_syntax.yaml"),
             StartsWith(kData + "bad_syntax.yaml:6:1: YAML syntax error: end of sequence flow not found"));
}

TEST_CASE("an unknown key is an error that lists the allowed keys and suggests the closest", "[loader]") {
  const std::string e = yamlErrorOf("camera:\n  eye: [0, 0, 5]\n  nera: 0.1\n");
  CHECK_THAT(e, StartsWith("t.yaml:3:3: unknown key 'nera' in camera (allowed: eye, target, up, fov, near, far)"));
  CHECK_THAT(e, Contains("did you mean 'near'?"));
  CHECK_THAT(yamlErrorOf("lihgts: []\n"), StartsWith("t.yaml:1:1: unknown key 'lihgts' in the scene"));
  CHECK_THAT(yamlErrorOf("lihgts: []\n"), Contains("did you mean 'lights'?"));
  // Nested sections check their keys too.
  CHECK_THAT(yamlErrorOf("lights:\n  - soft: {shape: none, spaceing: 1}\n"),
             StartsWith("t.yaml:2:25: unknown key 'spaceing' in lights.0.soft"));
  CHECK_THAT(yamlErrorOf("meshes:\n  b: {box: {sise: [1, 1, 1]}}\n"),
             StartsWith("t.yaml:2:13: unknown key 'sise' in meshes.b.box"));
  // A word far from every key gets no suggestion.
  CHECK_THAT(yamlErrorOf("shadow: {xyzzyplugh: 1}\n"), !Contains("did you mean"));
}

TEST_CASE("a duplicate key is an error at its second occurrence", "[loader]") {
  CHECK_THAT(yamlErrorOf("camera:\n  fov: 40\n  fov: 50\n"),
             StartsWith("t.yaml:3:3: duplicate key 'fov' (first written at line 2)"));
}

TEST_CASE("a value of the wrong type is an error at the value", "[loader]") {
  CHECK_THAT(yamlErrorOf("image:\n  width: wide\n"), StartsWith("t.yaml:2:10: image.width: expected a whole number, got 'wide'"));
  CHECK_THAT(yamlErrorOf("camera:\n  eye: 5\n"), StartsWith("t.yaml:2:8: camera.eye: expected a list of 3 numbers"));
  CHECK_THAT(yamlErrorOf("camera:\n  eye: [1, 2]\n"), StartsWith("t.yaml:2:8: camera.eye: expected a list of 3 numbers [x, y, z], got 2 values"));
  CHECK_THAT(yamlErrorOf("camera: [1, 2, 3]\n"), StartsWith("t.yaml:1:9: camera: expected a map of keys"));
  CHECK_THAT(yamlErrorOf("shadow: {two_sided: maybe}\n"), StartsWith("t.yaml:1:21: shadow.two_sided: expected true or false"));
  CHECK_THAT(yamlErrorOf("lights: {type: point}\n"), StartsWith("t.yaml:1:9: lights: expected a list of lights"));
  CHECK_THAT(yamlErrorOf("image: {width: 1.5}\n"), StartsWith("t.yaml:1:16: image.width: expected a whole number"));
}

TEST_CASE("NaN and infinity are rejected wherever a number is expected", "[loader]") {
  CHECK_THAT(yamlErrorOf("camera:\n  fov: .nan\n"), StartsWith("t.yaml:2:8: camera.fov: '.nan' is not allowed"));
  CHECK_THAT(yamlErrorOf("ambient: [0, .inf, 0]\n"), StartsWith("t.yaml:1:14: ambient.1: '.inf' is not allowed"));
  CHECK_THAT(yamlErrorOf("ambient: [0, -.Inf, 0]\n"), StartsWith("t.yaml:1:14: ambient.1: '-.Inf' is not allowed"));
  CHECK_THAT(yamlErrorOf("camera: {far: .inf}\n"), StartsWith("t.yaml:1:15: camera.far: write 'infinite'"));
  CHECK_THAT(yamlErrorOf("lights: [{position: [0, 1e999, 0]}]\n"), StartsWith("t.yaml:1:25: lights.0.position.1: '1e999' is out of the range"));
}

TEST_CASE("a missing mesh file is reported at its path in the scene", "[loader]") {
  CHECK_THAT(fileErrorOf("bad_missing_mesh.yaml"),
             StartsWith(kData + "bad_missing_mesh.yaml:4:15: meshes.gone.obj: mesh file '"));
  CHECK_THAT(fileErrorOf("bad_missing_mesh.yaml"), Contains("does not exist"));
}

TEST_CASE("a mesh path that is not a readable regular file is reported at its path", "[loader]") {
  // A folder: reading it would fail or, for a device, never end.
  CHECK_THAT(yamlErrorOf("meshes:\n  m: {obj: /}\n"), StartsWith("t.yaml:2:12: meshes.m.obj: '/' is not a regular file"));
  CHECK_THAT(yamlErrorOf("meshes:\n  m: {gltf: /dev/null}\n"), StartsWith("t.yaml:2:13: meshes.m.gltf: '/dev/null' is not a regular file"));
}

TEST_CASE("an error inside an OBJ file is reported in the OBJ file, naming the scene key", "[loader]") {
  const std::string e = fileErrorOf("bad_obj_index.yaml");
  CHECK_THAT(e, StartsWith(kData + "bad_index.obj:7:"));  // "f 1 7 4" on line 7
  CHECK_THAT(e, Contains("(mesh file of meshes.broken.obj at " + kData + "bad_obj_index.yaml:3:17)"));
}

TEST_CASE("a mesh without triangles is reported at the key that names it", "[loader]") {
  CHECK_THAT(fileErrorOf("bad_empty_obj.yaml"), StartsWith(kData + "bad_empty_obj.yaml:3:18: meshes.nothing.obj: "));
  CHECK_THAT(fileErrorOf("bad_empty_obj.yaml"), Contains("no triangles"));
}

TEST_CASE("bad primitive parameters are reported at the parameter", "[loader]") {
  CHECK_THAT(yamlErrorOf("meshes:\n  s: {sphere: {radius: 0}}\n"), StartsWith("t.yaml:2:24: meshes.s.sphere.radius: must be greater than 0"));
  CHECK_THAT(yamlErrorOf("meshes:\n  s: {sphere: {slices: 2}}\n"), StartsWith("t.yaml:2:24: meshes.s.sphere.slices: 2 is outside the allowed range [3, 1024]"));
  CHECK_THAT(yamlErrorOf("meshes:\n  s: {prism: {sides: 100000000}}\n"), StartsWith("t.yaml:2:22: meshes.s.prism.sides:"));
  CHECK_THAT(yamlErrorOf("meshes:\n  t: {torus: {major_radius: 1, minor_radius: 2}}\n"),
             StartsWith("t.yaml:2:46: meshes.t.torus: minor_radius must be less than major_radius"));
  CHECK_THAT(yamlErrorOf("meshes:\n  c: {cube: {}}\n"), StartsWith("t.yaml:2:7: unknown key 'cube' in meshes.c"));
  CHECK_THAT(yamlErrorOf("meshes:\n  c: {box: {}, sphere: {}}\n"), StartsWith("t.yaml:2:6: meshes.c: expected one of box, sphere"));
}

TEST_CASE("a scale of zero is a singular transform, reported at the scale", "[loader]") {
  CHECK_THAT(yamlErrorOf(kBoxScene + "  - {mesh: box, scale: [1, 0, 1]}\n"),
             StartsWith("t.yaml:5:24: nodes.1.scale: a scale of 0 flattens the node: the transform is singular"));
  CHECK_THAT(yamlErrorOf(kBoxScene + "  - {mesh: box, scale: 0}\n"), StartsWith("t.yaml:5:24: nodes.1.scale:"));
}

TEST_CASE("a singular or non-affine matrix is reported at the matrix", "[loader]") {
  // Columns 1 and 2 are equal: determinant 0.
  CHECK_THAT(yamlErrorOf(kBoxScene + "  - {mesh: box, matrix: [1, 1, 0, 0,  0, 0, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1]}\n"),
             StartsWith("t.yaml:5:25: nodes.1.matrix: the matrix is singular"));
  // A tiny but regular matrix is fine: the test is relative to the column lengths.
  CHECK(yamlErrorOf(kBoxScene + "  - {mesh: box, matrix: [1e-9, 0, 0, 0,  0, 1e-9, 0, 0,  0, 0, 1e-9, 0,  0, 0, 0, 1]}\n") ==
        "(no error)");
  CHECK_THAT(yamlErrorOf(kBoxScene + "  - {mesh: box, matrix: [1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 1, 1]}\n"),
             StartsWith("t.yaml:5:25: nodes.1.matrix: the last row must be 0 0 0 1"));
  CHECK_THAT(yamlErrorOf(kBoxScene + "  - {mesh: box, translate: [1, 0, 0], matrix: [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]}\n"),
             StartsWith("t.yaml:5:47: nodes.1.matrix: give either matrix or translate/rotate/scale"));
}

TEST_CASE("a rotation needs an axis that is not zero and an angle, or euler angles", "[loader]") {
  CHECK_THAT(yamlErrorOf(kBoxScene + "  - {mesh: box, rotate: {axis: [0, 0, 0], angle: 30}}\n"),
             StartsWith("t.yaml:5:32: nodes.1.rotate.axis: the rotation axis must not be the zero vector"));
  CHECK_THAT(yamlErrorOf(kBoxScene + "  - {mesh: box, rotate: {axis: [0, 1, 0]}}\n"),
             StartsWith("t.yaml:5:25: nodes.1.rotate: a rotation about an axis needs both axis and angle"));
}

TEST_CASE("a node naming a mesh or material that does not exist is an error with a suggestion", "[loader]") {
  CHECK_THAT(yamlErrorOf(kBoxScene + "  - {mesh: bx}\n"), StartsWith("t.yaml:5:12: nodes.1.mesh: no mesh named 'bx'; did you mean 'box'?"));
  CHECK_THAT(yamlErrorOf(kBoxScene + "  - {mesh: box, material: glass}\n"),
             StartsWith("t.yaml:5:27: nodes.1.material: no material named 'glass'"));
  CHECK_THAT(yamlErrorOf(kBoxScene + "  - {mesh: box, children: [{shadow_proxy: boxx}]}\n"),
             StartsWith("t.yaml:5:43: nodes.1.children.0.shadow_proxy: no mesh named 'boxx'; did you mean 'box'?"));
}

TEST_CASE("a camera whose up vector is parallel to the view direction is an error at up", "[loader]") {
  CHECK_THAT(yamlErrorOf("camera:\n  eye: [0, 5, 0]\n  target: [0, 0, 0]\n  up: [0, 2, 0]\n"),
             StartsWith("t.yaml:4:7: camera.up: the up vector is parallel to the view direction"));
  // Not written: the default up (0, 1, 0) is reported at the camera section.
  CHECK_THAT(yamlErrorOf("camera:\n  eye: [0, 5, 0]\n  target: [0, -1, 0]\n"),
             StartsWith("t.yaml:1:1: camera.up: the up vector is parallel"));
}

TEST_CASE("a camera whose eye equals its target is an error", "[loader]") {
  CHECK_THAT(yamlErrorOf("camera:\n  eye: [1, 2, 3]\n  target: [1, 2, 3]\n"),
             StartsWith("t.yaml:3:11: camera: eye and target are the same point"));
}

TEST_CASE("an image of zero size is an error at the side that is zero", "[loader]") {
  CHECK_THAT(yamlErrorOf("image:\n  width: 640\n  height: 0\n"), StartsWith("t.yaml:3:11: image.height: 0 is outside the allowed range [1, 16384]"));
  CHECK_THAT(yamlErrorOf("image: {width: 0}\n"), StartsWith("t.yaml:1:16: image.width: 0 is outside the allowed range [1, 16384]"));
  CHECK_THAT(yamlErrorOf("image: {width: -5}\n"), StartsWith("t.yaml:1:16: image.width: -5 is outside the allowed range [1, 16384]"));
  // A value far beyond the limit names the documented range, not an internal one.
  CHECK_THAT(yamlErrorOf("image: {width: 300000}\n"), StartsWith("t.yaml:1:16: image.width: 300000 is outside the allowed range [1, 16384]"));
}

TEST_CASE("an image too large to allocate is an error", "[loader]") {
  CHECK_THAT(yamlErrorOf("image: {width: 16385, height: 10}\n"), StartsWith("t.yaml:1:16: image.width: 16385 is outside the allowed range [1, 16384]"));
  // Each side allowed, but 16384 x 8192 = 2^27 pixels are more than 2^26.
  CHECK_THAT(yamlErrorOf("image:\n  width: 16384\n  height: 8192\n"), StartsWith("t.yaml:3:11: image: 16384 x 8192 pixels are more than"));
  CHECK(yamlErrorOf("image: {width: 16384, height: 4096}\n" + kBoxScene) == "(no error)");
}

TEST_CASE("a near plane that is not positive is an error", "[loader]") {
  CHECK_THAT(yamlErrorOf("camera:\n  near: -0.1\n"), StartsWith("t.yaml:2:9: camera.near: the near plane distance must be greater than 0"));
  CHECK_THAT(yamlErrorOf("camera: {near: 0}\n"), StartsWith("t.yaml:1:16: camera.near: the near plane distance must be greater than 0"));
}

TEST_CASE("a near plane at or beyond the far plane is an error at far", "[loader]") {
  CHECK_THAT(yamlErrorOf("camera:\n  near: 10\n  far: 5\n"), StartsWith("t.yaml:3:8: camera: near (10) must be less than far (5)"));
  CHECK_THAT(yamlErrorOf("camera: {near: 5, far: 5}\n"), StartsWith("t.yaml:1:24: camera: near (5) must be less than far (5)"));
}

TEST_CASE("an enum value that is not one of the names is an error with a suggestion", "[loader]") {
  CHECK_THAT(yamlErrorOf("lights: [{type: sun}]\n"), StartsWith("t.yaml:1:17: lights.0.type: 'sun' is not one of point, directional, spot"));
  CHECK_THAT(yamlErrorOf("image: {depth: float16}\n"), StartsWith("t.yaml:1:16: image.depth: 'float16' is not one of float32, unorm24"));
  CHECK_THAT(yamlErrorOf("generator: {type: forest}\n"), StartsWith("t.yaml:1:19: generator.type: 'forest' is not one of room, pumpkins, city, outdoor"));
}

TEST_CASE("values outside their range are errors at the value", "[loader]") {
  CHECK_THAT(yamlErrorOf("camera: {fov: 180}\n"), StartsWith("t.yaml:1:15: camera.fov: the vertical field of view must lie strictly between 0 and 180"));
  CHECK_THAT(yamlErrorOf("lights: [{spot_cutoff: 95}]\n"), StartsWith("t.yaml:1:24: lights.0.spot_cutoff: 95 is outside the allowed range [0, 90]"));
  CHECK_THAT(yamlErrorOf("lights: [{range: 0}]\n"), StartsWith("t.yaml:1:18: lights.0.range: must be greater than 0"));
  CHECK_THAT(yamlErrorOf("lights: [{type: directional, direction: [0, 0, 0]}]\n"),
             StartsWith("t.yaml:1:41: lights.0.direction: a direction must not be the zero vector"));
  CHECK_THAT(yamlErrorOf("lights: [{attenuation: [0, 0, 0]}]\n"), StartsWith("t.yaml:1:24: lights.0.attenuation:"));
  CHECK_THAT(yamlErrorOf("shadow: {map_size: 100000}\n"), StartsWith("t.yaml:1:20: shadow.map_size: 100000 is outside the allowed range"));
  CHECK_THAT(yamlErrorOf("shadow: {focus_region: 1}\n"), StartsWith("t.yaml:1:24: shadow.focus_region:"));
  CHECK_THAT(yamlErrorOf("generator: {type: city, houses: 0}\n"), StartsWith("t.yaml:1:33: generator.houses: 0 is outside the allowed range"));
  CHECK_THAT(yamlErrorOf("generator: {type: city, framed_houses: -1}\n"),
             StartsWith("t.yaml:1:40: generator.framed_houses: -1 is outside the allowed range [0, 4096]"));
}

TEST_CASE("a file that is not one map of sections is an error", "[loader]") {
  CHECK_THAT(yamlErrorOf(""), StartsWith("t.yaml: the file holds no YAML document"));
  CHECK_THAT(yamlErrorOf("- 1\n- 2\n"), StartsWith("t.yaml:1:1: a scene file is a map of sections"));
  // Reported at the "---" that starts the second document.
  CHECK_THAT(yamlErrorOf("camera: {}\n---\ncamera: {}\n"), StartsWith("t.yaml:2:1: a scene file holds one YAML document"));
  CHECK_THAT(yamlErrorOf("[1, 2]: x\n"), StartsWith("t.yaml:1:1: a key must be a plain name"));
}

TEST_CASE("an alias that contains itself is stopped by the nesting limit, not the stack", "[loader]") {
  CHECK_THAT(yamlErrorOf("camera: &a {eye: *a}\n"), Contains("nested more than 64 levels deep"));
}

TEST_CASE("aliases that expand exponentially are stopped by the value limit", "[loader]") {
  std::string yaml = "a0: &a0 [1, 1, 1, 1, 1, 1, 1, 1, 1, 1]\n";
  for (int i = 1; i <= 7; ++i) {
    const std::string prev = "*a" + std::to_string(i - 1);
    yaml += "a" + std::to_string(i) + ": &a" + std::to_string(i) + " [" + prev + ", " + prev + ", " + prev + ", " +
            prev + ", " + prev + ", " + prev + ", " + prev + ", " + prev + ", " + prev + ", " + prev + "]\n";
  }
  CHECK_THAT(yamlErrorOf(yaml), Contains("more than 1000000 values"));
}

TEST_CASE("a -D override with an unknown key is reported on the command line", "[loader]") {
  LoadOptions o;
  o.overrides = {"camera.near=0.01", "camera.nera=0.01"};
  // The second -D (line 2), column 8 where "nera" starts.
  CHECK_THAT(yamlErrorOf(kBoxScene, o), StartsWith("<command line>:2:8: unknown key 'nera' in camera"));
  CHECK_THAT(yamlErrorOf(kBoxScene, o), Contains("did you mean 'near'?"));
  o.overrides = {"shadw.method=zfail"};
  CHECK_THAT(yamlErrorOf(kBoxScene, o), StartsWith("<command line>:1:1: -D shadw: cannot override 'shadw'"));
  // A mesh's source can be overridden (tests/scene/override_nodes_test.cpp), its kind checked as in a file.
  o.overrides = {"meshes.box.box.size=[1, 1, 1]"};
  CHECK(yamlErrorOf(kBoxScene, o) == "(no error)");
  o.overrides = {"meshes.box.box.radius=1"};
  CHECK_THAT(yamlErrorOf(kBoxScene, o), StartsWith("<command line>:1:16: unknown key 'radius' in meshes.box.box"));
  o.overrides = {"lights.3.range=5"};
  CHECK_THAT(yamlErrorOf(kBoxScene, o), StartsWith("<command line>:1:8: lights.3: the scene has 0 light(s)"));
  o.overrides = {"camera.eye.x=5"};
  CHECK_THAT(yamlErrorOf(kBoxScene, o), StartsWith("<command line>:1:12: -D camera.eye.x: expected a key like camera.near"));
}

TEST_CASE("a -D that renames a light to a name with '.' is an error at the value, as in the file", "[loader]") {
  const std::string scene = kBoxScene + "lights:\n  - {name: bulb}\n";
  LoadOptions o;
  o.overrides = {"lights.0.name=a.b"};
  CHECK_THAT(yamlErrorOf(scene, o), StartsWith("<command line>:1:15: lights.0.name: the name 'a.b' must not contain '.'"));
  o.overrides = {"lights.bulb.name=lamp"};
  CHECK(yamlErrorOf(scene, o) == "(no error)");
  CHECK_THAT(yamlErrorOf(kBoxScene + "lights:\n  - {name: a.b}\n"), Contains("the name 'a.b' must not contain '.'"));
}

// The shadow technique's names are the registry's (src/shadow), which the scene library does not
// know: the loader keeps the name and where it was written, and the registry reports an unknown
// one there (tests/shadow/technique_registry_test.cpp checks the messages).
TEST_CASE("the loader keeps the shadow technique's name and where the file or a -D wrote it", "[loader]") {
  const Scene file = loadSceneFromString("shadow:\n  method: zfial\n", "t.yaml");
  CHECK(file.shadow.method == "zfial");
  CHECK(formatLocation(file.shadow.methodAt) == "t.yaml:2:11");
  LoadOptions o;
  o.overrides = {"shadow.method=zfial"};
  const Scene overridden = loadSceneFromString(kBoxScene, "t.yaml", o);
  CHECK(overridden.shadow.method == "zfial");
  CHECK(formatLocation(overridden.shadow.methodAt) == "<command line>:1:15");
  // Still a name: not empty, not a list.
  CHECK_THAT(yamlErrorOf("shadow: {method: ''}\n"), StartsWith("t.yaml:1:18: shadow.method: must not be empty"));
  CHECK_THAT(yamlErrorOf("shadow: {method: [zfail]}\n"), StartsWith("t.yaml:1:18: shadow.method:"));
}

TEST_CASE("a -D override with an unparsable value is reported at the value on the command line", "[loader]") {
  LoadOptions o;
  o.overrides = {"camera.near=abc"};
  CHECK_THAT(yamlErrorOf(kBoxScene, o), StartsWith("<command line>:1:13: camera.near: expected a number, got 'abc'"));
  o.overrides = {"camera.eye=[1, 2"};
  CHECK_THAT(yamlErrorOf(kBoxScene, o), StartsWith("<command line>:1:12: YAML syntax error"));
  o.overrides = {"camera.near"};
  CHECK_THAT(yamlErrorOf(kBoxScene, o), StartsWith("<command line>:1:1: -D expects key=value"));
  o.overrides = {"camera..near=1"};
  CHECK_THAT(yamlErrorOf(kBoxScene, o), StartsWith("<command line>:1:8: -D camera..near=1: empty name in the key"));
  // A value that is valid alone but makes the scene invalid is reported where it was given.
  o.overrides = {"camera.far=0.01"};
  CHECK_THAT(yamlErrorOf(kBoxScene, o), StartsWith("<command line>:1:12: camera: near (0.1) must be less than far (0.01)"));
}

TEST_CASE("a stray ',' where a document starts is a syntax error, not yaml-cpp's endless LoadAll loop", "[loader]") {
  // Found by fuzz/run.sh: yaml-cpp 0.7's LoadAll never returns on it (yaml-cpp issue #1040).
  CHECK_THAT(yamlErrorOf(","), StartsWith("t.yaml:1:1: YAML syntax error: unexpected token"));
  CHECK_THAT(yamlErrorOf("\n,\n"), StartsWith("t.yaml:2:1: YAML syntax error: unexpected token"));
  LoadOptions o;
  o.overrides = {"camera.near=,"};
  CHECK_THAT(yamlErrorOf(kBoxScene, o), StartsWith("<command line>:1:13: YAML syntax error: unexpected token"));
}

TEST_CASE("tessellation that would not fit in memory is an error at the primitive", "[loader][slow]") {
  CHECK_THAT(yamlErrorOf("meshes:\n  s: {sphere: {slices: 1024, stacks: 1024}}\n"),
             StartsWith("t.yaml:2:15: meshes.s.sphere: 1024 x 1024 segments are more than 262144 cells"));
  CHECK_THAT(yamlErrorOf("meshes:\n  t: {torus: {major_segments: 1000, minor_segments: 1000}}\n"),
             StartsWith("t.yaml:2:14: meshes.t.torus: 1000 x 1000 segments"));
  // 512 x 512 cells are 2 * 512 * 511 = 523264 triangles; 17 of them pass 2^23.
  std::string yaml = "meshes:\n";
  for (int i = 0; i < 17; ++i) yaml += "  s" + std::to_string(i) + ": {sphere: {slices: 512, stacks: 512}}\n";
  CHECK_THAT(yamlErrorOf(yaml), StartsWith("t.yaml:18:3: meshes: more than 8388608 triangles in all, up to 's16'"));
}

TEST_CASE("a scene file that does not exist or is a folder is an error naming the path", "[loader]") {
  CHECK_THAT(fileErrorOf("no_such_scene.yaml"), StartsWith(kData + "no_such_scene.yaml: scene file does not exist"));
  CHECK_THAT(fileErrorOf(""), StartsWith(kData + ": scene file is not a regular file"));
}

TEST_CASE("a scene file that is a FIFO or larger than the limit is refused before it is read", "[loader]") {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("shadowref_scene_file_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path fifo = dir / "fifo.yaml";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  // Reading a FIFO with no writer would block for ever; it must be refused at once.
  CHECK_THROWS_WITH(loadScene(fifo.string()), Catch::Matchers::Contains("scene file is not a regular file"));
  // A sparse file one byte over the limit: its size is known before anything is read.
  const fs::path huge = dir / "huge.yaml";
  { std::ofstream(huge) << "camera: {}\n"; }
  fs::resize_file(huge, kMaxSceneFileBytes + 1);
  CHECK_THROWS_WITH(loadScene(huge.string()),
                    Catch::Matchers::Contains("scene file has " + std::to_string(kMaxSceneFileBytes + 1) +
                                              " bytes, more than the limit of " + std::to_string(kMaxSceneFileBytes)));
  fs::remove_all(dir);
}
