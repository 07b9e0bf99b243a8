// holoray public API: symbol visibility. The library is built with hidden
// symbols; only what these headers declare is exported from libholoray.so.
#pragma once

#if defined(HOLORAY_BUILDING_API)
#define HOLORAY_API __attribute__((visibility("default")))
#else
#define HOLORAY_API
#endif
