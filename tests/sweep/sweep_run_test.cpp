// Running and merging a sweep (src/sweep/sweep_run.h, sweep_merge.h) on tiny frames: records
// written once, skipped when complete, redone when missing, truncated or another job's; the merged
// CSV the same bytes every time, its rows in id order.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "scene/animation.h"
#include "scene/scene_loader.h"
#include "shadow/frame_renderer.h"
#include "support/cli_run.h"
#include "sweep/sweep_merge.h"
#include "sweep/sweep_run.h"

using namespace shadowref;
using namespace shadowref::sweep;
namespace fs = std::filesystem;

namespace {

// Four untimed jobs of 16 x 12 pixels: two volume methods, a shadow map, and no shadows.
Spec tinySpec() {
  return parseSpec(R"(record: [error, counts]
set: {image.width: 16, image.height: 12}
groups:
  - {name: volumes, scenes: [scenes/room.yaml], methods: [none, zpass, zfail]}
  - {name: maps, scenes: [scenes/room.yaml], methods: [shadowmap], set: {shadow.map_size: 64}}
)",
                   "t.sweep.yaml");
}

fs::path freshFolder(const std::string& name) { return testing::freshScratchDir(name); }

std::vector<const Job*> all(const Spec& spec) { return shardJobs(spec, 1, 1); }

RunSummary run(const Spec& spec, const fs::path& dir, std::vector<std::string>* errors = nullptr) {
  RunOptions options;
  options.outDir = dir.string();
  options.timing = false;
  return runJobs(all(spec), options, [&](const std::string& m) {
    if (errors) errors->push_back(m);
  });
}

}  // namespace

TEST_CASE("a sweep run writes one record per job and skips complete records when run again", "[sweep]") {
  const Spec spec = tinySpec();
  const fs::path dir = freshFolder("sweep-resume");
  RunSummary first = run(spec, dir);
  CHECK(first.ran == 4);
  CHECK(first.skipped == 0);
  CHECK(first.failed + first.badInput == 0);
  std::map<std::string, std::string> bytes;
  for (const Job& j : spec.jobs) {
    REQUIRE(fs::exists(recordPath(dir.string(), j)));
    CHECK(recordIsComplete(recordPath(dir.string(), j), j, true));
    bytes[j.id] = testing::slurp(recordPath(dir.string(), j));
  }
  // Nothing but the records: no temporary file is left behind.
  CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 4);

  // Resume: every record is complete, nothing runs.
  const auto before = fs::last_write_time(recordPath(dir.string(), spec.jobs[0]));
  RunSummary again = run(spec, dir);
  CHECK(again.ran == 0);
  CHECK(again.skipped == 4);
  CHECK(fs::last_write_time(recordPath(dir.string(), spec.jobs[0])) == before);

  // A crash's leftovers: one record missing, one cut short, one another job's, one empty.
  fs::remove(recordPath(dir.string(), spec.jobs[0]));
  {
    const std::string path = recordPath(dir.string(), spec.jobs[1]);
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes[spec.jobs[1].id].substr(0, 40);
  }
  fs::copy_file(recordPath(dir.string(), spec.jobs[3]), recordPath(dir.string(), spec.jobs[2]),
                fs::copy_options::overwrite_existing);
  for (int i = 0; i < 3; ++i) CHECK_FALSE(recordIsComplete(recordPath(dir.string(), spec.jobs[size_t(i)]), spec.jobs[size_t(i)], false));
  RunSummary repaired = run(spec, dir);
  CHECK(repaired.ran == 3);
  CHECK(repaired.skipped == 1);
  // The redone records are the bytes of the first run: errors and counts do not vary.
  for (const Job& j : spec.jobs) CHECK(testing::slurp(recordPath(dir.string(), j)) == bytes[j.id]);
}

