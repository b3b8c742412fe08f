// The image-reading module (see image/channel_reader.h): OpenImageIO behind one C entry point,
// built as shadowref_image_reader.so and loaded by readChannelImage when an image is first read.
#include <filesystem>
#include <memory>
#include <stdexcept>

#include <OpenImageIO/imageio.h>

#include "image/channel_reader.h"
#include "scene/checked_arithmetic.h"

namespace shadowref {

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

// How many decoded bytes one byte of the file can hold at most, or 0 when the format or its
// compression gives no useful bound (then only ReadLimits::maxValues applies). Deflate expands a
// byte to at most 1032; EXR rle stores a run of at most 128 bytes in 2; pxr24 deflates 24 of each
// 32 bits.
uint64_t maxExpansion(const std::string& format, const std::string& compression) {
  if (format == "png") return 1032;
  if (format != "openexr") return 0;
  if (compression == "none") return 1;
  if (compression == "rle") return 128;
  if (compression == "zip" || compression == "zips") return 1032;
  if (compression == "pxr24") return 1376;
  return 0;
}

// Refuses a header that declares more than the limits or the file can hold, before any allocation.
void checkDeclaredSize(OIIO::ImageInput& in, const OIIO::ImageSpec& spec, const std::string& path,
                       const ReadLimits& limits) {
  auto refuse = [&](const std::string& why) { throw std::runtime_error("cannot read '" + path + "': " + why); };
  if (spec.depth > 1) refuse("volume images are not supported");
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
    refuse("the header declares an empty image (" + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
           ", " + std::to_string(spec.nchannels) + " channels)");
  const std::string declared = std::to_string(spec.width) + "x" + std::to_string(spec.height) + " pixels with " +
                               std::to_string(spec.nchannels) + " channels";
  const std::optional<uint64_t> pixels = checkedMul(uint64_t(spec.width), uint64_t(spec.height));
  const std::optional<uint64_t> values = pixels ? checkedMul(*pixels, uint64_t(spec.nchannels)) : std::nullopt;
  if (!values || *values > limits.maxValues)
    refuse("the header declares " + declared + ", more than the limit of " + std::to_string(limits.maxValues) +
           " channel values");
  const uint64_t expansion = maxExpansion(in.format_name(), spec.get_string_attribute("compression"));
  std::error_code ec;
  const uintmax_t fileBytes = std::filesystem::file_size(path, ec);
  if (expansion == 0 || ec) return;
  const uint64_t bytes = uint64_t(spec.image_bytes(true));  // in the file's own channel formats
  const std::optional<uint64_t> capacity = checkedMul(uint64_t(fileBytes), expansion);
  if (capacity && bytes > *capacity)
    refuse("the header declares " + declared + " (" + std::to_string(bytes) + " bytes of pixels), more than its " +
           std::to_string(fileBytes) + "-byte file can hold");
}

ChannelImage readWithOiio(const std::string& path, const ReadLimits& limits) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw std::runtime_error("cannot read '" + path + "': " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  checkDeclaredSize(*in, spec, path, limits);
  ChannelImage image;
  image.width = spec.width;
  image.height = spec.height;
  for (int c = 0; c < spec.nchannels; ++c) {
    image.names.push_back(spec.channel_name(c));
    image.data.push_back(readChannel(*in, spec, c, path));
    image.integer.push_back(isWideInteger(spec.channelformat(c)));
  }
  in->close();
  return image;
}

}  // namespace

extern "C" __attribute__((visibility("default"))) ChannelReader shadowref_channel_reader_v1() { return &readWithOiio; }

}  // namespace shadowref
