#include "sweep/sweep_merge.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "image/atomic_write.h"
#include "sweep/sweep_run.h"

namespace shadowref::sweep {

namespace {

using Json = nlohmann::json;

const char* const kColumns[] = {
    "id", "groups", "plots", "label", "scene", "method", "family", "frame", "overrides", "reference",
    // error against the reference ([pixel, light] pairs compared; fractions of them)
    "lights", "pixels", "mae", "wrong", "wrong_core", "shadowed",
    // the frame's pipeline counters
    "draw_calls", "triangles", "fragments", "stencil_writes", "depth_failed", "color_writes",
    // time per frame and the machine it was measured on
    "repetitions", "time_ms", "time_min_ms", "time_max_ms", "cpu_ms", "hostname", "cpu", "threads", "build"};

std::string csvField(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string fixed(double v, int digits) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", digits, v);
  return buffer;
}

std::string join(const std::vector<std::string>& parts, const char* sep) {
  std::string out;
  for (size_t i = 0; i < parts.size(); ++i) out += (i ? sep : "") + parts[i];
  return out;
}

std::string overridesText(const Job& job) {
  std::vector<std::string> parts;
  for (const auto& [k, v] : job.overrides) parts.push_back(k + "=" + v);
  return join(parts, " ");
}

std::string referenceText(const Job& job) {
  if (!job.record.error) return "";
  if (job.reference.shape == Reference::HardLight) return "point";
  return std::string(name(job.reference.shape)) + " " + fixed(job.reference.size, 3) + " x" +
         std::to_string(job.reference.samples);
}

// A number of the record at `section`.`key`, formatted, or "" when absent.
std::string number(const Json& r, const char* section, const char* key, int digits) {
  if (!r.contains(section) || !r[section].contains(key)) return "";
  const Json& v = r[section][key];
  if (v.is_number_integer() || v.is_number_unsigned()) return std::to_string(v.get<long long>());
  return fixed(v.get<double>(), digits);
}
std::string text(const Json& r, const char* section, const char* key) {
  if (!r.contains(section) || !r[section].contains(key)) return "";
  const Json& v = r[section][key];
  return v.is_string() ? v.get<std::string>() : v.dump();
}

std::vector<std::string> csvRow(const Job& job, const Json& r) {
  return {job.id, join(job.groups, " "), join(job.plots, " "), job.label, job.scene, job.method,
          methodFamily(job.method), std::to_string(job.frame), overridesText(job), referenceText(job),
          std::to_string(r.value("lights", 0)), number(r, "error", "pixels", 0), number(r, "error", "mae", 6),
          number(r, "error", "wrong", 6), number(r, "error", "wrong_core", 6), number(r, "error", "shadowed", 6),
          number(r, "counts", "draw_calls", 0), number(r, "counts", "triangles", 0), number(r, "counts", "fragments", 0),
          number(r, "counts", "stencil_writes", 0), number(r, "counts", "depth_failed", 0),
          number(r, "counts", "color_writes", 0), number(r, "time", "repetitions", 0), number(r, "time", "median_ms", 3),
          number(r, "time", "min_ms", 3), number(r, "time", "max_ms", 3), number(r, "time", "cpu_median_ms", 3),
          text(r, "machine", "hostname"), text(r, "machine", "cpu"), number(r, "machine", "threads", 0),
          text(r, "machine", "build")};
}

void writeText(const std::string& path, const std::string& bytes) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
  writeFileAtomically(path, [&](const TempFile& temp) { writeAllAt(temp.fd, bytes.data(), bytes.size(), 0); });
}

const std::vector<std::string> kFamilies = {"none", "shadow volumes", "shadow maps"};
const char* const kFamilyColours[] = {"#707070", "#3060a0", "#c03020"};

std::string safeName(const std::string& plot) {
  std::string out;
  for (char c : plot) out += std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' ? c : '-';
  return out;
}

// Runs gnuplot on `script` in `folder` (the scripts name their files relative to it, so that they
// are the same bytes wherever the plots go). 127: gnuplot is not installed.
int runGnuplot(const std::string& folder, const std::string& script) {
  const pid_t pid = fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    if (chdir(folder.c_str()) != 0) _exit(126);
    execlp("gnuplot", "gnuplot", script.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// One plot: a data block per method family (gnuplot's `index`), the script that draws it.
// Returns false when gnuplot is not installed.
bool writePlot(const std::string& plot, const std::vector<std::pair<const Job*, const Json*>>& points,
               const MergeOptions& options, MergeResult& result) {
  const std::string name = "plot-" + safeName(plot);
  const std::string base = (std::filesystem::path(options.plotsDir) / name).string();
  std::ostringstream data;
  data << "# " << plot << ": CPU time per frame (ms), MAE (%), configuration; one block per method family\n";
  bool anyZero = false;
  std::vector<bool> used(kFamilies.size(), false);
  for (size_t f = 0; f < kFamilies.size(); ++f) {
    bool header = false;
    for (const auto& [job, r] : points) {
      if (methodFamily(job->method) != kFamilies[f]) continue;
      if (!header) data << "# family: " << kFamilies[f] << "\n";
      header = true;
      const double mae = (*r)["error"]["mae"].get<double>() * 100.0;
      anyZero = anyZero || mae <= 0.0;
      used[f] = true;
      std::string label = job->method + (job->label.empty() ? "" : " " + job->label);
      std::replace(label.begin(), label.end(), '"', '\'');
      data << fixed((*r)["time"]["cpu_median_ms"].get<double>(), 3) << '\t' << fixed(mae, 6) << "\t\"" << label << "\"\n";
    }
    if (header) data << "\n\n";  // gnuplot's `index` counts the blocks so separated
  }
  std::ostringstream gp;
  gp << "set terminal pngcairo noenhanced size 1100,720 font \"DejaVu Sans,10\"\n"
     << "set output \"" << name << ".png\"\n"
     << "set title \"" << plot << ": shadow error against time per frame (every point labelled)\"\n"
     << "set grid\nset key top right\nset logscale x\n"
     << "set xlabel \"median CPU time per frame (ms)\"\n"
     << "set ylabel \"error: mean |visibility - reference| (%)\"\n"
     << (anyZero ? "set yrange [0:*]\n" : "set logscale y\n")
     << "set offsets graph 0.05, graph 0.35, graph 0.08, graph 0.05\n"
     << "set datafile separator \"\\t\"\n"
     << "plot";
  int block = 0;
  for (size_t f = 0; f < kFamilies.size(); ++f) {
    if (!used[f]) continue;
    gp << (block ? ", \\\n     " : " ") << "\"" << name << ".dat\" index " << block << " using 1:2 with points pt 7 ps 1.2 lc rgb \""
       << kFamilyColours[f] << "\" title \"" << kFamilies[f] << "\", \\\n     \"" << name << ".dat\" index " << block
       << " using 1:2:3 with labels left offset 0.7,0.4 font \",7\" tc rgb \"" << kFamilyColours[f] << "\" notitle";
    ++block;
  }
  gp << "\n";
  writeText(base + ".dat", data.str());
  writeText(base + ".gp", gp.str());
  result.written.push_back(base + ".dat");
  result.written.push_back(base + ".gp");
  if (!options.drawPlots) return true;
  const int status = runGnuplot(options.plotsDir, name + ".gp");
  if (status == 127) return false;
  if (status != 0 || !std::filesystem::exists(base + ".png"))
    result.notes.push_back("gnuplot failed on " + base + ".gp");
  else
    result.written.push_back(base + ".png");
  return true;
}

std::string percent(const Json& r, const char* key) {
  if (!r.contains("error")) return "";
  return fixed(r["error"][key].get<double>() * 100.0, 2) + " %";
}

std::string markdownTable(const Spec& spec, const std::vector<Json>& records) {
  std::vector<size_t> order(spec.jobs.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return spec.jobs[a].order < spec.jobs[b].order; });
  std::set<std::string> machines;
  for (const Json& r : records)
    if (r.contains("machine"))
      machines.insert(text(r, "machine", "hostname") + " (" + text(r, "machine", "cpu") + ", " +
                      number(r, "machine", "threads", 0) + " render thread" +
                      (number(r, "machine", "threads", 0) == "1" ? "" : "s") + ", " + text(r, "machine", "build") + ")");
  std::ostringstream md;
  md << "Timed on: " << (machines.empty() ? std::string("(not timed)") : join({machines.begin(), machines.end()}, "; "))
     << ".\n\n"
     << "| group | scene | configuration | method | lights | CPU ms | wall ms | MAE | wrong | wrong off edges | "
        "fragments | id |\n"
     << "| --- | --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- |\n";
  for (size_t i : order) {
    const Job& job = spec.jobs[i];
    const Json& r = records[i];
    md << "| " << join(job.groups, ", ") << " | " << std::filesystem::path(job.scene).stem().string() << " | "
       << (job.label.empty() ? "—" : job.label) << " | " << job.method << " | " << r.value("lights", 0) << " | "
       << number(r, "time", "cpu_median_ms", 1) << " | " << number(r, "time", "median_ms", 1) << " | " << percent(r, "mae")
       << " | " << percent(r, "wrong") << " | " << percent(r, "wrong_core") << " | "
       << number(r, "counts", "fragments", 0) << " | `" << job.id << "` |\n";
  }
  return md.str();
}

}  // namespace

std::string csvHeader() {
  std::vector<std::string> names(std::begin(kColumns), std::end(kColumns));
  return join(names, ",");
}

MergeResult mergeRecords(const Spec& spec, const MergeOptions& options) {
  MergeResult result;
  std::vector<Json> records(spec.jobs.size());
  for (size_t i = 0; i < spec.jobs.size(); ++i) {
    const Job& job = spec.jobs[i];
    const std::string path = recordPath(options.outDir, job);
    if (!recordIsComplete(path, job, false)) {
      result.missing.push_back(job.id);
      continue;
    }
    std::ifstream in(path, std::ios::binary);
    records[i] = Json::parse(in);
  }
  if (!result.missing.empty()) return result;

  std::ostringstream csv;
  csv << csvHeader() << "\n";
  for (size_t i = 0; i < spec.jobs.size(); ++i) {  // spec.jobs is sorted by id
    const std::vector<std::string> row = csvRow(spec.jobs[i], records[i]);
    for (size_t c = 0; c < row.size(); ++c) csv << (c ? "," : "") << csvField(row[c]);
    csv << "\n";
  }
  writeText(options.csv, csv.str());
  result.written.push_back(options.csv);

  if (!options.plotsDir.empty()) {
    std::map<std::string, std::vector<std::pair<const Job*, const Json*>>> plots;
    for (size_t i = 0; i < spec.jobs.size(); ++i)
      if (records[i].contains("time") && records[i].contains("error"))
        for (const std::string& p : spec.jobs[i].plots) plots[p].emplace_back(&spec.jobs[i], &records[i]);
    if (plots.empty()) result.notes.push_back("no job records both time and error: no plots");
    MergeOptions draw = options;
    for (const auto& [plot, points] : plots)
      if (!writePlot(plot, points, draw, result)) {
        draw.drawPlots = false;
        result.notes.push_back("gnuplot not found (scripts/setup.sh --role bench installs gnuplot-nox): plots not drawn");
      }
  }
  if (!options.table.empty()) {
    writeText(options.table, markdownTable(spec, records));
    result.written.push_back(options.table);
  }
  return result;
}

}  // namespace shadowref::sweep
