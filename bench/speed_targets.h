// The speed targets checked against one run's figures, so that a run of bench/vs-mesa says by
// itself which it met: each target a row, each compared scene a cell with its figure and "ok" or
// "SHORT". Rows marked as information (two threads against one, the host's capacity, per pixel
// against per vertex) carry no verdict. Nothing here becomes an exit status: timing on a shared
// host is a measurement, not a test (only determinism fails a run, in vs_mesa).
#pragma once

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace shadowref::bench {

// A line of a table of targets: the label in kTargetLabelWidth columns, then each cell right-aligned
// in kTargetCellWidth - 1 after a space (target_tally.h reads runs' tables back by these widths).
constexpr size_t kTargetLabelWidth = 44, kTargetCellWidth = 16;

inline std::string targetLine(const std::string& what, const std::vector<std::string>& cells) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%-*s", int(kTargetLabelWidth), what.c_str());
  std::string out = buf;
  for (const std::string& c : cells) {
    std::snprintf(buf, sizeof buf, " %*s", int(kTargetCellWidth - 1), c.c_str());
    out += buf;
  }
  return out + "\n";
}

class TargetTable {
 public:
  explicit TargetTable(std::vector<std::string> columns) : columns_(std::move(columns)) {}

  // A target met where value >= threshold, one value per column; the row reads "what >= threshold"
  // (the label is made from the number, so the two cannot disagree).
  void atLeast(const std::string& what, double threshold, const std::vector<double>& values) {
    Row r{what + " >= " + thresholdText(threshold), true, {}};
    for (double v : values) r.cells.push_back({format(v) + (v >= threshold ? " ok" : " SHORT"), v >= threshold});
    rows_.push_back(r);
  }
  // A target met where the flag is set, one per column; the cell says `yes` or `no`.
  void holds(const std::string& what, const std::vector<bool>& flags, const std::string& yes, const std::string& no) {
    Row r{what, true, {}};
    for (bool f : flags) r.cells.push_back({f ? yes : no, f});
    rows_.push_back(r);
  }
  // Figures shown beside the targets, without a verdict.
  void information(const std::string& what, const std::vector<double>& values) {
    Row r{what, false, {}};
    for (double v : values) r.cells.push_back({format(v), true});
    rows_.push_back(r);
  }
  // A target that is one figure for the whole run (a fit over a series), shown in the first column;
  // the row reads "what >= threshold".
  void single(const std::string& what, double value, double threshold) {
    rows_.push_back({what + " >= " + thresholdText(threshold), true,
                     {{format(value, 3) + (value >= threshold ? " ok" : " SHORT"), value >= threshold}}});
  }

  // Figures checked against a target, and how many of them fell short.
  int checked() const { return count(false); }
  int shortOf() const { return count(true); }

  std::string text() const {
    std::string out = targetLine("target", columns_);
    for (const Row& r : rows_) {
      std::vector<std::string> cells;
      for (const Cell& c : r.cells) cells.push_back(c.text);
      out += targetLine(r.what, cells);
    }
    return out + std::to_string(checked() - shortOf()) + " of " + std::to_string(checked()) +
           " figures at or above their targets\n";
  }

 private:
  struct Cell {
    std::string text;
    bool met = true;
  };
  struct Row {
    std::string what;
    bool target = true;  // false: information, no verdict
    std::vector<Cell> cells;
  };

  // A threshold as the targets state it: 1, 10, 0.95.
  static std::string thresholdText(double threshold) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", threshold);
    return buf;
  }
  // Cut, not rounded, to the decimals shown: a figure short of a threshold of as many decimals
  // never reads as reaching it (9.999 against 10 shows 9.99, not 10.00).
  static std::string format(double v, int decimals = 2) {
    const double scale = std::pow(10.0, decimals);
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, std::floor(v * scale) / scale);
    return buf;
  }
  int count(bool onlyShort) const {
    int n = 0;
    for (const Row& r : rows_)
      if (r.target)
        for (const Cell& c : r.cells) n += !onlyShort || !c.met;
    return n;
  }

  std::vector<std::string> columns_;
  std::vector<Row> rows_;
};

}  // namespace shadowref::bench
