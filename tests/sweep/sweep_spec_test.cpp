// Sweep files (src/sweep/sweep_spec.h): jobs expanded from groups, ids from the canonical
// configuration whatever the file's order, shards that partition the jobs, errors at file:line:col.
#include <catch2/catch.hpp>

#include <set>
#include <string>

#include "support/errors.h"
#include "sweep/sweep_spec.h"

using namespace shadowref;
using namespace shadowref::sweep;

namespace {

std::set<std::string> idsOf(const Spec& spec) {
  std::set<std::string> ids;
  for (const Job& j : spec.jobs) ids.insert(j.id);
  return ids;
}

// Scene paths are relative to the sweep file's folder: "t.sweep.yaml" lies in the source folder,
// where the tests run.
std::string errorOf(const std::string& yaml) {
  return testing::messageOf([&] { parseSpec(yaml, "t.sweep.yaml"); });
}

const char* const kSpec = R"(repetitions: 3
set: {image.width: 16, image.height: 12}
groups:
  - name: volumes
    scenes: [scenes/room.yaml]
    methods: [zpass, zfail]
    grid: {image.depth: [float32, unorm24]}
  - name: maps
    scenes: [scenes/outdoor.yaml]
    methods: [shadowmap]
    set: {shadow.pcf: 3}
    grid: {shadow.map_size: [64, 128], camera.far: [300, infinite]}
)";

// The same jobs: groups, methods, grid keys, grid values and set keys in another order.
const char* const kReordered = R"(groups:
  - name: maps
    grid: {camera.far: [infinite, 300], shadow.map_size: [128, 64]}
    set: {shadow.pcf: 3}
    methods: [shadowmap]
    scenes: [scenes/outdoor.yaml]
  - methods: [zfail, zpass]
    grid: {image.depth: [unorm24, float32]}
    scenes: [scenes/room.yaml]
    name: volumes
set: {image.height: 12, image.width: 16}
repetitions: 3
)";

}  // namespace

TEST_CASE("a sweep's jobs are the product of scenes, methods, cases and grid values", "[sweep]") {
  const Spec spec = parseSpec(kSpec, "t.sweep.yaml");
  REQUIRE(spec.jobs.size() == 2 * 2 + 2 * 2);
  for (const Job& j : spec.jobs) {
    CHECK(j.overrides.at("image.width") == "16");
    CHECK(j.repetitions == 3);
    CHECK(j.record.time);
    CHECK(j.record.error);
    CHECK(j.record.counts);
    CHECK(j.id.size() == kIdDigits);
  }
  // Sorted by id, and unique.
  for (size_t i = 1; i < spec.jobs.size(); ++i) CHECK(spec.jobs[i - 1].id < spec.jobs[i].id);
}

TEST_CASE("a job's canonical configuration and id are fixed values", "[sweep]") {
  const Spec spec = parseSpec(R"(record: [error, counts]
groups:
  - {name: g, scenes: [scenes/room.yaml], methods: [zfail], set: {image.width: 16, image.height: 12}}
)",
                              "t.sweep.yaml");
  REQUIRE(spec.jobs.size() == 1);
  const Job& job = spec.jobs[0];
  // Keys sorted, no spaces; no repetitions when the job is not timed.
  CHECK(job.canonical ==
        R"({"frame":0,"method":"zfail","overrides":{"image.height":"12","image.width":"16"},)"
        R"("record":["counts","error"],"reference":{"shape":"point"},"scene":"scenes/room.yaml"})");
  // `printf '%s' '<the canonical text>' | sha1sum`: 4cbc1d07be1b7c5bdef2c3cebc5c03c7bc065a18
  CHECK(job.id == "4cbc1d07be1b7c5b");
}

TEST_CASE("job ids do not depend on the order of the sweep file", "[sweep]") {
  const Spec a = parseSpec(kSpec, "t.sweep.yaml");
  const Spec b = parseSpec(kReordered, "t.sweep.yaml");
  REQUIRE(idsOf(a) == idsOf(b));
  for (size_t i = 0; i < a.jobs.size(); ++i) CHECK(a.jobs[i].canonical == b.jobs[i].canonical);
  // ... and do depend on every value: one changed value changes exactly the jobs it is part of.
  std::string changed = kSpec;
  changed.replace(changed.find("shadow.pcf: 3"), 13, "shadow.pcf: 5");
  const Spec c = parseSpec(changed, "t.sweep.yaml");
  std::set<std::string> common;
  for (const std::string& id : idsOf(c))
    if (idsOf(a).count(id)) common.insert(id);
  CHECK(common.size() == 4);  // the four room jobs
}

TEST_CASE("a configuration listed twice is one job in both groups", "[sweep]") {
  const Spec spec = parseSpec(R"(groups:
  - {name: b, scenes: [scenes/room.yaml], methods: [zpass, zfail], plot: p2}
  - {name: a, scenes: [scenes/room.yaml], methods: [zfail], plot: p1}
)",
                              "t.sweep.yaml");
  REQUIRE(spec.jobs.size() == 2);
  const Job& zfail = spec.jobs[0].method == "zfail" ? spec.jobs[0] : spec.jobs[1];
  CHECK(zfail.groups == std::vector<std::string>{"a", "b"});
  CHECK(zfail.plots == std::vector<std::string>{"p1", "p2"});
}

