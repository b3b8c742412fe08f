#include "scene/scene_meshes.h"

#include <filesystem>
#include <fstream>

#include "scene/adjacency.h"
#include "scene/mesh_import.h"
#include "scene/primitives.h"

namespace shadowref {

namespace {

struct BoxParams { glm::dvec3 size{1.0}; };
struct SphereParams { double radius = 1.0; int slices = 32, stacks = 16; };
struct RoundParams { double radius = 0.5, height = 1.0; int slices = 32; };  // cylinder, cone
struct TorusParams { double majorRadius = 1.0, minorRadius = 0.25; int majorSegments = 32, minorSegments = 16; };
struct PlaneParams { glm::dvec2 size{10.0}; double thickness = 0.1; };
struct PrismParams { int sides = 6; double radius = 0.5, height = 1.0; };

// Parameter tables: what each primitive accepts, with the defaults above for omitted keys.
template <class P>
Field<P> positive(std::string_view key, double P::*member) {
  return {key, [member](const YamlValue& v, P& p, const std::string& path, Provenance&) { p.*member = readPositive(v, path); }};
}
template <class P>
Field<P> count(std::string_view key, int P::*member, int min) {
  return {key, [member, min](const YamlValue& v, P& p, const std::string& path, Provenance&) {
            p.*member = readInt(v, path, min, kMaxSegments);
          }};
}

glm::dvec3 readPositiveVec3(const YamlValue& v, const std::string& path) {
  glm::dvec3 s = readVec3(v, path);
  if (!(s.x > 0.0 && s.y > 0.0 && s.z > 0.0)) failAt(v.at, path + ": every side must be greater than 0");
  return s;
}

// Each count alone may be large, but not both: the mesh would not fit in memory.
void checkGrid(int a, int b, const YamlValue& v, const std::string& path) {
  if (static_cast<long long>(a) * b > kMaxGridCells)
    failAt(v.at, path + ": " + std::to_string(a) + " x " + std::to_string(b) + " segments are more than " +
                     std::to_string(kMaxGridCells) + " cells");
}

template <class P>
P readParams(const YamlValue& v, const std::string& path, const std::vector<Field<P>>& fields, Provenance& where) {
  P params;
  applyFields(v, path, fields, params, where);
  return params;
}

Mesh readPrimitive(const std::string& kind, const YamlValue& v, const std::string& path, Provenance& where) {
  if (kind == "box") {
    static const std::vector<Field<BoxParams>> f{
        {"size", [](const YamlValue& x, BoxParams& p, const std::string& at, Provenance&) { p.size = readPositiveVec3(x, at); }}};
    return makeBox(readParams(v, path, f, where).size);
  }
  if (kind == "sphere") {
    static const std::vector<Field<SphereParams>> f{positive("radius", &SphereParams::radius),
                                                    count("slices", &SphereParams::slices, 3),
                                                    count("stacks", &SphereParams::stacks, 2)};
    SphereParams p = readParams(v, path, f, where);
    checkGrid(p.slices, p.stacks, v, path);
    return makeSphere(p.radius, p.slices, p.stacks);
  }
  if (kind == "cylinder" || kind == "cone") {
    static const std::vector<Field<RoundParams>> f{positive("radius", &RoundParams::radius),
                                                   positive("height", &RoundParams::height),
                                                   count("slices", &RoundParams::slices, 3)};
    RoundParams p = readParams(v, path, f, where);
    return kind == "cone" ? makeCone(p.radius, p.height, p.slices) : makeCylinder(p.radius, p.height, p.slices);
  }
  if (kind == "torus") {
    static const std::vector<Field<TorusParams>> f{
        positive("major_radius", &TorusParams::majorRadius), positive("minor_radius", &TorusParams::minorRadius),
        count("major_segments", &TorusParams::majorSegments, 3),
        count("minor_segments", &TorusParams::minorSegments, 3)};
    TorusParams p = readParams(v, path, f, where);
    checkGrid(p.majorSegments, p.minorSegments, v, path);
    // A tube thicker than the ring's radius passes through the axis: the surface intersects itself.
    if (!(p.minorRadius < p.majorRadius))
      failAt(where.find(path + ".minor_radius"), path + ": minor_radius must be less than major_radius");
    return makeTorus(p.majorRadius, p.minorRadius, p.majorSegments, p.minorSegments);
  }
  if (kind == "plane") {
    static const std::vector<Field<PlaneParams>> f{
        {"size", [](const YamlValue& x, PlaneParams& p, const std::string& at, Provenance&) {
           p.size = readVec2(x, at);
           if (!(p.size.x > 0.0 && p.size.y > 0.0)) failAt(x.at, at + ": every side must be greater than 0");
         }},
        positive("thickness", &PlaneParams::thickness)};
    PlaneParams p = readParams(v, path, f, where);
    return makePlane(p.size, p.thickness);
  }
  // prism
  static const std::vector<Field<PrismParams>> f{count("sides", &PrismParams::sides, 3),
                                                 positive("radius", &PrismParams::radius),
                                                 positive("height", &PrismParams::height)};
  PrismParams p = readParams(v, path, f, where);
  return makePrism(p.sides, p.radius, p.height);
}

// A mesh file named in the scene: it must exist and be a readable regular file (a device or a
// folder would hang or confuse the importer), checked here so the error points at the scene's key.
std::string resolveMeshFile(const YamlValue& v, const std::string& path, const std::string& baseDir) {
  namespace fs = std::filesystem;
  std::string written = readText(v, path);
  fs::path file = fs::path(written).is_absolute() ? fs::path(written) : fs::path(baseDir) / written;
  std::error_code ec;
  fs::file_status status = fs::status(file, ec);
  if (ec || !fs::exists(status)) failAt(v.at, path + ": mesh file '" + file.string() + "' does not exist");
  if (!fs::is_regular_file(status)) failAt(v.at, path + ": '" + file.string() + "' is not a regular file");
  if (!std::ifstream(file, std::ios::binary)) failAt(v.at, path + ": cannot read mesh file '" + file.string() + "'");
  return file.string();
}

Mesh readMeshFile(const std::string& kind, const YamlValue& v, const std::string& path, const std::string& baseDir) {
  std::string file = resolveMeshFile(v, path, baseDir);
  try {
    return kind == "obj" ? loadObj(file) : loadGltf(file);
  } catch (const SceneError& e) {
    // An error with a line inside the mesh file is reported there, saying which scene key led
    // there; one about the file as a whole (no triangles, not parsable) at the scene's key.
    if (e.where().line > 0)
      throw SceneError(e.where(), e.message() + " (mesh file of " + path + " at " + formatLocation(v.at) + ")");
    throw SceneError(v.at, path + ": " + file + ": " + e.message());
  }
}

const std::vector<std::string_view> kMeshKinds{"box", "sphere", "cylinder", "cone", "torus",
                                               "plane", "prism", "obj", "gltf"};

}  // namespace

std::shared_ptr<Mesh> readMeshSource(const YamlValue& source, const std::string& name, const std::string& path,
                                     const std::string& baseDir, Provenance& where) {
  auto oneSource = [&]() -> const YamlEntry* {
    if (!source.isMap()) return nullptr;
    const YamlEntry* found = nullptr;
    for (const YamlEntry& e : source.entries)
      if (e.key != "normals" && e.key != "crease_angle") {
        if (found) return nullptr;
        found = &e;
      }
    return found;
  };
  std::vector<std::string_view> allowed = kMeshKinds;
  allowed.insert(allowed.end(), {"normals", "crease_angle"});
  if (source.isMap()) checkKeys(source, path, allowed);
  const YamlEntry* found = oneSource();
  if (!found)
    failAt(source.at, path + ": expected one of " + joinNames(kMeshKinds) +
                          " with its parameters, e.g. 'box: {size: [1, 1, 1]}' or 'obj: meshes/house.obj'" +
                          " (and optionally normals: flat or smooth, crease_angle)");
  const YamlEntry& entry = *found;
  const std::string kindPath = path + "." + entry.key;
  where.record(kindPath, entry.value.at);
  Mesh mesh = (entry.key == "obj" || entry.key == "gltf")
                  ? readMeshFile(entry.key, entry.value, kindPath, baseDir)
                  : readPrimitive(entry.key, entry.value, kindPath, where);
  if (mesh.triangles.empty())
    failAt(entry.value.at, kindPath + ": mesh '" + name + "' has no triangles (after dropping degenerate ones)");
  // normals: flat (each triangle its face normal) or smooth (crease normals: smooth across edges
  // whose faces meet within crease_angle degrees, default 40); without it, a primitive keeps its
  // own normals and a file its normals (crease normals within 40 degrees where it has none).
  const YamlValue* normals = source.find("normals");
  const YamlValue* crease = source.find("crease_angle");
  static const EnumNames<bool> kNormalNames{{"flat", false}, {"smooth", true}};
  const bool smooth = normals && readEnum(*normals, path + ".normals", kNormalNames);
  if (crease && !smooth)
    failAt(crease->at, path + ".crease_angle: applies only with 'normals: smooth'" +
                           std::string(normals ? "" : " (add it: without it a file's own normals are used)"));
  if (normals) {
    if (smooth) computeCreaseNormals(mesh, crease ? readNumberInRange(*crease, path + ".crease_angle", 0.0, 180.0) : 40.0);
    else computeFlatNormals(mesh);
    buildAdjacency(mesh);
  }
  mesh.name = name;
  return std::make_shared<Mesh>(std::move(mesh));
}

}  // namespace shadowref
