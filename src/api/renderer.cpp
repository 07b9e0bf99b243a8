// The orchestration of one still, once for every front end: the options
// checked, the camera placed by the viewpoint, the buffers checked against
// memory, the scene built, then rendered whole or in bands.
#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "api/gpu_executor.hpp"
#include "api/internal.hpp"
#include "api/light_options.hpp"
#include "api/renderer_state.hpp"
#include "api/world_state.hpp"
#include "holoray/errors.hpp"
#include "holoray/render.hpp"
#include "render/render_context.hpp"
#include "render/emitters.hpp"
#include "render/environment.hpp"
#include "render/renderer.hpp"
#include "render/shadow_cache.hpp"
#include "render/view_sharing.hpp"
#include "holoray/stopwatch.hpp"

namespace holoray::api {

namespace {

AovSet aov_set(const Aovs& a) { return {a.albedo, a.depth, a.normal, a.id}; }

TraceStyle trace_style(Style s, const FrameCamera& camera) {
  switch (s) {
    case Style::packet: return TraceStyle::packet;
    case Style::subaperture: return TraceStyle::subaperture;
    case Style::horizontal: return TraceStyle::horizontal;
    case Style::vertical: return TraceStyle::vertical;
    case Style::automatic: break;
  }
  const holoray::LensArray* array = camera.lens_array();
  return array ? preferred_style(array->desc()) : TraceStyle::packet;
}

void check_options(const RenderOptions& o) {
  if (o.spp < 1) throw std::invalid_argument(fmt::format("spp: expected at least 1 sample per pixel, got {}", o.spp));
  if (o.threads < 0) throw std::invalid_argument(fmt::format("threads: expected 0 (all cores) or more, got {}", o.threads));
  static_assert(kMaxDepth == kDepthCap, "the API's depth limit is the renderer's");
  static_assert(kMaxShareViews == kMaxSharedViews, "the API's sharing limit is the renderer's");
  parse_device(o.device);
  if (o.max_depth < 0 || o.max_depth > kDepthCap)
    throw std::invalid_argument(fmt::format("max_depth: expected 1 to {} (0: the scene's), got {}", kDepthCap, o.max_depth));
  if (!(o.cache.cell > 0) || !std::isfinite(o.cache.cell))
    throw std::invalid_argument(fmt::format("cache cell: must be a positive number of lens pitches, got {}", o.cache.cell));
  if (!(o.cache.memory_mib >= 0) || !std::isfinite(o.cache.memory_mib))
    throw std::invalid_argument(fmt::format("cache memory: must be 0 MiB or more, got {}", o.cache.memory_mib));
  check_light(o.integrator, o.environment, o.cache.enabled);
  if (o.share_views < 0 || o.share_views > kMaxShareViews)
    throw std::invalid_argument(fmt::format("share_views: expected 0 to {} views on each side, got {}", kMaxShareViews, o.share_views));
  if (o.share_views > 0 && o.integrator != Integrator::path)
    throw std::invalid_argument("share_views: views share path samples: go with the path integrator");
  if (o.share_views > 0 && parse_device(o.device).gpu)
    throw std::invalid_argument("share_views: views share their samples on the CPU only");
  if (o.seed != 0 && o.integrator != Integrator::path)
    throw std::invalid_argument("seed: Whitted's integrator draws no random samples: go with the path integrator");
}

// A mesh file's camera, and where the focal plane stands when the file
// gives no point looked at (docs/guide/scenes.md, "File cameras").
std::string describe_viewpoint(const FrameCameraDesc& choice, const std::optional<Viewpoint>& vp) {
  if (!vp || vp->camera.empty()) return "";
  static constexpr const char* axis[] = {"vertical", "horizontal", "on the larger side"};
  std::string out = fmt::format("camera     '{}' from the file, ", vp->camera);
  if (vp->ortho_size > 0) out += fmt::format("orthographic, {:.6g} units {}", vp->ortho_size, axis[int(vp->fov_axis)]);
  else out += fmt::format("{:.4g} deg {}", vp->angle_deg, axis[int(vp->fov_axis)]);
  const bool pinhole = choice.get<FrameCameraDesc::Pinhole>() != nullptr;
  if (pinhole && (vp->clip_near > 0 || vp->clip_far < INFINITY))
    out += fmt::format("; sees {:.6g} to {:.6g} along its axis (the file's clipping)", vp->clip_near, vp->clip_far);
  if (!pinhole && !choice.placed_explicitly()) {  // an explicit placement has no focal plane of the camera's
    const double distance = choice.focus_distance.value_or(length(vp->at - vp->from));
    out += fmt::format("; focal plane {:.6g} from the eye ({})", distance,
                       choice.focus_distance ? "focus distance given" : "the depth of the scene's centre");
  }
  return out + "\n";
}

// The CLI's summary of the camera (docs/guide/stills.md shows it).
std::string describe_camera(const FrameCameraDesc& choice, const FrameCamera& camera, const Camera& public_camera) {
  const int width = camera.width(), height = camera.height();
  if (const auto* glass = camera.get<LookingGlassCamera>())
    return fmt::format("panel      {}x{} px, Looking Glass ({}): RGB subpixels, each along its lenticule's view, view cone {:.4g} deg\n",
                       width, height, std::get<LookingGlass>(public_camera).path, glass->calibration().view_cone_deg);
  if (const auto* quilt = camera.get<QuiltCamera>()) {
    const QuiltDesc& q = quilt->desc();
    return fmt::format("quilt      {}x{} px: {}x{} views of {}x{} px, view cone {:.4g} deg, sheared frusta on the viewpoint's focal plane\n",
                       width, height, q.columns, q.rows, q.view_width, q.view_height, q.view_cone_deg);
  }
  if (const auto* quilt_view = choice.get<FrameCameraDesc::Quilt>()) {
    const QuiltDesc& q = quilt_view->layout;
    return fmt::format("view       {}x{} px, quilt view {} of {}x{} (view cone {:.4g} deg)\n", width, height, quilt_view->view,
                       q.columns, q.rows, q.view_cone_deg);
  }
  if (const auto* view = camera.get<PinholeCamera>())
    return view->desc().ortho_height > 0
               ? fmt::format("view       {}x{} px, orthographic, {:.6g} units tall (the scene's viewpoint)\n", width, height,
                             view->desc().ortho_height)
               : fmt::format("view       {}x{} px, pinhole, field of view {:.4g} deg (the scene's viewpoint)\n", width, height,
                             view->desc().fov_deg);
  if (const auto* panel = camera.get<PanelView>()) {
    const DisplayDesc& d = choice.get<FrameCameraDesc::Display>()->display;
    const DisplayGeometry& g = panel->camera.geometry();
    return fmt::format("panel      {}x{} px, {} ({} per pixel), {} grid{}, {}\n", width, height,
                       d.subpixels == SubpixelOrder::none ? "whole pixels" : fmt::format("{} subpixels", to_string(d.subpixels)),
                       d.samples_per_pixel() == 1 ? "one line" : "three lines", to_string(d.grid),
                       d.slant_deg != 0 ? fmt::format(" slanted {:.4g} deg", d.slant_deg) : "", to_string(d.mode)) +
           fmt::format("lenses     pitch {:.6g} mm ({:.6g} px across a row), gap {:.6g} mm; {:.6g} scene units per mm\n",
                       d.pitch_mm, d.pixels_per_lens(), d.gap_mm, g.pixel_pitch / d.pixel_pitch_mm);
  }
  std::string out;
  if (choice.get<FrameCameraDesc::Display>())
    out += fmt::format("display    {}: whole pixels per lens, rendered as the EIA below\n", std::get<Display>(public_camera).path);
  const holoray::LensArray& a = *camera.lens_array();
  const LensArrayDesc& d = a.desc();
  out += fmt::format("EIA        {}x{} px, {} grid, {}x{} lenses x {} px, {}\n", width, height, to_string(d.grid), a.lens_count_x(),
                     a.lens_count_y(), d.pixels_per_lens, to_string(d.mode));
  out += fmt::format("lenses     pitch {:.6g}, gap {:.6g}, field of view {:.4g} deg\n", d.pitch, d.gap, a.lens_fov_deg());
  return out;
}

}  // namespace

RendererState& detail::RendererAccess::state(const Renderer& r) { return *r.state_; }


namespace {

// The camera placed on `desc`'s viewpoint and checked against the options
// and this machine's memory: what a Renderer does before anything is built.
void place_camera(RendererState& s, const SceneDesc& desc, const Camera& camera, const RenderOptions& options) {
  s.public_camera = camera;
  s.choice = frame_camera_desc(camera);
  const auto* pinhole = s.choice.get<FrameCameraDesc::Pinhole>();
  if (pinhole && pinhole->tachyon_samples && options.spp != 1)
    throw std::invalid_argument("tachyon samples: go with the pinhole camera and one sample per pixel");
  if (desc.source.empty() && !desc.viewpoint && !s.choice.placed_explicitly())
    throw std::invalid_argument("camera: the scene has no viewpoint to place it by: call set_viewpoint(), or place the lens array explicitly");
  s.placed = make_frame_camera(s.choice, desc.viewpoint, desc.source.empty() ? "the scene" : desc.source);
  const Aovs& a = options.aovs;
  const FrameCamera& frame_camera = s.camera();
  const holoray::LensArray* array_camera = frame_camera.lens_array();
  if ((frame_camera.get<PanelView>() || frame_camera.get<LookingGlassCamera>()) && (a.albedo || a.depth || a.normal || a.id))
    throw std::invalid_argument("aovs: not written for native panel images yet (colour only)");
  if (options.share_views > 0 && !frame_camera.get<QuiltCamera>())
    throw std::invalid_argument("share_views: goes with a quilt, whose views share their samples");
  if (options.cache.enabled && !array_camera)
    throw std::invalid_argument("`cache`: goes with the integral camera (its cells are sized in lens pitches)");

  // Refused before anything is allocated: the frame and its AOVs, the 8-bit
  // or float copy made on output, and a panel's samples (three per pixel
  // with subpixels), for the rows this process holds.
  const int width = frame_camera.width(), height = frame_camera.height();
  const MemoryShare share = options.memory_share ? options.memory_share(height, array_camera ? array_camera->desc().pixels_per_lens : 32)
                                                 : MemoryShare{height, height, ""};
  const int64_t held = share.held_rows, copied = share.copied_rows;
  const int64_t samples = static_cast<int64_t>(frame_camera.panel_samples_per_row()) * held;
  const AovSet aovs = aov_set(a);
  const uint64_t need = frame_bytes(held * width, aovs) + static_cast<uint64_t>(copied * width) * 12 + frame_bytes(samples, aovs) +
                        (options.share_views > 0 ? shared_views_bytes(int64_t{width} * height) : 0);
  const uint64_t have = physical_memory_bytes();
  if (have && need > have / 10 * 8)
    throw std::length_error(fmt::format("a {}x{} image needs {:.2f} GiB of buffers{}, more than 80% of this machine's {:.2f} GiB",
                                        width, height, need / 1073741824.0,
                                        share.where,
                                        have / 1073741824.0));
}

bool same_environment(const Environment& a, const Environment& b) {
  return a.file == b.file && a.colour == b.colour && a.strength == b.strength && a.rotation_deg == b.rotation_deg;
}

// A render's options on a World: its light options are the world's. Each
// left at its default takes the world's; one given otherwise is refused.
RenderOptions on_world(const WorldState& w, RenderOptions o) {
  const RenderOptions defaults;
  auto take = [](auto& field, const auto& world_value, const auto& default_value, bool same, const char* name) {
    if (!same && !(field == default_value))
      throw std::invalid_argument(fmt::format("{}: the world was built with other light options: build a World with these, "
                                              "or leave it at its default to take the world's", name));
    field = world_value;
  };
  take(o.integrator, w.integrator, defaults.integrator, o.integrator == w.integrator, "integrator");
  if (!same_environment(o.environment, w.environment_options) && !same_environment(o.environment, defaults.environment))
    throw std::invalid_argument("environment: the world was built with other light options: build a World with these, "
                                "or leave it at its default to take the world's");
  o.environment = w.environment_options;
  take(o.blender_principled, w.blender_principled, defaults.blender_principled, o.blender_principled == w.blender_principled,
       "blender_principled");
  take(o.max_depth, w.max_depth, defaults.max_depth, o.max_depth == w.max_depth, "max_depth");
  return o;
}

}  // namespace

void check_camera(const World& world, const Camera& camera, const RenderOptions& options) {
  const WorldState& w = *detail::WorldAccess::state(world);
  const RenderOptions o = on_world(w, options);
  check_options(o);
  RendererState scratch;
  place_camera(scratch, w.scene->desc, camera, o);
}

Renderer::Renderer(const Scene& scene, const Camera& camera, const RenderOptions& options)
    : state_(std::make_unique<RendererState>()) {
  const auto t_build = Clock::now();
  check_options(options);
  place_camera(*state_, scene.data()->desc, camera, options);
  set_up(World(scene, options), options, t_build, false);
}

Renderer::Renderer(const World& world, const Camera& camera, const RenderOptions& options)
    : state_(std::make_unique<RendererState>()) {
  const auto t_build = Clock::now();
  const RenderOptions o = on_world(*detail::WorldAccess::state(world), options);
  check_options(o);
  place_camera(*state_, detail::WorldAccess::state(world)->scene->desc, camera, o);
  set_up(world, o, t_build, true);
}

void Renderer::set_up(const World& world, const RenderOptions& options, Clock::time_point t_build, bool shared) {
  RendererState& s = *state_;
  s.options = options;
  s.world = detail::WorldAccess::state(world);
  const RenderScene& scene = *s.world->render_scene;
  s.settings = s.world->settings;
  s.settings.sample_salt = options.seed;
  const FrameCamera& frame_camera = s.camera();
  const DeviceChoice device = parse_device(options.device);
  // Embree's hierarchy is the CPU path's (built once for all the world's
  // renderers, here so that build_seconds counts it): a GPU render builds
  // only its own.
  if (!device.gpu) scene.accel().build();
  // Mesh textures take the MIP level of what one pixel sees.
  if (const auto angle = frame_camera.pixel_angle()) s.settings.footprint = {0, *angle};
  if (options.cache.enabled) {
    holoray::ShadowCacheOptions co;
    co.cell_size = options.cache.cell * frame_camera.lens_array()->desc().pitch;
    co.memory_limit_bytes = static_cast<uint64_t>(options.cache.memory_mib * 1048576.0);
    s.cache = std::make_unique<ShadowCache>(scene, co);
    s.settings.shadow_cache = s.cache.get();
  }
  s.style = trace_style(options.style, frame_camera);
  if (device.gpu)
    s.gpu = std::make_unique<GpuExecutor>(device, RenderContext(scene, s.settings), frame_camera, options,
                                          shared ? s.world->gpu_layouts.get() : nullptr);
  s.build.build_seconds = seconds_since(t_build);
  s.build.gpu_setup_seconds = s.gpu ? s.gpu->setup_seconds() : 0;
}

Renderer::~Renderer() = default;
Renderer::Renderer(Renderer&&) noexcept = default;
Renderer& Renderer::operator=(Renderer&&) noexcept = default;

int Renderer::width() const { return state_->camera().width(); }
int Renderer::height() const { return state_->camera().height(); }
int Renderer::band_rows() const {
  const holoray::LensArray* array = state_->camera().lens_array();
  return array ? array->desc().pixels_per_lens : 32;
}
size_t Renderer::skipped_polygons() const { return state_->world->render_scene->skipped_polygons(); }
const RenderStats& Renderer::build_stats() const { return state_->build; }

std::string Renderer::describe() const {
  return describe_viewpoint(state_->choice, state_->world->scene->desc.viewpoint) +
         describe_camera(state_->choice, state_->camera(), state_->public_camera);
}

const char* Renderer::style_name() const { return to_string(state_->style); }

std::string Renderer::device_name() const { return state_->gpu ? state_->gpu->name() : ""; }

Result Renderer::render(std::optional<std::array<int, 2>> rows) const {
  const RendererState& s = *state_;
  const std::stop_token stop = s.options.stop;
  if (stop.stop_requested()) throw Cancelled();
  holoray::RenderOptions ro;
  ro.spp = s.options.spp;
  ro.threads = s.options.threads;
  ro.aovs = aov_set(s.options.aovs);
  ro.style = s.style;
  ro.rows = rows;
  ro.share_views = s.options.share_views;
  const std::function<void(double)>& progress = s.options.progress;
  // Called after each tile: a stop request ends the render there (the
  // tile schedule rethrows on the calling thread once every worker is out).
  if (progress || stop.stop_possible())
    ro.progress = [&](double f) {
      if (stop.stop_requested()) throw Cancelled();
      if (progress) progress(f);
    };
  holoray::RenderStats st;
  RenderStats on_gpu;
  const RenderContext context(*s.world->render_scene, s.settings);
  FrameBuffers fb = s.gpu ? s.gpu->render(context, s.camera(), ro.aovs, ro.spp, rows, on_gpu)
                          : render_through(context, s.camera(), ro, st);
  Result out;
  out.colour = detail::ImageAccess::wrap(std::move(fb.colour));
  if (!fb.albedo.empty()) out.albedo = detail::ImageAccess::wrap(std::move(fb.albedo));
  if (!fb.depth.empty()) out.depth = detail::ImageAccess::wrap(std::move(fb.depth));
  if (!fb.normal.empty()) out.normal = detail::ImageAccess::wrap(std::move(fb.normal));
  if (!fb.id.empty()) out.id = detail::ImageAccess::wrap(std::move(fb.id));
  if (s.gpu) {
    out.stats = on_gpu;
  } else {
    out.stats.rays = to_api(st.rays);
    out.stats.trace_seconds = st.trace_seconds;
  }
  out.stats.build_seconds = s.build.build_seconds;
  out.stats.gpu_setup_seconds = s.build.gpu_setup_seconds;
  if (s.cache) {
    const ShadowCache& cache = *s.cache;
    const holoray::RayCounts& r = st.rays;
    const double q = static_cast<double>(std::max<uint64_t>(1, r.shadow_queries()));
    const auto& cells = cache.cells();
    out.cache_summary = fmt::format(
        "cache      {} cells of {:.4g} units, {:.1f} MiB (bound {:g} MiB){}; shadow queries {}: {:.1f}% by cells, "
        "{:.1f}% traced; {} sample rays\n",
        cells.slot_count(), cells.cell_size(), cache.bytes() / 1048576.0, s.options.cache.memory_mib,
        cells.uncovered_primitives() ? fmt::format(", {} primitives uncovered", cells.uncovered_primitives()) : "",
        r.shadow_queries(), 100.0 * r.shadow_cached / q, 100.0 * r.shadow / q, r.cache_samples);
  }
  return out;
}

Result render(const Scene& scene, const Camera& camera, const RenderOptions& options) {
  return Renderer(scene, camera, options).render();
}

uint64_t physical_memory_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page > 0 ? static_cast<uint64_t>(pages) * static_cast<uint64_t>(page) : 0;
}

api::RayCounts to_api(const holoray::RayCounts& r) {
  return {r.eye, r.shadow, r.reflected, r.refracted, r.shadow_cached, r.cache_samples};
}


}  // namespace holoray::api
