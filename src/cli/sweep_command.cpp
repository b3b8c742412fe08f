#include "cli/sweep_command.h"

#include <CLI/CLI.hpp>
#include <charconv>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli/cli_common.h"
#include "cli/version_info.h"
#include "memory/allocator_tuning.h"
#include "sweep/sweep_merge.h"
#include "sweep/sweep_run.h"

namespace shadowref::cli {

void addSweepCommand(CLI::App& app, SweepArgs& args) {
  CLI::App* sweep = app.add_subcommand(
      "sweep", "Run the jobs of a sweep file (scenes x -D grids x methods): time, shadow error, counts");
  sweep->add_option("spec", args.spec, "Sweep file (YAML, docs/sweeps.md)")->required();
  sweep->add_flag("--list", args.list, "Print one JSON line per job (id and configuration) and run nothing");
  sweep->add_option("--shard", args.shard, "K/N: run the K-th of N deterministic shares of the jobs (1 <= K <= N)");
  sweep->add_option("--out", args.out, "Folder of the job records <id>.json (default out/sweeps/<spec name>)");
  sweep->add_option("--threads", args.threads, "Render threads (0: one per CPU; default: the sweep file's, else 1)")
      ->check(wholeNumberIn(0, 256));
  sweep->add_flag("--no-timing", args.noTiming, "Time nothing: records hold errors and counts, and name no machine");
  sweep->add_flag("--merge", args.merge, "Merge the records into a CSV, plots and (with --table) a Markdown table");
  sweep->add_option("--csv", args.csv, "With --merge: the CSV (default OUTDIR/results.csv)");
  sweep->add_option("--plots", args.plots, "With --merge: the plots' folder (default OUTDIR/plots)");
  sweep->add_option("--table", args.table, "With --merge: write a Markdown table of every job to this file");
}

namespace {

bool parseShard(const std::string& text, int& k, int& n) {
  const size_t slash = text.find('/');
  if (slash == std::string::npos) return false;
  const char* end = text.data() + text.size();
  const auto a = std::from_chars(text.data(), text.data() + slash, k);
  const auto b = std::from_chars(text.data() + slash + 1, end, n);
  return a.ec == std::errc() && a.ptr == text.data() + slash && b.ec == std::errc() && b.ptr == end && n >= 1 &&
         n <= 1'000'000 && k >= 1 && k <= n;
}

std::string defaultOut(const std::string& spec) {
  std::string stem = std::filesystem::path(spec).stem().string();  // "tradeoffs.sweep" -> "tradeoffs"
  if (stem.size() > 6 && stem.ends_with(".sweep")) stem.resize(stem.size() - 6);
  return "out/sweeps/" + stem;
}

}  // namespace

int runSweep(const SweepArgs& args) {
  sweep::Spec spec;
  try {
    spec = sweep::loadSpec(args.spec);
  } catch (const SceneError& e) {
    std::cerr << e.what() << '\n';
    return kBadInput;
  } catch (const std::exception& e) {
    std::cerr << args.spec << ": " << e.what() << '\n';
    return kBadInput;
  }
  int k = 1, n = 1;
  if (!args.shard.empty() && !parseShard(args.shard, k, n)) {
    std::cerr << "sweep: --shard '" << args.shard << "' is not K/N with 1 <= K <= N (e.g. --shard 3/8)\n";
    return kBadInput;
  }
  if (args.merge && (args.list || !args.shard.empty())) {
    std::cerr << "sweep: --merge takes every shard's records; it goes with neither --list nor --shard\n";
    return kBadInput;
  }
  if (!args.merge && (!args.csv.empty() || !args.plots.empty() || !args.table.empty())) {
    std::cerr << "sweep: --csv, --plots and --table are outputs of --merge\n";
    return kBadInput;
  }
  const std::string out = args.out.empty() ? defaultOut(args.spec) : args.out;
  const std::vector<const sweep::Job*> jobs = sweep::shardJobs(spec, k, n);

  if (args.list) {
    for (const sweep::Job* job : jobs) {
      nlohmann::json line{{"id", job->id},          {"config", nlohmann::json::parse(job->canonical)},
                          {"groups", job->groups},  {"plots", job->plots},
                          {"label", job->label}};
      std::cout << line.dump() << '\n';
    }
    return kSuccess;
  }

  if (args.merge) {
    sweep::MergeOptions options;
    options.outDir = out;
    options.csv = args.csv.empty() ? out + "/results.csv" : args.csv;
    options.plotsDir = args.plots.empty() ? out + "/plots" : args.plots;
    options.table = args.table;
    try {
      const sweep::MergeResult result = sweep::mergeRecords(spec, options);
      if (!result.missing.empty()) {
        std::cerr << "sweep: " << result.missing.size() << " of " << spec.jobs.size() << " jobs have no complete record in "
                  << out << " (run their shards first), e.g. " << result.missing.front() << '\n';
        return kFailed;
      }
      for (const std::string& note : result.notes) std::cerr << "sweep: " << note << '\n';
      std::cerr << "sweep: merged " << spec.jobs.size() << " records into " << options.csv << '\n';
    } catch (const std::exception& e) {
      std::cerr << "sweep: " << e.what() << '\n';
      return kFailed;
    }
    return kSuccess;
  }

  // Jobs render frame after frame in one process, as `bench` does: freed buffers are kept for the
  // next frame instead of being returned to the kernel and faulted in again.
  keepFreedMemoryForReuse();
  sweep::RunOptions options;
  options.outDir = out;
  options.threads = args.threads >= 0 ? args.threads : spec.threads;
  options.timing = !args.noTiming;
  options.build = softwareName() + " " + buildInfo().isaLevel;
  options.progress = [](const std::string& line) { std::cerr << "sweep: " << line << '\n'; };
  sweep::RunSummary summary;
  try {
    summary = sweep::runJobs(jobs, options, [](const std::string& message) { std::cerr << "sweep: " << message << '\n'; });
  } catch (const std::exception& e) {
    std::cerr << "sweep: " << e.what() << '\n';
    return kFailed;
  }
  std::cerr << "sweep: shard " << k << "/" << n << ": " << summary.ran << " jobs run, " << summary.skipped
            << " already done, " << summary.failed + summary.badInput << " failed (records in " << out << ")\n";
  if (summary.badInput > 0) return kBadInput;
  return summary.failed > 0 ? kFailed : kSuccess;
}

}  // namespace shadowref::cli
