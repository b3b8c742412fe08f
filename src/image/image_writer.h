// Writing a Framebuffer to files: PNG for looking at, multi-channel EXR for checking.
// Every writer is atomic (see atomic_write.h): the file is complete or absent, never half-written.
// Failures throw std::runtime_error with the path and the reason.
//
// Row order: the framebuffer's row 0 is the BOTTOM row (as glReadPixels returns it); image files
// store the TOP row first. Every writer flips, so framebuffer pixel (0, 0) is the bottom-left pixel
// of the picture, i.e. the first pixel of the file's LAST scanline.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "image/output_metadata.h"
#include "gl/framebuffer.h"

namespace shadowref {

// An 8-bit image with the top row first, as it goes into a PNG: pixel (x, y) starts at
// (y * width + x) * channels. Used for pictures made here (false colour, legends).
struct Image8 {
  int width = 0;
  int height = 0;
  int channels = 3;  // 1 grey, 3 RGB, 4 RGBA
  std::vector<uint8_t> pixels;
};

// Every writer takes the file's provenance last (output_metadata.h): its attributes go into the
// EXR header or PNG tEXt chunks; the default, empty, writes none.

// Writes an Image8 as PNG (any path; the format is PNG whatever the extension).
void writePng8(const Image8& image, const std::string& path, const OutputMetadata& metadata = {});

// 8-bit colour: each channel c becomes round(c * 255) after clamping to [0, 1], computed in double
// so the product is exact and halves round up (0.5 -> 128). No transfer function is applied: the
// bytes are what an 8-bit GL colour buffer would hold. RGB by default, because a scene cleared with
// alpha 0 would otherwise open as a transparent picture; withAlpha adds A.
// Requires the colour buffer.
void writePng(const Framebuffer& fb, const std::string& path, bool withAlpha = false,
              const OutputMetadata& metadata = {});

// The bytes writePng writes: the colour buffer as 8-bit RGB (RGBA), top row first.
Image8 colorImage(const Framebuffer& fb, bool withAlpha = false);

// One extra EXR channel: 4-byte float or 32-bit unsigned values, width * height of them in
// FRAMEBUFFER order (index y * width + x, row 0 at the bottom), flipped on writing like the
// framebuffer's own channels.
enum class ChannelKind : uint8_t { Float, UInt32 };

struct NamedChannel {
  std::string name;
  ChannelKind kind = ChannelKind::Float;
  std::vector<float> floats;    // the values when kind == Float
  std::vector<uint32_t> uints;  // the values when kind == UInt32

  static NamedChannel floatChannel(std::string name, std::vector<float> values);
  static NamedChannel uintChannel(std::string name, std::vector<uint32_t> values);
  // A stencil buffer (e.g. one light's counts) as a UINT32 channel, e.g. "stencil.L0".
  static NamedChannel stencilChannel(std::string name, std::span<const uint8_t> stencil);
  size_t size() const { return kind == ChannelKind::Float ? floats.size() : uints.size(); }
};

struct ExrExtras {
  std::vector<NamedChannel> channels;  // written after the framebuffer's channels, in this order
};

// With several lights, one stencil channel per light, "stencil.<name>" (each light's counts after
// its volume pass; the framebuffer's own "stencil" holds the last light's); with one, none.
ExrExtras perLightStencilChannels(std::span<const PixelVector<uint8_t>> stencils, std::span<const std::string> names);

// The channels writeExr writes for fb, in order, each in framebuffer order:
//   R, G, B, A  FLOAT (32-bit: a reference keeps every bit the colour buffer holds)  if hasColor
//   Z           FLOAT, the window depth decoded from the depth codes                  if hasDepth
//   stencil     UINT32, the 8-bit counts                                              if hasStencil
// followed by extras. Throws std::invalid_argument for an extra of the wrong size or a name used
// twice. Shared with compareWithExr so a golden is compared with exactly what would be written.
std::vector<NamedChannel> exrChannels(const Framebuffer& fb, const ExrExtras& extras = {});

// Writes exrChannels(fb, extras) as a losslessly compressed (setExrCompression) scanline OpenEXR
// file with per-channel formats and no time stamp: the same framebuffer gives the same bytes.
// A framebuffer with no buffers and no extras is an error.
void writeExr(const Framebuffer& fb, const std::string& path, const ExrExtras& extras = {},
              const OutputMetadata& metadata = {});

// The threads writeExr compresses with (ZIP blocks are independent: the same bytes for any number);
// at most 1 (the default) compresses on the calling thread. For the whole process.
void setImageWriterThreads(int threads);

// OpenEXR's lossless compressions writeExr can use; every reader reads each of them. For the
// 800x640 room's six 32-bit channels (12.3 MB raw), one thread: RLE takes about a fifth of ZIP's
// time for a file 1.7 times as large, which keeps a render to EXR within a start-up budget of
// tens of milliseconds; ZIP (zlib's fastest level) is for keeping files; none is the fastest.
enum class ExrCompression { None, Rle, Zip };
inline constexpr ExrCompression kDefaultExrCompression = ExrCompression::Rle;
// "none", "rle", "zip"; nullopt for another name.
std::optional<ExrCompression> exrCompressionNamed(std::string_view name);
// The compression writeExr uses from now on, for the whole process (default RLE).
void setExrCompression(ExrCompression compression);

// Chooses by extension, case-insensitive: ".png" -> writePng, ".exr" -> writeExr. Any other
// extension throws std::invalid_argument naming the supported ones.
void writeImage(const Framebuffer& fb, const std::string& path, const OutputMetadata& metadata = {});

// A grey 8-bit PNG of width * height values (depth buffers, shadow maps) in FRAMEBUFFER order
// (row 0 at the bottom): lo maps to black, hi to white, round((v - lo) / (hi - lo) * 255) after
// clamping; NaN becomes black. Requires lo < hi.
void writeGreyPng(const std::vector<float>& values, int width, int height, const std::string& path,
                  float lo, float hi, const OutputMetadata& metadata = {});

// The same mapping without writing: the 8-bit grey picture, top row first.
Image8 greyImage(const std::vector<float>& values, int width, int height, float lo, float hi);

}  // namespace shadowref
