// Crease normals in near-linear time: the grouped computation gives bit for bit what the plain
// per-corner rule gives, and positions shared by hundreds of thousands of corners finish.
#include <cmath>
#include <cstring>
#include <unordered_map>

#include <catch2/catch.hpp>

#include "scene/adjacency.h"
#include "scene/primitives.h"

using namespace shadowref;

namespace {

// The rule written out plainly, O(corners x corners at the same position): each corner averages
// the area vectors of all triangles at its position (bit-equal, -0.0 == +0.0) whose unit normal is
// within the crease angle of its own, in triangle order; equal (position, normal) share a vertex.
Mesh referenceCrease(Mesh mesh, double creaseDegrees) {
  const double cosCrease = std::cos(glm::radians(creaseDegrees));
  const size_t count = mesh.triangles.size();
  std::vector<glm::dvec3> area(count), unit(count);
  for (size_t t = 0; t < count; ++t) {
    const glm::uvec3 tri = mesh.triangles[t];
    area[t] = glm::cross(mesh.positions[tri.y] - mesh.positions[tri.x], mesh.positions[tri.z] - mesh.positions[tri.x]);
    unit[t] = glm::length(area[t]) > 0.0 ? glm::normalize(area[t]) : glm::dvec3(0.0);
  }
  std::vector<glm::dvec3> positions, normals;
  std::vector<glm::uvec3> triangles(count);
  for (size_t t = 0; t < count; ++t)
    for (int i = 0; i < 3; ++i) {
      const glm::dvec3 p = mesh.positions[mesh.triangles[t][i]];
      glm::dvec3 n(0.0);
      for (size_t u = 0; u < count; ++u)
        for (int j = 0; j < 3; ++j)
          if (mesh.positions[mesh.triangles[u][j]] == p && glm::dot(unit[u], unit[t]) >= cosCrease) n += area[u];
      n = glm::length(n) > 0.0 ? glm::normalize(n) : glm::dvec3(0.0, 1.0, 0.0);
      size_t v = 0;
      while (v < positions.size() && !(positions[v] == p && normals[v] == n)) ++v;
      if (v == positions.size()) positions.push_back(p), normals.push_back(n);
      triangles[t][i] = static_cast<uint32_t>(v);
    }
  mesh.positions = positions;
  mesh.normals = normals;
  mesh.triangles = triangles;
  return mesh;
}

bool bitEqual(const glm::dvec3& a, const glm::dvec3& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// A fan of `sides` triangles around (0, 0, 0), its rim on the unit circle at height `rimZ`.
Mesh fan(int sides, double rimZ) {
  Mesh m;
  m.positions.push_back(glm::dvec3(0.0));
  for (int i = 0; i < sides; ++i) {
    const double a = 2.0 * M_PI * i / sides;
    m.positions.push_back({std::cos(a), std::sin(a), rimZ});
  }
  for (int i = 0; i < sides; ++i)
    m.triangles.push_back(glm::uvec3(0, 1 + i, 1 + (i + 1) % sides));
  return m;
}

}  // namespace

TEST_CASE("grouped crease normals equal the plain per-corner rule bit for bit", "[mesh][crease]") {
  for (Mesh m : {makeSphere(1.0, 24, 12), makeCone(0.5, 1.0, 32), makeTorus(1.0, 0.25, 24, 12), makeBox({1, 2, 3})}) {
    m.normals.clear();
    for (double crease : {40.0, 10.0, 100.0}) {
      const Mesh expected = referenceCrease(m, crease);
      Mesh actual = m;
      computeCreaseNormals(actual, crease);
      REQUIRE(actual.positions.size() == expected.positions.size());
      REQUIRE(actual.triangles == expected.triangles);
      for (size_t i = 0; i < actual.positions.size(); ++i) {
        CHECK(bitEqual(actual.positions[i], expected.positions[i]));
        CHECK(bitEqual(actual.normals[i], expected.normals[i]));
      }
    }
  }
}

TEST_CASE("a flat disc of 200 000 triangles gets one upward normal per position", "[mesh][crease][slow]") {
  constexpr int kSides = 200000;
  Mesh m = fan(kSides, 0.0);
  computeCreaseNormals(m, 40.0);
  // Every corner at a position sees the same triangles, all within the crease angle: one vertex each.
  CHECK(m.positions.size() == kSides + 1);
  double worst = 0.0;
  for (const glm::dvec3& n : m.normals) worst = std::max(worst, glm::length(n - glm::dvec3(0.0, 0.0, 1.0)));
  CHECK(worst < 1e-15);
}

TEST_CASE("a million corners at one apex with a million different normals finish smooth", "[mesh][crease][slow]") {
  // A shallow cone: its sides lean 0.57 degrees, so every pair of them is within the crease angle
  // and the apex normal is the mean of all, straight up by symmetry. The plain rule would compare
  // 10^12 pairs at the apex.
  constexpr int kSides = 1000000;
  Mesh m = fan(kSides, -0.01);
  computeCreaseNormals(m, 40.0);
  size_t apexVertices = 0;
  for (size_t i = 0; i < m.positions.size(); ++i)
    if (m.positions[i] == glm::dvec3(0.0)) {
      ++apexVertices;
      CHECK(glm::length(m.normals[i] - glm::dvec3(0.0, 0.0, 1.0)) < 1e-9);
    }
  CHECK(apexVertices == 1);
  CHECK(m.positions.size() == kSides + 1);
}
