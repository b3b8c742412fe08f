// `shadowref explore` serves its page through cpp-httplib, and Debian's cpp-httplib library is
// built with TLS and compression: linked into shadowref, libssl, libcrypto, zlib and three Brotli
// libraries would be loaded and relocated by every command, a few milliseconds of each `--help`,
// `check` or `render`. So the server is linked only into a program of its own, shadowref-explore:
// the same commands and options (the same objects) with the server in, built and installed beside
// shadowref, which hands every `explore` command line over to it unchanged.
#pragma once

namespace shadowref::cli {

// In shadowref, when argv is an `explore` command and shadowref-explore lies beside this program:
// replaces the process with shadowref-explore and argv (does not return). Otherwise returns, and
// the command runs here: `--export` and `--help` work, and the server reports where it is.
void handOverToExploreProgram(int argc, char** argv);

}  // namespace shadowref::cli
