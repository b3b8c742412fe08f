#include "scene/yaml_document.h"

#include <sstream>
#include <unordered_map>

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/eventhandler.h>
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
      // A fragment is one command-line argument however many newlines its value holds: its
      // line stays the argument's number, its column counts characters from the argument's
      // start. (yaml-cpp's mark at the end of the input says line 0, column 0: the value's start.)
      at.line = origin.line;
      at.column = origin.column + (m.line == 0 ? m.column : m.pos);
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
        countText(node.Scalar().size(), out.at);
        out.scalar = node.Scalar();
        break;
      case YAML::NodeType::Sequence:
        out.kind = YamlValue::Kind::List;
        for (const YAML::Node& child : node) out.items.push_back(convert(child, depth + 1));
        break;
      case YAML::NodeType::Map: {
        out.kind = YamlValue::Kind::Map;
        // The keys so far, with their lines, hashed: a map of n keys costs O(n), not O(n^2).
        std::unordered_map<std::string, int> seen;
        for (auto it = node.begin(); it != node.end(); ++it) convertEntry(out, seen, it->first, it->second, depth);
        break;
      }
    }
    return out;
  }

 private:
  void convertEntry(YamlValue& map, std::unordered_map<std::string, int>& seen, const YAML::Node& key,
                    const YAML::Node& value, int depth) {
    SourceLocation keyAt = map_(key.Mark());
    if (!key.IsScalar()) throw SceneError(keyAt, "a key must be a plain name, not " +
                                                     std::string(key.IsNull() ? "empty" : "a list or map"));
    countText(key.Scalar().size(), keyAt);
    const auto [first, isNew] = seen.emplace(key.Scalar(), keyAt.line);
    if (!isNew)
      throw SceneError(keyAt, "duplicate key '" + key.Scalar() + "' (first written at line " +
                                  std::to_string(first->second) + ")");
    YamlEntry entry{key.Scalar(), keyAt, convert(value, depth + 1)};
    // yaml-cpp marks an empty value ("key:" at the end of a line) on the next line; the key is
    // where the reader looks.
    if (entry.value.isNull()) entry.value.at = keyAt;
    map.entries.push_back(std::move(entry));
  }

  void countText(size_t bytes, const SourceLocation& at) {
    textBytes_ += bytes;
    if (textBytes_ > kYamlMaxTextBytes)
      throw SceneError(at, "the document's text is more than " + std::to_string(kYamlMaxTextBytes) +
                               " bytes after aliases are expanded");
  }

  MarkMapper map_;
  size_t count_ = 0;
  size_t textBytes_ = 0;
};

// Records where each document of a stream starts, and stops the parse at the first collection
// nested more than kYamlMaxDepth deep: yaml-cpp's parser recurses once per level and has its own
// guard only far deeper (about 500 block or 2000 flow levels), which reports no usable location.
// This pass runs before YAML::Load, so the recursive loader never sees such a document.
class DocumentCounter : public YAML::EventHandler {
 public:
  explicit DocumentCounter(const MarkMapper& map) : map_(map) {}
  std::vector<YAML::Mark> starts;
  void OnDocumentStart(const YAML::Mark& mark) override { starts.push_back(mark), depth_ = 0; }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t, const std::string&) override {}
  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
    enter(mark);
  }
  void OnSequenceEnd() override { --depth_; }
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
    enter(mark);
  }
  void OnMapEnd() override { --depth_; }

 private:
  void enter(const YAML::Mark& mark) {
    if (++depth_ > kYamlMaxDepth)
      throw SceneError(map_(mark), "lists and maps nested more than " + std::to_string(kYamlMaxDepth) + " levels deep");
  }

  const MarkMapper& map_;
  int depth_ = 0;
};

struct Documents {
  YAML::Node first;
  size_t count = 0;          // 0, 1, or 2 meaning "more than one"
  YAML::Mark secondStart;
};

// Not YAML::LoadAll: in yaml-cpp 0.7 it loops forever, allocating, on a stray flow token at
// document level (the input "," — yaml-cpp issue #1040, fixed upstream by PR #1319). Instead
// the stream is walked for at most two documents; a second one that starts where the first did
// is that bug's symptom, a token no document can begin with.
Documents loadDocuments(const std::string& text, const MarkMapper& map) {
  try {
    Documents docs;
    std::istringstream stream(text);
    YAML::Parser parser(stream);
    DocumentCounter counter(map);
    while (docs.count < 2 && parser.HandleNextDocument(counter)) ++docs.count;
    if (docs.count == 2) {
      const YAML::Mark& a = counter.starts.at(0);
      const YAML::Mark& b = counter.starts.at(1);
      if (a.pos == b.pos) throw SceneError(map(b), "YAML syntax error: unexpected token where a document should start");
      docs.secondStart = b;
    }
    if (docs.count > 0) docs.first = YAML::Load(text);
    return docs;
  } catch (const YAML::DeepRecursion& e) {
    // Not reached while DocumentCounter's bound is far below yaml-cpp's; its message ("bad
    // file") and mark would be no help.
    throw SceneError(map(e.mark), "YAML nested too deeply for the parser");
  } catch (const YAML::Exception& e) {
    // yaml-cpp's what() repeats the location in its own words; its msg is the bare reason.
    throw SceneError(map(e.mark), "YAML syntax error: " + e.msg);
  }
}

}  // namespace

YamlValue parseYaml(const std::string& text, const std::string& fileName) {
  MarkMapper map{SourceLocation{fileName, 0, 0}, false};
  Documents docs = loadDocuments(text, map);
  if (docs.count == 0) throw SceneError(SourceLocation{fileName, 0, 0}, "the file holds no YAML document");
  if (docs.count > 1) throw SceneError(map(docs.secondStart), "a scene file holds one YAML document, this is the second");
  return Converter(map).convert(docs.first, 0);
}

YamlValue parseYamlFragment(const std::string& text, const SourceLocation& origin) {
  MarkMapper map{origin, true};
  Documents docs = loadDocuments(text, map);
  if (docs.count == 0) {
    YamlValue empty;
    empty.at = origin;
    return empty;
  }
  if (docs.count > 1) throw SceneError(map(docs.secondStart), "more than one YAML document in a value");
  return Converter(map).convert(docs.first, 0);
}

}  // namespace shadowref
