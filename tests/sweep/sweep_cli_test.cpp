// `shadowref sweep` as a user runs it: exit status 2 and file:line:col for bad sweep files, bad
// -D values (placed in the sweep file, not on a command line) and bad flags; --merge exits 1
// until every record is there; --list prints one JSON line per job of the shard.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "support/cli_run.h"

using namespace shadowref::testing;
namespace fs = std::filesystem;

namespace {

fs::path writeSpec(const std::string& name, const std::string& text) {
  const fs::path path = testScratch() / name;
  std::ofstream(path) << text;
  return path;
}

std::string scenes() { return (fs::path(SHADOWREF_SOURCE_DIR) / "scenes").string(); }

}  // namespace

TEST_CASE("sweep reports bad sweep files and flags with exit 2", "[sweep][cli]") {
  const fs::path bad = writeSpec("bad.sweep.yaml", "groups:\n  - {name: a, scenes: [" + scenes() +
                                                       "/room.yaml], methods: [zfail], colour: 1}\n");
  CliRun r = runShadowref("sweep '" + bad.string() + "' --list");
  CHECK(r.status == 2);
  CHECK(r.err.rfind(bad.string() + ":2:", 0) == 0);
  CHECK(r.err.find("unknown key 'colour'") != std::string::npos);

  const fs::path good = writeSpec("good.sweep.yaml", "record: [error]\nset: {image.width: 16, image.height: 12}\n"
                                                     "groups:\n  - {name: a, scenes: [" + scenes() +
                                                     "/room.yaml], methods: [none, zpass, zfail]}\n");
  for (const char* flags : {"--shard 0/3", "--shard 4/3", "--shard 1/", "--shard x/2", "--merge --shard 1/2",
                            "--csv a.csv", "--threads -1"}) {
    INFO(flags);
    CHECK(runShadowref("sweep '" + good.string() + "' " + flags).status == 2);
  }
  // --list: one line per job of the shard, each with its id.
  r = runShadowref("sweep '" + good.string() + "' --list --shard 2/2");
  CHECK(r.status == 0);
  CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 1);
  CHECK(r.out.rfind("{\"config\":{", 0) == 0);
}

TEST_CASE("a bad -D value of a sweep file is reported where the file sets it", "[sweep][cli]") {
  const fs::path spec = writeSpec("badvalue.sweep.yaml", "record: [counts]\nset: {image.width: 16, image.height: 12}\n"
                                                         "groups:\n  - name: a\n    scenes: [" + scenes() +
                                                         "/room.yaml]\n    methods: [zfail]\n"
                                                         "    grid: {camera.fov: [50, 500]}\n");
  const fs::path out = testScratch() / "badvalue-out";
  fs::remove_all(out);
  const CliRun r = runShadowref("sweep '" + spec.string() + "' --out '" + out.string() + "'");
  CHECK(r.status == 2);
  // The value 500 at line 7, column 29 of the sweep file; the good job still ran.
  INFO(r.err);
  CHECK(r.err.find(spec.string() + ":7:29: camera.fov: ") != std::string::npos);
  CHECK(r.err.find("500 (in " + scenes() + "/room.yaml)") != std::string::npos);
  CHECK(r.err.find("<command line>") == std::string::npos);
  CHECK(r.err.find("1 jobs run") != std::string::npos);
  // The merge misses the failed job's record: exit 1, no CSV.
  const CliRun merge = runShadowref("sweep '" + spec.string() + "' --out '" + out.string() + "' --merge");
  CHECK(merge.status == 1);
  CHECK(merge.err.find("1 of 2 jobs have no complete record") != std::string::npos);
  CHECK_FALSE(fs::exists(out / "results.csv"));
}
