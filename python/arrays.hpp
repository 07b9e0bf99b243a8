// holoray/python: numpy arrays in and out. Out: an api::Image's samples as
// an array whose base keeps them alive (no copy). In: shapes, dtypes and
// values checked, every error naming the argument.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <array>
#include <vector>

#include "holoray/image.hpp"
#include "holoray/scene.hpp"

namespace holoray::python {

namespace py = pybind11;

/// The image's samples as float32 (H, W, C), or (H, W) when `squeeze` and C
/// is 1; not copied.
py::array image_to_numpy(const api::Image& image, bool squeeze = false);
/// An (H, W) or (H, W, C) array (C 1 to 4), float or integer, as an Image
/// (copied); `name` is the argument's name in messages.
api::Image numpy_to_image(const py::handle& array, const char* name);

/// Rows of an (N, K) numeric array (any layout, any real dtype), as doubles.
/// TypeError for a non-numeric dtype, ValueError for another shape.
template <size_t K>
std::vector<std::array<double, K>> rows_of(const py::handle& array, const char* name);
/// An (M, 3) integer array as face indices; TypeError for a non-integer
/// dtype, ValueError for negative or too large indices or another shape.
std::vector<std::array<uint32_t, 3>> faces_of(const py::handle& array, const char* name);
/// A texture (H, W, 3|4): uint8 (sRGB codes, as image files hold them) or
/// float (linear, 0..1, encoded to sRGB codes).
api::Texture texture_of(const py::handle& array, const char* name);
/// Three finite numbers.
std::array<double, 3> vec3_of(const py::handle& value, const char* name);

}  // namespace holoray::python
