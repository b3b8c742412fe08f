// Merging a sweep's records: one CSV of every job (rows by id, the same bytes for the same
// records, whichever shards wrote them), one error-against-time plot per plot name (gnuplot,
// every point labelled by its configuration, coloured by method family) and a Markdown table.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "sweep/sweep_spec.h"

namespace shadowref::sweep {

struct MergeOptions {
  std::string outDir;    // where the records are
  std::string csv;       // the CSV written
  std::string plotsDir;  // plot-<name>.dat, plot-<name>.gp and, with gnuplot, plot-<name>.png; "" for none
  std::string table;     // a Markdown table of every job; "" for none
  bool drawPlots = true; // run gnuplot on the scripts (when it is installed)
};

// The CSV's header line (without the newline): the columns, in order.
std::string csvHeader();

struct MergeResult {
  std::vector<std::string> missing;  // ids of jobs without a complete record
  std::vector<std::string> written;  // the files written
  std::vector<std::string> notes;    // e.g. gnuplot not found: plots not drawn
};

// Writes the outputs when every job of `spec` has a complete record (outputs are written
// atomically); otherwise writes nothing and lists the missing jobs.
MergeResult mergeRecords(const Spec& spec, const MergeOptions& options);

}  // namespace shadowref::sweep
