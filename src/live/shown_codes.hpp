// holoray/live: the 8-bit codes a window shows, exactly those `holoray
// render` writes to a PNG (image_io.hpp's encode_8bit), and back.
#pragma once

#include <cstdint>
#include <vector>

#include "gpu/presenter.hpp"
#include "image/image.hpp"
#include "image/image_io.hpp"

namespace holoray::live {

/// threshold[k]: the least float whose code under `encoding` is k + 1 or
/// more, found by bisection over the floats in [0, 1] (encode_8bit rises
/// with its value, 0 at 0 and 255 at 1, NaN 0).
gpu::CodeThresholds code_thresholds(Encoding encoding);

/// An RGB image whose encode_8bit codes under the thresholds' encoding are
/// `rgb` (width x height x 3 codes): code k > 0 as threshold[k - 1], 0 as
/// 0. Written as a PNG with that encoding, its bytes are `rgb`.
ImageBuffer image_of_codes(const std::vector<uint8_t>& rgb, int width, int height, const gpu::CodeThresholds& thresholds);

}  // namespace holoray::live
