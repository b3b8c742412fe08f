#include "image/atomic_write.h"

#include <array>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <limits>
#include <stdexcept>

#include <fcntl.h>
#include <unistd.h>

namespace shadowref {

namespace {

std::string systemError(int error) { return std::strerror(error); }

// The temporary files being written, for the signal handler. A slot is Free, or Live with the
// NUL-terminated path of a temporary file that may exist. The handler reads only Live slots; a slot
// turns Live only after its path is complete (release), so the handler never sees half a path.
// Lock-free atomics and unlink() are async-signal-safe.
enum SlotState : int { kFree = 0, kClaimed = 1, kLive = 2 };
struct Slot {
  std::atomic<int> state{kFree};
  std::array<char, 4096> path{};
};
constexpr size_t kSlots = 32;  // more concurrent writes than this are not cleaned up on a signal
std::array<Slot, kSlots> liveTemps;
// Set first by the handler: a writer that registers a file while the handler runs sees it after
// creating the file and removes the file itself (see createTempFile).
std::atomic<bool> dying{false};

extern "C" void removeTempsAndDie(int sig) {
  dying.store(true);
  for (Slot& slot : liveTemps)
    if (slot.state.load() == kLive) ::unlink(slot.path.data());
  // Die by the same signal, so the parent sees what happened (a shell reports 128 + sig). The
  // signal is blocked while the handler runs and is delivered on return, with the default action.
  ::signal(sig, SIG_DFL);
  ::raise(sig);
}

int registerTemp(const std::string& path) {
  if (path.size() >= Slot{}.path.size()) return -1;
  for (size_t i = 0; i < kSlots; ++i) {
    int expected = kFree;
    if (!liveTemps[i].state.compare_exchange_strong(expected, kClaimed)) continue;
    std::memcpy(liveTemps[i].path.data(), path.c_str(), path.size() + 1);
    liveTemps[i].state.store(kLive);
    return int(i);
  }
  return -1;
}

void unregisterTemp(int slot) {
  if (slot >= 0) liveTemps[size_t(slot)].state.store(kFree);
}

// Sleeps while the test hook asks for it (see atomic_write.h).
void holdForTests() {
  if (std::getenv("SHADOWREF_TEST_HOLD_TEMP_FILE") == nullptr) return;
  std::fprintf(stderr, "holding the temporary file (SHADOWREF_TEST_HOLD_TEMP_FILE)\n");
  for (int i = 0; i < 600; ++i) {
    const timespec tenth{0, 100'000'000};
    ::nanosleep(&tenth, nullptr);
  }
}

struct OpenTemp {
  TempFile file;
  int slot = -1;
};

// Creates the temporary file with O_EXCL (never reuses someone else's file) and mode 0666, so the
// finished output gets the permissions the user's umask asks for (mkstemp would force 0600). The
// name is registered for the signal handler BEFORE the file exists, so no moment has a file the
// handler does not know of.
OpenTemp createTempFile(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  for (int attempt = 0; attempt < 100; ++attempt) {
    OpenTemp t;
    t.file.path = path + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter.fetch_add(1));
    t.slot = registerTemp(t.file.path);
    t.file.fd = ::open(t.file.path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    const int error = errno;
    if (t.file.fd >= 0) {
      if (dying.load()) {  // the handler may have passed this slot already: remove it ourselves
        ::unlink(t.file.path.c_str());
        for (;;) ::pause();  // the handler's thread is ending the process
      }
      return t;
    }
    unregisterTemp(t.slot);
    if (error != EEXIST)
      throw std::runtime_error("cannot write '" + path + "': cannot create a temporary file there: " +
                               systemError(error));
  }
  throw std::runtime_error("cannot write '" + path + "': no free temporary file name");
}

void discard(OpenTemp& t) {
  if (t.file.fd >= 0) ::close(t.file.fd);
  t.file.fd = -1;
  ::unlink(t.file.path.c_str());
  unregisterTemp(t.slot);
}

}  // namespace

void writeAllAt(int fd, const void* data, size_t size, uint64_t offset) {
  const char* bytes = static_cast<const char*>(data);
  while (size > 0) {
    if (offset > uint64_t(std::numeric_limits<off_t>::max()))
      throw std::runtime_error("file offset " + std::to_string(offset) + " is too large");
    const ssize_t n = ::pwrite(fd, bytes, size, off_t(offset));
    if (n < 0) {
      if (errno == EINTR) continue;
      throw std::runtime_error(systemError(errno));
    }
    if (n == 0) throw std::runtime_error("the file system accepted no more bytes");
    bytes += n;
    size -= size_t(n);
    offset += uint64_t(n);
  }
}

void writeFileAtomically(const std::string& path, const std::function<void(const TempFile& temp)>& write) {
  OpenTemp temp = createTempFile(path);
  holdForTests();
  try {
    write(temp.file);
    // The data must be on disk before the rename makes it the target: otherwise a crash could leave
    // a complete-looking name with missing blocks. close() reports late errors (NFS, quotas).
    if (::fsync(temp.file.fd) != 0)
      throw std::runtime_error("cannot flush the file to disk: " + systemError(errno));
    const int fd = temp.file.fd;
    temp.file.fd = -1;
    if (::close(fd) != 0) throw std::runtime_error("cannot close the file: " + systemError(errno));
  } catch (const std::exception& e) {
    discard(temp);
    throw std::runtime_error("cannot write '" + path + "': " + e.what());
  } catch (...) {
    discard(temp);
    throw;
  }
  if (std::rename(temp.file.path.c_str(), path.c_str()) != 0) {
    const std::string reason = systemError(errno);
    discard(temp);
    throw std::runtime_error("cannot write '" + path + "': cannot rename the finished file into place: " +
                             reason);
  }
  unregisterTemp(temp.slot);
}

void removeTempFilesOnSignals() {
  struct sigaction action {};
  action.sa_handler = removeTempsAndDie;
  sigemptyset(&action.sa_mask);
  sigaddset(&action.sa_mask, SIGINT);
  sigaddset(&action.sa_mask, SIGTERM);
  action.sa_flags = 0;
  for (int sig : {SIGINT, SIGTERM}) {
    struct sigaction old {};
    // A signal ignored by the parent (nohup, a background job of a non-interactive shell) stays
    // ignored, as POSIX asks of programs that catch signals.
    if (::sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
    ::sigaction(sig, &action, nullptr);
  }
}

}  // namespace shadowref
