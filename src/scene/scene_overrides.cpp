#include "scene/scene_overrides.h"

#include "scene/scene_loader.h"

#include <algorithm>
#include <functional>

#include "scene/scene_nodes.h"
#include "scene/scene_sections.h"

namespace shadowref {

// Built from the value outwards, in a loop: the depth is the key's segment count, which
// parseOverrides bounds, but nothing here should depend on that.
YamlValue Override::asTree(size_t from) const {
  YamlValue tree = value;
  for (size_t i = path.size(); i > from; --i) {
    YamlValue map;
    map.kind = YamlValue::Kind::Map;
    map.at = path[i - 1].at;
    map.entries.push_back(YamlEntry{path[i - 1].text, path[i - 1].at, std::move(tree)});
    tree = std::move(map);
  }
  return tree;
}

std::vector<Override> parseOverrides(const std::vector<std::string>& texts) {
  std::vector<Override> out;
  for (size_t i = 0; i < texts.size(); ++i) {
    const std::string& text = texts[i];
    const int line = static_cast<int>(i + 1);
    auto at = [&](size_t offset) { return SourceLocation{kCommandLineFile, line, static_cast<int>(offset + 1)}; };
    const size_t equals = text.find('=');
    if (equals == std::string::npos)
      failAt(at(0), "-D expects key=value (e.g. camera.near=0.01), got '" + text + "'");
    Override o;
    size_t start = 0;
    for (;;) {
      size_t dot = text.find('.', start);
      size_t end = (dot == std::string::npos || dot > equals) ? equals : dot;
      std::string segment = text.substr(start, end - start);
      if (segment.empty()) failAt(at(start), "-D " + text + ": empty name in the key");
      // A key is a path into the scene, a few names deep; one nested deeper than any YAML value
      // may be (kYamlMaxDepth) names nothing, and its tree would only cost stack to take apart.
      if (o.path.size() == size_t(kYamlMaxDepth))
        failAt(at(start), "-D key: more than " + std::to_string(kYamlMaxDepth) + " names separated by '.'");
      o.path.push_back({segment, at(start)});
      if (end == equals) break;
      start = end + 1;
    }
    o.value = parseYamlFragment(text.substr(equals + 1), at(equals + 1));
    out.push_back(std::move(o));
  }
  return out;
}

const std::vector<std::string_view>& overridableSections() {
  static const std::vector<std::string_view> names{"image",  "camera",    "ambient", "background", "lights", "materials",
                                                   "meshes", "nodes",     "shadow",  "generator",  "limits"};
  return names;
}

namespace {

std::string joined(const Override& o, size_t count) {
  std::string s;
  for (size_t i = 0; i < count && i < o.path.size(); ++i) s += (i ? "." : "") + o.path[i].text;
  return s;
}

// lights.N or lights.NAME: the index of the scene's light with that number or name.
size_t findLight(const Override& o, const Scene& scene, const Removals& removed) {
  if (o.path.size() < 2) failAt(o.path[0].at, "-D lights needs a light and a key, e.g. lights.0.range=5, or lights.0=off");
  const Override::Segment& which = o.path[1];
  auto live = [&](size_t index) {
    if (std::find(removed.lights.begin(), removed.lights.end(), index) != removed.lights.end())
      failAt(which.at, "lights." + which.text + ": the light '" + scene.lights[index].name +
                           "' was removed by an earlier -D");
    return index;
  };
  bool isIndex = which.text.find_first_not_of("0123456789") == std::string::npos;
  if (isIndex) {
    size_t index = which.text.size() > 6 ? scene.lights.size() : std::stoul(which.text);
    if (index < scene.lights.size()) return live(index);
    failAt(which.at, "lights." + which.text + ": the scene has " + std::to_string(scene.lights.size()) +
                         " light(s), numbered from 0");
  }
  std::vector<std::string_view> names;
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    if (scene.lights[i].name == which.text) return live(i);
    names.push_back(scene.lights[i].name);
  }
  std::string message = "lights." + which.text + ": no light named '" + which.text + "'";
  std::string_view near = closestName(which.text, names);
  if (!near.empty()) message += "; did you mean '" + std::string(near) + "'?";
  else if (names.empty()) message += " (the scene has no lights)";
  failAt(which.at, message);
}

// `value` must be off (false): removing is the only thing a light or node itself can be set to.
void requireOff(const Override& o, const std::string& what) {
  const bool on = readBool(o.value, joined(o, o.path.size()));
  if (on)
    failAt(o.value.at, joined(o, o.path.size()) + ": only 'off' (remove the " + what + ") can be given here; to change a " +
                           what + ", name a key, e.g. " + joined(o, o.path.size()) +
                           (what == "light" ? ".range=5" : ".cast_shadows=false"));
}

// nodes.PATH: every node whose path (names from the root joined by '/', as `shadowref info` and
// the pixel history print them) is PATH, as child indices from the roots.
std::vector<std::vector<size_t>> findNodes(const Override& o, const Scene& scene, const Removals& removed) {
  if (o.path.size() < 2)
    failAt(o.path[0].at, "-D nodes needs a node path and a key, e.g. nodes.table/leg0.cast_shadows=false, or nodes.table=off");
  const Override::Segment& which = o.path[1];
  std::vector<std::vector<size_t>> found;
  std::vector<std::string> paths;  // every node's path, for the message
  std::vector<size_t> at;
  const std::function<void(const Node&, const std::string&)> visit = [&](const Node& node, const std::string& parent) {
    const std::string path = parent.empty() ? node.name : parent + "/" + node.name;
    if (path == which.text) found.push_back(at);
    paths.push_back(path);
    for (size_t c = 0; c < node.children.size(); ++c) {
      at.push_back(c);
      visit(node.children[c], path);
      at.pop_back();
    }
  };
  for (size_t r = 0; r < scene.roots.size(); ++r) {
    at.assign(1, r);
    visit(scene.roots[r], "");
  }
  for (const std::vector<size_t>& f : found)
    for (const std::vector<size_t>& gone : removed.nodes)
      if (f.size() >= gone.size() && std::equal(gone.begin(), gone.end(), f.begin()))
        failAt(which.at, "nodes." + which.text + ": the node was removed by an earlier -D");
  if (!found.empty()) return found;
  std::string message = "nodes." + which.text + ": no node with the path '" + which.text + "'";
  // A bare name of a nested node: the full path is what the key needs.
  std::vector<std::string_view> names(paths.begin(), paths.end());
  std::string_view suggestion;
  for (const std::string& p : paths)
    if (p.size() > which.text.size() && p.compare(p.size() - which.text.size(), std::string::npos, which.text) == 0 &&
        p[p.size() - which.text.size() - 1] == '/')
      suggestion = p;
  if (suggestion.empty()) suggestion = closestName(which.text, names);
  if (!suggestion.empty()) message += "; did you mean '" + std::string(suggestion) + "'?";
  else if (paths.empty()) message += " (the scene has no nodes)";
  else message += " (a node is named by its path from the root, e.g. '" + paths.back() + "')";
  failAt(which.at, message);
}

Node& nodeAt(Scene& scene, const std::vector<size_t>& at) {
  Node* node = &scene.roots[at[0]];
  for (size_t i = 1; i < at.size(); ++i) node = &node->children[at[i]];
  return *node;
}

Material& findMaterial(const Override& o, Scene& scene) {
  if (o.path.size() < 3) failAt(o.path[0].at, "-D materials needs a material and a key, e.g. materials.wall.diffuse=0.5");
  const Override::Segment& which = o.path[1];
  std::vector<std::string_view> names;
  for (Material& m : scene.materials) {
    if (m.name == which.text) return m;
    names.push_back(m.name);
  }
  std::string message = "materials." + which.text + ": no material named '" + which.text + "'";
  std::string_view near = closestName(which.text, names);
  if (!near.empty()) message += "; did you mean '" + std::string(near) + "'?";
  failAt(which.at, message);
}

void requireLength(const Override& o, size_t length, const char* example) {
  if (o.path.size() != length)
    failAt(o.path[std::min(length, o.path.size() - 1)].at,
           "-D " + joined(o, o.path.size()) + ": expected a key like " + example);
}

}  // namespace

