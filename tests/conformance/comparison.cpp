#include "conformance/comparison.h"

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>

#include "gl/fragment_shader.h"
#include "trace/osmesa/osmesa_replay.h"
#include "trace/replay_target.h"
#include "trace/trace_file.h"
#include "trace/trace_recorder.h"

namespace shadowref::conformance {

namespace {

// The recorder's pipelines see exactly what a frame's pass would give them.
void execute(Pipeline& p, const DrawStep& d) {
  std::vector<ClipVertex> vertices(d.vertices.size());
  for (size_t i = 0; i < d.vertices.size(); ++i) {
    // GL's vertex pipeline is float: the trace holds the float clip coordinates both sides get.
    const glm::dvec4& q = d.vertices[i].clip;
    vertices[i].position = {double(float(q.x)), double(float(q.y)), double(float(q.z)), double(float(q.w))};
    for (int c = 0; c < 4; ++c) vertices[i].varyings[size_t(c)] = d.vertices[i].color[c];
  }
  static const ColorVaryingShader shader;
  DrawCall call;
  call.state = &d.state;
  call.vertices = vertices;
  call.shader = &shader;
  p.draw(call);
  p.endPass();
}

void execute(Pipeline& p, const ClearStep& c) {
  ClearRequest q;
  q.state = c.state;
  if (c.color) q.color = c.colorValue;
  if (c.depth) q.depth = c.depthValue;
  if (c.stencil) q.stencil = c.stencilValue;
  if (c.accum) q.accum = c.accumValue;
  p.clear(q);
}

void execute(Pipeline& p, const AccumStep& a) { p.accumulate(a.state, a.op, a.value); }

std::string fileNameOf(const std::string& caseName) {
  std::string out;
  for (char ch : caseName) out += (std::isalnum(static_cast<unsigned char>(ch)) ? ch : '-');
  return out + ".srtrace";
}

std::string driverOfEnvironment() {
  const char* env = std::getenv("GALLIUM_DRIVER");
  return env && *env ? env : "llvmpipe";
}

}  // namespace

trace::Trace captureScenario(const Scenario& scenario) {
  trace::TraceRecorder recorder;
  const std::unique_ptr<PipelineMaker> inner = makePipelineMaker(PipelineKind::Reference);
  const std::unique_ptr<PipelineMaker> maker = recorder.wrap(*inner);
  Framebuffer fb(scenario.width, scenario.height, DepthFormat::Unorm24);
  {
    const std::unique_ptr<Pipeline> p = maker->make(fb);
    for (const Step& step : scenario.steps) std::visit([&](const auto& s) { execute(*p, s); }, step);
  }
  if (const char* folder = std::getenv("SHADOWREF_CONFORMANCE_TRACES")) {
    recorder.write(std::string(folder) + "/" + fileNameOf(scenario.name));
  }
  return trace::parseTrace(recorder.finish());
}

Replayed replayScenario(const Scenario& scenario) {
  Replayed r;
  r.trace = captureScenario(scenario);
  const auto on = [&](const std::string& target) {
    return trace::replayOn(r.trace, *trace::parseReplayTarget(target), trace::ReplayMode::FixedFunction, 1).buffers.at(0);
  };
  r.shadowref = on("reference");
  r.mesa = on("osmesa:" + driverOfEnvironment());
  return r;
}

CaseResult compare(const Scenario& scenario, const Replayed& replayed) {
  CaseResult r;
  r.name = scenario.name;
  r.colorTolerance255 = scenario.colorTolerance255;
  r.depthTolerance = scenario.depthTolerance;
  r.minStencilAgreement = scenario.minStencilAgreement;
  r.note = scenario.note;
  const trace::Comparison c = trace::compareBuffers(replayed.trace, {&replayed.shadowref}, {replayed.mesa},
                                                    {trace::Tolerances{false, scenario.colorTolerance255, scenario.depthTolerance}});
  for (const trace::BufferComparison& b : c.targets.at(0).buffers) {
    // A buffer shadowref never allocated (depth or stencil of a case that does not use it) is
    // not compared: the pixels are those of the buffers that are.
    if (b.pixels > r.pixels) {
      r.pixels = b.pixels;
      r.edgePixels = b.edgePixels;
    }
    if (b.buffer == "colour") r.maxColorDiff255 = b.maxDifferenceOffEdge;
    if (b.buffer == "depth") r.maxDepthDiff = uint32_t(b.maxDifferenceOffEdge);
    if (b.buffer == "stencil") {
      r.stencilMismatchOnEdge = b.differingOnEdge;
      r.stencilMismatchOffEdge = b.differingOffEdge;
    }
    if (r.firstOffEdgeDifference.empty() && !b.firstOffEdge.empty()) r.firstOffEdgeDifference = b.buffer + " " + b.firstOffEdge;
  }
  if (std::getenv("SHADOWREF_CONFORMANCE_VERBOSE")) std::cerr << scenario.name << ":\n" << trace::reportText(c);
  return r;
}

std::string markdownRow(const CaseResult& r) {
  char agreement[32], colour[32];
  std::snprintf(agreement, sizeof agreement, "%.2f %%", 100.0 * r.stencilAgreement());
  std::snprintf(colour, sizeof colour, "%.2f / %.0f", r.maxColorDiff255, r.colorTolerance255);
  std::ostringstream o;
  o << "| " << r.name << " | " << r.driver << " | " << r.pixels << " | " << r.edgePixels << " | " << agreement
    << " | " << r.stencilMismatchOnEdge << " / " << r.stencilMismatchOffEdge << " | " << r.maxDepthDiff << " / "
    << r.depthTolerance << " | " << colour << " | " << (r.meetsIssueExpectation() ? "yes" : r.withinDocumentedBounds() ? "explained" : "**NO**")
    << " | " << r.note << " |";
  return o.str();
}

CaseResult runCase(const Scenario& scenario) {
  CaseResult r = compare(scenario, replayScenario(scenario));
  const std::string renderer = trace::osmesaRenderer();
  r.driver = renderer;
  for (const char* known : {"softpipe", "llvmpipe"})
    if (renderer.find(known) != std::string::npos) r.driver = known;
  if (const char* path = std::getenv("SHADOWREF_CONFORMANCE_REPORT")) {
    std::ofstream out(path, std::ios::app);
    out << markdownRow(r) << "\n";
  }
  return r;
}

}  // namespace shadowref::conformance
