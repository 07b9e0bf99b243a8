// A sweep over pixels per lens with holoray's C++ API: one scene, read and
// built once (a World); for each P an EIA of the same array width, its centre sub-aperture
// view's share of scene pixels, and the time. Writes eia_P.png.
//
//   sweep_pitch SCENE.nff [OUT_DIR]
#include <holoray/holoray.hpp>

#include <cmath>
#include <cstdio>
#include <string>

namespace api = holoray::api;

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s SCENE [OUT_DIR]\n", argv[0]);
    return 2;
  }
  const std::string out = argc > 2 ? argv[2] : ".";
  try {
    const api::World world(api::Scene::load(argv[1]));
    std::printf("built in %.3f s\n", world.build_seconds());
    for (int p : {4, 6, 8}) {
      api::LensArray array;
      array.lenses_x = array.lenses_y = 96 / p;  // the same image width in pixels
      array.pixels_per_lens = p;
      api::RenderOptions options;
      options.aovs.depth = true;
      const api::Result r = api::Renderer(world, array, options).render();
      // Pixels of the centre sub-aperture view that see the scene.
      int seen = 0, views = 0;
      for (int y = p / 2; y < r.depth.height(); y += p)
        for (int x = p / 2; x < r.depth.width(); x += p, ++views) seen += std::isfinite(*r.depth.at(x, y));
      const std::string file = out + "/eia_" + std::to_string(p) + ".png";
      api::write_image(file, r.colour);
      std::printf("P %d: %dx%d px, %d of %d lenses see the scene at their centre, traced in %.3f s, %s\n", p,
                  r.colour.width(), r.colour.height(), seen, views, r.stats.trace_seconds, file.c_str());
    }
  } catch (const api::SceneError& e) {
    std::fprintf(stderr, "%s\n", e.what());  // file:line:col, the line and a caret
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sweep_pitch: %s\n", e.what());
    return 1;
  }
  return 0;
}
