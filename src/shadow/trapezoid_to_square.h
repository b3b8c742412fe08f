// N_T: the projective map of a trapezoid onto the square [−1, 1]² ([Hempe 2004, §4.1.2], after
// [Martin & Tan 2004]), built as Hempe's 8 steps, N_T = S2 · T3 · N · S1 · H · T2 · R · T1,
// one function per step. Each step computes its parameter u (and v) from the trapezoid corners
// carried through the product of the steps before it, exactly as the thesis writes.
//
// Corners: t0, t1 on the base line (the long, far side), t2, t3 on the top line (the short,
// near side); t0–t3 and t1–t2 are the side lines. N_T maps
//   t0 -> (−1, −1),  t1 -> (+1, −1),  t2 -> (+1, +1),  t3 -> (−1, +1)
// (top line to y = +1, base line to y = −1, as the 80 % rule of [Hempe 2004, §4.1.2] has it). When
// t0, t1, t2, t3 run counter-clockwise, N_T preserves orientation on the trapezoid, so face
// culling in a map pass drawn through N_T keeps its meaning.
//
// The z row of N_T is (0, 0, 1, 0) as in the thesis: z is carried, but divided by the new w after
// the projection. For an orthographic light that w is constant along each light ray, so depth
// order along a ray is kept, and z/w is affine in window coordinates (N_T is projective), so the
// rasterizer's linear depth interpolation stays exact; only the depth scale varies per texel.
#pragma once

#include <array>

#include <glm/glm.hpp>

namespace shadowref {

using TrapezoidCorners = std::array<glm::dvec2, 4>;

// Step 1: T1 moves the centre of the top line, u = (t2 + t3) / 2, to the origin.
glm::dmat4 trapezoidStepT1(const TrapezoidCorners& t);
// Step 2: R turns the top line onto the x axis: u = (t2 − t3) / |t2 − t3|,
// R = [[x_u, y_u], [y_u, −x_u]] (det −1: a reflection, as in Martin & Tan; it sends u to +x).
glm::dmat4 trapezoidStepR(const TrapezoidCorners& t);
// Step 3: T2 moves the intersection i of the side lines (t0, t3) and (t1, t2) to the origin:
// u = R · T1 · i.
glm::dmat4 trapezoidStepT2(const TrapezoidCorners& t, const glm::dmat4& soFar);
// Step 4: H shears the trapezoid symmetric about the y axis: u = (T2·R·T1·(t2 + t3)) / 2,
// H = [[1, −x_u / y_u], [0, 1]].
// Erratum: [Hempe 2004, §4.1.2] prints H with 1/y_u in row 2 (and calls the shear "gesichert", for
// "geschert"). Martin & Tan's H has 1 there. The product is the same either way — step 5 takes
// its u after H and scales y by 1/y_u, so the two variants differ only in which step scales y —
// but 1 keeps H a pure shear, as its name says.
glm::dmat4 trapezoidStepH(const TrapezoidCorners& t, const glm::dmat4& soFar);
// Step 5: S1 scales so that the top line lies at y = 1 and the side lines meet at 90°:
// u = H·T2·R·T1·t2, S1 = diag(1/x_u, 1/y_u).
glm::dmat4 trapezoidStepS1(const TrapezoidCorners& t, const glm::dmat4& soFar);
// Step 6: N, the projective map that turns the trapezoid into a rectangle:
// (x, y, z, w) -> (x, y + w, z, y).
glm::dmat4 trapezoidStepN();
// Step 7: T3 moves the rectangle's centre to the origin along y:
// u = N·S1·H·T2·R·T1·t0, v = … · t2, translation −(y_u/w_u + y_v/w_v) / 2.
glm::dmat4 trapezoidStepT3(const TrapezoidCorners& t, const glm::dmat4& soFar);
// Step 8: S2 scales y so the rectangle fills [−1, 1]²: u = T3·N·S1·H·T2·R·T1·t0,
// S2 = diag(1, −w_u / y_u).
glm::dmat4 trapezoidStepS2(const TrapezoidCorners& t, const glm::dmat4& soFar);

// The intersection i of the side lines t0–t3 and t1–t2 (the trapezoid's apex q).
glm::dvec2 sideLineIntersection(const TrapezoidCorners& t);

// N_T = S2 · T3 · N · S1 · H · T2 · R · T1 ([Hempe 2004, §4.1.2]). The side lines must not be
// parallel.
glm::dmat4 trapezoidToSquare(const TrapezoidCorners& t);

// The affine map of a parallelogram (rectangle) onto [−1, 1]² with the same corner convention,
// t0 -> (−1, −1), t1 -> (+1, −1), t3 -> (−1, +1) (t2 follows): the limit of trapezoidToSquare
// when the side lines become parallel, and the bounding-rectangle fallback
// ([Hempe 2004, Listing 10e]).
glm::dmat4 parallelogramToSquare(const TrapezoidCorners& t);

}  // namespace shadowref
