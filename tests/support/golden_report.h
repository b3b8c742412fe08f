// What a golden test does when its golden does not match: it writes a failure report with pictures
// (image/failure_report.h) under the build tree and names the page in the test's output.
// scripts/update-goldens.sh runs the golden tests without writing first, so the same report shows
// what an update would change.
#pragma once

#include <string>

#include "image/channel_image.h"
#include "image/image_compare.h"
#include "image/image_writer.h"

namespace shadowref::testing {

// Where the reports go: $SHADOWREF_GOLDEN_REPORT_DIR when set, else <build>/golden-report.
std::string goldenReportFolder();

struct GoldenOutcome {
  bool passed = false;
  std::string message;  // the comparison report, and on failure "report: <page>"
  std::string page;     // the case's HTML page, written only on failure
};

// Compares what writeExr would write for fb and extras (A, the result) with the golden EXR (B, the
// reference) with Tolerances::golden(); on failure writes the report for case `name` under
// `folder`. A missing golden fails with a message naming it and writes no report.
GoldenOutcome checkGoldenExr(const std::string& name, const Framebuffer& fb, const ExrExtras& extras,
                             const std::string& goldenPath, const std::string& folder = goldenReportFolder());

// The report for two framebuffers that should be equal (a frame hash that no longer matches: the
// reference pipeline's frame against the one whose hash differs), compared exactly. Returns the page.
std::string reportFrames(const std::string& name, const Framebuffer& reference, const Framebuffer& result,
                         const std::string& resultLabel, const std::string& note,
                         const std::string& folder = goldenReportFolder());

}  // namespace shadowref::testing
