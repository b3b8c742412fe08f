// A mesh's `normals: flat | smooth` and `crease_angle` keys, on a tetrahedron without normals whose
// face normals are worked out by hand: (0, 0, -1), (0, -1, 0), (-1, 0, 0) and (1, 1, 1)/√3. The
// axis faces' normals are 90° apart; each is acos(-1/√3) ≈ 125.3° from the slanted face's (the
// faces meet at 54.7°). Each face's area vector (the cross product of two edges) has length 1, the
// slanted one √3.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "scene/scene_loader.h"

using namespace shadowref;
using Catch::Matchers::StartsWith;

namespace {

const Mesh& tetra(const std::string& keys, Scene& holder) {
  holder = loadSceneFromString("meshes:\n  t: {obj: tests/data/meshes/tetra_no_normals.obj" + keys + "}\n"
                               "nodes:\n  - {mesh: t}\n",
                               "t.yaml");
  return *holder.meshes.at(0);
}

// The normals of the render vertices at position p, sorted, each rounded to 1e-12.
std::vector<glm::dvec3> normalsAt(const Mesh& m, const glm::dvec3& p) {
  std::vector<glm::dvec3> out;
  for (size_t i = 0; i < m.positions.size(); ++i)
    if (m.positions[i] == p) {
      glm::dvec3 n = glm::round(m.normals[i] * 1e12) / 1e12;
      if (std::find(out.begin(), out.end(), n) == out.end()) out.push_back(n);
    }
  std::sort(out.begin(), out.end(), [](const glm::dvec3& a, const glm::dvec3& b) {
    return a.x != b.x ? a.x < b.x : a.y != b.y ? a.y < b.y : a.z < b.z;
  });
  return out;
}

glm::dvec3 rounded(glm::dvec3 v) { return glm::round(glm::normalize(v) * 1e12) / 1e12; }

std::string errorOf(const std::string& keys) {
  try {
    Scene s;
    tetra(keys, s);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST_CASE("normals: flat gives each triangle its face normal", "[loader][normals]") {
  Scene s;
  const Mesh& m = tetra(", normals: flat", s);
  REQUIRE(m.triangles.size() == 4);
  CHECK(m.positions.size() == 12);  // three vertices of its own per triangle
  const glm::dvec3 expected[4] = {{0, 0, -1}, {0, -1, 0}, {-1, 0, 0}, glm::dvec3(1, 1, 1) / std::sqrt(3.0)};
  for (size_t t = 0; t < 4; ++t)
    for (int c = 0; c < 3; ++c) {
      INFO("triangle " << t << " corner " << c);
      CHECK(rounded(m.normals[m.triangles[t][c]]) == rounded(expected[t]));
    }
}

TEST_CASE("normals: smooth averages the faces within the crease angle", "[loader][normals]") {
  const glm::dvec3 corner(1, 0, 0);  // where the faces (0, 0, -1), (0, -1, 0) and the slanted one meet
  Scene s;
  // 40°, the default: no two normals are that close; every corner keeps its face's normal.
  CHECK(normalsAt(tetra(", normals: smooth", s), corner) ==
        std::vector<glm::dvec3>{rounded({0, -1, 0}), rounded({0, 0, -1}), rounded({1, 1, 1})});
  // 100°: the two axis faces take each other ((0, 0, -1) + (0, -1, 0)), not the slanted face.
  CHECK(normalsAt(tetra(", normals: smooth, crease_angle: 100", s), corner) ==
        std::vector<glm::dvec3>{rounded({0, -1, -1}), rounded({1, 1, 1})});
  // 130°: all three faces everywhere: (0, 0, -1) + (0, -1, 0) + (1, 1, 1) = (1, 0, 0), one vertex.
  CHECK(normalsAt(tetra(", normals: smooth, crease_angle: 130", s), corner) == std::vector<glm::dvec3>{rounded({1, 0, 0})});
}

TEST_CASE("normals: without the key a file without normals gets the 40-degree crease normals", "[loader][normals]") {
  Scene a, b;
  const Mesh& plain = tetra("", a);
  const Mesh& smooth = tetra(", normals: smooth, crease_angle: 40", b);
  CHECK(plain.positions == smooth.positions);
  CHECK(plain.normals == smooth.normals);
  CHECK(plain.triangles == smooth.triangles);
}

TEST_CASE("normals: bad values are errors at the key", "[loader][normals]") {
  CHECK_THAT(errorOf(", normals: round"), StartsWith("t.yaml:2:61: meshes.t.normals: 'round' is not one of flat, smooth"));
  CHECK_THAT(errorOf(", crease_angle: 30"),
             StartsWith("t.yaml:2:66: meshes.t.crease_angle: applies only with 'normals: smooth'"));
  CHECK_THAT(errorOf(", normals: flat, crease_angle: 30"),
             StartsWith("t.yaml:2:81: meshes.t.crease_angle: applies only with 'normals: smooth'"));
  CHECK_THAT(errorOf(", normals: smooth, crease_angle: 190"), StartsWith("t.yaml:2:"));
}
