// Hostile mesh files: every one is rejected with a located message (or, where what it attacks is
// never read, loads), and nothing crashes, hangs or allocates without bound. The files of
// tests/data/hostile/ are small; inputs that only hurt by their size are written here at run time.
// Expected line:column values were read off the files by hand.
#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <catch2/catch.hpp>

#include "../image/temp_dir.h"
#include "scene/mesh_import.h"
#include "scene/scene_loader.h"
#include "scene/scene_error.h"
#include "support/errors.h"
#include "mesh_checks.h"

using namespace shadowref;
using shadowref::testing::sceneErrorOf;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using shadowref::test::TempDir;

namespace {

const std::string kHostile = std::string(SHADOWREF_SOURCE_DIR) + "/tests/data/hostile/";
const std::string kMeshes = std::string(SHADOWREF_SOURCE_DIR) + "/tests/data/meshes/";

SceneError gltfError(const std::string& path) { return sceneErrorOf([&] { loadGltf(path); }); }
SceneError objError(const std::string& path) { return sceneErrorOf([&] { loadObj(path); }); }

void write(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

void requireAt(const SceneError& e, const std::string& file, int line, int column) {
  INFO(e.what());
  CHECK(e.where().file == file);
  CHECK(e.where().line == line);
  CHECK(e.where().column == column);
  CHECK(std::string(e.what()) == file + ":" + std::to_string(line) + ":" + std::to_string(column) + ": " + e.message());
}

// tetra.gltf with its buffer in a file `bin` of `binBytes` bytes (its first 72 are the tetrahedron).
void writeTetraWithExternalBuffer(const TempDir& dir, const std::string& bin, size_t binBytes) {
  std::ifstream in(kMeshes + "tetra.gltf");
  std::string text((std::istreambuf_iterator<char>(in)), {});
  const size_t begin = text.find("data:"), end = text.find('"', begin);
  text.replace(begin, end - begin, bin);
  write(dir.file("tetra.gltf"), text);
  if (binBytes) {
    // The 72 bytes of the embedded buffer, written out, then zeros.
    const std::string b64 = "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAAAIA/AAACAAEAAAABAAMAAAADAAIAAQACAAMA";
    std::string bytes;
    auto value = [](char c) { return c == '/' ? 63 : c == '+' ? 62 : c >= 'a' ? c - 'a' + 26 : c >= 'A' ? c - 'A' : c - '0' + 52; };
    for (size_t i = 0; i < b64.size(); i += 4) {
      const int v = value(b64[i]) << 18 | value(b64[i + 1]) << 12 | value(b64[i + 2]) << 6 | value(b64[i + 3]);
      bytes += {static_cast<char>(v >> 16), static_cast<char>((v >> 8) & 0xff), static_cast<char>(v & 0xff)};
    }
    REQUIRE(bytes.size() == 72);
    bytes.resize(binBytes, '\0');
    write(dir.file(bin), bytes);
  }
}

}  // namespace

// --- glTF: locations from our own knowledge, never from a message ---------------------------------

TEST_CASE("a glTF buffer name that reads like a location does not forge the error's location", "[mesh][hostile]") {
  const std::string path = kHostile + "gltf_forged_location.gltf";
  const SceneError e = gltfError(path);
  requireAt(e, path, 49, 11);  // the uri's value
  CHECK_THAT(e.message(), Contains("not found"));
}

TEST_CASE("a glTF buffer name of 100 000 characters is reported, not scanned by a regex", "[mesh][hostile]") {
  const std::string path = kHostile + "gltf_long_name.gltf";
  const SceneError e = gltfError(path);
  requireAt(e, path, 49, 11);
  CHECK_THAT(e.message(), Contains("cannot be read"));
}

TEST_CASE("glTF JSON syntax errors are located at the offending character", "[mesh][hostile]") {
  const std::string path = kMeshes + "broken.gltf";
  const SceneError e = gltfError(path);
  requireAt(e, path, 3, 15);  // '  "scenes": [ ,' -- the ','
  CHECK(e.message() == "JSON syntax error at ','");
}

TEST_CASE("glTF JSON nested deeper than 64 is rejected at the bracket that goes too deep", "[mesh][hostile]") {
  const std::string path = kHostile + "gltf_deep_nesting.gltf";
  std::ifstream in(path);
  std::string text((std::istreambuf_iterator<char>(in)), {});
  // The root object is level 1: the 64th '[' of extras opens level 65.
  const int column = static_cast<int>(text.find("\"extras\": [") + 10 + 63) + 1;
  const SceneError e = gltfError(path);
  requireAt(e, path, 1, column);
  CHECK(e.message() == "JSON nested more than 64 deep");
}

// --- glTF: overflow-safe bounds ---------------------------------------------------------------------

TEST_CASE("a glTF accessor byteOffset near 2^64 cannot wrap around the bounds check", "[mesh][hostile]") {
  const std::string path = kHostile + "gltf_huge_byte_offset.gltf";
  const SceneError e = gltfError(path);
  requireAt(e, path, 80, 18);
  CHECK(e.message() == "POSITION: accessor reaches outside its buffer view of 48 bytes");
}

TEST_CASE("a glTF accessor reaching past its buffer view is located at the accessor", "[mesh][hostile]") {
  // count 40 of 2-byte indices in a 24-byte view; the accessor has no byteOffset written.
  const std::string path = kMeshes + "tetra_bad_accessor.gltf";
  const SceneError e = gltfError(path);
  requireAt(e, path, 81, 3);
  CHECK_THAT(e.message(), Contains("reaches outside its buffer view of 24 bytes"));
}

TEST_CASE("a glTF index beyond the primitive's vertices is located at its accessor", "[mesh][hostile]") {
  const std::string path = kHostile + "gltf_index_out_of_range.gltf";
  const SceneError e = gltfError(path);
  requireAt(e, path, 81, 3);
  CHECK(e.message() == "index 7 (element 4) is out of range: the primitive has 4 vertices");
}

// --- glTF: the node hierarchy and the triangle budget -----------------------------------------------

TEST_CASE("a glTF node reached twice is rejected instead of expanding 2^31 times", "[mesh][hostile]") {
  const std::string path = kHostile + "gltf_node_dag.gltf";
  const SceneError e = gltfError(path);
  // Depth first: nodes 0, 1, ..., 31 through the first children, then node 30's second child.
  requireAt(e, path, 197, 5);
  CHECK(e.message() == "node 31 is reached a second time (glTF node hierarchies are strict trees)");
}

TEST_CASE("a glTF primitive claiming more triangles than the budget is rejected before reading", "[mesh][hostile]") {
  const std::string path = kHostile + "gltf_triangle_claim.gltf";
  const SceneError e = gltfError(path);
  requireAt(e, path, 25, 3);  // the node that places the mesh
  CHECK(e.message() == "the node hierarchy holds more than 8388608 triangles");
}

// --- .glb layout ------------------------------------------------------------------------------------

TEST_CASE("a .glb that loads gives the same tetrahedron as the .gltf", "[mesh]") {
  const Mesh m = loadGltf(kMeshes + "tetra.glb");
  shadowref::testing::requireClosedOutward(m);
  CHECK(m.bounds.min == glm::dvec3(1.0, 2.0, 3.0));
  CHECK(m.bounds.max == glm::dvec3(3.0, 4.0, 5.0));
  CHECK(signedVolume(m) == Approx(8.0 / 6.0));
}

TEST_CASE("a .glb chunk longer than the file is rejected at its header's byte offset", "[mesh][hostile]") {
  const std::string path = kHostile + "glb_chunk_overread.glb";
  const SceneError e = gltfError(path);
  CHECK(e.where().file == path);
  CHECK(e.where().line == 0);
  // 12-byte header, 8-byte JSON chunk header, 600 bytes of JSON: the BIN chunk starts at 620.
  CHECK(e.message() == "at byte 620: chunk of 80 bytes reaches past the end of the file");
}

TEST_CASE("a .glb header that claims another length than the file's is rejected", "[mesh][hostile]") {
  const SceneError e = gltfError(kHostile + "glb_bad_length.glb");
  CHECK(e.message() == "at byte 8: the header says the file has 2147483648 bytes, it has 700");
}

// --- side files: regular, bounded, checked before reading ---------------------------------------------

TEST_CASE("glTF buffer files that are folders or devices are rejected before reading", "[mesh][hostile]") {
  for (const char* name : {"gltf_directory_uri.gltf", "gltf_dev_zero.gltf"}) {
    const std::string path = kHostile + name;
    const SceneError e = gltfError(path);
    requireAt(e, path, 49, 11);
    CHECK_THAT(e.message(), Contains("is not a regular file"));
  }
}

TEST_CASE("a glTF buffer file that is a FIFO is rejected without blocking", "[mesh][hostile]") {
  TempDir dir("gltf-fifo");
  writeTetraWithExternalBuffer(dir, "tetra.bin", 0);
  REQUIRE(::mkfifo(dir.file("tetra.bin").c_str(), 0600) == 0);
  const SceneError e = gltfError(dir.file("tetra.gltf"));
  CHECK(e.where().line == 49);
  CHECK_THAT(e.message(), Contains("is not a regular file"));
  // And a mesh file that is a FIFO.
  REQUIRE(::mkfifo(dir.file("fifo.obj").c_str(), 0600) == 0);
  CHECK(objError(dir.file("fifo.obj")).message() == "mesh file is not a regular file");
}

TEST_CASE("a glTF buffer file longer than its byteLength is rejected before it is read", "[mesh][hostile]") {
  TempDir dir("gltf-bin-size");
  writeTetraWithExternalBuffer(dir, "tetra.bin", 100);
  const SceneError e = gltfError(dir.file("tetra.gltf"));
  CHECK(e.where().line == 49);
  CHECK_THAT(e.message(), Contains("has 100 bytes, byteLength says 72"));
}

TEST_CASE("a glTF data URI of another length than byteLength is located at the uri", "[mesh][hostile]") {
  TempDir dir("gltf-data-uri");
  std::ifstream in(kMeshes + "tetra.gltf");
  std::string text((std::istreambuf_iterator<char>(in)), {});
  const size_t at = text.find("\"byteLength\": 72");
  REQUIRE(at != std::string::npos);
  text.replace(at, 16, "\"byteLength\": 100");
  write(dir.file("tetra.gltf"), text);
  const SceneError e = gltfError(dir.file("tetra.gltf"));
  requireAt(e, dir.file("tetra.gltf"), 49, 11);
  CHECK(e.message() == "the data URI holds 72 bytes, byteLength says 100");
}

TEST_CASE("a glTF with an external buffer file of the declared length loads", "[mesh]") {
  TempDir dir("gltf-bin-ok");
  writeTetraWithExternalBuffer(dir, "tetra.bin", 72);
  const Mesh m = loadGltf(dir.file("tetra.gltf"));
  CHECK(signedVolume(m) == Approx(8.0 / 6.0));
}

TEST_CASE("glTF images are never loaded, so an image's out-of-range buffer view is harmless", "[mesh]") {
  const Mesh m = loadGltf(kMeshes + "tetra_image_view.gltf");
  shadowref::testing::requireClosedOutward(m);
  CHECK(signedVolume(m) == Approx(8.0 / 6.0));
}

// --- OBJ ----------------------------------------------------------------------------------------------

TEST_CASE("OBJ face indices of LONG_MIN and beyond 64 bits are errors, not overflows", "[mesh][hostile]") {
  const std::string minPath = kHostile + "obj_long_min.obj";
  const SceneError min = objError(minPath);
  requireAt(min, minPath, 4, 7);
  CHECK(min.message() == "vertex index -9223372036854775808 reaches before the first vertex (3 so far)");
  const std::string bigPath = kHostile + "obj_overflow_index.obj";
  const SceneError big = objError(bigPath);
  requireAt(big, bigPath, 4, 7);
  CHECK(big.message() == "vertex index '99999999999999999999' out of range");
}

TEST_CASE("OBJ hexadecimal floats are rejected, as the one parser that reads and checks sees them", "[mesh][hostile]") {
  const std::string path = kHostile + "obj_hex_float.obj";
  const SceneError e = objError(path);
  requireAt(e, path, 1, 3);
  CHECK(e.message() == "'0x1p3' is a hexadecimal number; OBJ coordinates are decimal");
}

TEST_CASE("an OBJ mtllib is never opened, not even when it names /dev/zero", "[mesh][hostile]") {
  const Mesh m = loadObj(kMeshes + "tetra_mtllib_dev_zero.obj");
  shadowref::testing::requireClosedOutward(m);
  CHECK(m.triangles.size() == 4);
}

TEST_CASE("OBJ with 60 000 material switches and a FIFO as mtllib loads in linear time", "[mesh][hostile]") {
  TempDir dir("obj-materials");
  REQUIRE(::mkfifo(dir.file("materials.mtl").c_str(), 0600) == 0);  // would block if opened
  std::string text = "mtllib materials.mtl\n";
  constexpr int kTriangles = 60000;
  for (int i = 0; i < kTriangles; ++i) {
    const std::string x = std::to_string(2 * i);
    text += "v " + x + " 0 0\nv " + x + ".5 0 0\nv " + x + " 1 0\nusemtl material" + std::to_string(i) + "\nf -3 -2 -1\n";
  }
  write(dir.file("many.obj"), text);
  const Mesh m = loadObj(dir.file("many.obj"));
  CHECK(m.triangles.size() == kTriangles);
  CHECK(m.openEdges == 3 * kTriangles);
}

TEST_CASE("an OBJ face of 100 000 corners is triangulated in linear time as a fan", "[mesh][hostile]") {
  TempDir dir("obj-big-face");
  constexpr int kCorners = 100000;
  std::string text, face = "f";
  for (int i = 0; i < kCorners; ++i) {
    const double a = 2.0 * M_PI * i / kCorners;
    char line[96];
    std::snprintf(line, sizeof line, "v %.17g %.17g 0\n", std::cos(a), std::sin(a));
    text += line;
    face += " " + std::to_string(i + 1);
  }
  write(dir.file("disc.obj"), text + face + "\n");
  const Mesh m = loadObj(dir.file("disc.obj"));
  CHECK(m.triangles.size() == kCorners - 2);  // a convex n-gon is n - 2 triangles
  CHECK(m.openEdges == kCorners);             // its outline
  CHECK(m.nonManifoldEdges == 0);
  double worst = 0.0;  // crease normals of a flat face: straight up, to rounding
  for (const glm::dvec3& n : m.normals) worst = std::max(worst, glm::length(n - glm::dvec3(0.0, 0.0, 1.0)));
  CHECK(worst < 1e-15);
}

TEST_CASE("a non-convex OBJ face is ear-clipped, one beyond the corner limit rejected", "[mesh][hostile]") {
  TempDir dir("obj-nonconvex");
  // An L of six corners, counter-clockwise: area 3, which a fan from corner 0 would not cover right.
  write(dir.file("l.obj"), "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\nf 1 2 3 4 5 6\n");
  const Mesh m = loadObj(dir.file("l.obj"));
  REQUIRE(m.triangles.size() == 4);
  double area = 0.0;
  for (const glm::uvec3& t : m.triangles) {
    const glm::dvec3 n = glm::cross(m.positions[t.y] - m.positions[t.x], m.positions[t.z] - m.positions[t.x]);
    CHECK(n.z > 0.0);  // every triangle keeps the face's winding
    area += 0.5 * n.z;
  }
  CHECK(area == 3.0);
  const std::string path = kHostile + "obj_nonconvex_big.obj";
  const SceneError e = objError(path);
  requireAt(e, path, 302, 1);
  CHECK(e.message() == "face with 300 corners is not convex; non-convex faces may have at most 256 corners (split it)");
}

// --- every hostile scene ---------------------------------------------------------------------------

TEST_CASE("every scene of tests/data/hostile is rejected with a located SceneError", "[mesh][hostile][loader]") {
  size_t scenes = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kHostile)) {
    if (entry.path().extension() != ".yaml") continue;
    // A scene with NAME.args is refused only with those command-line arguments (a bad -D, say):
    // tests/cli/hostile_scenes.sh runs it through the CLI.
    std::filesystem::path args = entry.path();
    if (std::filesystem::exists(args.replace_extension(".args"))) continue;
    ++scenes;
    INFO(entry.path().string());
    const SceneError e = sceneErrorOf([&] { loadScene(entry.path().string()); });
    // Inside the mesh file (line and column, or a .glb's byte offset), or at the scene's mesh key.
    CHECK((e.where().file != entry.path().string() || e.where().line > 0));
  }
  CHECK(scenes >= 15);
}
