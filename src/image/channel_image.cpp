#include "image/channel_image.h"

#include <memory>
#include <stdexcept>

#include <OpenImageIO/imageio.h>

namespace shadowref {

int ChannelImage::channelIndex(const std::string& name) const {
  for (size_t c = 0; c < names.size(); ++c)
    if (names[c] == name) return int(c);
  return -1;
}

namespace {

bool isWideInteger(OIIO::TypeDesc t) {
  return t.basetype == OIIO::TypeDesc::UINT32 || t.basetype == OIIO::TypeDesc::INT32;
}

// Reads one channel in the type that keeps its meaning (see readChannelImage).
std::vector<double> readChannel(OIIO::ImageInput& in, const OIIO::ImageSpec& spec, int c,
                                const std::string& path) {
  const size_t n = size_t(spec.width) * size_t(spec.height);
  std::vector<double> values(n);
  const OIIO::TypeDesc stored = spec.channelformat(c);
  bool ok;
  if (isWideInteger(stored)) {
    // Read in the stored type itself: OpenImageIO converts between integer types by rescaling
    // (255 in uint8 becomes 65535 in uint16), which would turn a count into something else.
    std::vector<uint32_t> raw(n);
    ok = in.read_image(0, 0, c, c + 1, stored, raw.data());
    for (size_t i = 0; i < n; ++i)
      values[i] = stored.basetype == OIIO::TypeDesc::INT32 ? double(int32_t(raw[i])) : double(raw[i]);
  } else {
    ok = in.read_image(0, 0, c, c + 1, OIIO::TypeDesc::DOUBLE, values.data());
  }
  if (!ok) throw std::runtime_error("cannot read '" + path + "': " + in.geterror());
  return values;
}

}  // namespace

ChannelImage readChannelImage(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw std::runtime_error("cannot read '" + path + "': " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.depth > 1) throw std::runtime_error("cannot read '" + path + "': volume images are not supported");
  ChannelImage image;
  image.width = spec.width;
  image.height = spec.height;
  for (int c = 0; c < spec.nchannels; ++c) {
    image.names.push_back(spec.channel_name(c));
    image.data.push_back(readChannel(*in, spec, c, path));
  }
  in->close();
  return image;
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
  }
  return image;
}

}  // namespace shadowref
