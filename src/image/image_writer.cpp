#include "image/image_writer.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>
#include <atomic>
#include <csetjmp>
#include <cstring>
#include <stdexcept>

#include <png.h>
#include <zlib.h>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfThreading.h>

#include "image/atomic_write.h"

namespace shadowref {

namespace {

// The encoders write straight into the temporary file's descriptor through writeAllAt, so a short
// write (ENOSPC, EFBIG, ...) is an error with the system's reason, never a silently shorter file.
// libpng and OpenEXR are called directly, not through OpenImageIO: a program linked against
// Debian's OpenImageIO loads some 260 shared libraries before main (about half a second), while
// these two need a handful. The files hold the same channels, types, names and attributes.

// --- PNG (libpng) ---

// libpng reports errors by longjmp; nothing with a destructor lives between the setjmp and the
// calls that may jump (writePngRows keeps only plain pointers there).
struct PngSink {
  int fd = -1;
  uint64_t offset = 0;
  std::string failure;  // the first failed write or libpng's message; empty while all went well
};

extern "C" void pngWrite(png_structp png, png_bytep data, png_size_t size) {
  auto* sink = static_cast<PngSink*>(png_get_io_ptr(png));
  try {
    writeAllAt(sink->fd, data, size, sink->offset);
    sink->offset += size;
    return;
  } catch (const std::exception& e) {
    sink->failure = e.what();
  }
  png_error(png, "write failed");  // a longjmp: only once the exception is finished with
}
extern "C" void pngFlush(png_structp) {}
extern "C" void pngError(png_structp png, png_const_charp message) {
  auto* sink = static_cast<PngSink*>(png_get_error_ptr(png));
  if (sink->failure.empty()) sink->failure = message;
  png_longjmp(png, 1);
}
extern "C" void pngWarning(png_structp, png_const_charp) {}

// False when libpng failed (the reason in sink.failure). rows[r] is the r-th row from the top;
// texts are tEXt chunks. The image data is deflated with zlib's run-length strategy after libpng's
// adaptive row filters: much faster than zlib's default search for a somewhat larger file, and
// still lossless (a PNG is for looking at; the EXR is the record). The bytes depend only on the
// pixels and the texts.
[[nodiscard]] bool writePngRows(PngSink& sink, int width, int height, int colorType, png_bytep* rows,
                                png_text* texts, int textCount) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &sink, pngError, pngWarning);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, info ? &info : nullptr);
    return false;
  }
  png_set_write_fn(png, &sink, pngWrite, pngFlush);
  png_set_IHDR(png, info, png_uint_32(width), png_uint_32(height), 8, colorType, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_compression_strategy(png, Z_RLE);
  if (textCount > 0) png_set_text(png, info, texts, textCount);
  png_write_info(png, info);
  png_write_image(png, rows);
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return true;
}

// PNG keywords for the provenance attributes, as OpenImageIO names them (and reads them back):
// ImageDescription is PNG's "Description"; every other attribute keeps its name.
std::string pngKeyword(const std::string& attribute) {
  return attribute == "ImageDescription" ? "Description" : attribute;
}

void writePngFile(const TempFile& temp, const Image8& image, const OutputMetadata& metadata) {
  const auto attributes = metadataAttributes(metadata);
  std::vector<std::string> keys;
  keys.reserve(attributes.size());
  for (const auto& [name, value] : attributes) keys.push_back(pngKeyword(name));
  std::vector<png_text> texts(attributes.size());
  for (size_t i = 0; i < attributes.size(); ++i) {
    texts[i].compression = PNG_TEXT_COMPRESSION_NONE;
    texts[i].key = keys[i].data();
    texts[i].text = const_cast<char*>(attributes[i].second.c_str());
    texts[i].text_length = attributes[i].second.size();
  }
  std::vector<png_bytep> rows(size_t(image.height));
  const size_t stride = size_t(image.width) * size_t(image.channels);
  for (size_t r = 0; r < rows.size(); ++r) rows[r] = const_cast<png_bytep>(image.pixels.data() + r * stride);
  const int colorType = image.channels == 1   ? PNG_COLOR_TYPE_GRAY
                        : image.channels == 3 ? PNG_COLOR_TYPE_RGB
                                              : PNG_COLOR_TYPE_RGB_ALPHA;
  PngSink sink;
  sink.fd = temp.fd;
  if (!writePngRows(sink, image.width, image.height, colorType, rows.data(), texts.data(), int(texts.size())))
    throw std::runtime_error(sink.failure.empty() ? "the PNG writer failed" : sink.failure);
}

