#include "tradeoffs/report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <sstream>

namespace shadowref::bench {

namespace {

bool measured(const Row& r) { return r.timing.ok && r.errorMessage.empty(); }

std::string fixed(double v, int digits) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", digits, v);
  return buffer;
}
std::string percent(double fraction, int digits = 2) { return fixed(100.0 * fraction, digits) + " %"; }
std::string mib(long kib) { return fixed(double(kib) / 1024.0, 1); }
std::string ms(const Row* r) { return r && r->timing.ok ? fixed(r->timing.medianMs, 1) : "—"; }
std::string err(const Row* r, double ShadowError::*field) {
  return r && r->errorMessage.empty() ? percent(r->error.*field) : "—";
}

const Row* find(const std::vector<Row>& rows, const std::string& group, const std::string& variant,
                const std::string& method) {
  for (const Row& r : rows)
    if (r.experiment.group == group && r.experiment.variant == variant && r.experiment.method == method) return &r;
  return nullptr;
}

// Frame-rate loss of `slow` against `fast`: 1 - fps_slow / fps_fast = 1 - t_fast / t_slow, as
// [Kuhn 2016, §5.4.1] states its "Verlustrate".
std::string loss(const Row* fast, const Row* slow) {
  if (!fast || !slow || !fast->timing.ok || !slow->timing.ok) return "—";
  return fixed(100.0 * (1.0 - fast->timing.medianMs / slow->timing.medianMs), 0) + " %";
}

std::string csvField(const std::string& s) {
  if (s.find_first_of(",\"") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string join(const std::vector<std::string>& v, const char* sep) {
  std::string out;
  for (size_t i = 0; i < v.size(); ++i) out += (i ? sep : "") + v[i];
  return out;
}

}  // namespace

void markParetoFronts(std::vector<Row>& rows) {
  for (Row& a : rows) {
    a.pareto = false;
    if (a.experiment.plot.empty() || !measured(a)) continue;
    bool dominated = false;
    for (const Row& b : rows) {
      if (&a == &b || b.experiment.plot != a.experiment.plot || !measured(b)) continue;
      const bool noWorse = b.timing.medianMs <= a.timing.medianMs && b.error.mae <= a.error.mae;
      const bool better = b.timing.medianMs < a.timing.medianMs || b.error.mae < a.error.mae;
      if (noWorse && better) dominated = true;
    }
    a.pareto = !dominated;
  }
}

void writeCsv(const std::string& path, const RunInfo& info, const std::vector<Row>& rows) {
  std::ofstream out(path);
  out << "group,scene,variant,method,overrides,width,height,threads,frames,rounds,lights_rendered,cpu_median_ms,cpu_fastest_round_ms,cpu_min_ms,cpu_max_ms,"
         "peak_rss_kib,wall_median_ms,reference,pixels,mae,wrong,wrong_off_edges,reference_shadowed,plot,pareto,note\n";
  for (const Row& r : rows) {
    const Experiment& e = r.experiment;
    out << csvField(e.group) << ',' << csvField(e.scene) << ',' << csvField(e.variant) << ',' << e.method << ','
        << csvField(join(e.overrides, " ")) << ',' << info.size.width << ',' << info.size.height << ',' << info.threads
        << ',' << info.frames << ',' << info.rounds << ',' << r.lightsRendered << ',';
    if (r.timing.ok)
      out << fixed(r.timing.medianMs, 3) << ',' << fixed(r.timing.fastestRoundMs, 3) << ','
          << fixed(r.timing.minMs, 3) << ',' << fixed(r.timing.maxMs, 3) << ',' << r.timing.peakRssKiB << ','
          << fixed(r.timing.wallMedianMs, 3) << ',';
    else out << ",,,,,,";
    out << name(e.reference) << ',';
    if (r.errorMessage.empty())
      out << r.error.pixels << ',' << fixed(r.error.mae, 6) << ',' << fixed(r.error.wrong, 6) << ','
          << fixed(r.error.wrongCore, 6) << ',' << fixed(r.error.shadowed, 6) << ',';
    else out << ",,,,,";
    out << csvField(e.plot) << ',' << (r.pareto ? 1 : 0) << ','
        << csvField(r.timing.ok ? r.errorMessage : r.timing.error) << '\n';
  }
}

void writePlotData(const std::string& directory, const std::vector<Row>& rows) {
  std::map<std::string, std::vector<const Row*>> plots;
  for (const Row& r : rows)
    if (!r.experiment.plot.empty() && measured(r)) plots[r.experiment.plot].push_back(&r);
  for (auto& [plot, members] : plots) {
    std::sort(members.begin(), members.end(),
              [](const Row* a, const Row* b) { return a->timing.medianMs < b->timing.medianMs; });
    std::ofstream all(directory + "/plot-" + plot + ".dat"), front(directory + "/plot-" + plot + "-front.dat");
    all << "# cpu_median_ms mae_percent label\n";
    front << "# cpu_median_ms mae_percent label\n";
    for (const Row* r : members) {
      const std::string line = fixed(r->timing.medianMs, 3) + " " + fixed(100.0 * r->error.mae, 4) + " \"" +
                               r->experiment.method + " " + r->experiment.variant + "\"\n";
      all << line;
      if (r->pareto) front << line;
    }
  }
  // Error against map size, standard and trapezoidal ([Hempe 2004, §6.1]).
  std::ofstream sizes(directory + "/series-map-size.dat");
  sizes << "# map_size sm_ms sm_wrong_percent tsm_ms tsm_wrong_percent\n";
  for (int n : {128, 256, 512, 1024, 2048, 4096}) {
    const Row* sm = find(rows, "map_size", std::to_string(n), "shadowmap");
    const Row* tsm = find(rows, "map_size", std::to_string(n), "tsm");
    if (!sm || !tsm || !measured(*sm) || !measured(*tsm)) continue;
    sizes << n << ' ' << fixed(sm->timing.medianMs, 3) << ' ' << fixed(100 * sm->error.wrong, 4) << ' '
          << fixed(tsm->timing.medianMs, 3) << ' ' << fixed(100 * tsm->error.wrong, 4) << '\n';
  }
  // Time against house count ([Kuhn 2016, §5.4.1]).
  std::ofstream houses(directory + "/series-houses.dat");
  houses << "# houses random_none random_zpass single_none single_zpass (ms)\n";
  for (int n : {8, 16, 32, 64, 100}) {
    const std::string h = "houses=" + std::to_string(n);
    houses << n << ' ' << ms(find(rows, "houses", h + " random", "none")) << ' '
           << ms(find(rows, "houses", h + " random", "zpass")) << ' ' << ms(find(rows, "houses", h + " single", "none"))
           << ' ' << ms(find(rows, "houses", h + " single", "zpass")) << '\n';
  }
  std::ofstream lights(directory + "/series-lights.dat");
  lights << "# lights none_ms zpass_ms\n";
  for (int n = 1; n <= 9; ++n) {
    const std::string l = "lights=" + std::to_string(n);
    lights << n << ' ' << ms(find(rows, "lights", l, "none")) << ' ' << ms(find(rows, "lights", l, "zpass")) << '\n';
  }
}

namespace {

class Markdown {
 public:
  explicit Markdown(std::ostream& out) : out_(out) {}
  void table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& body) {
    out_ << "| " << join(header, " | ") << " |\n|";
    for (size_t i = 0; i < header.size(); ++i) out_ << (i == 0 ? " --- |" : " ---: |");
    out_ << '\n';
    for (const auto& row : body) out_ << "| " << join(row, " | ") << " |\n";
    out_ << '\n';
  }
  std::ostream& text() { return out_; }

 private:
  std::ostream& out_;
};

std::vector<const Row*> group(const std::vector<Row>& rows, const std::string& g) {
  std::vector<const Row*> out;
  for (const Row& r : rows)
    if (r.experiment.group == g) out.push_back(&r);
  return out;
}

void housesSection(Markdown& md, const std::vector<Row>& rows) {
  md.text() << "## Shadows against the number of houses ([Kuhn 2016, §5.4.1])\n\n"
               "One light; z-pass volumes (the city's camera is outside every volume). \"Loss\" is the documents' "
               "*Verlustrate*: 1 − fps with shadows / fps without. The document measured its loss with one model "
               "(Haus01, our model 0) and the random city with shadows only.\n\n";
  const std::map<int, std::string> paper = {{8, "28 %"}, {16, "51 %"}, {100, "71 %"}};
  std::vector<std::vector<std::string>> body;
  for (int n : {8, 16, 32, 64, 100}) {
    const std::string h = "houses=" + std::to_string(n);
    const Row *rn = find(rows, "houses", h + " random", "none"), *rz = find(rows, "houses", h + " random", "zpass");
    const Row *sn = find(rows, "houses", h + " single", "none"), *sz = find(rows, "houses", h + " single", "zpass");
    body.push_back({std::to_string(n), ms(rn), ms(rz), loss(rn, rz), ms(sn), ms(sz), loss(sn, sz),
                    paper.count(n) ? paper.at(n) : "—", err(rz, &ShadowError::wrong), err(sz, &ShadowError::wrong),
                    err(sn, &ShadowError::shadowed), sz && sz->timing.ok ? mib(sz->timing.peakRssKiB) : "—"});
  }
  md.table({"houses", "random: none ms", "random: z-pass ms", "random: loss", "Haus01: none ms", "Haus01: z-pass ms",
            "Haus01: loss", "loss in [Kuhn 2016, §5.4.1]", "random: z-pass wrong", "Haus01: z-pass wrong",
            "Haus01: shadowed (none's error)", "Haus01 z-pass peak MiB"},
           body);
}

void lightsSection(Markdown& md, const std::vector<Row>& rows) {
  md.text() << "## Shadows against the number of lights ([Kuhn 2016, §5.4.1])\n\n"
               "16 houses of one model (Haus02, our model 1), z-pass volumes, lights `sun0` … `sun8` of the city "
               "generator. Loss as above; the error counts every (pixel, light) pair.\n\n";
  const std::map<int, std::string> paper = {{4, "18 %"}, {9, "53 %"}};
  std::vector<std::vector<std::string>> body;
  for (int n = 1; n <= 9; ++n) {
    const std::string l = "lights=" + std::to_string(n);
    const Row *none = find(rows, "lights", l, "none"), *zp = find(rows, "lights", l, "zpass");
    body.push_back({std::to_string(n), ms(none), ms(zp), loss(none, zp), paper.count(n) ? paper.at(n) : "—",
                    err(zp, &ShadowError::wrong), err(none, &ShadowError::shadowed),
                    zp && zp->timing.ok ? mib(zp->timing.peakRssKiB) : "—"});
  }
  md.table({"lights", "none ms", "z-pass ms", "loss (ours)", "loss in [Kuhn 2016, §5.4.1]", "z-pass wrong",
            "shadowed (none's error)", "z-pass peak MiB"},
           body);
}

void countingSection(Markdown& md, const std::vector<Row>& rows) {
  md.text() << "## z-pass against z-fail and auto ([Kuhn 2016, §5.4.2])\n\n"
               "\"More frames\" is fps(z-pass) / fps(z-fail) − 1 = t(z-fail) / t(z-pass) − 1, the documents' measure. "
               "\"wrong\" is the fraction of compared pixels whose stencil verdict differs from the oracle's shadow ray; "
               "\"off edges\" leaves out pixels within one pixel of a contour or shadow outline, where a one-pixel "
               "disagreement is rasterization, not counting.\n\n";
  const std::map<std::string, std::string> paper = {{"room", "27 %"}, {"pumpkins", "45.8 %"}, {"city-64", "9.8 %"}};
  std::vector<std::vector<std::string>> body;
  for (const std::string v : {"room", "pumpkins", "city-64"}) {
    const Row *none = find(rows, "counting", v, "none"), *zp = find(rows, "counting", v, "zpass"),
              *zf = find(rows, "counting", v, "zfail"), *au = find(rows, "counting", v, "auto");
    std::string more = "—";
    if (zp && zf && zp->timing.ok && zf->timing.ok)
      more = fixed(100.0 * (zf->timing.medianMs / zp->timing.medianMs - 1.0), 1) + " %";
    body.push_back({v, ms(none), ms(zp), ms(zf), ms(au), more, paper.at(v), err(zp, &ShadowError::wrong),
                    err(zp, &ShadowError::wrongCore), err(zf, &ShadowError::wrong), err(zf, &ShadowError::wrongCore),
                    err(au, &ShadowError::wrongCore), err(none, &ShadowError::shadowed)});
  }
  md.table({"scene", "none ms", "z-pass ms", "z-fail ms", "auto ms", "z-pass more frames (ours)", "[Kuhn 2016, §5.4.2]",
            "z-pass wrong", "z-pass wrong off edges", "z-fail wrong", "z-fail wrong off edges", "auto wrong off edges",
            "shadowed (none's error)"},
           body);
}

void softSection(Markdown& md, const std::vector<Row>& rows) {
  md.text() << "## Soft shadows ([Kuhn 2016, §5.3, §4.2]; [Hempe 2004, §4.2])\n\n"
               "The room with its light lowered to y = 2.6. References: *square* = the area light "
               "[−0.25, 0.25]² in the light's horizontal plane (square_y spacing 0.25 spans it; area16 with side 0.5 "
               "runs round its edge), *sphere* = the sphere of radius 0.25 (sphere14's points lie on it); each by "
               "shadow rays to its sample points from the oracle's surface point of every pixel. MAE is the mean "
               "absolute difference of the light's visibility in [0, 1]; \"× hard\" the time against hard z-fail. "
               "[Kuhn 2016, §5.3] reports 64 → 18 fps for 8 extra lights: 3.6× the time.\n\n";
  const Row* hard = find(rows, "soft", "hard (vs square)", "zfail");
  std::vector<std::vector<std::string>> body;
  for (const Row* r : group(rows, "soft")) {
    std::string times = "—";
    if (hard && hard->timing.ok && r->timing.ok) times = fixed(r->timing.medianMs / hard->timing.medianMs, 2) + "×";
    body.push_back({r->experiment.variant, r->experiment.method, std::to_string(r->lightsRendered), ms(r), times,
                    name(r->experiment.reference), err(r, &ShadowError::mae), err(r, &ShadowError::wrong),
                    r->timing.ok ? mib(r->timing.peakRssKiB) : "—"});
  }
  md.table({"configuration", "method", "lights", "ms", "× hard", "reference", "MAE", "wrong (at 0.5)", "peak MiB"},
           body);
}

void mapSizeSection(Markdown& md, const std::vector<Row>& rows) {
  md.text() << "## Shadow-map and TSM resolution ([Hempe 2004, §6.1])\n\n"
               "The outdoor scene (directional light, far plane 300), polygon offset 1.1 / 4, nearest sampling. "
               "[Hempe 2004, §6.1]: TSM at 256² looks like a standard map at 1024².\n\n";
  std::vector<std::vector<std::string>> body;
  const Row* none = find(rows, "map_size", "no shadows", "none");
  if (none)
    body.push_back({"none", ms(none), err(none, &ShadowError::wrong), "", "", "", "",
                    none->timing.ok ? mib(none->timing.peakRssKiB) : "—", ""});
  for (int n : {128, 256, 512, 1024, 2048, 4096}) {
    const Row *sm = find(rows, "map_size", std::to_string(n), "shadowmap"),
              *tsm = find(rows, "map_size", std::to_string(n), "tsm");
    body.push_back({std::to_string(n) + "²", ms(sm), err(sm, &ShadowError::wrong), err(sm, &ShadowError::wrongCore),
                    ms(tsm), err(tsm, &ShadowError::wrong), err(tsm, &ShadowError::wrongCore),
                    sm && sm->timing.ok ? mib(sm->timing.peakRssKiB) : "—",
                    tsm && tsm->timing.ok ? mib(tsm->timing.peakRssKiB) : "—"});
  }
  md.table({"map", "standard ms", "standard wrong", "standard wrong off edges", "TSM ms", "TSM wrong",
            "TSM wrong off edges", "standard peak MiB", "TSM peak MiB"},
           body);
  const Row *tsm256 = find(rows, "map_size", "256", "tsm"), *sm1024 = find(rows, "map_size", "1024", "shadowmap");
  if (tsm256 && sm1024 && measured(*tsm256) && measured(*sm1024))
    md.text() << "Measured: TSM 256² is wrong at " << percent(tsm256->error.wrong) << " of the lit-or-shadowed pixels, "
              << "the standard map at 1024² at " << percent(sm1024->error.wrong) << " ("
              << (tsm256->error.wrong <= sm1024->error.wrong ? "the claim holds here" : "the claim does not hold here")
              << ").\n\n";
}

void plainSection(Markdown& md, const std::vector<Row>& rows, const std::string& g, const std::string& title,
                  const std::string& intro) {
  md.text() << "## " << title << "\n\n" << intro << "\n\n";
  std::vector<std::vector<std::string>> body;
  for (const Row* r : group(rows, g))
    body.push_back({r->experiment.variant, r->experiment.method, ms(r), err(r, &ShadowError::mae),
                    err(r, &ShadowError::wrong), err(r, &ShadowError::wrongCore),
                    r->timing.ok ? mib(r->timing.peakRssKiB) : "—",
                    !r->timing.ok ? r->timing.error : r->errorMessage});
  md.table({"configuration", "method", "ms", "MAE", "wrong", "wrong off edges", "peak MiB", "note"}, body);
}

void paretoSection(Markdown& md, const std::vector<Row>& rows) {
  md.text() << "## Error against time, per scene\n\n"
               "Each plot holds the configurations that render the same picture; the error is the MAE of the "
               "light's visibility (for hard references the fraction of wrong pixels, PCF's fractions counting in "
               "between). The line joins the Pareto front: configurations no other one beats in both time and "
               "error.\n\n";
  std::map<std::string, std::vector<const Row*>> plots;
  for (const Row& r : rows)
    if (!r.experiment.plot.empty() && r.pareto) plots[r.experiment.plot].push_back(&r);
  for (auto& [plot, front] : plots) {
    std::sort(front.begin(), front.end(),
              [](const Row* a, const Row* b) { return a->timing.medianMs < b->timing.medianMs; });
    md.text() << "![" << plot << "](images/tradeoff-" << plot << ".png)\n\n" << "Front of *" << plot << "*: ";
    std::vector<std::string> names;
    for (const Row* r : front)
      names.push_back(r->experiment.method + " " + r->experiment.variant + " (" + fixed(r->timing.medianMs, 1) +
                      " ms, " + percent(r->error.mae) + ")");
    md.text() << join(names, "; ") << ".\n\n";
  }
  md.text() << "![map size](images/tradeoff-map-size.png)\n\n![houses](images/tradeoff-houses.png)\n\n"
               "![lights](images/tradeoff-lights.png)\n\n";
}

}  // namespace

void writeMarkdown(const std::string& path, const RunInfo& info, const std::vector<Row>& rows) {
  std::ofstream out(path);
  Markdown md(out);
  out << "# The trade, measured\n\n"
         "What each choice costs in time and memory and what it buys in accuracy, measured on this renderer. "
         "Generated by `scripts/bench-tradeoffs.sh` (program `bench/tradeoffs/`); every number below is "
         "in [`bench/results/tradeoffs.csv`](../bench/results/tradeoffs.csv). Do not edit the tables by hand: run "
         "the script.\n\n"
         "## How it was measured\n\n";
  out << "- **Machine**: " << info.cpu << ", " << info.cores << " cores (nproc); **" << info.threads
      << " render thread" << (info.threads == 1 ? "" : "s") << "**; commit `" << info.commit << "`; " << info.date
      << "; the whole run took " << fixed(info.wallSeconds / 60.0, 1) << " min.\n"
      << "- **Load**: load average before: `" << info.loadBefore << "`, after: `" << info.loadAfter
      << "`. The machine is a virtual one on a shared host that runs at two speeds about 1.5× apart and "
         "switches between them within minutes; the rounds below blunt that, not wholly. Two runs of this bench "
         "minutes apart (at 380cb3d), scaled to agree on the median configuration, agreed within 10 % on 84 of "
         "102 configurations and within 15 % on 89; the rest differed by up to 1.5×: read differences under "
         "about 15 % as noise, and a single larger one with care.\n"
      << "- **Time**: **CPU time** per frame (`CLOCK_PROCESS_CPUTIME_ID`), every configuration in a fresh child "
         "process (`tradeoffs --probe`) that renders one warm-up frame and then "
      << info.frames << " timed frames of `renderFrame`, their median the probe's time. Every configuration is "
         "probed once in each of "
      << info.rounds
      << " rounds, each round starting a step further down the list, so that a configuration's probes lie "
         "spread over the whole run; the time in the tables is the **median of its rounds' medians** "
         "(`bench/tradeoffs/round_timing.h`). The CSV keeps the fastest round's median too "
         "(`cpu_fastest_round_ms`), the wall-time median, and the fastest and slowest frame of any round. CPU "
         "time, not wall time: the time a probe waits while another process of this machine holds its core is "
         "not charged to it. "
         "Images are **"
      << info.size.width << "×" << info.size.height
      << "** (the documents used 800×640), so absolute times are not theirs; ratios are what compares.\n"
      << "- **Peak memory**: the child's peak resident set, `VmHWM` of `/proc/self/status` at its end: program, "
         "libraries, the loaded scene and every buffer and shadow map (not `getrusage`'s `ru_maxrss`, which Linux "
         "carries over from the forking parent). A child that loads nothing peaks at "
      << mib(info.baselineRssKiB) << " MiB; subtract that for the configuration's own share.\n"
      << "- **Ground truth, hard shadows**: the ray-casting oracle (`src/oracle`, independent of "
         "the rasterizer): per pixel the first hit of the primary ray and a shadow ray to the light (`lit`). For "
         "shadow volumes the oracle's camera uses P_inf as the volume renderer does.\n"
      << "- **Ground truth, soft shadows**: " << info.referenceSamples
      << " shadow rays per pixel from the oracle's surface point to points spread evenly over the area light "
         "(grid cell centres on a square, a Fibonacci spiral on a sphere); the reference is the fraction that "
         "arrive.\n"
      << "- **The renderer's verdict**: shadow volumes — a light is seen where its stencil count is 0 "
         "(`FrameResult::stencilPerLight`); soft volumes average that over the light's copies. Shadow maps — the "
         "frame is rendered again with the compare-fail value 0, so that a shadowed fragment is black and the "
         "frame is (ambient + light) · visibility; visibility = brightness / brightness of the unshadowed frame. "
         "`none` sees every light everywhere.\n"
      << "- **Which pixels count**: the oracle hits a surface there and the light visibly adds to it (the "
         "unshadowed frame with that light alone is brighter than the ambient-only frame by more than "
      << kContributionThreshold
      << " in mean RGB); elsewhere a shadow, right or wrong, cannot be seen.\n"
      << "- **Columns**: *wrong* — fraction of counted (pixel, light) pairs where renderer and reference disagree "
         "about lit (visibility ≥ 0.5); *wrong off edges* — the same without the oracle's near-edge pixels (within "
         "one pixel of a geometry or volume contour or a shadow outline); *MAE* — mean |visibility − reference|.\n\n";

  countingSection(md, rows);
  housesSection(md, rows);
  lightsSection(md, rows);
  softSection(md, rows);
  mapSizeSection(md, rows);
  plainSection(md, rows, "pcf", "Percentage-closer filtering",
               "k × k PCF on the outdoor scene, standard map 1024² and TSM 256². A hard reference: PCF's "
               "fractional edges count by how far they are from 0 or 1 (MAE).");
  plainSection(md, rows, "bias", "Depth bias ([Hempe 2004, §3.2])",
               "Polygon offset in the map pass (factor, units), back faces only, or a constant bias added in the "
               "comparison; standard 1024², TSM 256². Too little bias shows as shadow acne (lit surfaces called "
               "shadowed), too much as light leaking at contact (peter-panning).");
  plainSection(md, rows, "depth", "float32 against 24-bit depth",
               "`image.depth=unorm24` for the camera's depth buffer.");
  plainSection(md, rows, "far", "P_inf against a finite far plane",
               "Shadow volumes always render with P_inf ([Kuhn 2016, §3.3]), so the far plane reaches only the shadow-map "
               "methods here; `docs/numerics.md` measures the depth precision P_inf costs.");
  paretoSection(md, rows);
  std::ifstream notes("bench/tradeoffs/notes.md");
  if (notes) out << notes.rdbuf();
}

}  // namespace shadowref::bench
