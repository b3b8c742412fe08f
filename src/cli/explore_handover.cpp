#include "cli/explore_handover.h"

#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <string_view>
#include <system_error>

#include "cli/cli_common.h"
#include "explore/explore_server.h"

namespace shadowref::cli {

namespace {

// shadowref-explore in the folder of the running program ("shadowref-explore" when that cannot be
// read).
std::filesystem::path exploreProgram() {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::filesystem::path("shadowref-explore") : self.parent_path() / "shadowref-explore";
}

}  // namespace

void handOverToExploreProgram(int argc, char** argv) {
  if (argc < 2 || std::string_view(argv[1]) != "explore") return;
  const std::filesystem::path program = exploreProgram();
  if (!program.has_parent_path() || ::access(program.c_str(), X_OK) != 0) return;
  ::execv(program.c_str(), argv);  // returns only when it failed: then run here
}

}  // namespace shadowref::cli

namespace shadowref::explore {

// The server of the programs that do not link it (shadowref, shadowref-gl): reached only when the
// hand-over above found no shadowref-explore to run.
int runExploreServer(const ExploreOptions&) {
  std::cerr << "explore: the explorer's server is the program " << cli::exploreProgram().string()
            << ", which is missing (build the shadowref_explore_program target, or install it beside shadowref)\n";
  return cli::kFailed;
}

}  // namespace shadowref::explore
