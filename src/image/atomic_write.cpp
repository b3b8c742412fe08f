#include "image/atomic_write.h"

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include <fcntl.h>
#include <unistd.h>

namespace shadowref {

namespace {

std::string systemError() { return std::strerror(errno); }

// Creates the temporary file with O_EXCL (never reuses someone else's file) and mode 0666, so the
// finished output gets the permissions the user's umask asks for (mkstemp would force 0600).
std::string createTempFile(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  for (int attempt = 0; attempt < 100; ++attempt) {
    std::string temp = path + ".tmp-" + std::to_string(::getpid()) + "-" +
                       std::to_string(counter.fetch_add(1));
    int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0) {
      ::close(fd);
      return temp;
    }
    if (errno != EEXIST) {
      throw std::runtime_error("cannot write '" + path + "': cannot create a temporary file there: " +
                               systemError());
    }
  }
  throw std::runtime_error("cannot write '" + path + "': no free temporary file name");
}

}  // namespace

void writeFileAtomically(const std::string& path,
                         const std::function<void(const std::string& tempPath)>& write) {
  const std::string temp = createTempFile(path);
  try {
    write(temp);
  } catch (const std::exception& e) {
    std::remove(temp.c_str());
    throw std::runtime_error("cannot write '" + path + "': " + e.what());
  } catch (...) {
    std::remove(temp.c_str());
    throw;
  }
  if (std::rename(temp.c_str(), path.c_str()) != 0) {
    const std::string reason = systemError();
    std::remove(temp.c_str());
    throw std::runtime_error("cannot write '" + path + "': cannot rename the finished file into place: " +
                             reason);
  }
}

}  // namespace shadowref
