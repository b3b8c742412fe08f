// `shadowref replay --on osmesa:*|egl:*` runs on a real OpenGL through OSMesa or EGL, which load LLVM: linked
// into shadowref, that alone would add about 90 ms to the start of every command. So shadowref
// links no OSMesa, and a command line that names an OSMesa or EGL target is handed over, unchanged, to
// shadowref-gl: the same program (the same sources and options) with those replays linked in,
// installed and built beside it.
#pragma once

namespace shadowref::cli {

// In shadowref, when argv is a `replay` naming an "osmesa:" or "egl:" target and shadowref-gl lies beside
// this program: replaces the process with shadowref-gl and argv (does not return). Otherwise
// returns, and the command runs here (where a missing OSMesa is reported as such).
void handOverToGlProgram(int argc, char** argv);

}  // namespace shadowref::cli
