// What a shadowref process loads: none of the libraries only one command needs. The explorer's
// server (cpp-httplib, which brings OpenSSL and Brotli) lives in shadowref-explore, OSMesa (which
// brings LLVM) in shadowref-gl, OpenImageIO in the image reader `compare` loads; shadowref hands
// `explore` over to shadowref-explore unchanged, and without it still exports and says where the
// server is. The dynamic loader's own account (LD_DEBUG=files) names every file it loads.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "support/cli_run.h"

namespace fs = std::filesystem;
using shadowref::testing::CliRun;
using shadowref::testing::freshScratchDir;
using shadowref::testing::runShell;

namespace {

// The files the dynamic loader opened for `PROGRAM ARGS` (its "file=NAME" lines), the program's own
// output in out.
std::vector<std::string> loadedFiles(const std::string& program, const std::string& args, CliRun* run = nullptr) {
  const CliRun r = runShell("LD_DEBUG=files '" + program + "' " + args);
  std::vector<std::string> files;
  for (size_t at = r.err.find("file="); at != std::string::npos; at = r.err.find("file=", at + 1)) {
    const size_t end = r.err.find_first_of(" \t\n", at);
    files.push_back(r.err.substr(at + 5, end - at - 5));
  }
  if (run) *run = r;
  return files;
}

bool loadsAny(const std::vector<std::string>& files, const std::vector<std::string>& prefixes) {
  for (const std::string& file : files) {
    const std::string name = fs::path(file).filename().string();
    for (const std::string& prefix : prefixes)
      if (name.rfind(prefix, 0) == 0) return true;
  }
  return false;
}

const std::vector<std::string> kOneCommandLibraries{"libcpp-httplib", "libssl", "libcrypto",  "libbrotli",
                                                    "libOpenImageIO", "libOSMesa", "libLLVM"};

}  // namespace

TEST_CASE("shadowref loads none of the libraries only explore, compare or a replay on OSMesa need", "[cli][startup]") {
  const fs::path dir = freshScratchDir("startup-libraries");
  const std::string out = (dir / "x").string();
  for (const std::string& args :
       {std::string("--help"), std::string("check scenes/room.yaml"), std::string("info scenes/room.yaml"),
        "render scenes/minimal.yaml -D image.width=32 -D image.height=24 --quiet -o " + out + ".png -o " + out + ".exr"}) {
    INFO(args);
    CliRun r;
    const std::vector<std::string> files = loadedFiles(SHADOWREF_CLI, args, &r);
    CHECK(r.status == 0);
    // The loader's account is there (libc at least), so an empty list cannot pass.
    CHECK(loadsAny(files, {"libc.so"}));
    CHECK_FALSE(loadsAny(files, kOneCommandLibraries));
  }
}

TEST_CASE("shadowref explore runs in shadowref-explore, which links the server", "[cli][startup]") {
  CliRun r;
  const std::vector<std::string> files = loadedFiles(SHADOWREF_CLI, "explore --help", &r);
  CHECK(r.status == 0);
  CHECK(r.out.find("explore [OPTIONS] [scene]") != std::string::npos);
  // shadowref itself links no cpp-httplib (above): loading it shows the hand-over.
  CHECK(loadsAny(files, {"libcpp-httplib"}));
}

TEST_CASE("without shadowref-explore beside it, shadowref explore exports and names the missing server",
          "[cli][startup]") {
  const fs::path dir = freshScratchDir("lone-shadowref");
  fs::copy_file(SHADOWREF_CLI, dir / "shadowref");
  const std::string lone = "'" + (dir / "shadowref").string() + "' ";

  const CliRun help = runShell(lone + "explore --help");
  CHECK(help.status == 0);
  CHECK(help.out.find("--export") != std::string::npos);

  const CliRun serve = runShell(lone + "explore --port 0");
  CHECK(serve.status == 1);
  CHECK(serve.err.find((dir / "shadowref-explore").string()) != std::string::npos);
  CHECK(serve.out.empty());  // no URL: nothing serves

  const CliRun exported =
      runShell(lone + "explore --export '" + (dir / "page").string() + "' -D image.width=32 -D image.height=24");
  CHECK(exported.status == 0);
  CHECK(fs::is_regular_file(dir / "page" / "index.html"));
}
