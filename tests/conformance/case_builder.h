// Small helpers that conformance cases are written with: triangles placed in window coordinates
// (converted to clip space exactly, so both implementations see the same positions), seeded
// triangle soups, and the Catch2 checks of the issue-2 expectation.
#pragma once

#include <cstdint>

#include <catch2/catch.hpp>

#include "conformance/comparison.h"
#include "osmesa/scenario.h"

namespace shadowref::conformance {

// Clip coordinates of window position (wx, wy) and NDC depth zNdc, scaled by w (w > 0). For a
// power-of-two viewport and wx, wy on a 1/256 grid the division by w gives back exact values.
glm::dvec4 windowToClip(const Viewport& vp, double wx, double wy, double zNdc, double w = 1.0);

// Appends triangle (a, b, c), each given as (window x, window y, NDC z), in one colour.
void addTriangle(DrawStep& d, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec4& color);

// `count` triangles with vertices anywhere in the viewport widened by `margin` pixels, NDC depth
// in [-0.9, 0.9], random colours with alpha; positions on the 1/256 sub-pixel grid when
// `onSubpixelGrid`, arbitrary doubles otherwise. Deterministic for a seed.
std::vector<ColoredVertex> triangleSoup(const Viewport& vp, int count, uint32_t seed, bool onSubpixelGrid,
                                        double margin = 8.0);

// The Catch2 checks of CaseResult::withinDocumentedBounds, with the numbers shown on failure.
void checkAgreement(const CaseResult& r);

}  // namespace shadowref::conformance