// --- OpenEXR ---

// OpenEXR's output stream over the temporary file's descriptor. The first failed write is kept:
// OpenEXR writes the table of line offsets from OutputFile's destructor, which swallows errors,
// so the writer checks failure() once the file is closed.
class DescriptorStream final : public Imf::OStream {
 public:
  explicit DescriptorStream(const TempFile& temp) : Imf::OStream(temp.path.c_str()), fd_(temp.fd) {}
  void write(const char c[], int n) override {
    try {
      if (!failure_.empty()) throw std::runtime_error(failure_);
      writeAllAt(fd_, c, size_t(n), position_);
    } catch (const std::exception& e) {
      if (failure_.empty()) failure_ = e.what();
      throw;
    }
    position_ += uint64_t(n);
  }
  uint64_t tellp() override { return position_; }
  void seekp(uint64_t pos) override { position_ = pos; }
  const std::string& failure() const { return failure_; }

 private:
  int fd_;
  uint64_t position_ = 0;
  std::string failure_;
};

// The image row (0 = top) that holds framebuffer row y (0 = bottom).
int fileRow(int y, int height) { return height - 1 - y; }

uint8_t toByte(double v01) {
  if (!(v01 > 0.0)) return 0;  // also NaN
  if (v01 >= 1.0) return 255;
  return uint8_t(std::round(v01 * 255.0));
}

std::string lowerExtension(const std::string& path) {
  size_t slash = path.find_last_of('/');
  size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

void checkImage8(const Image8& image) {
  if (image.width <= 0 || image.height <= 0) throw std::invalid_argument("image size must be positive");
  if (image.channels != 1 && image.channels != 3 && image.channels != 4)
    throw std::invalid_argument("an 8-bit image has 1, 3 or 4 channels");
  if (image.pixels.size() != size_t(image.width) * size_t(image.height) * size_t(image.channels))
    throw std::invalid_argument("8-bit image pixel count does not match its size");
}

}  // namespace

void writePng8(const Image8& image, const std::string& path, const OutputMetadata& metadata) {
  checkImage8(image);
  writeFileAtomically(path, [&](const TempFile& temp) { writePngFile(temp, image, metadata); });
}

void writePng(const Framebuffer& fb, const std::string& path, bool withAlpha, const OutputMetadata& metadata) {
  if (!fb.hasColor()) throw std::invalid_argument("cannot write '" + path + "': the framebuffer has no colour buffer");
  writePng8(colorImage(fb, withAlpha), path, metadata);
}

Image8 colorImage(const Framebuffer& fb, bool withAlpha) {
  if (!fb.hasColor()) throw std::invalid_argument("the framebuffer has no colour buffer");
  Image8 image;
  image.width = fb.width();
  image.height = fb.height();
  image.channels = withAlpha ? 4 : 3;
  image.pixels.resize(size_t(image.width) * size_t(image.height) * size_t(image.channels));
  for (int y = 0; y < fb.height(); ++y) {
    for (int x = 0; x < fb.width(); ++x) {
      glm::vec4 c = fb.colorAt(x, y);
      size_t out = (size_t(fileRow(y, fb.height())) * size_t(fb.width()) + size_t(x)) * size_t(image.channels);
      for (int k = 0; k < image.channels; ++k) image.pixels[out + size_t(k)] = toByte(double(c[k]));
    }
  }
  return image;
}

NamedChannel NamedChannel::floatChannel(std::string name, std::vector<float> values) {
  NamedChannel c;
  c.name = std::move(name);
  c.kind = ChannelKind::Float;
  c.floats = std::move(values);
  return c;
}

NamedChannel NamedChannel::uintChannel(std::string name, std::vector<uint32_t> values) {
  NamedChannel c;
  c.name = std::move(name);
  c.kind = ChannelKind::UInt32;
  c.uints = std::move(values);
  return c;
}

NamedChannel NamedChannel::stencilChannel(std::string name, std::span<const uint8_t> stencil) {
  return uintChannel(std::move(name), std::vector<uint32_t>(stencil.begin(), stencil.end()));
}

ExrExtras perLightStencilChannels(std::span<const PixelVector<uint8_t>> stencils, std::span<const std::string> names) {
  ExrExtras extras;
  if (stencils.size() < 2) return extras;
  for (size_t i = 0; i < stencils.size(); ++i)
    extras.channels.push_back(NamedChannel::stencilChannel("stencil." + names[i], stencils[i]));
  return extras;
}

