// The documentation holds together: every relative link in README.md, golden/README.md and
// docs/*.md names a file of the repository, every #anchor a heading of the page it points to (as
// GitHub makes anchors of headings), and every option `shadowref --help` and its subcommands'
// --help print is documented somewhere in README.md or docs/.
#include <catch2/catch.hpp>

#include <cctype>
#include <filesystem>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "support/cli_run.h"

namespace {

namespace fs = std::filesystem;
using shadowref::testing::runShadowref;
using shadowref::testing::slurp;

const fs::path kRoot = SHADOWREF_SOURCE_DIR;

std::vector<fs::path> pages() {
  std::vector<fs::path> out = {kRoot / "README.md", kRoot / "golden" / "README.md"};
  for (const auto& entry : fs::directory_iterator(kRoot / "docs"))
    if (entry.path().extension() == ".md") out.push_back(entry.path());
  return out;
}

// The page's lines outside fenced code blocks (``` … ```), where links and headings are markup.
std::vector<std::string> proseLines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  bool fenced = false;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("```", 0) == 0) {
      fenced = !fenced;
      continue;
    }
    if (!fenced) lines.push_back(line);
  }
  return lines;
}

// A code point of UTF-8 text from position i (advanced past it); malformed bytes count as one.
char32_t nextCodePoint(const std::string& s, size_t& i) {
  const auto byte = [&](size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char b = byte(i);
  int extra = b >= 0xF0 ? 3 : b >= 0xE0 ? 2 : b >= 0xC0 ? 1 : 0;
  char32_t c = extra == 3 ? b & 0x07 : extra == 2 ? b & 0x0F : extra == 1 ? b & 0x1F : b;
  ++i;
  for (; extra > 0 && i < s.size() && (byte(i) & 0xC0) == 0x80; --extra, ++i) c = (c << 6) | (byte(i) & 0x3F);
  return c;
}

// GitHub's anchor of a heading: lower case, every character that is not a letter, digit, '_',
// '-' or space dropped, spaces made '-'. Outside ASCII, the symbols these pages use in headings
// (§, ·, …, dashes, arrows, maths) are dropped and letters and superscript digits kept.
std::string anchorOf(const std::string& heading) {
  std::string out;
  for (size_t i = 0; i < heading.size();) {
    const size_t from = i;
    const char32_t c = nextCodePoint(heading, i);
    if (c < 0x80) {
      if (std::isalnum(static_cast<int>(c)) || c == '_' || c == '-') out += char(std::tolower(static_cast<int>(c)));
      else if (c == ' ') out += '-';
      continue;
    }
    const bool superscript = c == 0xB2 || c == 0xB3 || c == 0xB9 || (c >= 0x2070 && c <= 0x209F);
    const bool symbol = (c >= 0xA0 && c <= 0xBF) || c == 0xD7 || c == 0xF7 || (c >= 0x2000 && c <= 0x2BFF);
    if (superscript || !symbol) out += heading.substr(from, i - from);
  }
  return out;
}

std::set<std::string> anchorsOf(const fs::path& page) {
  static const std::regex heading(R"(^#{1,6}\s+(.*?)\s*$)");
  std::set<std::string> anchors;
  std::map<std::string, int> seen;
  for (const std::string& line : proseLines(slurp(page))) {
    std::smatch m;
    if (!std::regex_match(line, m, heading)) continue;
    const std::string a = anchorOf(m[1].str());
    const int n = seen[a]++;
    anchors.insert(n == 0 ? a : a + "-" + std::to_string(n));
  }
  return anchors;
}

}  // namespace

TEST_CASE("documentation: anchors are made as GitHub makes them", "[docs]") {
  CHECK(anchorOf("Provenance: which build, scene and settings made a file") ==
        "provenance-which-build-scene-and-settings-made-a-file");
  CHECK(anchorOf("The oracle: ray-traced visibility and error maps (`render --oracle`)") ==
        "the-oracle-ray-traced-visibility-and-error-maps-render---oracle");
  CHECK(anchorOf("Near plane under P_inf (1e-1 … 1e-6)") == "near-plane-under-p_inf-1e-1--1e-6");
  CHECK(anchorOf("[Hempe 2004, §6.1]: does TSM at 256² look like it?") == "hempe-2004-61-does-tsm-at-256²-look-like-it");
}

