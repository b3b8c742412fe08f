// Citations resolve: every key in square brackets that src/, support/, tests/, bench/ and the
// documentation (README.md, docs/) cite —
// an author and a year, "GL 2.1", "SV slides" or "DSS article", optionally followed by ", §x.y" —
// has an entry "**[Key]**" in docs/references.md; and nothing cites what a reader of the
// repository cannot open (the project's planning files, issue numbers, the source documents by
// their file numbers, or the thesis' own bracket keys).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

const fs::path kRoot = SHADOWREF_SOURCE_DIR;

std::string readFile(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The text files of src/, support/, tests/, bench/, the scenes users start from and the
// documentation (not bench/results/: recorded runs, kept as printed; not node_modules/: installed
// npm packages).
std::vector<fs::path> sourceFiles() {
  std::vector<fs::path> out = {kRoot / "README.md", kRoot / "golden" / "README.md"};
  for (const char* dir : {"src", "support", "tests", "bench", "scenes", "docs"}) {
    for (auto it = fs::recursive_directory_iterator(kRoot / dir); it != fs::recursive_directory_iterator(); ++it) {
      // tests/browser/node_modules: npm's copy of others' packages (npm ci), not this project's text.
      if (it->is_directory() && (it->path() == kRoot / "bench" / "results" || it->path().filename() == "node_modules")) {
        it.disable_recursion_pending();
        continue;
      }
      const std::string ext = it->path().extension().string();
      if (it->is_regular_file() &&
          (ext == ".h" || ext == ".cpp" || ext == ".md" || ext == ".sh" || ext == ".yaml" ||
           it->path().filename() == "CMakeLists.txt"))
        out.push_back(it->path());
    }
  }
  return out;
}

// A citation: "[Key]" or "[Key, locator]", the key an author list and a year, or one of the
// three keys without a year.
const std::regex kCitation(R"(\[((?:[A-Z][A-Za-z'&. -]*? (?:19|20)[0-9]{2})|GL 2\.1|SV slides|DSS article)(?:, [^\]\n]*)?\])");

std::set<std::string> citedKeys(const std::string& text) {
  std::set<std::string> keys;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), kCitation); it != std::sregex_iterator(); ++it)
    keys.insert((*it)[1].str());
  return keys;
}

// The keys docs/references.md defines: each entry starts with "**[Key]**".
std::set<std::string> definedKeys(const std::string& references) {
  static const std::regex entry(R"(\*\*\[([^\]\n]+)\]\*\*)");
  std::set<std::string> keys;
  for (auto it = std::sregex_iterator(references.begin(), references.end(), entry); it != std::sregex_iterator(); ++it)
    keys.insert((*it)[1].str());
  return keys;
}

}  // namespace

TEST_CASE("citation keys: the scanner finds keys with and without a locator, and nothing else", "[docs]") {
  const std::set<std::string> keys =
      citedKeys("a (" + std::string("[Kuhn 2016, §3.2]") + ") b [McGuire et al. 2003] c [GL 2.1, §4.1.5] d " +
                "[SV slides] e [volumes][extrusion] f [0, 1] g [Nobody " + "1999]");
  CHECK(keys == std::set<std::string>{"Kuhn 2016", "McGuire et al. 2003", "GL 2.1", "SV slides", "Nobody 1999"});
  CHECK(definedKeys("- **[Kuhn 2016]** Marcel Kuhn.\n- **[GL 2.1]** Segal") ==
        std::set<std::string>{"Kuhn 2016", "GL 2.1"});
}

TEST_CASE("citation keys: every key cited in the code and the documentation has an entry in docs/references.md", "[docs]") {
  const fs::path referencesFile = kRoot / "docs" / "references.md";
  REQUIRE(fs::exists(referencesFile));
  const std::set<std::string> defined = definedKeys(readFile(referencesFile));
  // The four source documents and the specification are always there.
  for (const char* key : {"Kuhn 2016", "Hempe 2004", "SV slides", "DSS article", "GL 2.1"}) CHECK(defined.count(key) == 1);
  CHECK(defined.count("Nobody 1999") == 0);

  std::map<std::string, std::vector<std::string>> unresolved;  // key -> files citing it
  size_t filesWithCitations = 0;
  std::set<std::string> cited;
  for (const fs::path& file : sourceFiles()) {
    const std::set<std::string> keys = citedKeys(readFile(file));
    if (!keys.empty()) ++filesWithCitations;
    for (const std::string& key : keys) {
      cited.insert(key);
      if (!defined.count(key)) unresolved[key].push_back(fs::relative(file, kRoot).string());
    }
  }
  // Not vacuous: the code cites the documents in many places.
  CHECK(filesWithCitations > 50);
  CHECK(cited.count("Kuhn 2016") == 1);
  CHECK(cited.count("Hempe 2004") == 1);
  for (const auto& [key, files] : unresolved) {
    INFO("[" << key << "] cited in " << files.front() << (files.size() > 1 ? " and others" : "")
             << " has no entry \"**[" << key << "]**\" in docs/references.md");
    CHECK(false);
  }
}

TEST_CASE("citation keys: the code and the documentation cite nothing a reader cannot open", "[docs]") {
  // Built from pieces, so that this file does not match its own patterns.
  const std::string md = ".md";
  const std::vector<std::pair<std::string, std::regex>> forbidden = {
      {"a planning file", std::regex("(SPEC|STYLE)" + std::string("\\") + md)},
      {"an issue number", std::regex("[Ii]ss" + std::string("ue [0-9]"))},
      {"a source document by its file number", std::regex("\\b00[0-4] (" + std::string("§|Abb\\.|Listing)"))},
      {"a key of the thesis' bibliography", std::regex("\\[[A-Z]{2,6}[0-9]{2}" + std::string("\\]"))},
  };
  CHECK(std::regex_search("see " + std::string("SPEC") + md + " §3", forbidden[0].second));
  CHECK(std::regex_search("(0" + std::string("00 §3.2)"), forbidden[2].second));

  size_t scanned = 0;
  for (const fs::path& file : sourceFiles()) {
    ++scanned;
    std::istringstream in(readFile(file));
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
      for (const auto& [what, pattern] : forbidden) {
        if (std::regex_search(line, pattern)) {
          INFO(fs::relative(file, kRoot).string() << ":" << number << " cites " << what << ": " << line);
          CHECK(false);
        }
      }
    }
  }
  CHECK(scanned > 100);
}