void applyOverride(const Override& o, Scene& scene, ResourceLimits& limits, Provenance& where, Removals& removed) {
  const std::string& section = o.path[0].text;
  if (section == "image") {
    requireLength(o, 2, "image.width");
    applyImage(o.asTree(1), scene, where);
  } else if (section == "camera") {
    requireLength(o, 2, "camera.near");
    applyCamera(o.asTree(1), scene.camera, where);
  } else if (section == "shadow") {
    requireLength(o, 2, "shadow.method");
    applyShadow(o.asTree(1), scene.shadow, where);
  } else if (section == "limits") {
    requireLength(o, 2, "limits.max_triangles");
    applyLimits(o.asTree(1), limits, where);
  } else if (section == "ambient" || section == "background") {
    requireLength(o, 1, section == "ambient" ? "ambient=[0.1, 0.1, 0.1]" : "background=0.5");
    (section == "ambient" ? scene.ambient : scene.background) = readColor(o.value, section);
    where.record(section, o.value.at);
  } else if (section == "lights") {
    const size_t index = findLight(o, scene, removed);
    if (o.path.size() == 2) {
      requireOff(o, "light");
      removed.lights.push_back(index);
      return;
    }
    applyLight(o.asTree(2), scene.lights[index], "lights." + std::to_string(index), where);
  } else if (section == "nodes") {
    for (const std::vector<size_t>& at : findNodes(o, scene, removed)) {
      if (o.path.size() == 2) {
        requireOff(o, "node");
        removed.nodes.push_back(at);
        continue;
      }
      applyNodeOverride(o.asTree(2), nodeAt(scene, at), "nodes." + o.path[1].text, scene, where);
    }
  } else if (section == "materials") {
    Material& material = findMaterial(o, scene);
    applyMaterial(o.asTree(2), material, "materials." + material.name, where);
  } else {
    std::string message = "-D " + section + ": cannot override '" + section + "' (allowed: " +
                          joinNames(overridableSections()) + ")";
    std::string_view near = closestName(section, overridableSections());
    if (!near.empty()) message += "; did you mean '" + std::string(near) + "'?";
    failAt(o.path[0].at, message);
  }
}

void removeOverridden(const Removals& removed, Scene& scene) {
  // Deepest and last first, so that each index still names the node it named when recorded.
  std::vector<std::vector<size_t>> nodes = removed.nodes;
  std::sort(nodes.begin(), nodes.end(), std::greater<>());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  for (const std::vector<size_t>& at : nodes) {
    if (at.size() == 1) {
      scene.roots.erase(scene.roots.begin() + std::ptrdiff_t(at[0]));
      continue;
    }
    Node& parent = nodeAt(scene, std::vector<size_t>(at.begin(), at.end() - 1));
    parent.children.erase(parent.children.begin() + std::ptrdiff_t(at.back()));
  }
  std::vector<size_t> lights = removed.lights;
  std::sort(lights.begin(), lights.end(), std::greater<>());
  lights.erase(std::unique(lights.begin(), lights.end()), lights.end());
  for (size_t index : lights) scene.lights.erase(scene.lights.begin() + std::ptrdiff_t(index));
}

}  // namespace shadowref
