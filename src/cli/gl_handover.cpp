#include "cli/gl_handover.h"

#include <unistd.h>

#include <filesystem>
#include <string_view>
#include <system_error>

namespace shadowref::cli {

void handOverToGlProgram(int argc, char** argv) {
#ifndef SHADOWREF_GL_PROGRAM
  if (argc < 2 || std::string_view(argv[1]) != "replay") return;
  bool namesGl = false;
  for (int i = 2; i < argc; ++i) {
    const std::string_view arg(argv[i]);
    if (arg.find("osmesa:") != std::string_view::npos || arg.find("egl:") != std::string_view::npos) namesGl = true;
  }
  if (!namesGl) return;
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) return;
  const std::filesystem::path gl = self.parent_path() / "shadowref-gl";
  if (::access(gl.c_str(), X_OK) != 0) return;
  ::execv(gl.c_str(), argv);  // returns only when it failed: then run here
#else
  (void)argc;
  (void)argv;
#endif
}

}  // namespace shadowref::cli