namespace {

// One channel of an EXR as the values where they already are: `count` values of 4 bytes, the i-th
// (framebuffer order) at values + i * stride. The colour channels are read in place from the
// colour buffer, the extras from their vectors; only Z (decoded) and the stencil (widened to 32
// bits) need storage of their own, in ExrStorage.
struct ExrPlane {
  std::string name;
  ChannelKind kind = ChannelKind::Float;
  const char* values = nullptr;
  size_t stride = 4;
};
struct ExrStorage {
  std::vector<float> z;
  std::vector<uint32_t> stencil;
};

// The channels of exrChannels' contract, in its order, with its checks.
std::vector<ExrPlane> exrPlanes(const Framebuffer& fb, const ExrExtras& extras, ExrStorage& storage) {
  const size_t n = size_t(fb.width()) * size_t(fb.height());
  std::vector<ExrPlane> planes;
  if (fb.hasColor()) {
    const char* names[4] = {"R", "G", "B", "A"};
    const char* first = reinterpret_cast<const char*>(fb.color().data());
    for (size_t k = 0; k < 4; ++k)
      planes.push_back({names[k], ChannelKind::Float, first + k * sizeof(float), sizeof(glm::vec4)});
  }
  if (fb.hasDepth()) {
    storage.z.resize(n);
    for (size_t i = 0; i < n; ++i) storage.z[i] = float(fb.depthCodec().decode(fb.depthCodes()[i]));
    planes.push_back({"Z", ChannelKind::Float, reinterpret_cast<const char*>(storage.z.data())});
  }
  if (fb.hasStencil()) {
    storage.stencil.assign(fb.stencil().begin(), fb.stencil().end());
    planes.push_back({"stencil", ChannelKind::UInt32, reinterpret_cast<const char*>(storage.stencil.data())});
  }
  for (const NamedChannel& extra : extras.channels) {
    if (extra.name.empty()) throw std::invalid_argument("an extra EXR channel has no name");
    if (extra.size() != n)
      throw std::invalid_argument("extra EXR channel '" + extra.name + "' has " + std::to_string(extra.size()) +
                                  " values, the framebuffer " + std::to_string(n));
    const char* values = extra.kind == ChannelKind::Float ? reinterpret_cast<const char*>(extra.floats.data())
                                                          : reinterpret_cast<const char*>(extra.uints.data());
    planes.push_back({extra.name, extra.kind, values});
  }
  std::set<std::string> seen;
  for (const ExrPlane& p : planes)
    if (!seen.insert(p.name).second) throw std::invalid_argument("EXR channel '" + p.name + "' is given twice");
  return planes;
}

}  // namespace

std::vector<NamedChannel> exrChannels(const Framebuffer& fb, const ExrExtras& extras) {
  const size_t n = size_t(fb.width()) * size_t(fb.height());
  ExrStorage storage;
  std::vector<NamedChannel> channels;
  for (const ExrPlane& p : exrPlanes(fb, extras, storage)) {
    NamedChannel c;
    c.name = p.name;
    c.kind = p.kind;
    if (p.kind == ChannelKind::Float) c.floats.resize(n);
    else c.uints.resize(n);
    char* out = p.kind == ChannelKind::Float ? reinterpret_cast<char*>(c.floats.data()) : reinterpret_cast<char*>(c.uints.data());
    for (size_t i = 0; i < n; ++i) std::memcpy(out + i * 4, p.values + i * p.stride, 4);
    channels.push_back(std::move(c));
  }
  return channels;
}

namespace {
// How many threads OpenEXR compresses with (setImageWriterThreads); 0 compresses on the caller's.
std::atomic<int> exrThreads{0};
std::atomic<ExrCompression> exrCompression{kDefaultExrCompression};

Imf::Compression openExrCompression(ExrCompression c) {
  switch (c) {
    case ExrCompression::None: return Imf::NO_COMPRESSION;
    case ExrCompression::Rle: return Imf::RLE_COMPRESSION;
    case ExrCompression::Zip: return Imf::ZIP_COMPRESSION;
  }
  return Imf::ZIP_COMPRESSION;
}
}  // namespace

void setImageWriterThreads(int threads) { exrThreads.store(threads > 1 ? threads : 0); }

std::optional<ExrCompression> exrCompressionNamed(std::string_view name) {
  if (name == "none") return ExrCompression::None;
  if (name == "rle") return ExrCompression::Rle;
  if (name == "zip") return ExrCompression::Zip;
  return std::nullopt;
}

void setExrCompression(ExrCompression compression) { exrCompression.store(compression); }

