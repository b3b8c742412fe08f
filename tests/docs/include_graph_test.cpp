// The include graph keeps its layers: the reference pipeline's definitions (src/gl) never see the
// fast executor (src/exec), so that the reference stays a readable, scalar definition of every
// byte and the executor depends on it, not the other way round. One row of kRules per rule: the
// files under a folder may not include any header under the listed folders.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

const fs::path kRoot = SHADOWREF_SOURCE_DIR;

struct IncludeRule {
  const char* folder;                    // relative to the source root
  std::vector<const char*> forbidden;    // include paths starting with these are not allowed there
};

// The algorithms, the command, the library interface, the explorer, the scene model, the image
// files and capture and replay see the pipelines only through the interface in src/gl
// (gl/pipeline.h): the executor's machinery (threads, bands, kept setups) must not leak into them.
const std::vector<IncludeRule> kRules = {
    {"src/gl", {"exec/"}},
    {"src/shadow", {"exec/"}},
    {"src/cli", {"exec/"}},
    {"src/scene", {"exec/"}},
    {"src/image", {"exec/"}},
    {"src/views", {"exec/"}},
    {"src/api", {"exec/"}},
    {"src/oracle", {"exec/"}},
    {"src/explore", {"exec/"}},
    {"src/sweep", {"exec/"}},
    {"src/trace", {"exec/"}},
};

// The quoted includes of a file, with their line numbers.
std::vector<std::pair<int, std::string>> quotedIncludes(const fs::path& file) {
  static const std::regex include(R"(^\s*#\s*include\s*"([^"]+)\")");
  std::vector<std::pair<int, std::string>> out;
  std::ifstream in(file);
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    std::smatch m;
    if (std::regex_search(line, m, include)) out.emplace_back(n, m[1].str());
  }
  return out;
}

}  // namespace

TEST_CASE("no file includes a header of a layer its rule forbids", "[docs][include_graph]") {
  for (const IncludeRule& rule : kRules) {
    const fs::path folder = kRoot / rule.folder;
    REQUIRE(fs::is_directory(folder));
    int files = 0;
    for (const fs::directory_entry& entry : fs::recursive_directory_iterator(folder)) {
      const std::string ext = entry.path().extension().string();
      if (!entry.is_regular_file() || (ext != ".h" && ext != ".cpp")) continue;
      ++files;
      for (const auto& [line, path] : quotedIncludes(entry.path())) {
        for (const char* prefix : rule.forbidden) {
          INFO(fs::relative(entry.path(), kRoot).string() << ":" << line << ": includes \"" << path << "\"");
          CHECK(path.rfind(prefix, 0) != 0);
        }
      }
    }
    CHECK(files > 0);  // the rule looked at something
  }
}

TEST_CASE("the include rule finds a forbidden include", "[docs][include_graph]") {
  // The same parsing on a file that breaks the rule: the test above can fail.
  const fs::path file = fs::temp_directory_path() / "shadowref_include_graph_probe.cpp";
  {
    std::ofstream out(file);
    out << "#include <vector>\n// #include \"exec/x.h\" in a comment is not an include\n  #  include \"exec/renderer.h\"\n";
  }
  const auto includes = quotedIncludes(file);
  fs::remove(file);
  REQUIRE(includes.size() == 1);
  CHECK(includes[0].first == 3);
  CHECK(includes[0].second == "exec/renderer.h");
}

namespace {

// The lines of a file that contain `word`, with their numbers.
std::vector<std::pair<int, std::string>> linesWith(const fs::path& file, const std::string& word) {
  std::vector<std::pair<int, std::string>> out;
  std::ifstream in(file);
  std::string line;
  for (int n = 1; std::getline(in, line); ++n)
    if (line.find(word) != std::string::npos) out.emplace_back(n, line);
  return out;
}

}  // namespace

// The executor's speed machinery (thread pools, span scratch) is owned by explicit objects — the
// pipeline maker, the renderer — never by the threads: state kept per thread would outlive the
// renderer that filled it and tie bytes or memory to whichever thread ran a task.
TEST_CASE("no source file keeps state per thread (thread_local)", "[docs][include_graph]") {
  int files = 0;
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(kRoot / "src")) {
    const std::string ext = entry.path().extension().string();
    if (!entry.is_regular_file() || (ext != ".h" && ext != ".cpp")) continue;
    ++files;
    for (const auto& [line, text] : linesWith(entry.path(), "thread_local")) {
      INFO(fs::relative(entry.path(), kRoot).string() << ":" << line << ": " << text);
      CHECK(false);
    }
  }
  CHECK(files > 50);  // it looked at the sources
}

TEST_CASE("the thread_local rule finds the word", "[docs][include_graph]") {
  const fs::path file = fs::temp_directory_path() / "shadowref_thread_local_probe.cpp";
  {
    std::ofstream out(file);
    out << "int a;\nstatic thread_local int b;\n";
  }
  const auto lines = linesWith(file, "thread_local");
  fs::remove(file);
  REQUIRE(lines.size() == 1);
  CHECK(lines[0].first == 2);
}
