#include "support/golden_report.h"

#include <cstdlib>
#include <filesystem>

#include "image/failure_report.h"

namespace shadowref::testing {

std::string goldenReportFolder() {
  if (const char* dir = std::getenv("SHADOWREF_GOLDEN_REPORT_DIR"); dir && *dir) return dir;
  return std::string(SHADOWREF_BINARY_DIR) + "/golden-report";
}

GoldenOutcome checkGoldenExr(const std::string& name, const Framebuffer& fb, const ExrExtras& extras,
                             const std::string& goldenPath, const std::string& folder) {
  GoldenOutcome outcome;
  if (!std::filesystem::exists(goldenPath)) {
    outcome.message = "missing golden " + goldenPath +
                      ": run scripts/update-goldens.sh --write after checking the change is intended";
    return outcome;
  }
  const ChannelImage reference = readChannelImage(goldenPath);
  const ChannelImage result = channelImageOf(fb, extras);
  CompareResult comparison = compareChannelImages(result, reference, Tolerances::golden());
  comparison.nameA = "this build's frame";
  comparison.nameB = goldenPath;
  outcome.passed = comparison.passed;
  outcome.message = formatReport(comparison);
  if (outcome.passed) return outcome;
  ReportCase c;
  c.name = name;
  c.referenceLabel = "golden (" + std::filesystem::path(goldenPath).filename().string() + ")";
  c.resultLabel = "this build";
  c.note = "The frame this build renders against the golden " + goldenPath +
           " (colour within 1/255, everything else exact). If the change is intended, scripts/update-goldens.sh "
           "--write rewrites the golden.";
  c.reference = &reference;
  c.result = &result;
  c.comparison = &comparison;
  outcome.page = writeFailureReport(folder, c);
  outcome.message += "report: " + outcome.page + "\n";
  return outcome;
}

std::string reportFrames(const std::string& name, const Framebuffer& reference, const Framebuffer& result,
                         const std::string& resultLabel, const std::string& note, const std::string& folder) {
  const ChannelImage ref = channelImageOf(reference);
  const ChannelImage res = channelImageOf(result);
  CompareResult comparison = compareChannelImages(res, ref, Tolerances{});
  comparison.nameA = resultLabel;
  comparison.nameB = "reference pipeline";
  ReportCase c;
  c.name = name;
  c.referenceLabel = "reference pipeline";
  c.resultLabel = resultLabel;
  c.note = note;
  c.reference = &ref;
  c.result = &res;
  c.comparison = &comparison;
  return writeFailureReport(folder, c);
}

}  // namespace shadowref::testing
