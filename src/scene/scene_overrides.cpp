#include "scene/scene_overrides.h"

#include "scene/scene_loader.h"
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
  static const std::vector<std::string_view> names{"image",     "camera", "ambient",   "background", "lights",
                                                   "materials", "shadow", "generator", "limits"};
  return names;
}

namespace {

std::string joined(const Override& o, size_t count) {
  std::string s;
  for (size_t i = 0; i < count && i < o.path.size(); ++i) s += (i ? "." : "") + o.path[i].text;
  return s;
}

// lights.N or lights.NAME: the scene's light with that index or name.
Light& findLight(const Override& o, Scene& scene) {
  if (o.path.size() < 3) failAt(o.path[0].at, "-D lights needs a light and a key, e.g. lights.0.range=5");
  const Override::Segment& which = o.path[1];
  bool isIndex = which.text.find_first_not_of("0123456789") == std::string::npos;
  if (isIndex) {
    size_t index = which.text.size() > 6 ? scene.lights.size() : std::stoul(which.text);
    if (index < scene.lights.size()) return scene.lights[index];
    failAt(which.at, "lights." + which.text + ": the scene has " + std::to_string(scene.lights.size()) +
                         " light(s), numbered from 0");
  }
  std::vector<std::string_view> names;
  for (Light& l : scene.lights) {
    if (l.name == which.text) return l;
    names.push_back(l.name);
  }
  std::string message = "lights." + which.text + ": no light named '" + which.text + "'";
  std::string_view near = closestName(which.text, names);
  if (!near.empty()) message += "; did you mean '" + std::string(near) + "'?";
  failAt(which.at, message);
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

void applyOverride(const Override& o, Scene& scene, ResourceLimits& limits, Provenance& where) {
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
    Light& light = findLight(o, scene);
    const std::string path = "lights." + std::to_string(&light - scene.lights.data());
    applyLight(o.asTree(2), light, path, where);
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

}  // namespace shadowref
