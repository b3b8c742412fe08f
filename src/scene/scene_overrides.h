// -D key=value overrides: a dotted path into the scene and a YAML value, applied
// after the file to the finished scene — `lights.0` is the scene's first light whether the file
// or a generator made it. `generator.*` is the exception: it changes the generator's options
// before the generator runs.
//
// Locations: an error in the i-th override (counted from 1) is reported as
// "<command line>:i:column", the column counted in its "key=value" text.
#pragma once

#include <string>
#include <vector>

#include "scene/resource_limits.h"
#include "scene/scene.h"
#include "scene/yaml_fields.h"

namespace shadowref {

struct Override {
  struct Segment {
    std::string text;
    SourceLocation at;
  };
  std::vector<Segment> path;  // "lights.0.range" -> lights, 0, range
  YamlValue value;

  // The override as a small document: {path[from]: {path[from+1]: ... value}}, keys located on
  // the command line, so the section readers check it exactly as they check the file.
  YamlValue asTree(size_t from) const;
};

// Splits and parses every "key=value"; throws SceneError for a missing '=', an empty path
// segment, or a value that is not YAML.
std::vector<Override> parseOverrides(const std::vector<std::string>& texts);

// What the overrides removed (`-D lights.NAME=off`, `-D nodes.PATH=off`). They are dropped only
// after the scene is validated (removeOverridden), so that while the overrides are applied every
// light and node keeps the number it has in the file: `lights.1` means the same light before and
// after `lights.0=off`.
struct Removals {
  std::vector<size_t> lights;              // indices into scene.lights
  std::vector<std::vector<size_t>> nodes;  // a node as child indices from the roots: {root, child, ...}
};

// Applies one override (not generator.*, meshes.*) to the scene, or to the scene's resource
// limits (limits.*). Throws SceneError for an unknown path, a missing light, node or material, a
// key with more than kYamlMaxDepth names, or a value of the wrong type.
void applyOverride(const Override& o, Scene& scene, ResourceLimits& limits, Provenance& where, Removals& removed);

// Drops what the overrides removed from the validated scene.
void removeOverridden(const Removals& removed, Scene& scene);

// The top-level names an override may start with.
const std::vector<std::string_view>& overridableSections();

}  // namespace shadowref
