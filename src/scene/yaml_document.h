// A YAML document as the scene loader reads it: a tree of maps, lists and scalars in which every
// value and every map key knows where it was written ("file:line:column", 1-based).
//
// Why our own tree and not YAML::Node: the loader needs the location of each key (for "unknown
// key" messages), duplicate keys must be errors (yaml-cpp keeps both silently), aliases may form
// cycles or expand exponentially in yaml-cpp's graph, and -D overrides build small trees whose
// locations point into the command line instead of a file.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "scene/scene_error.h"

namespace shadowref {

struct YamlEntry;

struct YamlValue {
  enum class Kind { Null, Scalar, List, Map };
  Kind kind = Kind::Null;
  std::string scalar;             // Kind::Scalar: the text as written, quotes removed
  std::vector<YamlValue> items;   // Kind::List
  std::vector<YamlEntry> entries; // Kind::Map, in the order written; keys are unique
  SourceLocation at;

  bool isNull() const { return kind == Kind::Null; }
  bool isScalar() const { return kind == Kind::Scalar; }
  bool isList() const { return kind == Kind::List; }
  bool isMap() const { return kind == Kind::Map; }
  const YamlValue* find(std::string_view key) const;  // Map: the value under key, or nullptr
  const char* kindName() const;                       // "a number or text", "a list", ...
};

struct YamlEntry {
  std::string key;
  SourceLocation keyAt;
  YamlValue value;
};

// Limits that keep a hostile or broken file from exhausting memory or the stack: aliases can
// expand a small file exponentially, and an alias can even refer to its own ancestor.
inline constexpr int kYamlMaxDepth = 64;
inline constexpr size_t kYamlMaxValues = 1'000'000;
// The text of every scalar and key after aliases are expanded: an alias copies its text, so a
// long string repeated by aliases could otherwise ask for terabytes.
inline constexpr size_t kYamlMaxTextBytes = size_t(1) << 26;

// Parses one YAML document. `fileName` is used in locations. Throws SceneError for syntax
// errors (at yaml-cpp's mark), duplicate keys, non-scalar keys, more than one document, an empty
// document and the limits above.
YamlValue parseYaml(const std::string& text, const std::string& fileName);

// Parses a value written on one line somewhere else (a -D override's value): locations are
// `origin` shifted by the column within `text`. Empty text is a Null value.
YamlValue parseYamlFragment(const std::string& text, const SourceLocation& origin);

}  // namespace shadowref
