// holoray/accel: Embree 3 and Embree 4 behind one set of calls. The two
// major versions differ, for what holoray uses, only in how a query is
// called: Embree 3 takes an RTCIntersectContext before the ray, Embree 4 an
// optional RTCIntersectArguments / RTCOccludedArguments after it, and the
// coherence hint moved from the context's flags to the arguments' flags.
// Rays, hits, packets, geometry, user-geometry and filter callbacks keep
// their layouts and names (the user-geometry callbacks' `context->instID`
// included), so everything else in accel/ is written once against these.
// HOLORAY_EMBREE_MAJOR (3 or 4) comes from the build: the version CMake found.
#pragma once

#if HOLORAY_EMBREE_MAJOR >= 4
#include <embree4/rtcore.h>
#else
#include <embree3/rtcore.h>
#endif

namespace holoray::embree {

#if HOLORAY_EMBREE_MAJOR >= 4

inline RTCIntersectArguments intersect_args(bool coherent) {
  RTCIntersectArguments a;
  rtcInitIntersectArguments(&a);
  a.flags = coherent ? RTC_RAY_QUERY_FLAG_COHERENT : RTC_RAY_QUERY_FLAG_INCOHERENT;
  return a;
}
inline RTCOccludedArguments occluded_args(bool coherent) {
  RTCOccludedArguments a;
  rtcInitOccludedArguments(&a);
  a.flags = coherent ? RTC_RAY_QUERY_FLAG_COHERENT : RTC_RAY_QUERY_FLAG_INCOHERENT;
  return a;
}

/// Nearest hit of one ray (rtcIntersect1); `coherent`: Embree's coherent traversal.
inline void intersect1(RTCScene scene, RTCRayHit& rh, bool coherent) {
  RTCIntersectArguments a = intersect_args(coherent);
  rtcIntersect1(scene, &rh, &a);
}
/// Any hit of one ray (rtcOccluded1): tfar becomes -infinity when blocked.
inline void occluded1(RTCScene scene, RTCRay& ray, bool coherent) {
  RTCOccludedArguments a = occluded_args(coherent);
  rtcOccluded1(scene, &ray, &a);
}
/// rtcIntersect16 over the lanes whose valid[k] is -1.
inline void intersect16(const int* valid, RTCScene scene, RTCRayHit16& rh, bool coherent) {
  RTCIntersectArguments a = intersect_args(coherent);
  rtcIntersect16(valid, scene, &rh, &a);
}
/// rtcOccluded16 over the lanes whose valid[k] is -1.
inline void occluded16(const int* valid, RTCScene scene, RTCRay16& ray, bool coherent) {
  RTCOccludedArguments a = occluded_args(coherent);
  rtcOccluded16(valid, scene, &ray, &a);
}

#else

inline RTCIntersectContext context(bool coherent) {
  RTCIntersectContext c;
  rtcInitIntersectContext(&c);
  if (coherent) c.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  return c;
}

inline void intersect1(RTCScene scene, RTCRayHit& rh, bool coherent) {
  RTCIntersectContext c = context(coherent);
  rtcIntersect1(scene, &c, &rh);
}
inline void occluded1(RTCScene scene, RTCRay& ray, bool coherent) {
  RTCIntersectContext c = context(coherent);
  rtcOccluded1(scene, &c, &ray);
}
inline void intersect16(const int* valid, RTCScene scene, RTCRayHit16& rh, bool coherent) {
  RTCIntersectContext c = context(coherent);
  rtcIntersect16(valid, scene, &c, &rh);
}
inline void occluded16(const int* valid, RTCScene scene, RTCRay16& ray, bool coherent) {
  RTCIntersectContext c = context(coherent);
  rtcOccluded16(valid, scene, &c, &ray);
}

#endif

}  // namespace holoray::embree
