#include "image/image_writer.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <set>
#include <stdexcept>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "image/atomic_write.h"

namespace shadowref {

namespace {

// OpenImageIO's output goes through this proxy straight to the temporary file's descriptor, so
// every byte passes writeAllAt: a plugin that ignores a short write (the PNG one does) cannot hide
// it, because the first failure is kept here and reported after close.
class DescriptorSink final : public OIIO::Filesystem::IOProxy {
 public:
  explicit DescriptorSink(const TempFile& temp) : IOProxy(temp.path, Write), fd_(temp.fd) {}
  const char* proxytype() const override { return "shadowref-descriptor"; }
  size_t write(const void* buf, size_t size) override {
    const size_t n = pwrite(buf, size, m_pos);
    m_pos += int64_t(n);
    return n;
  }
  size_t pwrite(const void* buf, size_t size, int64_t offset) override {
    if (!failure_.empty() || offset < 0) return 0;
    try {
      writeAllAt(fd_, buf, size, uint64_t(offset));
    } catch (const std::exception& e) {
      failure_ = e.what();
      return 0;
    }
    end_ = std::max(end_, uint64_t(offset) + size);
    return size;
  }
  size_t read(void*, size_t) override { return 0; }
  size_t pread(void*, size_t, int64_t) override { return 0; }
  size_t size() const override { return size_t(end_); }
  const std::string& failure() const { return failure_; }

 private:
  int fd_;
  uint64_t end_ = 0;
  std::string failure_;  // the first failed write, empty while every byte arrived
};

// Writes one image through OpenImageIO into the already created (empty) temporary file. The plugin
// is chosen by format name, because the temporary file's name does not end in the extension.
void writeWithOiio(const TempFile& temp, const char* formatName, const OIIO::ImageSpec& spec,
                   OIIO::TypeDesc dataFormat, const void* data) {
  auto out = OIIO::ImageOutput::create(formatName);
  if (!out) throw std::runtime_error(std::string("OpenImageIO has no ") + formatName + " writer: " +
                                     OIIO::geterror());
  if (!out->supports("ioproxy"))
    throw std::runtime_error(std::string("OpenImageIO's ") + formatName + " writer cannot write through a proxy");
  DescriptorSink sink(temp);
  out->set_ioproxy(&sink);
  auto failed = [&](std::string reason) {
    if (!sink.failure().empty()) reason = sink.failure();  // the cause, not its consequence
    return std::runtime_error(reason.empty() ? "the image writer failed" : reason);
  };
  if (!out->open(temp.path, spec)) throw failed(out->geterror());
  if (!out->write_image(dataFormat, data)) {
    std::string reason = out->geterror();
    out->close();
    throw failed(reason);
  }
  if (!out->close()) throw failed(out->geterror());
  if (!sink.failure().empty()) throw failed("");
}

// Provenance as string attributes: OpenImageIO writes them as EXR header attributes and as PNG
// tEXt chunks (ImageDescription under PNG's keyword "Description").
void addMetadata(OIIO::ImageSpec& spec, const OutputMetadata& metadata) {
  for (const auto& [name, value] : metadataAttributes(metadata)) spec.attribute(name, value);
}

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
  OIIO::ImageSpec spec(image.width, image.height, image.channels, OIIO::TypeDesc::UINT8);
  addMetadata(spec, metadata);
  writeFileAtomically(path, [&](const TempFile& temp) {
    writeWithOiio(temp, "png", spec, OIIO::TypeDesc::UINT8, image.pixels.data());
  });
}

void writePng(const Framebuffer& fb, const std::string& path, bool withAlpha, const OutputMetadata& metadata) {
  if (!fb.hasColor()) throw std::invalid_argument("cannot write '" + path + "': the framebuffer has no colour buffer");
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
  writePng8(image, path, metadata);
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

std::vector<NamedChannel> exrChannels(const Framebuffer& fb, const ExrExtras& extras) {
  const size_t n = size_t(fb.width()) * size_t(fb.height());
  std::vector<NamedChannel> channels;
  if (fb.hasColor()) {
    const char* names[4] = {"R", "G", "B", "A"};
    for (int k = 0; k < 4; ++k) {
      std::vector<float> v(n);
      for (size_t i = 0; i < n; ++i) v[i] = fb.color()[i][k];
      channels.push_back(NamedChannel::floatChannel(names[k], std::move(v)));
    }
  }
  if (fb.hasDepth()) {
    std::vector<float> z(n);
    for (size_t i = 0; i < n; ++i) z[i] = float(fb.depthCodec().decode(fb.depthCodes()[i]));
    channels.push_back(NamedChannel::floatChannel("Z", std::move(z)));
  }
  if (fb.hasStencil()) channels.push_back(NamedChannel::stencilChannel("stencil", fb.stencil()));

  for (const NamedChannel& extra : extras.channels) {
    if (extra.name.empty()) throw std::invalid_argument("an extra EXR channel has no name");
    if (extra.size() != n)
      throw std::invalid_argument("extra EXR channel '" + extra.name + "' has " + std::to_string(extra.size()) +
                                  " values, the framebuffer " + std::to_string(n));
    channels.push_back(extra);
  }
  std::set<std::string> seen;
  for (const NamedChannel& c : channels)
    if (!seen.insert(c.name).second) throw std::invalid_argument("EXR channel '" + c.name + "' is given twice");
  return channels;
}

void writeExr(const Framebuffer& fb, const std::string& path, const ExrExtras& extras, const OutputMetadata& metadata) {
  const std::vector<NamedChannel> channels = exrChannels(fb, extras);
  if (channels.empty())
    throw std::invalid_argument("cannot write '" + path + "': the framebuffer has no buffers to write");
  const int w = fb.width(), h = fb.height(), nc = int(channels.size());

  // Per-channel formats: without them OpenImageIO would store every channel in one format.
  OIIO::ImageSpec spec(w, h, nc, OIIO::TypeDesc::FLOAT);
  spec.channelnames.clear();
  spec.channelformats.clear();
  spec.alpha_channel = -1;
  spec.z_channel = -1;
  for (int k = 0; k < nc; ++k) {
    const NamedChannel& c = channels[size_t(k)];
    spec.channelnames.push_back(c.name);
    spec.channelformats.push_back(c.kind == ChannelKind::Float ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT32);
    if (c.name == "A") spec.alpha_channel = k;
    if (c.name == "Z") spec.z_channel = k;
  }
  spec.attribute("compression", "zip");
  // An empty DateTime keeps OpenImageIO from stamping the current time into the header, so the same
  // framebuffer always gives the same bytes (goldens diff cleanly).
  spec.attribute("DateTime", "");
  addMetadata(spec, metadata);

  // Every channel is 4 bytes wide, so a pixel is nc words; floats travel as their bit patterns.
  std::vector<uint32_t> words(size_t(w) * size_t(h) * size_t(nc));
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const size_t src = fb.index(x, y);
      const size_t dst = (size_t(fileRow(y, h)) * size_t(w) + size_t(x)) * size_t(nc);
      for (int k = 0; k < nc; ++k) {
        const NamedChannel& c = channels[size_t(k)];
        words[dst + size_t(k)] = c.kind == ChannelKind::Float ? std::bit_cast<uint32_t>(c.floats[src]) : c.uints[src];
      }
    }
  }
  writeFileAtomically(path, [&](const TempFile& temp) {
    // TypeUnknown: the data is in the file's own per-channel formats.
    writeWithOiio(temp, "openexr", spec, OIIO::TypeUnknown, words.data());
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
