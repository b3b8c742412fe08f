// Runs of the shadowref command (or any shell command) as a user meets them: the exit status and
// what it wrote to stdout and stderr.
#pragma once

#include <filesystem>
#include <string>

namespace shadowref::testing {

struct CliRun {
  int status = -1;  // the exit status; -1 when the command did not exit (a signal)
  std::string out, err;
};

// A folder of this test process's own under the system's temporary folder (made if missing).
std::filesystem::path testScratch();

// testScratch() / name, emptied: made anew, whatever an earlier run left in it.
std::filesystem::path freshScratchDir(const std::string& name);

// A file's bytes.
std::string slurp(const std::filesystem::path& file);

// Runs `command` (shell syntax) in the source folder.
CliRun runShell(const std::string& command);
// Runs the shadowref binary under test with `args` (shell syntax) in the source folder.
CliRun runShadowref(const std::string& args);

}  // namespace shadowref::testing
