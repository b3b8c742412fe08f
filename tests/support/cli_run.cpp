#include "support/cli_run.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

namespace shadowref::testing {

namespace fs = std::filesystem;

fs::path testScratch() {
  const fs::path dir = fs::temp_directory_path() / ("shadowref-tests-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

fs::path freshScratchDir(const std::string& name) {
  const fs::path dir = testScratch() / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string slurp(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

CliRun runShell(const std::string& command) {
  const fs::path dir = testScratch();
  const std::string cmd = std::string("cd '") + SHADOWREF_SOURCE_DIR + "' && " + command + " >'" +
                          (dir / "out.txt").string() + "' 2>'" + (dir / "err.txt").string() + "'";
  const int raw = std::system(cmd.c_str());
  CliRun r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = slurp(dir / "out.txt");
  r.err = slurp(dir / "err.txt");
  return r;
}

CliRun runShadowref(const std::string& args) { return runShell(std::string("'") + SHADOWREF_CLI + "' " + args); }

}  // namespace shadowref::testing
