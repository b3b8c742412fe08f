#include "scene/scene_loader.h"

#include "scene/input_file.h"

#include "scene/animation.h"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <unordered_map>

#include "scene/scene_generator.h"
#include "scene/scene_meshes.h"
#include "scene/scene_nodes.h"
#include "scene/scene_overrides.h"
#include "scene/scene_sections.h"
#include "scene/scene_validation.h"
#include "scene/yaml_document.h"

namespace shadowref {

namespace {

const std::vector<std::string_view> kTopLevelKeys{"image",     "camera", "ambient", "background", "lights", "materials",
                                                  "meshes",    "nodes",  "generator", "shadow", "limits",
                                                  "animation"};

// Light names and material names are how a file or a -D reaches what a generator made.
void checkName(const std::string& name, const SourceLocation& at, const std::string& path) {
  if (name.find('.') != std::string::npos)
    failAt(at, path + ": the name '" + name + "' must not contain '.' (it separates names in -D keys)");
}

// lights: a list. A light whose name matches one the generator made changes that light's keys;
// any other is a new light (named "light<index>" when it has no name).
void readLights(const YamlValue& list, Scene& scene, Provenance& where) {
  if (list.isNull()) return;
  if (!list.isList()) failAt(list.at, "lights: expected a list of lights, got " + std::string(list.kindName()));
  // Name -> index, so that a file of n lights costs O(n), not O(n^2); the last of equal names
  // wins, as the linear search it replaces did.
  std::unordered_map<std::string, size_t> byName;
  for (size_t i = 0; i < scene.lights.size(); ++i) byName[scene.lights[i].name] = i;
  for (const YamlValue& item : list.items) {
    if (!item.isMap()) failAt(item.at, "lights: each light is a map of keys (type, position, ...), got " +
                                           std::string(item.kindName()));
    Light* light = nullptr;
    if (const YamlValue* name = item.find("name")) {
      std::string text = readText(*name, "lights.name");
      checkName(text, name->at, "lights");
      if (auto it = byName.find(text); it != byName.end()) light = &scene.lights[it->second];
    }
    if (!light) {
      scene.lights.emplace_back();
      light = &scene.lights.back();
      light->name = "light" + std::to_string(scene.lights.size() - 1);
    }
    const size_t index = static_cast<size_t>(light - scene.lights.data());
    applyLight(item, *light, "lights." + std::to_string(index), where);
    byName[light->name] = index;
  }
}

// materials: a map name -> keys. `default` is the material of nodes that name none.
void readMaterials(const YamlValue& map, Scene& scene, Provenance& where) {
  if (map.isNull()) return;
  if (!map.isMap()) failAt(map.at, "materials: expected a map of name: {ambient, diffuse, ...}, got " +
                                       std::string(map.kindName()));
  std::unordered_map<std::string, size_t> byName;  // O(n) for n materials; the last of equal names wins
  for (size_t i = 0; i < scene.materials.size(); ++i) byName[scene.materials[i].name] = i;
  for (const YamlEntry& e : map.entries) {
    checkName(e.key, e.keyAt, "materials");
    Material* material = nullptr;
    if (auto it = byName.find(e.key); it != byName.end()) material = &scene.materials[it->second];
    if (!material) {
      byName[e.key] = scene.materials.size();
      scene.materials.push_back(Material{});
      material = &scene.materials.back();
      material->name = e.key;
    }
    applyMaterial(e.value, *material, "materials." + e.key, where);
  }
}

// meshes: a map name -> source. A name the generator used replaces that mesh everywhere.
void readMeshes(const YamlValue& map, Scene& scene, const std::string& baseDir, Provenance& where) {
  if (map.isNull()) return;
  if (!map.isMap()) failAt(map.at, "meshes: expected a map of name: source, got " + std::string(map.kindName()));
  size_t triangles = 0;
  std::unordered_map<std::string, std::vector<size_t>> byName;  // O(n) for n meshes
  for (size_t i = 0; i < scene.meshes.size(); ++i) byName[scene.meshes[i]->name].push_back(i);
  for (const YamlEntry& e : map.entries) {
    std::shared_ptr<Mesh> mesh = readMeshSource(e.value, e.key, "meshes." + e.key, baseDir, where);
    triangles += mesh->triangles.size();
    if (triangles > kMaxSceneFileTriangles)
      failAt(e.keyAt, "meshes: more than " + std::to_string(kMaxSceneFileTriangles) + " triangles in all, up to '" +
                          e.key + "'");
    std::vector<size_t>& same = byName[e.key];
    for (size_t i : same) scene.meshes[i] = mesh;
    if (same.empty()) {
      same.push_back(scene.meshes.size());
      scene.meshes.push_back(std::move(mesh));
    }
  }
}

void readNodes(const YamlValue& list, Scene& scene, const ResourceLimits& limits, Provenance& where) {
  if (list.isNull()) return;
  if (!list.isList()) failAt(list.at, "nodes: expected a list of nodes, got " + std::string(list.kindName()));
  for (Node& node : readNodeList(list, scene.roots.size(), scene, limits, where)) scene.roots.push_back(std::move(node));
}

// Overrides of generator.* are merged into the file's generator section before it runs.
void mergeInto(YamlValue& base, const YamlValue& overlay) {
  if (!base.isMap() || !overlay.isMap()) {
    base = overlay;
    return;
  }
  for (const YamlEntry& o : overlay.entries) {
    YamlEntry* existing = nullptr;
    for (YamlEntry& b : base.entries)
      if (b.key == o.key) existing = &b;
    if (existing) mergeInto(existing->value, o.value);
    else base.entries.push_back(o);
  }
}

// -D meshes.NAME.KEY...=value: merged into the source of the file's mesh NAME.
void mergeMeshOverride(const Override& o, YamlValue& meshes) {
  if (o.path.size() < 3)
    failAt(o.path[0].at, "-D meshes needs a mesh and a key, e.g. meshes.ball.sphere.slices=64 or meshes.house.normals=flat");
  const Override::Segment& which = o.path[1];
  std::vector<std::string_view> names;
  if (meshes.isMap())
    for (YamlEntry& e : meshes.entries) {
      if (e.key == which.text) {
        mergeInto(e.value, o.asTree(2));
        return;
      }
      names.push_back(e.key);
    }
  std::string message = "meshes." + which.text + ": no mesh named '" + which.text +
                        "' in the file's meshes section (only those can be overridden)";
  std::string_view near = closestName(which.text, names);
  if (!near.empty()) message += "; did you mean '" + std::string(near) + "'?";
  failAt(which.at, message);
}

Scene buildScene(const YamlValue& root, const std::string& displayName, const std::string& baseDir,
                 const LoadOptions& options) {
  Provenance where{SourceLocation{displayName, 0, 0}};
  if (!root.isMap())
    failAt(root.at, "a scene file is a map of sections (" + joinNames(kTopLevelKeys) + "), got " + root.kindName());
  checkKeys(root, "", kTopLevelKeys);
  const std::vector<Override> overrides = parseOverrides(options.overrides);
  auto section = [&](std::string_view key) {
    const YamlValue* v = root.find(key);
    return v ? *v : YamlValue{};
  };

  Scene scene;
  scene.sourceFile = displayName;
  ResourceLimits limits;
  // The generator runs first; the file's sections then change or add to what it made.
  YamlValue generator = section("generator");
  for (const Override& o : overrides) {
    if (o.path[0].text != "generator") continue;
    if (generator.isScalar()) generator = generatorShorthand(generator);
    mergeInto(generator, o.asTree(1));
  }
  if (!generator.isNull() || root.find("generator")) runGenerator(generator, scene, where);
  // A check of a value the file did not write (the default camera.up) points at its section.
  for (const YamlEntry& e : root.entries) where.record(e.key, e.keyAt);

  if (const YamlValue* v = root.find("image")) applyImage(*v, scene, where);
  if (const YamlValue* v = root.find("camera")) applyCamera(*v, scene.camera, where);
  if (const YamlValue* v = root.find("ambient")) scene.ambient = readColor(*v, "ambient"), where.record("ambient", v->at);
  if (const YamlValue* v = root.find("background"))
    scene.background = readColor(*v, "background"), where.record("background", v->at);
  if (const YamlValue* v = root.find("shadow")) applyShadow(*v, scene.shadow, where);
  if (const YamlValue* v = root.find("limits")) applyLimits(*v, limits, where);
  // limits.* overrides take effect now: reading the nodes already counts them against the budget.
  Removals removed;
  for (const Override& o : overrides)
    if (o.path[0].text == "limits") applyOverride(o, scene, limits, where, removed);
  readMaterials(section("materials"), scene, where);
  readLights(section("lights"), scene, where);
  // meshes.* overrides change the file's mesh sources before they are read (a mesh is made from
  // its source once; what is read is checked as the file's own keys are).
  YamlValue meshes = section("meshes");
  for (const Override& o : overrides)
    if (o.path[0].text == "meshes") mergeMeshOverride(o, meshes);
  readMeshes(meshes, scene, baseDir, where);
  readNodes(section("nodes"), scene, limits, where);

  for (const Override& o : overrides)
    if (o.path[0].text != "generator" && o.path[0].text != "limits" && o.path[0].text != "meshes")
      applyOverride(o, scene, limits, where, removed);
  validateScene(scene, limits, where);
  // The names -D took out: their tracks are skipped, not errors.
  RemovedNames removedNames;
  for (size_t i : removed.lights) removedNames.lights.insert(scene.lights[i].name);
  for (const std::vector<size_t>& path : removed.nodes) {
    const std::vector<Node>* level = &scene.roots;
    std::string name;
    for (size_t i : path) {
      name += (name.empty() ? "" : "/") + (*level)[i].name;
      level = &(*level)[i].children;
    }
    removedNames.nodes.insert(name);
  }
  removeOverridden(removed, scene);
  // Read against the finished scene: tracks name its lights and nodes as they are now.
  if (const YamlValue* v = root.find("animation")) {
    scene.animation = std::make_shared<const Animation>(readAnimation(*v, scene, limits, removedNames));
    // The first and last frames are checked now, so `check` reports a camera that ends inside
    // its target; frames between are checked as they are rendered.
    (void)sceneAt(scene, 0.0);
    (void)sceneAt(scene, scene.animation->lastKeyTime());
  }
  return scene;
}

}  // namespace

Scene loadSceneFromString(const std::string& yaml, const std::string& displayName, const LoadOptions& options) {
  return buildScene(parseYaml(yaml, displayName), displayName, ".", options);
}

Scene loadScene(const std::string& path, const LoadOptions& options) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) throw SceneError(SourceLocation{path, 0, 0}, "scene file does not exist");
  // The same checks as every side file: a regular file of bounded size, its size known first, so
  // a FIFO, a device or a huge file is refused before a byte is read.
  const std::string text = readInputFile(path, "scene file", kMaxSceneFileBytes);
  fs::path parent = fs::path(path).parent_path();
  return buildScene(parseYaml(text, path), path, parent.empty() ? "." : parent.string(), options);
}

}  // namespace shadowref
