// holoray/image: the 8-bit sRGB code of a linear value, by table. The
// definition is the formula, floor(255 e(v) + 1/2) with e the sRGB transfer
// function (IEC 61966-2-1) in float; the table gives its codes without a pow
// per channel (a 2048x2048 PNG of a mesh scene is 12.6 M of them, and each
// MIP level of an sRGB texture averages through the same encoding).
#pragma once

#include <cstdint>

namespace holoray {

/// floor(255 e(v) + 1/2) clamped to 0..255, e(v) = 12.92 v up to 0.0031308,
/// else 1.055 v^(1/2.4) - 0.055, in float, v first clamped to [0, 1]; NaN
/// gives 0. The formula itself: the reference that srgb_code() equals.
uint8_t srgb_code_by_formula(float v);

/// srgb_code_by_formula(v) for every float v, read from the 255 linear
/// values where the code steps (each the least float whose formula code
/// reaches it, found by bisection with the formula, so both give the same
/// code wherever the formula's code never decreases as v grows; the tests
/// check every float within 4096 ULPs of each step).
uint8_t srgb_code(float v);

/// The least float v in [0, 1] with srgb_code_by_formula(v) >= c, for c in
/// 1..255: the table's steps, for the tests.
float srgb_code_step(int c);

}  // namespace holoray
