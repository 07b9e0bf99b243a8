// holoray/render: the path integrator (RenderSettings::integrator = path):
// unidirectional path tracing with next-event estimation and multiple
// importance sampling (Veach 1997, ch. 9; pbrt-v4's PathIntegrator), Russian
// roulette after the third bounce, on the CPU over Embree. What it computes
// per vertex (the BSDF, its sampling, the lights' falloff, the
// environment's mapping, the sampler) is the shared shading/ headers, the
// same text the GPU kernels compile.
//
// Light it sees: the scene's point, spot and directional lights (delta
// lights, sampled every vertex), the environment (RenderSettings::
// environment, importance-sampled and MIS-weighted against the BSDF; the
// scene's background colour when none is given), and emissive surfaces
// (glTF emission, Tachyon's light spheres), reached by the BSDF's rays.
#pragma once

#include <cstdint>

#include "render/ray_counts.hpp"
#include "render/render_context.hpp"
#include "shading/sampler.h"

namespace holoray {

/// Radiance (linear RGB) arriving along `ray` (world; the eye ray of a
/// pixel sample), its random numbers from `sampler` (its first pair is the
/// caller's: the pixel position). `first` (optional) gets the first hit's
/// surface and `first_t` its distance along the ray; `hit_found` says
/// whether there was one. Counts its rays into `counts`.
Vec3 path_radiance(const RenderContext& scene, const Ray& ray, shading::HrSampler& sampler, RayCounts& counts,
                   SurfacePoint* first = nullptr, Hit* first_hit = nullptr, bool* hit_found = nullptr);

/// What a ray that left the scene sees under the path integrator: the
/// environment along `dir` (world, unit), else the background colour.
Vec3 path_escape(const RenderContext& scene, const Vec3& dir);

}  // namespace holoray
