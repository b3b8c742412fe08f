// An output file is written completely or not at all: the bytes go to a temporary file beside the
// target, which is renamed over the target only once every byte is known to be on disk.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

namespace shadowref {

// The temporary file a write fills: its name and a descriptor open for writing.
struct TempFile {
  std::string path;
  int fd = -1;
};

// Writes all `size` bytes at `offset` through fd, continuing after partial writes and EINTR. A write
// that stops short (ENOSPC, EFBIG, EIO, ...) throws std::runtime_error with the system's reason:
// every byte of an output goes through here, so no short write can pass unnoticed.
void writeAllAt(int fd, const void* data, size_t size, uint64_t offset);

// Calls write(temp) with a fresh, empty, uniquely named file "path.tmp-<pid>-<n>" in the target's
// directory (same file system, so the final rename is atomic), then flushes it to disk (fsync),
// closes it and renames it to path, checking each step. If write throws or any step fails, the
// temporary file is removed and a std::runtime_error naming path is thrown; an existing file at
// path is left untouched.
//
// Test hook: when the environment variable SHADOWREF_TEST_HOLD_TEMP_FILE is set, the writer waits
// up to 60 s after creating the temporary file, so that a test can send a signal at exactly that
// moment (tests/cli/cli_test.cpp). It changes nothing else.
void writeFileAtomically(const std::string& path, const std::function<void(const TempFile& temp)>& write);

// Installs handlers for SIGINT and SIGTERM that remove every temporary file still being written,
// then end the process by the same signal (a shell reports 130 or 143). The handler only reads a
// fixed-size static table and calls unlink(), both async-signal-safe. SIGKILL cannot be caught: it
// may leave a "*.tmp-<pid>-<n>" file, never a damaged target. Called once, by main().
void removeTempFilesOnSignals();

}  // namespace shadowref
