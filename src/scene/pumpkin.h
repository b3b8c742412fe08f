// The pumpkins of the Halloween scene ([Kuhn 2016, Fig. 5.2]): a ribbed, squashed sphere, and the
// hollow lantern — a closed shell (outer skin, inner skin, and rims joining them around every
// opening) with openings for the lid and a face, so the light inside escapes only through them.
#pragma once

#include "scene/mesh.h"

namespace shadowref {

struct PumpkinShape {
  double radius = 0.4;     // around the equator, at the top of a rib
  double squash = 0.72;    // height / width
  int ribs = 9;
  double ribDepth = 0.06;  // groove depth as a fraction of the radius
  int slices = 54, stacks = 32;
};

// Centred at the origin (the bottom is below y = 0: place it with its bounds).
Mesh makePumpkin(const PumpkinShape& shape);

// The lantern: openings are the lid (around the north pole) and a face — two triangular eyes and
// a mouth with one tooth — looking along +x. Four openings through a sphere-like shell make a closed
// surface of genus 3: V - E + F = 2 - 2·3 = -4.
inline constexpr int kLanternOpenings = 4;
Mesh makeHollowPumpkin(const PumpkinShape& shape, double wallThickness);

}  // namespace shadowref
