// Provenance as a user meets it: `shadowref --version`, and the metadata of every image a render
// writes, read back with OpenImageIO and checked against values found independently (the scene
// hash by coreutils' sha1sum, the vector level and compiler from this file's own predefined macros).
#include <catch2/catch.hpp>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#include <OpenImageIO/imageio.h>

#include "support/cli_run.h"

namespace fs = std::filesystem;
using shadowref::testing::CliRun;
using shadowref::testing::runShadowref;
using shadowref::testing::runShell;
using shadowref::testing::slurp;

namespace {

fs::path scratch() {
  const fs::path dir = fs::temp_directory_path() / ("shadowref-provenance-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

// "name: value" lines after the first, as a map.
std::map<std::string, std::string> versionFields(const std::string& text) {
  std::map<std::string, std::string> fields;
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    const size_t colon = line.find(": ");
    if (colon != std::string::npos) fields[line.substr(0, colon)] = line.substr(colon + 2);
  }
  return fields;
}

// The level this file was compiled for: the test is built with the same -march as shadowref.
std::string expectedIsaLevel() {
#if defined(__AVX512F__) && defined(__AVX512BW__) && defined(__AVX512VL__) && defined(__AVX512DQ__)
  return "x86-64-v4";
#elif defined(__AVX2__) && defined(__FMA__) && defined(__BMI2__)
  return "x86-64-v3";
#else
  return "baseline";
#endif
}

std::string expectedCompiler() {
#if defined(__clang__)
  return "Clang " + std::to_string(__clang_major__) + "." + std::to_string(__clang_minor__) + "." +
         std::to_string(__clang_patchlevel__);
#elif defined(__GNUC__)
  return "GNU " + std::to_string(__GNUC__) + "." + std::to_string(__GNUC_MINOR__) + "." +
         std::to_string(__GNUC_PATCHLEVEL__);
#else
  return "";
#endif
}

std::map<std::string, std::string> shadowrefAttributes(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  REQUIRE(in);
  std::map<std::string, std::string> attributes;
  for (const OIIO::ParamValue& p : in->spec().extra_attribs) {
    const std::string name = p.name().string();
    if (name == "Software" || name == "ImageDescription" || name.rfind("shadowref:", 0) == 0)
      attributes[name] = p.get_string();
  }
  return attributes;
}

}  // namespace

TEST_CASE("shadowref --version prints the version, revision, vector level and compiler and exits 0", "[cli][provenance]") {
  const CliRun r = runShadowref("--version");
  INFO(r.out << r.err);
  CHECK(r.status == 0);
  CHECK(r.err.empty());
  CHECK(r.out.rfind(std::string("shadowref ") + SHADOWREF_VERSION + "\n", 0) == 0);
  const auto fields = versionFields(r.out);
  REQUIRE(fields.count("revision"));
  const std::string revision = fields.at("revision");
  CHECK(std::regex_match(revision, std::regex("[0-9a-f]{7,40}(-dirty)?|unknown")));
  if (revision != "unknown") {
    // A commit of this repository (the binary may be older than the newest commit).
    const std::string hash = revision.substr(0, revision.find('-'));
    CHECK(runShell("git cat-file -e '" + hash + "^{commit}'").status == 0);
  }
  REQUIRE(fields.count("isa"));
  REQUIRE(fields.count("compiler"));
  CHECK(fields.at("isa") == expectedIsaLevel());
  CHECK(fields.at("compiler") == expectedCompiler());
  CHECK(fields.count("build type") == 1);
  // --version wins over the missing subcommand, and --help lists it.
  CHECK(runShadowref("--help").out.find("--version") != std::string::npos);
}

TEST_CASE("every image a render writes names the program, scene, hash, overrides, threads", "[cli][provenance]") {
  const fs::path dir = scratch();
  const std::string revision = versionFields(runShadowref("--version").out)["revision"];
  const CliRun sum = runShell("sha1sum scenes/minimal.yaml");
  REQUIRE(sum.status == 0);
  const std::string sceneSha1 = sum.out.substr(0, 40);
  const std::string png = (dir / "m.png").string(), exr = (dir / "m.exr").string();
  const std::string args = "render scenes/minimal.yaml -D image.width=40 -D image.height=30 "
                           "-D 'ambient=[0.2, 0.2, 0.2]' --method zpass --threads 2 --dump depth --dump stencil --quiet";
  const CliRun r = runShadowref(args + " -o '" + png + "' -o '" + exr + "'");
  INFO(r.err);
  REQUIRE(r.status == 0);

  const std::map<std::string, std::string> common = {
      {"Software", std::string("shadowref ") + SHADOWREF_VERSION + " (" + revision + ")"},
      {"shadowref:method", "zpass"},
      {"shadowref:scene", "scenes/minimal.yaml"},
      {"shadowref:scene-sha1", sceneSha1},
      {"shadowref:overrides", "-D image.width=40 -D image.height=30 -D 'ambient=[0.2, 0.2, 0.2]'"},
      {"shadowref:threads", "2"},
      {"shadowref:pipeline", "fast"},
  };
  const std::map<std::string, std::string> files = {
      {png, "frame"}, {exr, "frame"}, {(dir / "m.depth.png").string(), "depth"},
      {(dir / "m.stencil-L0.png").string(), "stencil L0"}};
  for (const auto& [file, content] : files) {
    INFO(file);
    auto expected = common;
    expected["shadowref:content"] = content;
    expected["ImageDescription"] = content + " of scenes/minimal.yaml, shadow method zpass";
    const auto attributes = shadowrefAttributes(file);
    CHECK(attributes.size() == expected.size());
    for (const auto& [key, value] : expected) {
      INFO(key);
      CHECK((attributes.count(key) ? attributes.at(key) : "(missing)") == value);
    }
  }

  // The same command gives the same bytes, metadata included.
  const std::string png2 = (dir / "again.png").string(), exr2 = (dir / "again.exr").string();
  REQUIRE(runShadowref(args + " -o '" + png2 + "' -o '" + exr2 + "'").status == 0);
  CHECK(slurp(png) == slurp(png2));
  CHECK(slurp(exr) == slurp(exr2));
}

TEST_CASE("the built-in scene is named as such and has no file hash, and no -D gives no overrides", "[cli][provenance]") {
  const std::string png = (scratch() / "builtin.png").string();
  REQUIRE(runShadowref("render -D image.width=32 -D image.height=24 --threads 1 --quiet -o '" + png + "'").status == 0);
  const auto attributes = shadowrefAttributes(png);
  CHECK(attributes.at("shadowref:scene") == "<builtin:room>");
  CHECK(attributes.at("shadowref:method") == "zfail");
  CHECK(attributes.at("shadowref:threads") == "1");
  CHECK(attributes.count("shadowref:scene-sha1") == 0);

  const std::string exr = (scratch() / "plain.exr").string();
  REQUIRE(runShadowref("render scenes/minimal.yaml --threads 1 --quiet -o '" + exr + "'").status == 0);
  CHECK(shadowrefAttributes(exr).count("shadowref:overrides") == 0);
  CHECK(shadowrefAttributes(exr).at("shadowref:scene") == "scenes/minimal.yaml");
}
