// holoray/image, internal: the image module's one loop over every core.
#pragma once

#include <cstddef>

#ifndef HOLORAY_STD_THREADS
#include <tbb/parallel_for.h>
#endif

namespace holoray {

/// fn(k) for k in [0, count), on every core through oneTBB; in order on the
/// calling thread in the ThreadSanitizer build (HOLORAY_STD_THREADS), which
/// sees no oneTBB. fn must not depend on the order.
template <class Fn>
void parallel_each(size_t count, Fn&& fn) {
#ifdef HOLORAY_STD_THREADS
  for (size_t k = 0; k < count; ++k) fn(k);
#else
  tbb::parallel_for(size_t{0}, count, [&](size_t k) { fn(k); });
#endif
}

}  // namespace holoray