TEST_CASE("a record holds the job's error and counts, and its time only when timed", "[sweep]") {
  const Spec spec = tinySpec();
  const Job* none = nullptr;
  for (const Job& j : spec.jobs)
    if (j.method == "none") none = &j;
  REQUIRE(none);
  RunOptions options;
  options.timing = false;
  const std::string untimed = runJob(*none, options);
  CHECK(untimed.find("\"time\"") == std::string::npos);
  CHECK(untimed.find("\"machine\"") == std::string::npos);
  CHECK(untimed.find("\"id\":\"" + none->id + "\"") != std::string::npos);
  // `none` sees the light everywhere: its error is the share of counted pixels the oracle calls
  // shadowed, exactly.
  CHECK(untimed.find("\"stencil_writes\":0") != std::string::npos);

  Job timed = *none;
  timed.record.time = true;
  timed.repetitions = 1;
  options.timing = true;
  options.build = "test build";
  const std::string withTime = runJob(timed, options);
  CHECK(withTime.find("\"median_ms\"") != std::string::npos);
  CHECK(withTime.find("\"hostname\":\"" + thisMachine().hostname + "\"") != std::string::npos);
  CHECK(withTime.find("\"build\":\"test build\"") != std::string::npos);
}

TEST_CASE("merging gives the same CSV bytes every time, rows in id order, or names what is missing", "[sweep]") {
  const Spec spec = tinySpec();
  const fs::path dir = freshFolder("sweep-merge");
  MergeOptions options;
  options.outDir = dir.string();
  options.csv = (dir / "a.csv").string();
  options.table = (dir / "table.md").string();

  // Before any job ran: every job is missing and nothing is written.
  MergeResult early = mergeRecords(spec, options);
  CHECK(early.missing.size() == 4);
  CHECK_FALSE(fs::exists(options.csv));

  run(spec, dir);
  MergeResult result = mergeRecords(spec, options);
  REQUIRE(result.missing.empty());
  const std::string first = testing::slurp(options.csv);
  options.csv = (dir / "b.csv").string();
  mergeRecords(spec, options);
  CHECK(testing::slurp(options.csv) == first);

  std::istringstream lines(first);
  std::string line;
  std::getline(lines, line);
  CHECK(line == csvHeader());
  const size_t columns = std::count(line.begin(), line.end(), ',') + 1;
  std::vector<std::string> ids;
  while (std::getline(lines, line)) {
    CHECK(size_t(std::count(line.begin(), line.end(), ',')) + 1 == columns);  // no field here holds a comma
    ids.push_back(line.substr(0, line.find(',')));
  }
  REQUIRE(ids.size() == 4);
  for (size_t i = 0; i < ids.size(); ++i) CHECK(ids[i] == spec.jobs[i].id);
  CHECK(std::is_sorted(ids.begin(), ids.end()));
  // Untimed: no plot data, and a table with a row per job.
  const std::string table = testing::slurp(dir / "table.md");
  for (const Job& j : spec.jobs) CHECK(table.find("`" + j.id + "`") != std::string::npos);
}

TEST_CASE("a job's frame of an animated scene is that scene at frame / fps", "[sweep]") {
  const Spec spec = parseSpec(R"(record: [counts]
set: {image.width: 40, image.height: 32}
groups:
  - {name: circle, scenes: [scenes/anim_room_circle.yaml], methods: [zfail], frames: [0, 6]}
)",
                              "t.sweep.yaml");
  REQUIRE(spec.jobs.size() == 2);
  RunOptions options;
  options.timing = false;
  LoadOptions load;
  load.overrides = {"image.width=40", "image.height=32"};
  const Scene loaded = loadScene("scenes/anim_room_circle.yaml", load);
  REQUIRE(loaded.animation);
  std::set<std::string> counts;
  for (const Job& job : spec.jobs) {
    INFO("frame " << job.frame);
    const nlohmann::json record = nlohmann::json::parse(runJob(job, options));
    FrameOptions frame;
    frame.method = "zfail";
    const RasterStats expected = renderFrame(sceneAt(loaded, double(job.frame) / loaded.animation->fps), frame).stats;
    CHECK(record["counts"]["fragments"] == expected.fragments);
    CHECK(record["counts"]["stencil_writes"] == expected.stencilWrites);
    counts.insert(record["counts"].dump());
  }
  CHECK(counts.size() == 2);  // the light has moved between frames 0 and 6
}
