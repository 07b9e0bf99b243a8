// holoray/render: the records the path integrator (render/path_integrator.h)
// reads a scene's lights through, one text for both devices: each device's
// hooks fill them from its own storage (the CPU's RenderScene, the GPU's
// buffers), and the integrator samples them the same way. hr_real and
// hr_vec3 are double and Vec3 on the CPU (render/path_compat.hpp), float on
// the GPU. World frame; units as docs/lights.md gives them.
#ifndef HOLORAY_RENDER_PATH_RECORDS_H
#define HOLORAY_RENDER_PATH_RECORDS_H

#include "shading/bsdf.h"
#include "shading/lights.h"
#include "shading/sampler.h"

#ifdef __cplusplus
#include "render/path_compat.hpp"
#else
#ifndef hr_real
#define hr_real float
#define hr_vec3 vec3
#endif
#define hr_d3(v) (v)
#define hr_f3(v) (v)
#define hr_mul3(a, b) ((a) * (b))
#define HR_PATH_INF uintBitsToFloat(0x7f800000u)
#define HR_PATH_PI 3.141592653589793
#endif

// The rays the integrator counts (its hook hr_path_count).
#define HR_PATH_RAY_SHADOW 1
#define HR_PATH_RAY_REFLECTED 2
#define HR_PATH_RAY_REFRACTED 3

HR_BEGIN

/// Whether a colour has any light in it (NaN counts as none).
HR_FN bool hr_path_positive(vec3 c) { return c.x > 0.0f || c.y > 0.0f || c.z > 0.0f; }

/// A point, spot or directional light (render_scene.hpp, PointLight).
/// `intensity` is its colour (the radiance a white Lambertian surface
/// facing it shows at unit falloff); `direction` where its light travels;
/// `cos_half_angle` a directional light's disc (1: a delta light);
/// `radius` a point or spot light's sphere (0: a delta light); `skip` a
/// headlight the render leaves out.
struct HrPathLight {
  int kind;  ///< HR_LIGHT_KIND_*
  hr_vec3 position, direction, intensity;
  hr_real cos_half_angle, radius;
  HrLightFalloff falloff;
  bool skip;
};

/// An area light (scene_desc.hpp, AreaLight): a rectangle (or the ellipse
/// inscribed in it) of centre `centre`, half-extent axes `axis_u`,
/// `axis_v`, lighting the side its unit `normal` faces with radiance
/// `radiance`; `area` its area.
struct HrPathAreaLight {
  hr_vec3 centre, axis_u, axis_v, normal, radiance;
  hr_real area;
  bool ellipse;
};

/// A path's vertex: where it is (`p`), its geometric normal turned to the
/// side the path came from (`ng`), the points just above and below it that
/// its rays leave from, its shading frame (t, b, n: n the shading normal
/// on the path's side), the direction back along the path in that frame
/// (`wo`) and its BSDF.
struct HrPathVertex {
  hr_vec3 p, ng, above, below;
  vec3 t, b, n, wo;
  HrBsdf bsdf;
};

/// A path between its vertices (hr_path_start, hr_path_step): the ray it
/// traces next (world; t over (tmin, tmax)), the light it has gathered, the
/// fraction of what it meets next that reaches the eye (`throughput`), and
/// how it got here: whether its last bounce was a delta lobe (`specular`:
/// no MIS on what it meets), that bounce's density (`last_pdf`) and the
/// vertex it meets next (`depth`, the eye ray's 1). Plain data: a wavefront
/// keeps it in device memory between its stages (gpu/shaders/wavefront.glsl).
struct HrPathState {
  hr_vec3 o, dir;
  hr_real tmin, tmax;
  hr_vec3 radiance, throughput;
  bool specular;
  float last_pdf;
  int depth;
};

HR_END

#endif
