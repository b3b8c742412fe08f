#include "explore/scene_save.h"

#include <optional>
#include <sstream>
#include <stdexcept>

#include <yaml-cpp/yaml.h>

namespace shadowref::explore {

namespace {

std::vector<std::string> split(const std::string& key) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(key);
  while (std::getline(in, part, '.')) parts.push_back(part);
  return parts;
}

bool isIndex(const std::string& s) {
  return !s.empty() && s.size() < 6 && s.find_first_not_of("0123456789") == std::string::npos;
}

// Sets map[path...] = value, making the maps on the way.
void setPath(YAML::Node node, const std::vector<std::string>& path, size_t from, const YAML::Node& value) {
  for (size_t i = from; i + 1 < path.size(); ++i) {
    if (!node[path[i]] || !node[path[i]].IsMap()) node[path[i]] = YAML::Node(YAML::NodeType::Map);
    node.reset(node[path[i]]);  // rebinds (operator= would copy into the node)
  }
  node[path.back()] = value;
}

}  // namespace

std::string sceneWithOverrides(const std::string& source, const std::vector<std::string>& overrides,
                               const std::vector<std::string>& lightNames, const std::string& from) {
  YAML::Node root = YAML::Load(source);
  if (!root.IsMap()) throw std::runtime_error("the scene is not a YAML map");
  std::vector<std::string> comments;
  for (const std::string& text : overrides) {
    const size_t eq = text.find('=');
    if (eq == std::string::npos) continue;
    const std::vector<std::string> path = split(text.substr(0, eq));
    const YAML::Node value = YAML::Load(text.substr(eq + 1));
    if (path.empty()) continue;
    const std::string& section = path[0];
    if ((section == "image" || section == "camera" || section == "shadow") && path.size() == 2) {
      setPath(root, path, 0, value);
    } else if ((section == "ambient" || section == "background") && path.size() == 1) {
      root[section] = value;
    } else if (section == "generator" && path.size() >= 2 && root["generator"]) {
      if (root["generator"].IsScalar()) {
        YAML::Node g(YAML::NodeType::Map);
        g["type"] = root["generator"].as<std::string>();
        root["generator"] = g;
      }
      setPath(root["generator"], path, 1, value);
    } else if (section == "lights" && path.size() >= 2) {
      std::string name = path[1];
      if (isIndex(name) && std::stoul(name) < lightNames.size()) name = lightNames[std::stoul(name)];
      if (!root["lights"] || !root["lights"].IsSequence()) root["lights"] = YAML::Node(YAML::NodeType::Sequence);
      YAML::Node lights = root["lights"];
      std::optional<size_t> at;
      for (size_t i = 0; i < lights.size(); ++i)
        if (lights[i]["name"] && lights[i]["name"].as<std::string>() == name) at = i;
      if (path.size() == 2) {  // lights.NAME=off
        if (at) {
          YAML::Node kept(YAML::NodeType::Sequence);
          for (size_t i = 0; i < lights.size(); ++i)
            if (i != *at) kept.push_back(lights[i]);
          root["lights"] = kept;
        } else {
          comments.push_back(text);
        }
        continue;
      }
      if (!at) {
        YAML::Node light(YAML::NodeType::Map);
        light["name"] = name;
        lights.push_back(light);
        at = lights.size() - 1;
      }
      setPath(lights[*at], path, 2, value);
    } else {
      comments.push_back(text);
    }
  }
  if (root["lights"] && root["lights"].IsSequence() && root["lights"].size() == 0) root.remove("lights");
  std::ostringstream out;
  out << "# Saved by shadowref explore from " << from << ".\n"
      << "# Mesh paths are relative to the folder of " << from << ".\n";
  if (!comments.empty()) {
    out << "# A scene file cannot say these; render with them on the command line:\n";
    for (const std::string& c : comments) out << "#   -D " << c << '\n';
  }
  YAML::Emitter emitter;
  emitter << root;
  out << emitter.c_str() << '\n';
  return out.str();
}

}  // namespace shadowref::explore
