// The speed targets over many runs of bench/vs-mesa (vs_mesa --tally FILE...): each run's own
// table of targets (issue_targets.h, the end of its output) read back, and for every figure in how
// many runs it was met. On a shared host one run is a sample: this shows which figures a run meets
// nearly always, which depend on the host, and — for two threads / one — how that follows the
// host's capacity for two threads measured beside each figure, how often llvmpipe's own two
// threads / one reached the same line in the same runs, and — where the target is judged on frames
// in turn in one process — how often shadowref's separate processes did.
#pragma once

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <istream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "issue_targets.h"

namespace shadowref::bench {

// One run's table of targets as TargetTable::text prints it.
struct RunTargets {
  struct Row {
    std::string what;                  // the label, without its leading spaces
    bool indented = false;             // an information row under a target (capacity, llvmpipe)
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
  // Two threads / one is split by the host's capacity for two threads in the same cell: at or
  // above the target's line the host left room for it, below it no renderer could reach it.
  void add(const std::string& name, const RunTargets& run) {
    if (columns_.empty()) columns_ = run.columns;
    runs_.push_back({name, run.commit, run.met, run.checked});
    const RunTargets::Row* target = nullptr;  // the last target row, for the rows indented under it
    std::vector<bool> twoThreadsMet(run.columns.size(), true), llvmpipeMet(run.columns.size(), true);
    bool twoThreadRows = false;
    int twoThreadCells = 0, roomCells = 0;  // two-thread figures, and those with room beside them
    for (const RunTargets::Row& row : run.rows) {
      if (!row.indented) target = row.threshold || isYesNo(row) ? &row : nullptr;
      if (target && !row.indented) {
        Counts& c = counts(row.what, row.what);
        for (size_t i = 0; i < row.cells.size(); ++i) c.add(i, cellMet(row.cells[i]));
        if (isTwoThreads(row.what)) {
          twoThreadRows = true;
          twoThreadCells += int(row.cells.size());
          for (size_t i = 0; i < row.cells.size() && i < twoThreadsMet.size(); ++i)
            twoThreadsMet[i] = twoThreadsMet[i] && cellMet(row.cells[i]);
        }
      } else if (target && target->threshold && isTwoThreads(target->what)) {
        const double line = *target->threshold;
        const std::string threshold = target->what.substr(target->what.find(" >= ") + 4);
        if (row.what.rfind("the host's capacity for two threads", 0) == 0) {
          Counts& room = counts(target->what + "|room", "  where the host's capacity was >= " + threshold);
          Counts& none = counts(target->what + "|none", "  where it was below " + threshold);
          for (size_t i = 0; i < row.cells.size() && i < target->cells.size(); ++i) {
            const std::optional<double> capacity = tally_detail::leadingNumber(row.cells[i]);
            if (!capacity) continue;
            (*capacity >= line ? room : none).add(i, cellMet(target->cells[i]));
            roomCells += *capacity >= line;
          }
        } else if (row.what.rfind("separate processes, 2 threads / 1", 0) == 0) {
          // Beside a target judged on frames in turn: the same ratio from separate processes.
          Counts& c = counts(target->what + "|separate", "  separate processes >= " + threshold + ", same runs");
          for (size_t i = 0; i < row.cells.size(); ++i)
            if (const std::optional<double> v = tally_detail::leadingNumber(row.cells[i])) c.add(i, *v >= line);
        } else if (row.what.rfind("llvmpipe's 2 threads / 1", 0) == 0) {
          Counts& c = counts(target->what + "|llvmpipe", "  llvmpipe's 2 threads / 1 >= " + threshold + ", same runs");
          for (size_t i = 0; i < row.cells.size(); ++i) {
            const std::optional<double> v = tally_detail::leadingNumber(row.cells[i]);
            if (!v) continue;
            c.add(i, *v >= line);
            if (i < llvmpipeMet.size()) llvmpipeMet[i] = llvmpipeMet[i] && *v >= line;
          }
        }
      }
    }
    if (twoThreadRows) {
      const bool allMet = std::all_of(twoThreadsMet.begin(), twoThreadsMet.end(), [](bool b) { return b; });
      ++twoThreadRuns_;
      allTwoThreads_ += allMet;
      allLlvmpipe_ += std::all_of(llvmpipeMet.begin(), llvmpipeMet.end(), [](bool b) { return b; });
      if (roomCells == twoThreadCells) {
        ++roomEverywhere_;
        roomEverywhereAllMet_ += allMet;
      }
    }
  }

  int runs() const { return int(runs_.size()); }

  std::string text() const {
    std::string out = "The speed targets over " + std::to_string(runs_.size()) +
                      " runs: in how many runs each figure was met\n" + targetLine("target", columns_);
    for (const std::string& key : order_) out += targetLine(counts_.at(key).label, cellsOf(key));
    if (twoThreadRuns_ > 0)
      out += "runs with every two-thread figure met: shadowref " + std::to_string(allTwoThreads_) + ", llvmpipe " +
             std::to_string(allLlvmpipe_) + " (of " + std::to_string(twoThreadRuns_) + ")\n" +
             "runs with the host's capacity for two threads at or above the line in every two-thread cell: " +
             std::to_string(roomEverywhere_) + " (every two-thread figure met in " + std::to_string(roomEverywhereAllMet_) +
             " of them)\n";
    out += "figures met, run by run:\n";
    for (const RunLine& r : runs_)
      out += "  " + std::to_string(r.met) + " of " + std::to_string(r.checked) + "  " + r.name +
             (r.commit.empty() ? "" : " (" + r.commit + ")") + "\n";
    return out;
  }

 private:
  struct Counts {
    std::string label;
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

  static bool isYesNo(const RunTargets::Row& row) {
    return !row.threshold && !row.cells.empty() && !tally_detail::leadingNumber(row.cells[0]);
  }
  static bool isTwoThreads(const std::string& what) { return what.find("2 threads / 1 >= ") != std::string::npos; }

  // The count kept under `key`, printed as `label` (a target row's own label, or the label of a
  // line under it).
  Counts& counts(const std::string& key, const std::string& label) {
    auto [it, added] = counts_.try_emplace(key);
    if (added) {
      order_.push_back(key);
      it->second.label = label;
    }
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
  int twoThreadRuns_ = 0, allTwoThreads_ = 0, allLlvmpipe_ = 0;
  int roomEverywhere_ = 0, roomEverywhereAllMet_ = 0;  // runs whose every two-thread cell had room
};

}  // namespace shadowref::bench
