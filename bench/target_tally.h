// The speed targets over many runs of bench/vs-mesa (vs_mesa --tally FILE...): each run's own
// table of targets (speed_targets.h, the end of its output) read back, and for every figure in how
// many runs it was met. On a shared host one run is a sample: this shows which figures a run meets
// nearly always and which depend on the host. Rows without a verdict (information, such as two
// threads against one) are not counted.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <istream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "speed_targets.h"

namespace shadowref::bench {

// One run's table of targets as TargetTable::text prints it.
struct RunTargets {
  struct Row {
    std::string what;                  // the label, without its leading spaces
    bool indented = false;             // an information row under another row
    std::optional<double> threshold;   // "what >= threshold"; none for information and yes/no rows
    std::vector<std::string> cells;    // as printed: "1.76 SHORT", "identical", "2.15"
  };
  std::string commit;                  // from the "commit:" line the bench script writes first
  std::vector<std::string> columns;
  std::vector<Row> rows;
  int met = 0, checked = 0;            // the table's last line: "met of checked figures ..."
};

namespace tally_detail {

inline std::string trim(const std::string& s) {
  const size_t a = s.find_first_not_of(' ');
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(' ') - a + 1);
}

inline std::vector<std::string> words(const std::string& s) {
  std::vector<std::string> out;
  size_t i = 0;
  while (true) {
    i = s.find_first_not_of(' ', i);
    if (i == std::string::npos) return out;
    const size_t j = s.find(' ', i);
    out.push_back(s.substr(i, j - i));
    if (j == std::string::npos) return out;
    i = j;
  }
}

// The number a cell starts with ("1.76 SHORT", "2.15"); none for "identical".
inline std::optional<double> leadingNumber(const std::string& cell) {
  const char* begin = cell.c_str();
  char* end = nullptr;
  const double v = std::strtod(begin, &end);
  if (end == begin) return std::nullopt;
  return v;
}

}  // namespace tally_detail

// Reads one run's output; nullopt when it has no table of targets (a run from before the bench
// printed one, or one cut short before its last line).
inline std::optional<RunTargets> readRunTargets(std::istream& in) {
  using namespace tally_detail;
  RunTargets run;
  std::string line;
  bool inTable = false;
  while (std::getline(in, line)) {
    if (line.rfind("commit: ", 0) == 0) {
      const std::vector<std::string> w = words(line.substr(8));
      if (!w.empty()) run.commit = w[0];
    }
    if (!inTable) {
      if (line.rfind("target ", 0) == 0 && line.size() > kTargetLabelWidth) {
        run.columns = words(line.substr(kTargetLabelWidth));
        inTable = true;
      }
      continue;
    }
    int met = 0, checked = 0, end = 0;  // end: set only where the whole sentence matched
    if (std::sscanf(line.c_str(), "%d of %d figures at or above their targets%n", &met, &checked, &end) == 2 && end > 0) {
      run.met = met;
      run.checked = checked;
      return run;
    }
    if (line.size() <= kTargetLabelWidth) continue;
    RunTargets::Row row;
    row.indented = line[0] == ' ';
    row.what = trim(line.substr(0, kTargetLabelWidth));
    for (size_t at = kTargetLabelWidth; at < line.size(); at += kTargetCellWidth) row.cells.push_back(trim(line.substr(at, kTargetCellWidth)));
    const size_t ge = row.what.find(" >= ");
    if (ge != std::string::npos) row.threshold = std::strtod(row.what.c_str() + ge + 4, nullptr);
    run.rows.push_back(row);
  }
  return std::nullopt;
}

// Whether a cell of a target row was met: "… ok", or a yes/no row's "identical".
inline bool cellMet(const std::string& cell) {
  return (cell.size() > 3 && cell.compare(cell.size() - 3, 3, " ok") == 0) || cell == "identical";
}

// The figures over the runs, row by row in the first run's order (a row another run lacks counts
// only where it is).
class TargetTally {
 public:
  void add(const std::string& name, const RunTargets& run) {
    if (columns_.empty()) columns_ = run.columns;
    runs_.push_back({name, run.commit, run.met, run.checked});
    for (const RunTargets::Row& row : run.rows) {
      if (row.indented || !(row.threshold || isYesNo(row)) || retired(row.what)) continue;
      Counts& c = counts(row.what);
      for (size_t i = 0; i < row.cells.size(); ++i) c.add(i, cellMet(row.cells[i]));
    }
  }

  int runs() const { return int(runs_.size()); }

  std::string text() const {
    std::string out = "The speed targets over " + std::to_string(runs_.size()) +
                      " runs: in how many runs each figure was met\n" + targetLine("target", columns_);
    for (const std::string& what : order_) out += targetLine(what, cellsOf(what));
    out += "figures met, run by run:\n";
    for (const RunLine& r : runs_)
      out += "  " + std::to_string(r.met) + " of " + std::to_string(r.checked) + "  " + r.name +
             (r.commit.empty() ? "" : " (" + r.commit + ")") + "\n";
    return out;
  }

 private:
  struct Counts {
    std::vector<int> met, seen;
    void add(size_t column, bool ok) {
      if (met.size() <= column) {
        met.resize(column + 1, 0);
        seen.resize(column + 1, 0);
      }
      met[column] += ok;
      ++seen[column];
    }
  };
  struct RunLine {
    std::string name, commit;
    int met = 0, checked = 0;
  };

  // Two threads against one was once judged (>= 1.8) and is now a figure without a verdict: on a
  // shared host of two cores the host decides it, not the code. Runs saved before still carry the
  // verdict; it is not counted.
  static bool retired(const std::string& what) { return what.find("2 threads / 1") != std::string::npos; }
  static bool isYesNo(const RunTargets::Row& row) {
    return !row.threshold && !row.cells.empty() && !tally_detail::leadingNumber(row.cells[0]);
  }

  // The count of the target row labelled `what`, made at its first sight.
  Counts& counts(const std::string& what) {
    auto [it, added] = counts_.try_emplace(what);
    if (added) order_.push_back(what);
    return it->second;
  }
  std::vector<std::string> cellsOf(const std::string& what) const {
    const Counts& c = counts_.at(what);
    std::vector<std::string> cells;
    for (size_t i = 0; i < c.seen.size(); ++i) cells.push_back(std::to_string(c.met[i]) + "/" + std::to_string(c.seen[i]));
    return cells;
  }

  std::vector<std::string> columns_;
  std::vector<RunLine> runs_;
  std::map<std::string, Counts> counts_;
  std::vector<std::string> order_;
};

}  // namespace shadowref::bench
