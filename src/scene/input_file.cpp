#include "scene/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "scene/scene_error.h"

namespace shadowref {

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& message) {
  throw SceneError(SourceLocation{path, 0, 0}, message);
}

void checkStatus(const struct stat& st, const std::string& path, const std::string& what, std::uint64_t maxBytes) {
  if (!S_ISREG(st.st_mode)) fail(path, what + " is not a regular file");
  const auto size = static_cast<std::uint64_t>(st.st_size);
  if (size > maxBytes)
    fail(path, what + " has " + std::to_string(size) + " bytes, more than the limit of " + std::to_string(maxBytes));
}

// Closes the descriptor on every path out, exceptions included.
struct Descriptor {
  int fd;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

std::uint64_t checkInputFile(const std::string& path, const std::string& what, std::uint64_t maxBytes) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0)
    fail(path, errno == ENOENT || errno == ENOTDIR ? what + " not found" : what + " cannot be read: " + std::strerror(errno));
  checkStatus(st, path, what, maxBytes);
  return static_cast<std::uint64_t>(st.st_size);
}

std::string readInputFile(const std::string& path, const std::string& what, std::uint64_t maxBytes) {
  checkInputFile(path, what, maxBytes);  // the clear message for a missing file or a folder
  // O_NONBLOCK: should the path have become a FIFO since the check, open does not wait for a writer.
  const Descriptor file{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)};
  if (file.fd < 0) fail(path, what + " cannot be opened: " + std::strerror(errno));
  struct stat st {};
  if (::fstat(file.fd, &st) != 0) fail(path, what + " cannot be read: " + std::strerror(errno));
  checkStatus(st, path, what, maxBytes);
  std::string bytes(static_cast<size_t>(st.st_size), '\0');
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t got = ::read(file.fd, bytes.data() + done, bytes.size() - done);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) fail(path, what + " cannot be read: " + std::strerror(errno));
    if (got == 0) fail(path, what + " became shorter while it was read");
    done += static_cast<size_t>(got);
  }
  return bytes;
}

}  // namespace shadowref