TEST_CASE("cases choose their methods and label the jobs, and {scene} names a plot per scene", "[sweep]") {
  const Spec spec = parseSpec(R"(groups:
  - name: g
    scenes: [scenes/room.yaml, scenes/pumpkins.yaml]
    plot: "{scene}"
    cases:
      - {label: hard, methods: [none, zfail]}
      - {label: soft, methods: [zfail], set: {lights.0.soft.shape: square_y}}
    grid: {image.width: [16, 32]}
)",
                              "t.sweep.yaml");
  REQUIRE(spec.jobs.size() == 2 * (2 + 1) * 2);
  int soft = 0;
  for (const Job& j : spec.jobs) {
    CHECK(j.plots.size() == 1);
    CHECK(j.plots[0] == (j.scene == "scenes/room.yaml" ? "room" : "pumpkins"));
    CHECK(j.label == (j.overrides.count("lights.0.soft.shape") ? "soft " : "hard ") + std::string("width=") +
                         j.overrides.at("image.width"));
    soft += j.overrides.count("lights.0.soft.shape") ? 1 : 0;
    if (j.overrides.count("lights.0.soft.shape")) CHECK(j.method == "zfail");
  }
  CHECK(soft == 4);
}

TEST_CASE("the shards partition the jobs", "[sweep]") {
  const Spec spec = parseSpec(R"(groups:
  - {name: g, scenes: [scenes/room.yaml], methods: [none, zpass, zfail, auto], grid: {image.width: [8, 9, 10]}}
)",
                              "t.sweep.yaml");
  REQUIRE(spec.jobs.size() == 12);
  for (int n = 1; n <= 13; ++n) {
    std::multiset<std::string> seen;
    size_t smallest = spec.jobs.size(), largest = 0;
    for (int k = 1; k <= n; ++k) {
      const std::vector<const Job*> shard = shardJobs(spec, k, n);
      smallest = std::min(smallest, shard.size());
      largest = std::max(largest, shard.size());
      for (const Job* j : shard) seen.insert(j->id);
    }
    INFO("n = " << n);
    CHECK(seen.size() == spec.jobs.size());  // every job in some shard ...
    CHECK(std::set<std::string>(seen.begin(), seen.end()) == idsOf(spec));  // ... exactly once
    CHECK(largest - smallest <= 1);
  }
}

TEST_CASE("sweep file errors name file, line and column", "[sweep]") {
  CHECK(errorOf("groups:\n  - name: a\n    scenes: [scenes/room.yaml]\n    methods: [zfail]\n    colour: 3\n") ==
        "t.sweep.yaml:5:5: unknown key 'colour' in groups.0 (allowed: name, scenes, methods, set, grid, cases, "
        "frames, record, reference, repetitions, plot)");
  CHECK(errorOf("groups:\n  - {name: a, scenes: [scenes/room.yaml], methods: [zpass, zfial]}\n") ==
        "t.sweep.yaml:2:60: groups.0.methods.1: 'zfial' is not one of none, zpass, zfail, auto, shadowmap, tsm; did "
        "you mean 'zfail'?");
  CHECK(errorOf("groups:\n  - {name: a, scenes: [scenes/nowhere.yaml], methods: [zfail]}\n") ==
        "t.sweep.yaml:2:24: groups.0.scenes.0: no scene file 'scenes/nowhere.yaml'");
  CHECK(errorOf("groups:\n  - {name: a, scenes: [scenes/room.yaml], methods: [zfail], grid: {image.width: 8}}\n") ==
        "t.sweep.yaml:2:81: groups.0.grid.image.width: expected a list of at least one value, got a single value");
  CHECK(errorOf("groups:\n  - {name: a, scenes: [scenes/room.yaml], methods: [zfail], frames: [-1]}\n") ==
        "t.sweep.yaml:2:70: groups.0.frames.0: -1 is outside the allowed range [0, 1000000]");
  CHECK(errorOf("record: [time, time]\ngroups: []\n") == "t.sweep.yaml:1:16: record: 'time' is listed twice");
  CHECK(errorOf("groups:\n  - {name: a, scenes: [scenes/room.yaml], methods: [zfail]}\n  - {name: a, scenes: "
                "[scenes/room.yaml], methods: [zpass]}\n") ==
        "t.sweep.yaml:3:12: groups.1.name: a second group named 'a'");
  CHECK(errorOf("reference: {shape: square}\ngroups: []\n") ==
        "t.sweep.yaml:1:12: reference: an area reference ('square') needs a size");
  CHECK(errorOf("thread: 2\n").rfind("t.sweep.yaml:1:1: unknown key 'thread'", 0) == 0);
  // A grid that would multiply out to more jobs than any sweep needs is refused before expanding.
  CHECK(errorOf("groups:\n  - name: a\n    scenes: [scenes/room.yaml]\n    methods: [zfail]\n    grid: {a: "
                "[1,2,3,4,5,6,7,8,9,10], b: [1,2,3,4,5,6,7,8,9,10], c: [1,2,3,4,5,6,7,8,9,10], d: "
                "[1,2,3,4,5,6,7,8,9,10], e: [1,2,3,4,5,6,7,8,9,10], f: [1,2,3,4,5,6,7,8,9,10]}\n") ==
        "t.sweep.yaml:2:5: groups.0: more than 100000 jobs in the sweep");
}

TEST_CASE("methods are grouped into families for the plots' colours", "[sweep]") {
  CHECK(methodFamily("none") == "none");
  CHECK(methodFamily("zpass") == "shadow volumes");
  CHECK(methodFamily("zfail") == "shadow volumes");
  CHECK(methodFamily("auto") == "shadow volumes");
  CHECK(methodFamily("shadowmap") == "shadow maps");
  CHECK(methodFamily("tsm") == "shadow maps");
}
