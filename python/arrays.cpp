#include "arrays.hpp"

#include <cmath>
#include <memory>
#include <string>

#include "holoray/image.hpp"

namespace holoray::python {

namespace {

std::string shape_text(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t k = 0; k < a.ndim(); ++k) s += (k ? ", " : "") + std::to_string(a.shape(k));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

py::array as_array(const py::handle& h, const char* name) {
  py::array a = py::array::ensure(h);
  if (!a) throw py::type_error(std::string(name) + ": expected an array-like of numbers");
  const char kind = a.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u' && kind != 'b')
    throw py::type_error(std::string(name) + ": expected numbers, got dtype " + std::string(py::str(a.dtype())));
  return a;
}

}  // namespace

py::array image_to_numpy(const api::Image& image, bool squeeze) {
  auto* keep = new std::shared_ptr<void>(image.storage());
  py::capsule base(keep, [](void* p) { delete static_cast<std::shared_ptr<void>*>(p); });
  const py::ssize_t h = image.height(), w = image.width(), c = image.channels(), f = sizeof(float);
  auto* data = const_cast<float*>(image.data());
  if (squeeze && c == 1) return py::array_t<float>({h, w}, {w * f, f}, data, base);
  return py::array_t<float>({h, w, c}, {w * c * f, c * f, f}, data, base);
}

api::Image numpy_to_image(const py::handle& h, const char* name) {
  py::array a = as_array(h, name);
  if (a.ndim() != 2 && a.ndim() != 3)
    throw py::value_error(std::string(name) + ": expected an image (H, W) or (H, W, C), got shape " + shape_text(a));
  const int height = static_cast<int>(a.shape(0)), width = static_cast<int>(a.shape(1));
  const int channels = a.ndim() == 3 ? static_cast<int>(a.shape(2)) : 1;
  if (height < 1 || width < 1 || channels < 1 || channels > 4)
    throw py::value_error(std::string(name) + ": expected at least 1x1 pixels and 1 to 4 channels, got shape " + shape_text(a));
  // uint8 images are codes: k / 255, as read_image gives them.
  const bool codes = a.dtype().kind() == 'u' && a.itemsize() == 1;
  auto f = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(a);
  api::Image img(width, height, channels);
  const float* src = f.data();
  float* dst = img.data();
  const float scale = codes ? 1.0f / 255.0f : 1.0f;
  for (size_t k = 0; k < img.size(); ++k) dst[k] = src[k] * scale;
  return img;
}

template <size_t K>
std::vector<std::array<double, K>> rows_of(const py::handle& h, const char* name) {
  py::array a = as_array(h, name);
  if (a.ndim() != 2 || a.shape(1) != static_cast<py::ssize_t>(K))
    throw py::value_error(std::string(name) + ": expected shape (N, " + std::to_string(K) + "), got " + shape_text(a));
  auto d = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
  const size_t n = static_cast<size_t>(d.shape(0));
  std::vector<std::array<double, K>> out(n);
  const double* p = d.data();
  for (size_t i = 0; i < n; ++i)
    for (size_t k = 0; k < K; ++k) {
      const double x = p[i * K + k];
      if (!std::isfinite(x))
        throw py::value_error(std::string(name) + ": row " + std::to_string(i) + " has a NaN or infinite value");
      out[i][k] = x;
    }
  return out;
}
template std::vector<std::array<double, 2>> rows_of<2>(const py::handle&, const char*);
template std::vector<std::array<double, 3>> rows_of<3>(const py::handle&, const char*);

std::vector<std::array<uint32_t, 3>> faces_of(const py::handle& h, const char* name) {
  py::array a = py::array::ensure(h);
  if (!a) throw py::type_error(std::string(name) + ": expected an integer array of shape (M, 3)");
  const char kind = a.dtype().kind();
  if (kind != 'i' && kind != 'u')
    throw py::type_error(std::string(name) + ": expected integer vertex indices, got dtype " + std::string(py::str(a.dtype())));
  if (a.ndim() != 2 || a.shape(1) != 3)
    throw py::value_error(std::string(name) + ": expected shape (M, 3), got " + shape_text(a));
  auto d = py::array_t<int64_t, py::array::c_style | py::array::forcecast>::ensure(a);
  const size_t m = static_cast<size_t>(d.shape(0));
  std::vector<std::array<uint32_t, 3>> out(m);
  const int64_t* p = d.data();
  for (size_t i = 0; i < m; ++i)
    for (int k = 0; k < 3; ++k) {
      const int64_t v = p[i * 3 + k];
      if (v < 0 || v > 0xffffffffLL)
        throw py::value_error(std::string(name) + ": row " + std::to_string(i) + " has vertex index " + std::to_string(v) +
                              ", outside the vertices");
      out[i][k] = static_cast<uint32_t>(v);
    }
  return out;
}

api::Texture texture_of(const py::handle& h, const char* name) {
  py::array a = as_array(h, name);
  if (a.ndim() != 3 || (a.shape(2) != 3 && a.shape(2) != 4) || a.shape(0) < 1 || a.shape(1) < 1)
    throw py::value_error(std::string(name) + ": expected shape (H, W, 3) or (H, W, 4), got " + shape_text(a));
  if (a.shape(0) * a.shape(1) > (py::ssize_t{1} << 28))
    throw py::value_error(std::string(name) + ": more than 2^28 texels");
  api::Texture t;
  t.height = static_cast<int>(a.shape(0));
  t.width = static_cast<int>(a.shape(1));
  t.channels = static_cast<int>(a.shape(2));
  t.codes.resize(static_cast<size_t>(t.width) * t.height * t.channels);
  if (a.dtype().kind() == 'u' && a.itemsize() == 1) {
    auto u = py::array_t<uint8_t, py::array::c_style | py::array::forcecast>::ensure(a);
    std::copy(u.data(), u.data() + t.codes.size(), t.codes.begin());
    return t;
  }
  auto f = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(a);
  const float* p = f.data();
  for (size_t k = 0; k < t.codes.size(); ++k) {
    if (!std::isfinite(p[k])) throw py::value_error(std::string(name) + ": has a NaN or infinite value");
    // Colour channels are linear light, sRGB-encoded as files hold them; alpha is coverage, as it is.
    const bool alpha = t.channels == 4 && k % 4 == 3;
    t.codes[k] = api::encode_8bit(p[k], alpha ? api::Encoding::linear : api::Encoding::srgb);
  }
  return t;
}

std::array<double, 3> vec3_of(const py::handle& value, const char* name) {
  py::array a = as_array(value, name);
  if (a.size() != 3 || a.ndim() > 1) throw py::value_error(std::string(name) + ": expected three numbers");
  auto d = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
  std::array<double, 3> out{d.data()[0], d.data()[1], d.data()[2]};
  for (double x : out)
    if (!std::isfinite(x)) throw py::value_error(std::string(name) + ": a value is NaN or infinite");
  return out;
}

}  // namespace holoray::python
