#include <string>

#include <catch2/catch.hpp>

#include "scene/mesh_import.h"
#include "scene/scene_error.h"
#include "support/errors.h"
#include "mesh_checks.h"

using namespace shadowref;
using shadowref::testing::sceneErrorOf;

namespace {

std::string meshFile(const std::string& name) {
  return std::string(SHADOWREF_SOURCE_DIR) + "/tests/data/meshes/" + name;
}

}  // namespace

TEST_CASE("OBJ cube with split vertices welds to a closed mesh of 8 vertices and 18 edges", "[mesh]") {
  const Mesh m = loadObj(meshFile("cube_split.obj"));
  CHECK(m.name == "cube_split");
  CHECK(m.positions.size() == 24);  // one render vertex per (position, normal) pair
  CHECK(m.triangles.size() == 12);
  CHECK(m.weldedPositions.size() == 8);
  CHECK(m.edges.size() == 18);
  shadowref::testing::requireClosedOutward(m);
  shadowref::testing::requireNormalsAgreeWithWinding(m);
  CHECK(signedVolume(m) == 8.0);
  CHECK(m.bounds.min == glm::dvec3(-1.0));
  CHECK(m.bounds.max == glm::dvec3(1.0));
}

TEST_CASE("OBJ without normals gets computed ones and relative indices resolve", "[mesh]") {
  const Mesh m = loadObj(meshFile("tetra_no_normals.obj"));
  shadowref::testing::requireClosedOutward(m);
  shadowref::testing::requireNormalsAgreeWithWinding(m);
  CHECK(signedVolume(m) == Approx(1.0 / 6.0));
}

TEST_CASE("OBJ index out of range is reported at its line and column", "[mesh]") {
  const std::string path = meshFile("bad_index.obj");
  const SceneError e = sceneErrorOf([&] { loadObj(path); });
  CHECK(e.where().file == path);
  CHECK(e.where().line == 8);
  CHECK(e.where().column == 7);
  CHECK(std::string(e.what()) == path + ":8:7: " + e.message());
  CHECK(e.message().find("out of range") != std::string::npos);
}

TEST_CASE("OBJ relative index before the first vertex is reported at its line", "[mesh]") {
  const SceneError e = sceneErrorOf([&] { loadObj(meshFile("negative_index.obj")); });
  CHECK(e.where().line == 5);
  CHECK(e.where().column == 9);
}

TEST_CASE("OBJ NaN coordinate is reported at its line and column", "[mesh]") {
  const SceneError e = sceneErrorOf([&] { loadObj(meshFile("nan_vertex.obj")); });
  CHECK(e.where().line == 3);
  CHECK(e.where().column == 5);
  CHECK(e.message().find("NaN") != std::string::npos);
}

TEST_CASE("OBJ without faces is rejected as having no triangles", "[mesh]") {
  const SceneError e = sceneErrorOf([&] { loadObj(meshFile("empty.obj")); });
  CHECK(e.message().find("no triangles") != std::string::npos);
}

TEST_CASE("missing mesh files give a SceneError naming the file", "[mesh]") {
  const std::string obj = meshFile("does_not_exist.obj");
  const SceneError e = sceneErrorOf([&] { loadObj(obj); });
  CHECK(e.where().file == obj);
  CHECK(e.message() == "mesh file not found");
  const std::string gltf = meshFile("does_not_exist.gltf");
  CHECK(sceneErrorOf([&] { loadGltf(gltf); }).where().file == gltf);
  CHECK(sceneErrorOf([&] { loadObj(meshFile("")); }).message() == "mesh file is not a regular file");
}

TEST_CASE("a tiny glTF with an embedded buffer loads with its node transforms", "[mesh]") {
  const Mesh m = loadGltf(meshFile("tetra.gltf"));
  shadowref::testing::requireClosedOutward(m);
  shadowref::testing::requireNormalsAgreeWithWinding(m);
  // Unit tetrahedron scaled by 2 in the child node, moved by (1, 2, 3) in its parent.
  CHECK(m.bounds.min == glm::dvec3(1.0, 2.0, 3.0));
  CHECK(m.bounds.max == glm::dvec3(3.0, 4.0, 5.0));
  CHECK(signedVolume(m) == Approx(8.0 / 6.0));
}

TEST_CASE("glTF accessor reaching outside its buffer is rejected", "[mesh]") {
  const SceneError e = sceneErrorOf([&] { loadGltf(meshFile("tetra_bad_accessor.gltf")); });
  CHECK(e.where().file == meshFile("tetra_bad_accessor.gltf"));
}

TEST_CASE("glTF JSON syntax error keeps the parser's line and column", "[mesh]") {
  const SceneError e = sceneErrorOf([&] { loadGltf(meshFile("broken.gltf")); });
  CHECK(e.where().line == 3);
  CHECK(e.where().column > 0);
}