void writeExr(const Framebuffer& fb, const std::string& path, const ExrExtras& extras, const OutputMetadata& metadata) {
  ExrStorage storage;
  const std::vector<ExrPlane> planes = exrPlanes(fb, extras, storage);
  if (planes.empty())
    throw std::invalid_argument("cannot write '" + path + "': the framebuffer has no buffers to write");
  const int w = fb.width(), h = fb.height();

  // The header OpenImageIO used to write, attribute for attribute: the picture's windows, the
  // provenance as strings (ImageDescription as EXR's "comments"), and an empty capDate, the time
  // stamp's place, so the same framebuffer always gives the same bytes; the compression chosen.
  Imf::Header header(w, h);
  header.compression() = openExrCompression(exrCompression.load());
  // zlib's fastest level for ZIP: the float channels hardly compress further at higher levels,
  // which take longer (the file is read the same way; the level is not stored in it).
  header.zipCompressionLevel() = 1;
  for (const ExrPlane& p : planes)
    header.channels().insert(p.name, Imf::Channel(p.kind == ChannelKind::Float ? Imf::FLOAT : Imf::UINT));
  header.insert("capDate", Imf::StringAttribute(""));
  for (const auto& [name, value] : metadataAttributes(metadata))
    header.insert(name == "ImageDescription" ? "comments" : name, Imf::StringAttribute(value));

  // One slice per channel, straight from its values in framebuffer order: the file's row r (top
  // first) is framebuffer row h - 1 - r, so each slice starts at the top row and steps down (a
  // negative row stride, as two's complement in OpenEXR's size_t), and nothing is interleaved.
  Imf::FrameBuffer slices;
  for (const ExrPlane& p : planes) {
    const ptrdiff_t rowBytes = ptrdiff_t(w) * ptrdiff_t(p.stride);
    char* top = const_cast<char*>(p.values) + ptrdiff_t(h - 1) * rowBytes;
    slices.insert(p.name, Imf::Slice(p.kind == ChannelKind::Float ? Imf::FLOAT : Imf::UINT, top, p.stride,
                                     size_t(-rowBytes)));
  }
  writeFileAtomically(path, [&](const TempFile& temp) {
    DescriptorStream stream(temp);
    try {
      // Every compression works on independent blocks of rows (16 for ZIP, 1 for RLE and none):
      // the bytes do not depend on the threads.
      const int threads = exrThreads.load();
      if (threads > 0 && Imf::globalThreadCount() != threads) Imf::setGlobalThreadCount(threads);
      Imf::OutputFile file(stream, header, threads);
      file.setFrameBuffer(slices);
      file.writePixels(h);
    } catch (const std::exception& e) {
      throw std::runtime_error(stream.failure().empty() ? e.what() : stream.failure());  // the cause first
    }
    if (!stream.failure().empty()) throw std::runtime_error(stream.failure());
  });
}

void writeImage(const Framebuffer& fb, const std::string& path, const OutputMetadata& metadata) {
  const std::string ext = lowerExtension(path);
  if (ext == ".png") return writePng(fb, path, false, metadata);
  if (ext == ".exr") return writeExr(fb, path, {}, metadata);
  throw std::invalid_argument("cannot write '" + path + "': unknown image type " +
                              (ext.empty() ? std::string("(no extension)") : "'" + ext + "'") +
                              "; use .png (8-bit colour) or .exr (colour, Z, stencil)");
}

Image8 greyImage(const std::vector<float>& values, int width, int height, float lo, float hi) {
  if (width <= 0 || height <= 0) throw std::invalid_argument("grey image size must be positive");
  if (values.size() != size_t(width) * size_t(height))
    throw std::invalid_argument("grey image has " + std::to_string(values.size()) + " values for " +
                                std::to_string(width) + "x" + std::to_string(height) + " pixels");
  if (!(lo < hi)) throw std::invalid_argument("grey image range needs lo < hi");
  Image8 image;
  image.width = width;
  image.height = height;
  image.channels = 1;
  image.pixels.resize(values.size());
  const double range = double(hi) - double(lo);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      double v = values[size_t(y) * size_t(width) + size_t(x)];
      image.pixels[size_t(fileRow(y, height)) * size_t(width) + size_t(x)] = toByte((v - double(lo)) / range);
    }
  return image;
}

void writeGreyPng(const std::vector<float>& values, int width, int height, const std::string& path,
                  float lo, float hi, const OutputMetadata& metadata) {
  writePng8(greyImage(values, width, height, lo, hi), path, metadata);
}

}  // namespace shadowref
