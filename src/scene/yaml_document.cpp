#include "scene/yaml_document.h"

#include <yaml-cpp/yaml.h>

namespace shadowref {

const YamlValue* YamlValue::find(std::string_view key) const {
  for (const YamlEntry& e : entries)
    if (e.key == key) return &e.value;
  return nullptr;
}

const char* YamlValue::kindName() const {
  switch (kind) {
    case Kind::Null: return "nothing";
    case Kind::Scalar: return "a single value";
    case Kind::List: return "a list";
    case Kind::Map: return "a map of keys";
  }
  return "?";
}

namespace {

// yaml-cpp marks are 0-based, -1 when unknown; ours are 1-based, 0 when unknown.
struct MarkMapper {
  SourceLocation origin;  // file; line/column of the text's first character (1-based)
  bool shifted = false;   // a fragment: keep origin's line, shift columns

  SourceLocation operator()(const YAML::Mark& m) const {
    SourceLocation at{origin.file, 0, 0};
    if (m.is_null() || m.line < 0) return at;
    if (!shifted) {
      at.line = m.line + 1;
      at.column = m.column + 1;
    } else {
      at.line = origin.line + m.line;
      at.column = (m.line == 0 ? origin.column : 1) + m.column;
    }
    return at;
  }
};

class Converter {
 public:
  explicit Converter(MarkMapper map) : map_(std::move(map)) {}

  YamlValue convert(const YAML::Node& node, int depth) {
    YamlValue out;
    out.at = map_(node.Mark());
    if (++count_ > kYamlMaxValues)
      throw SceneError(out.at, "the document holds more than " + std::to_string(kYamlMaxValues) +
                                   " values (aliases expanding too far?)");
    if (depth > kYamlMaxDepth)
      throw SceneError(out.at, "values nested more than " + std::to_string(kYamlMaxDepth) +
                                   " levels deep (an alias referring to itself?)");
    switch (node.Type()) {
      case YAML::NodeType::Undefined:
      case YAML::NodeType::Null:
        out.kind = YamlValue::Kind::Null;
        break;
      case YAML::NodeType::Scalar:
        out.kind = YamlValue::Kind::Scalar;
        out.scalar = node.Scalar();
        break;
      case YAML::NodeType::Sequence:
        out.kind = YamlValue::Kind::List;
        for (const YAML::Node& child : node) out.items.push_back(convert(child, depth + 1));
        break;
      case YAML::NodeType::Map:
        out.kind = YamlValue::Kind::Map;
        for (auto it = node.begin(); it != node.end(); ++it) convertEntry(out, it->first, it->second, depth);
        break;
    }
    return out;
  }

 private:
  void convertEntry(YamlValue& map, const YAML::Node& key, const YAML::Node& value, int depth) {
    SourceLocation keyAt = map_(key.Mark());
    if (!key.IsScalar()) throw SceneError(keyAt, "a key must be a plain name, not " +
                                                     std::string(key.IsNull() ? "empty" : "a list or map"));
    for (const YamlEntry& e : map.entries)
      if (e.key == key.Scalar())
        throw SceneError(keyAt, "duplicate key '" + e.key + "' (first written at line " +
                                    std::to_string(e.keyAt.line) + ")");
    YamlEntry entry{key.Scalar(), keyAt, convert(value, depth + 1)};
    // yaml-cpp marks an empty value ("key:" at the end of a line) on the next line; the key is
    // where the reader looks.
    if (entry.value.isNull()) entry.value.at = keyAt;
    map.entries.push_back(std::move(entry));
  }

  MarkMapper map_;
  size_t count_ = 0;
};

std::vector<YAML::Node> loadAll(const std::string& text, const MarkMapper& map) {
  try {
    return YAML::LoadAll(text);
  } catch (const YAML::Exception& e) {
    // yaml-cpp's what() repeats the location in its own words; its msg is the bare reason.
    throw SceneError(map(e.mark), "YAML syntax error: " + e.msg);
  }
}

}  // namespace

YamlValue parseYaml(const std::string& text, const std::string& fileName) {
  MarkMapper map{SourceLocation{fileName, 0, 0}, false};
  std::vector<YAML::Node> docs = loadAll(text, map);
  if (docs.empty()) throw SceneError(SourceLocation{fileName, 0, 0}, "the file holds no YAML document");
  if (docs.size() > 1)
    throw SceneError(map(docs[1].Mark()), "a scene file holds one YAML document, this is the second");
  return Converter(map).convert(docs[0], 0);
}

YamlValue parseYamlFragment(const std::string& text, const SourceLocation& origin) {
  MarkMapper map{origin, true};
  std::vector<YAML::Node> docs = loadAll(text, map);
  if (docs.empty()) {
    YamlValue empty;
    empty.at = origin;
    return empty;
  }
  if (docs.size() > 1) throw SceneError(map(docs[1].Mark()), "more than one YAML document in a value");
  return Converter(map).convert(docs[0], 0);
}

}  // namespace shadowref
