#include "image/channel_image.h"

#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <stdexcept>

#include <dlfcn.h>
#include <unistd.h>

#include "image/channel_reader.h"
#include "image/exr_header_check.h"
#include "image/png_chunk_check.h"

namespace shadowref {

int ChannelImage::channelIndex(const std::string& name) const {
  for (size_t c = 0; c < names.size(); ++c)
    if (names[c] == name) return int(c);
  return -1;
}

namespace {

// Before any image library sees the file: a regular file of bounded size (a FIFO would block,
// /dev/zero never end), for an OpenEXR file every header attribute within the file's bytes, and
// for a PNG every chunk.
void checkFile(const std::string& path, const ReadLimits& limits) {
  auto refuse = [&](const std::string& why) { throw std::runtime_error("cannot read '" + path + "': " + why); };
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) refuse("no such file");
  if (!S_ISREG(st.st_mode)) refuse("not a regular file");
  if (std::uint64_t(st.st_size) > limits.maxFileBytes)
    refuse("the file has " + std::to_string(st.st_size) + " bytes, more than the limit of " +
           std::to_string(limits.maxFileBytes));
  std::ifstream file(path, std::ios::binary);
  char magic[8] = {};
  file.read(magic, 8);
  const std::string_view head(magic, size_t(file.gcount()));
  const bool exr = head.size() >= 4 && looksLikeExr(head.substr(0, 4)), png = looksLikePng(head);
  if (!exr && !png) return;
  file.clear();
  file.seekg(0);
  const std::string bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  if (const std::string problem = exr ? checkExrHeaders(bytes) : checkPngChunks(bytes); !problem.empty())
    refuse(problem);
}

#ifndef SHADOWREF_IMAGE_READER_LINKED
// Where the reader module may be, first found wins: beside an installed program (the path from
// its bin/ folder to lib/shadowref/, fixed when configuring), then in the build tree.
std::vector<std::string> readerModuleCandidates() {
  std::vector<std::string> candidates;
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec)
    candidates.push_back((exe.parent_path() / SHADOWREF_IMAGE_READER_FROM_BINDIR / "shadowref_image_reader.so").string());
  candidates.push_back(std::string(SHADOWREF_IMAGE_READER_BUILD_DIR) + "/shadowref_image_reader.so");
  return candidates;
}

ChannelReader loadReaderModule() {
  std::string tried;
  for (const std::string& candidate : readerModuleCandidates()) {
    if (::access(candidate.c_str(), R_OK) != 0) {
      tried += (tried.empty() ? "" : ", ") + candidate;
      continue;
    }
    // Never closed: the reader's code and OpenImageIO stay for the rest of the process.
    void* module = ::dlopen(candidate.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!module) throw std::runtime_error(std::string("cannot load the image reader: ") + ::dlerror());
    auto* entry = reinterpret_cast<ChannelReader (*)()>(::dlsym(module, "shadowref_channel_reader_v1"));
    if (!entry) throw std::runtime_error("cannot load the image reader: " + candidate + " has no entry point");
    return entry();
  }
  throw std::runtime_error("reading images needs the module shadowref_image_reader.so (OpenImageIO), not found at " +
                           tried);
}
#endif

// The reader, loaded once; a failed load is retried (and reported) on the next call.
ChannelReader channelReader() {
#ifdef SHADOWREF_IMAGE_READER_LINKED
  return shadowref_channel_reader_v1();
#else
  static const ChannelReader reader = loadReaderModule();
  return reader;
#endif
}

}  // namespace

ChannelImage readChannelImage(const std::string& path, const ReadLimits& limits) {
  checkFile(path, limits);
  const ChannelReader read = channelReader();
  return read(path, limits);
}

ChannelImage channelImageOf(const Framebuffer& fb, const ExrExtras& extras) {
  ChannelImage image;
  image.width = fb.width();
  image.height = fb.height();
  for (const NamedChannel& channel : exrChannels(fb, extras)) {
    std::vector<double> values(size_t(fb.width()) * size_t(fb.height()));
    for (int y = 0; y < fb.height(); ++y)
      for (int x = 0; x < fb.width(); ++x) {
        const size_t src = fb.index(x, y);
        const size_t dst = size_t(fb.height() - 1 - y) * size_t(fb.width()) + size_t(x);
        values[dst] = channel.kind == ChannelKind::Float ? double(channel.floats[src]) : double(channel.uints[src]);
      }
    image.names.push_back(channel.name);
    image.data.push_back(std::move(values));
    image.integer.push_back(channel.kind == ChannelKind::UInt32);
  }
  return image;
}

}  // namespace shadowref