TEST_CASE("documentation: every relative link names a file, and every #anchor a heading of it", "[docs]") {
  static const std::regex link(R"(\]\(([^)\s]+)\))");
  size_t links = 0, anchors = 0;
  std::map<fs::path, std::set<std::string>> headings;
  for (const fs::path& page : pages()) {
    REQUIRE(fs::exists(page));
    const std::vector<std::string> lines = proseLines(slurp(page));
    for (size_t n = 0; n < lines.size(); ++n) {
      for (auto it = std::sregex_iterator(lines[n].begin(), lines[n].end(), link); it != std::sregex_iterator(); ++it) {
        const std::string target = (*it)[1].str();
        if (std::regex_search(target, std::regex("^[a-z]+:"))) continue;  // https:, mailto:
        ++links;
        const size_t hash = target.find('#');
        const std::string file = target.substr(0, hash);
        const fs::path resolved = file.empty() ? page : (page.parent_path() / file).lexically_normal();
        INFO(fs::relative(page, kRoot).string() << " links to " << target);
        if (!fs::exists(resolved)) {
          FAIL_CHECK("no such file: " << fs::relative(resolved, kRoot).string());
          continue;
        }
        if (hash == std::string::npos || resolved.extension() != ".md") continue;
        ++anchors;
        if (!headings.count(resolved)) headings[resolved] = anchorsOf(resolved);
        CHECK(headings[resolved].count(target.substr(hash + 1)) == 1);
      }
    }
  }
  // Not vacuous: the pages link to each other, to sections and to pictures.
  CHECK(links > 100);
  CHECK(anchors > 10);
}

TEST_CASE("documentation: every option of shadowref and its subcommands is documented", "[docs][cli]") {
  std::string documented;
  for (const fs::path& page : pages()) documented += slurp(page);
  // Written as a whole word: `--dump` does not document `--dump-region`.
  const auto isDocumented = [&](const std::string& option) {
    for (size_t at = documented.find(option); at != std::string::npos; at = documented.find(option, at + 1)) {
      const size_t end = at + option.size();
      const char next = end < documented.size() ? documented[end] : ' ';
      if (!std::islower(static_cast<unsigned char>(next)) && !std::isdigit(static_cast<unsigned char>(next)) && next != '-')
        return true;
    }
    return false;
  };
  // The subcommands: the lines under "Subcommands:" in the top-level help.
  const shadowref::testing::CliRun top = runShadowref("--help");
  REQUIRE(top.status == 0);
  std::vector<std::string> commands = {""};
  {
    std::istringstream in(top.out);
    bool listing = false;
    for (std::string line; std::getline(in, line);) {
      if (line.rfind("Subcommands:", 0) == 0) listing = true;
      else if (listing && line.empty()) break;
      else if (listing) {
        std::smatch m;
        if (std::regex_search(line, m, std::regex(R"(^\s+([a-z]+)\s)"))) commands.push_back(m[1].str());
      }
    }
  }
  CHECK(commands.size() >= 8);
  static const std::regex optionLine(R"(^\s+(?:-[A-Za-z],)?(--[a-z][a-z0-9-]*))");
  size_t options = 0;
  for (const std::string& command : commands) {
    const shadowref::testing::CliRun help = runShadowref(command + " --help");
    REQUIRE(help.status == 0);
    std::istringstream in(help.out);
    for (std::string line; std::getline(in, line);) {
      std::smatch m;
      if (!std::regex_search(line, m, optionLine) || m[1].str() == "--help") continue;
      ++options;
      INFO("shadowref " << command << (command.empty() ? "" : " ") << m[1].str()
                        << " is in --help but in neither README.md nor docs/");
      CHECK(isDocumented(m[1].str()));
    }
  }
  CHECK(options > 50);
}
