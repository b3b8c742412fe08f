// A teaching view: a picture of a buffer (one picture pixel per buffer pixel) and the legend that
// says what its colours mean. The picture and the legend's values are kept apart, so that a front
// end can draw the legend its own way (the page) or have it drawn beside the picture
// (composeView, the command line's PNGs).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "image/image_writer.h"
#include "views/colour_map.h"

namespace shadowref::views {

enum class LegendKind {
  None,
  ColourBar,  // a continuous quantity from lo (viridis 0) to hi (viridis 1), drawn beside the picture
  Swatches,   // a few discrete values, one colour each, drawn under the picture
  Ramp,       // many discrete values on viridis from lo to hi with ticks at `values`, under the picture
};

struct ViewLegend {
  LegendKind kind = LegendKind::None;
  std::string quantity;        // "eye depth", "stored depth", "stencil count"
  double lo = 0.0, hi = 0.0;   // ColourBar and Ramp: the values of the ends
  std::vector<int> values;     // Swatches: the values present, increasing; Ramp: the ticks
  std::vector<Rgb8> colours;   // Swatches: each value's colour
  std::vector<std::string> labels;  // Swatches and Ramp: each value's text; ColourBar: lo's, hi's
  Rgb8 background{0, 0, 0};    // the colour of pixels with no value (nothing drawn there)
  bool hasBackground = false;  // whether the picture has such pixels
  // Lines drawn over the picture (a shadow map's camera frustum and trapezoid) and what each
  // colour shows; the page names them, composeView leaves them to the documentation.
  std::vector<std::pair<std::string, Rgb8>> outlines;
};

struct View {
  Image8 picture;  // RGBA, 4 channels, alpha 255; top row first (the buffer's row 0 at the bottom)
  ViewLegend legend;
};

// The picture with its legend drawn: a colour bar to the right (its top the high end) with the
// ends' labels; swatches or a ramp with ticks on a strip beneath. Digits are 3x5 glyphs scaled by
// glyphScale. The legend's size depends only on the picture's size and the number of labels
// (at most kMaxSwatches swatches), never on how many values the buffer holds.
Image8 composeView(const View& view, int glyphScale = 2);

// Writes composeView(view) as a PNG with the file's provenance.
void writeViewPng(const View& view, const std::string& path, const OutputMetadata& metadata = {}, int glyphScale = 2);

// An RGBA picture of the given size filled with one colour.
Image8 filledPicture(int width, int height, Rgb8 colour);
// Sets pixel (x, y) of the BUFFER (row 0 at the bottom) in a picture of its size.
void setBufferPixel(Image8& picture, int x, int y, Rgb8 colour);

}  // namespace shadowref::views
