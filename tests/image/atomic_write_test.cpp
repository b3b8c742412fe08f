// writeFileAtomically under failure: a full device, a signal in the middle of a write. The end-to-end
// cases (a PNG and an EXR over the file-size limit, SIGTERM to the CLI) are in tests/cli/cli_test.cpp.
#include <csignal>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include <catch2/catch.hpp>
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include "image/atomic_write.h"
#include "image/temp_dir.h"

using namespace shadowref;
using shadowref::test::TempDir;

namespace {

bool containsText(const std::string& haystack, const std::string& needle) {
  return haystack.find(needle) != std::string::npos;
}

std::string contentOf(const std::string& path) {
  std::ifstream in(path);
  std::string s;
  std::getline(in, s);
  return s;
}

}  // namespace

TEST_CASE("writeAllAt reports a full device instead of a short write", "[image][atomic]") {
  const int fd = ::open("/dev/full", O_WRONLY | O_CLOEXEC);
  REQUIRE(fd >= 0);
  const char bytes[64] = {};
  try {
    writeAllAt(fd, bytes, sizeof bytes, 0);
    FAIL("no exception");
  } catch (const std::runtime_error& e) {
    CHECK(containsText(e.what(), std::strerror(ENOSPC)));
  }
  ::close(fd);
}

TEST_CASE("a write error inside the writer leaves the old target and no temporary file", "[image][atomic]") {
  TempDir dir("atomic-full");
  const std::string path = dir.file("keep.txt");
  std::ofstream(path) << "old";
  try {
    writeFileAtomically(path, [](const TempFile& temp) {
      writeAllAt(temp.fd, "new", 3, 0);
      const int full = ::open("/dev/full", O_WRONLY | O_CLOEXEC);
      REQUIRE(full >= 0);
      try {
        writeAllAt(full, "more", 4, 0);  // the disk fills up half-way through
      } catch (...) {
        ::close(full);
        throw;
      }
    });
    FAIL("no exception");
  } catch (const std::runtime_error& e) {
    CHECK(containsText(e.what(), "cannot write '" + path + "'"));
    CHECK(containsText(e.what(), std::strerror(ENOSPC)));
  }
  CHECK(dir.entries() == std::vector<std::string>{"keep.txt"});
  CHECK(contentOf(path) == "old");
}

TEST_CASE("SIGTERM and SIGINT during a write remove the temporary file and end the process by the signal",
          "[image][atomic]") {
  for (const int sig : {SIGTERM, SIGINT}) {
    TempDir dir("atomic-signal-" + std::to_string(sig));
    const std::string path = dir.file("out.bin");
    std::ofstream(path) << "old";
    const pid_t child = ::fork();
    REQUIRE(child >= 0);
    if (child == 0) {
      // The child writes half a file and is then interrupted, as by Ctrl-C or kill.
      removeTempFilesOnSignals();
      try {
        writeFileAtomically(path, [sig](const TempFile& temp) {
          writeAllAt(temp.fd, "half", 4, 0);
          ::raise(sig);
        });
      } catch (...) {
      }
      ::_exit(0);  // reached only if the signal did not end the process
    }
    int status = 0;
    REQUIRE(::waitpid(child, &status, 0) == child);
    CHECK(WIFSIGNALED(status));
    CHECK((WIFSIGNALED(status) ? WTERMSIG(status) : 0) == sig);  // a shell reports 128 + sig
    CHECK(dir.entries() == std::vector<std::string>{"out.bin"});
    CHECK(contentOf(path) == "old");
  }
}
