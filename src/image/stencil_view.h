// Teaching views of the stencil buffer (--dump stencil, --dump-region):
// a false-colour picture with a legend, and the counts of a region as a numeric grid. They answer
// "what count does this pixel hold?" — the count that decides whether it is in shadow
// ([Kuhn 2016, §3.2]).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "image/image_writer.h"
#include "gl/framebuffer.h"

namespace shadowref {

struct StencilViewOptions {
  // Read the 8-bit value as signed: 128..255 are -128..-1. Wrapping ops (INCR_WRAP/DECR_WRAP) make
  // a count of -1 the value 255, e.g. z-pass with the camera inside a volume
  // ([Kuhn 2016, Fig. 3.3]).
  bool signedCounts = false;
  int pixelScale = 1;  // each stencil pixel becomes pixelScale x pixelScale picture pixels
  int glyphScale = 2;  // legend digits are 3x5 glyphs scaled by this
  bool legend = true;
};

// The count a stencil value stands for under the options.
int stencilCount(uint8_t value, bool signedCounts);

// The false colour of a count: 0 black; 1..16 a fixed palette of distinct colours (1 red, 2 green,
// 3 yellow, 4 blue, ...), larger counts hues spread by the golden ratio; a negative count -k is the
// colour of k at half brightness, never black.
std::array<uint8_t, 3> stencilColour(int count);

// The picture, top row first: the stencil (framebuffer order, row 0 at the bottom, so it is flipped
// like every other image) and below it, on a dark grey strip, one framed swatch per count present
// with its number ("+1"/"-1" when signed), in increasing order, wrapped into rows.
Image8 stencilFalseColour(std::span<const uint8_t> stencil, int width, int height,
                          const StencilViewOptions& options = {});
Image8 stencilFalseColour(const Framebuffer& fb, const StencilViewOptions& options = {});

// The picture as a PNG, with the file's provenance (see image_writer.h).
void writeStencilPng(std::span<const uint8_t> stencil, int width, int height, const std::string& path,
                     const StencilViewOptions& options = {}, const OutputMetadata& metadata = {});
void writeStencilPng(const Framebuffer& fb, const std::string& path, const StencilViewOptions& options = {},
                     const OutputMetadata& metadata = {});

// The counts of the region x..x+w-1, y..y+h-1 (framebuffer coordinates, y = row with row 0 at the
// BOTTOM) as text: a title line, a header of x labels, then one line per row, TOP row first, each
// starting with its y label. Numbers are right-aligned in equal columns. The region is clipped to
// the framebuffer (the title says so); w or h <= 0, or a region wholly outside, throws
// std::invalid_argument.
std::string stencilGrid(std::span<const uint8_t> stencil, int fbWidth, int fbHeight, int x, int y, int w,
                        int h, bool signedCounts = false);
std::string stencilGrid(const Framebuffer& fb, int x, int y, int w, int h, bool signedCounts = false);

}  // namespace shadowref
