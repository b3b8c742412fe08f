#include "sweep/sweep_spec.h"

#include <nettle/sha1.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>

#include "scene/input_file.h"
#include "scene/yaml_document.h"
#include "scene/yaml_fields.h"
#include "shadow/technique.h"
#include "shadow/technique_registry.h"

namespace shadowref::sweep {

namespace {

// A job grid multiplies: a file of a few lines could otherwise ask for billions of jobs.
constexpr size_t kMaxJobs = 100'000;

// A -D value and where the sweep file writes it.
struct Setting {
  std::string key, value;
  SourceLocation at;
};

// Settings a group inherits from the top of the file unless it sets them itself.
struct Defaults {
  RecordWhat record{true, true, true};
  ReferenceSpec reference;
  int repetitions = 5;
  std::vector<Setting> set;
};

// A -D value as text: a scalar as written, a list as "[a, b, c]" (what the scene loader reads
// back as the same list), a map as "{k: v}".
std::string valueText(const YamlValue& v, const std::string& path) {
  switch (v.kind) {
    case YamlValue::Kind::Scalar: return v.scalar;
    case YamlValue::Kind::List: {
      std::string s = "[";
      for (size_t i = 0; i < v.items.size(); ++i) s += (i ? ", " : "") + valueText(v.items[i], path);
      return s + "]";
    }
    case YamlValue::Kind::Map: {
      std::string s = "{";
      for (size_t i = 0; i < v.entries.size(); ++i)
        s += (i ? ", " : "") + v.entries[i].key + ": " + valueText(v.entries[i].value, path);
      return s + "}";
    }
    case YamlValue::Kind::Null: break;
  }
  failAt(v.at, path + ": needs a value");
}

const YamlValue& requireList(const YamlValue& v, const std::string& path) {
  if (!v.isList() || v.items.empty()) failAt(v.at, path + ": expected a list of at least one value, got " + v.kindName());
  return v;
}

// `set`: a map of -D keys to values.
std::vector<Setting> readSet(const YamlValue& v, const std::string& path) {
  if (!v.isMap()) failAt(v.at, path + ": expected a map of -D keys to values, got " + v.kindName());
  std::vector<Setting> out;
  for (const YamlEntry& e : v.entries) out.push_back({e.key, valueText(e.value, path + "." + e.key), e.value.at});
  return out;
}

RecordWhat readRecord(const YamlValue& v, const std::string& path) {
  requireList(v, path);
  RecordWhat r;
  const EnumNames<int> names = {{"time", 0}, {"error", 1}, {"counts", 2}};
  for (size_t i = 0; i < v.items.size(); ++i) {
    const int what = readEnum(v.items[i], path + "." + std::to_string(i), names);
    bool& flag = what == 0 ? r.time : what == 1 ? r.error : r.counts;
    if (flag) failAt(v.items[i].at, path + ": '" + v.items[i].scalar + "' is listed twice");
    flag = true;
  }
  return r;
}

ReferenceSpec readReference(const YamlValue& v, const std::string& path, ReferenceSpec r) {
  checkKeys(v, path, {"shape", "size", "samples"});
  const EnumNames<Reference> shapes = {
      {"point", Reference::HardLight}, {"square", Reference::AreaSquare}, {"sphere", Reference::AreaSphere}};
  if (const YamlValue* s = v.find("shape")) r.shape = readEnum(*s, path + ".shape", shapes);
  if (const YamlValue* s = v.find("size")) r.size = readPositive(*s, path + ".size");
  if (const YamlValue* s = v.find("samples")) r.samples = readInt(*s, path + ".samples", 1, 65536);
  if (r.shape != Reference::HardLight && r.size <= 0.0)
    failAt(v.at, path + ": an area reference ('" + std::string(name(r.shape)) + "') needs a size");
  return r;
}

std::string sha1Hex(const std::string& text) {
  sha1_ctx ctx;
  sha1_init(&ctx);
  sha1_update(&ctx, text.size(), reinterpret_cast<const uint8_t*>(text.data()));
  uint8_t digest[SHA1_DIGEST_SIZE];
  sha1_digest(&ctx, SHA1_DIGEST_SIZE, digest);
  static const char* hex = "0123456789abcdef";
  std::string out;
  for (uint8_t b : digest) {
    out += hex[b >> 4];
    out += hex[b & 15];
  }
  return out;
}

std::string shortKey(const std::string& key) {
  const size_t dot = key.rfind('.');
  return dot == std::string::npos ? key : key.substr(dot + 1);
}

struct Case {
  std::string label;
  std::vector<Setting> set;
  std::vector<std::string> methods;  // empty: the group's
};

std::vector<std::string> readMethods(const YamlValue& v, const std::string& path) {
  std::vector<std::string> methods;
  for (size_t i = 0; i < requireList(v, path).items.size(); ++i) {
    const YamlValue& m = v.items[i];
    const std::string method = readText(m, path + "." + std::to_string(i));
    if (!findTechnique(method)) failAt(m.at, path + "." + std::to_string(i) + ": " + unknownTechniqueMessage(method));
    methods.push_back(method);
  }
  return methods;
}

struct GridAxis {
  std::string key;
  std::vector<std::string> values;
  std::vector<SourceLocation> at;
};

void readGroup(const YamlValue& g, const std::string& path, const Defaults& defaults,
               const std::filesystem::path& folder, std::vector<Job>& jobs) {
  checkKeys(g, path,
            {"name", "scenes", "methods", "set", "grid", "cases", "frames", "record", "reference", "repetitions", "plot"});
  const YamlValue* nameValue = g.find("name");
  if (!nameValue) failAt(g.at, path + ": a group needs a name");
  const std::string groupName = readText(*nameValue, path + ".name");
  std::string plot = groupName;
  if (const YamlValue* v = g.find("plot")) plot = readText(*v, path + ".plot");

  const YamlValue* scenesValue = g.find("scenes");
  if (!scenesValue) failAt(g.at, path + ": a group needs scenes");
  std::vector<std::pair<std::string, std::string>> scenes;  // as written, as opened
  for (size_t i = 0; i < requireList(*scenesValue, path + ".scenes").items.size(); ++i) {
    const YamlValue& s = scenesValue->items[i];
    const std::string written = readText(s, path + ".scenes." + std::to_string(i));
    const std::filesystem::path opened = std::filesystem::path(written).is_absolute() ? std::filesystem::path(written) : folder / written;
    if (!std::filesystem::is_regular_file(opened))
      failAt(s.at, path + ".scenes." + std::to_string(i) + ": no scene file '" + opened.string() + "'");
    scenes.emplace_back(written, opened.lexically_normal().string());
  }

  std::vector<std::string> methods;
  if (const YamlValue* v = g.find("methods")) methods = readMethods(*v, path + ".methods");

  std::vector<Setting> set = defaults.set;
  if (const YamlValue* v = g.find("set"))
    for (auto& kv : readSet(*v, path + ".set")) set.push_back(std::move(kv));

  std::vector<Case> cases;
  if (const YamlValue* v = g.find("cases")) {
    requireList(*v, path + ".cases");
    for (size_t i = 0; i < v->items.size(); ++i) {
      const YamlValue& c = v->items[i];
      const std::string cpath = path + ".cases." + std::to_string(i);
      checkKeys(c, cpath, {"label", "set", "methods"});
      Case one;
      if (const YamlValue* l = c.find("label")) one.label = readText(*l, cpath + ".label");
      if (const YamlValue* m = c.find("methods")) one.methods = readMethods(*m, cpath + ".methods");
      if (const YamlValue* s = c.find("set")) one.set = readSet(*s, cpath + ".set");
      cases.push_back(std::move(one));
    }
  } else {
    cases.emplace_back();
  }
  for (const Case& c : cases)
    if (methods.empty() && c.methods.empty()) failAt(g.at, path + ": a group needs methods (or each of its cases)");

  std::vector<GridAxis> grid;
  if (const YamlValue* v = g.find("grid")) {
    if (!v->isMap()) failAt(v->at, path + ".grid: expected a map of -D keys to lists of values, got " + v->kindName());
    for (const YamlEntry& e : v->entries) {
      GridAxis axis{e.key, {}, {}};
      const std::string apath = path + ".grid." + e.key;
      for (const YamlValue& item : requireList(e.value, apath).items) {
        axis.values.push_back(valueText(item, apath));
        axis.at.push_back(item.at);
      }
      grid.push_back(std::move(axis));
    }
  }

  std::vector<int> frames = {0};
  if (const YamlValue* v = g.find("frames")) {
    frames.clear();
    for (size_t i = 0; i < requireList(*v, path + ".frames").items.size(); ++i)
      frames.push_back(readInt(v->items[i], path + ".frames." + std::to_string(i), 0, 1'000'000));
  }
  const RecordWhat record = g.find("record") ? readRecord(*g.find("record"), path + ".record") : defaults.record;
  const ReferenceSpec reference =
      g.find("reference") ? readReference(*g.find("reference"), path + ".reference", defaults.reference) : defaults.reference;
  const int repetitions =
      g.find("repetitions") ? readInt(*g.find("repetitions"), path + ".repetitions", 1, 10000) : defaults.repetitions;

  size_t combinations = 1;  // of the grid's values
  for (const GridAxis& a : grid) {
    combinations *= a.values.size();
    if (combinations > kMaxJobs) break;
  }
  size_t methodCount = 0;
  for (const Case& c : cases) methodCount += c.methods.empty() ? methods.size() : c.methods.size();
  if (combinations > kMaxJobs || scenes.size() * methodCount * frames.size() * combinations + jobs.size() > kMaxJobs)
    failAt(g.at, path + ": more than " + std::to_string(kMaxJobs) + " jobs in the sweep");

  for (const auto& [written, opened] : scenes)
    for (const Case& c : cases)
      for (const std::string& method : c.methods.empty() ? methods : c.methods)
        for (size_t combo = 0; combo < combinations; ++combo)
          for (int frame : frames) {
            Job job;
            job.scene = written;
            job.scenePath = opened;
            job.method = method;
            job.frame = frame;
            job.record = record;
            job.reference = reference;
            job.repetitions = repetitions;
            job.groups = {groupName};
            // "{scene}" in a plot's name: one plot per scene of the group.
            std::string jobPlot = plot;
            if (const size_t at = jobPlot.find("{scene}"); at != std::string::npos)
              jobPlot.replace(at, 7, std::filesystem::path(written).stem().string());
            job.plots = {jobPlot};
            // Later layers win: the file's and the group's `set`, the case's, then the grid.
            for (const Setting& x : set) job.overrides[x.key] = x.value, job.overrideAt[x.key] = x.at;
            for (const Setting& x : c.set) job.overrides[x.key] = x.value, job.overrideAt[x.key] = x.at;
            std::string label = c.label;
            size_t rest = combo;
            for (size_t a = grid.size(); a-- > 0;) {  // the last axis varies fastest
              const size_t v = rest % grid[a].values.size();
              rest /= grid[a].values.size();
              job.overrides[grid[a].key] = grid[a].values[v];
              job.overrideAt[grid[a].key] = grid[a].at[v];
            }
            rest = combo;
            std::vector<std::string> parts(grid.size());
            for (size_t a = grid.size(); a-- > 0;) {
              parts[a] = shortKey(grid[a].key) + "=" + grid[a].values[rest % grid[a].values.size()];
              rest /= grid[a].values.size();
            }
            for (const std::string& p : parts) label += (label.empty() ? "" : " ") + p;
            job.label = label;
            job.order = jobs.size();
            jobs.push_back(std::move(job));
          }
}

}  // namespace

std::string canonicalJson(const Job& job) {
  nlohmann::json j;  // an object's keys come out sorted: the text depends on the values only
  j["scene"] = job.scene;
  j["method"] = job.method;
  j["frame"] = job.frame;
  j["overrides"] = nlohmann::json::object();
  for (const auto& [k, v] : job.overrides) j["overrides"][k] = v;
  nlohmann::json record = nlohmann::json::array();
  if (job.record.counts) record.push_back("counts");
  if (job.record.error) record.push_back("error");
  if (job.record.time) record.push_back("time");
  j["record"] = record;
  if (job.record.error) {
    j["reference"] = {{"shape", name(job.reference.shape)}};
    if (job.reference.shape != Reference::HardLight) {
      j["reference"]["size"] = job.reference.size;
      j["reference"]["samples"] = job.reference.samples;
    }
  }
  if (job.record.time) j["repetitions"] = job.repetitions;
  return j.dump();
}

Spec parseSpec(const std::string& yaml, const std::string& file) {
  const YamlValue root = parseYaml(yaml, file);
  if (!root.isMap()) failAt(root.at, "a sweep file is a map with the key 'groups', got " + std::string(root.kindName()));
  checkKeys(root, "", {"threads", "repetitions", "record", "reference", "set", "groups"});
  Spec spec;
  spec.file = file;
  Defaults defaults;
  if (const YamlValue* v = root.find("threads")) spec.threads = readInt(*v, "threads", 0, 256);
  if (const YamlValue* v = root.find("repetitions")) defaults.repetitions = readInt(*v, "repetitions", 1, 10000);
  if (const YamlValue* v = root.find("record")) defaults.record = readRecord(*v, "record");
  if (const YamlValue* v = root.find("reference")) defaults.reference = readReference(*v, "reference", defaults.reference);
  if (const YamlValue* v = root.find("set")) defaults.set = readSet(*v, "set");
  const YamlValue* groups = root.find("groups");
  if (!groups) failAt(root.at, "a sweep file needs 'groups'");
  requireList(*groups, "groups");
  const std::filesystem::path folder = std::filesystem::path(file).parent_path();
  std::vector<Job> jobs;
  std::set<std::string> names;
  for (size_t i = 0; i < groups->items.size(); ++i) {
    const YamlValue& g = groups->items[i];
    const std::string path = "groups." + std::to_string(i);
    if (!g.isMap()) failAt(g.at, path + ": expected a map, got " + g.kindName());
    if (const YamlValue* n = g.find("name"); n && n->isScalar() && !names.insert(n->scalar).second)
      failAt(n->at, path + ".name: a second group named '" + n->scalar + "'");
    readGroup(g, path, defaults, folder, jobs);
  }
  for (Job& job : jobs) {
    job.canonical = canonicalJson(job);
    job.id = sha1Hex(job.canonical).substr(0, kIdDigits);
  }
  // One job per configuration, whatever lists it how often: its groups and plots are the union,
  // its label the one of its first (group, label) by name, so nothing depends on the file's order.
  std::sort(jobs.begin(), jobs.end(), [](const Job& a, const Job& b) {
    return std::tie(a.id, a.groups, a.label) < std::tie(b.id, b.groups, b.label);
  });
  for (Job& job : jobs) {
    if (!spec.jobs.empty() && spec.jobs.back().id == job.id) {
      Job& kept = spec.jobs.back();
      kept.order = std::min(kept.order, job.order);
      if (kept.canonical != job.canonical) throw std::runtime_error(file + ": two jobs share the id " + job.id);
      for (std::vector<std::string> Job::*list : {&Job::groups, &Job::plots}) {
        std::vector<std::string>& into = kept.*list;
        for (const std::string& s : job.*list)
          if (std::find(into.begin(), into.end(), s) == into.end()) into.push_back(s);
        std::sort(into.begin(), into.end());
      }
      continue;
    }
    spec.jobs.push_back(std::move(job));
  }
  return spec;
}

Spec loadSpec(const std::string& path) { return parseSpec(readInputFile(path, "sweep file", kMaxSceneFileBytes), path); }

std::vector<const Job*> shardJobs(const Spec& spec, int k, int n) {
  std::vector<const Job*> out;
  for (size_t i = size_t(k - 1); i < spec.jobs.size(); i += size_t(n)) out.push_back(&spec.jobs[i]);
  return out;
}

std::string methodFamily(const std::string& method) {
  if (method == "none") return "none";
  const ShadowTechnique* t = findTechnique(method);
  return t && t->countsInStencil ? "shadow volumes" : "shadow maps";
}

}  // namespace shadowref::sweep
