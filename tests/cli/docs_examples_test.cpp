// The documentation's quoted output stays true. README.md and docs/*.md mark each command whose
// printed output they quote with an HTML comment, invisible on the rendered page:
//
//   <!-- docs-test: build/shadowref ARGS -->
//       the fenced block that follows quotes its output (stdout, then stderr), line by line;
//   <!-- docs-test: build/shadowref ARGS | expect: TEXT | line: LINE -->
//       the page's text quotes TEXT from the output, or LINE as a whole line of it;
//   <!-- docs-test: let S = VALUE -->
//       later commands on the page say $S for VALUE.
// After the command, 'status: N' says it exits with N (default 0), e.g. compare's WARNING (1).
//
// This test runs every marked command (from a scratch folder holding a link to scenes/, so that
// output files land there) and checks that each quoted line and each LINE is a line of the output
// and each TEXT appears in it, runs of blanks counted as one. A change that moves a quoted number
// fails here until the page is updated. The command must also appear on the page as written, and
// the numbers of an 'expect:' or 'line:' in the page's text, so that neither the command nor the
// quote can drift from the marker.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;

namespace {

const fs::path kRoot = SHADOWREF_SOURCE_DIR;
const std::string kMarker = "<!-- docs-test:";
const std::string kCli = "build/shadowref";

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> linesOf(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// Trimmed, with every run of blanks as one space: column alignment is not what the text quotes.
std::string squeezed(const std::string& s) {
  std::string out;
  for (char c : s) {
    const bool blank = c == ' ' || c == '\t' || c == '\r';
    if (blank) {
      if (!out.empty() && out.back() != ' ') out += ' ';
    } else {
      out += c;
    }
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

std::string trimmed(std::string s) {
  while (!s.empty() && s.front() == ' ') s.erase(s.begin());
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

std::vector<std::string> split(const std::string& s, const std::string& sep) {
  std::vector<std::string> parts;
  size_t from = 0;
  for (size_t at; (at = s.find(sep, from)) != std::string::npos; from = at + sep.size())
    parts.push_back(s.substr(from, at - from));
  parts.push_back(s.substr(from));
  return parts;
}

// A number in a quoted text, and whether a line holds it whole (not as part of a longer one).
const std::regex kNumber(R"(-?[0-9]+(\.[0-9]+)?)");

bool containsNumber(const std::string& line, const std::string& number) {
  for (size_t at = line.find(number); at != std::string::npos; at = line.find(number, at + 1)) {
    const bool digitBefore = at > 0 && (std::isdigit(static_cast<unsigned char>(line[at - 1])) || line[at - 1] == '.');
    const size_t end = at + number.size();
    const bool digitAfter = end < line.size() && std::isdigit(static_cast<unsigned char>(line[end]));
    if (!digitBefore && !digitAfter) return true;
  }
  return false;
}

struct Check {
  std::string where;    // page:line of the marker
  std::string command;  // as on the page ($S and all)
  std::vector<std::string> quoted;  // lines that must each be a line of the output (squeezed)
  std::vector<std::string> texts;   // texts that must each appear in the output (squeezed)
  int status = 0;                   // the exit status the command must end with
};

// The checks a page's markers ask for. Malformed markers are reported as failures, not skipped.
std::vector<Check> checksOf(const fs::path& page, std::map<std::string, std::string>& vars,
                            std::vector<std::string>& errors) {
  const std::vector<std::string> lines = linesOf(slurp(page));
  const std::string name = fs::relative(page, kRoot).string();
  std::vector<Check> checks;
  for (size_t i = 0; i < lines.size(); ++i) {
    const size_t at = lines[i].find(kMarker);
    if (at == std::string::npos) continue;
    const std::string where = name + ":" + std::to_string(i + 1);
    const size_t end = lines[i].find("-->", at);
    if (end == std::string::npos) {
      errors.push_back(where + ": a docs-test marker must end on its own line with -->");
      continue;
    }
    const std::string body = trimmed(lines[i].substr(at + kMarker.size(), end - at - kMarker.size()));
    if (body.rfind("let ", 0) == 0) {
      const size_t eq = body.find('=');
      if (eq == std::string::npos) {
        errors.push_back(where + ": 'let' needs NAME = VALUE");
        continue;
      }
      vars[trimmed(body.substr(4, eq - 4))] = trimmed(body.substr(eq + 1));
      continue;
    }
    const std::vector<std::string> parts = split(body, " | ");
    Check c{where, trimmed(parts[0]), {}, {}};
    if (c.command.rfind(kCli + " ", 0) != 0) {
      errors.push_back(where + ": the command must start with " + kCli + ": " + c.command);
      continue;
    }
    for (size_t k = 1; k < parts.size(); ++k) {
      if (parts[k].rfind("expect: ", 0) == 0)
        c.texts.push_back(squeezed(parts[k].substr(8)));
      else if (parts[k].rfind("line: ", 0) == 0)
        c.quoted.push_back(squeezed(parts[k].substr(6)));
      else if (parts[k].rfind("status: ", 0) == 0 && std::regex_match(trimmed(parts[k].substr(8)), std::regex("[0-9]{1,3}")))
        c.status = std::stoi(parts[k].substr(8));
      else
        errors.push_back(where + ": after the command, each part must be 'expect: TEXT', 'line: LINE' or 'status: N'");
    }
    const bool quotesInline = !c.texts.empty() || !c.quoted.empty();
    if (!quotesInline) {  // the next fenced block quotes the output
      size_t j = i + 1;
      while (j < lines.size() && trimmed(lines[j]).empty()) ++j;
      if (j == lines.size() || lines[j].rfind("```", 0) != 0) {
        errors.push_back(where + ": a marker without 'expect:' or 'line:' must be followed by a fenced block");
        continue;
      }
      for (++j; j < lines.size() && lines[j].rfind("```", 0) != 0; ++j)
        if (!squeezed(lines[j]).empty()) c.quoted.push_back(squeezed(lines[j]));
      if (c.quoted.empty()) errors.push_back(where + ": the fenced block after the marker is empty");
    }
    // The command as the reader sees it: in the page's text outside the marker itself.
    bool shown = false;
    for (size_t k = 0; k < lines.size() && !shown; ++k)
      shown = k != i && lines[k].find(kMarker) == std::string::npos && lines[k].find(c.command) != std::string::npos;
    if (!shown) errors.push_back(where + ": the page does not show the command " + c.command);
    // The numbers an 'expect:' or 'line:' checks are the ones the page's text quotes: each must
    // appear on the page outside the markers, or the marker could be updated and the text not.
    for (const std::vector<std::string>* list : {&c.texts, &c.quoted}) {
      if (list == &c.quoted && !quotesInline) break;  // a fenced block is the quote itself
      for (const std::string& t : *list)
        for (auto it = std::sregex_iterator(t.begin(), t.end(), kNumber); it != std::sregex_iterator(); ++it) {
          const std::string number = it->str();
          bool quotedOnPage = false;
          for (size_t k = 0; k < lines.size() && !quotedOnPage; ++k)
            quotedOnPage = lines[k].find(kMarker) == std::string::npos && containsNumber(lines[k], number);
          if (!quotedOnPage)
            errors.push_back(where + ": the page's text does not quote " + number + " (from '" + t + "')");
        }
    }
    checks.push_back(c);
  }
  return checks;
}

std::string expand(std::string command, const std::map<std::string, std::string>& vars) {
  for (const auto& [name, value] : vars)
    for (size_t at; (at = command.find("$" + name)) != std::string::npos;)
      command.replace(at, name.size() + 1, value);
  return command;
}

// Runs the command, its stdout and stderr captured (in that order), from a scratch folder that links to the scenes.
struct Output {
  int status = -1;
  std::string text;
};

fs::path scratch() { return fs::temp_directory_path() / ("shadowref-docs-" + std::to_string(::getpid())); }

Output runCommand(const std::string& command) {
  const fs::path dir = scratch();
  fs::create_directories(dir / "out");
  if (!fs::exists(dir / "scenes")) fs::create_directory_symlink(kRoot / "scenes", dir / "scenes");
  const std::string args = command.substr(kCli.size());
  const std::string cmd = "cd '" + dir.string() + "' && '" + std::string(SHADOWREF_CLI) + "'" + args + " >'" +
                          (dir / "stdout.txt").string() + "' 2>'" + (dir / "stderr.txt").string() + "'";
  const int raw = std::system(cmd.c_str());
  Output out;
  out.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  out.text = slurp(dir / "stdout.txt") + "\n" + slurp(dir / "stderr.txt");
  return out;
}

}  // namespace

TEST_CASE("the output README.md and docs/ quote is what the commands print", "[cli][docs]") {
  std::vector<fs::path> pages = {kRoot / "README.md"};
  for (const auto& entry : fs::directory_iterator(kRoot / "docs"))
    if (entry.path().extension() == ".md") pages.push_back(entry.path());

  std::map<std::string, Output> ran;  // each distinct command once
  std::map<std::string, int> perPage;
  for (const fs::path& page : pages) {
    std::map<std::string, std::string> vars;
    std::vector<std::string> errors;
    const std::vector<Check> checks = checksOf(page, vars, errors);
    for (const std::string& e : errors) FAIL_CHECK(e);
    perPage[page.filename().string()] = int(checks.size());
    for (const Check& c : checks) {
      const std::string command = expand(c.command, vars);
      if (!ran.count(command)) ran[command] = runCommand(command);
      const Output& out = ran[command];
      INFO(c.where << ": " << command << "\n" << out.text);
      CHECK(out.status == c.status);
      std::vector<std::string> outLines;
      for (const std::string& l : linesOf(out.text)) outLines.push_back(squeezed(l));
      const std::string all = squeezed(out.text);
      for (const std::string& q : c.quoted) {
        INFO("quoted line: " << q);
        CHECK(std::find(outLines.begin(), outLines.end(), q) != outLines.end());
      }
      for (const std::string& t : c.texts) {
        INFO("quoted text: " << t);
        CHECK(all.find(t) != std::string::npos);
      }
    }
  }
  // The pages that quote output keep their markers: a page that lost them would pass unchecked.
  CHECK(perPage["README.md"] >= 2);
  CHECK(perPage["teaching.md"] >= 4);
  std::error_code ignored;
  fs::remove_all(scratch(), ignored);
}
