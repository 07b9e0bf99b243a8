// holoray/gpu: the rendered frame (trace.comp's colour and AOV buffers, on
// the device) packed into the 8-bit B8G8R8A8 pixels a window shows
// (gpu/presenter.hpp), one invocation per pixel shown. The colour's codes
// are the ones `holoray render` writes to a PNG: a code is how many of the
// 255 thresholds a value reaches, each threshold the least float that
// image/image_io.cpp's encode_8bit gives that code or more (found on the
// host by bisection), so linear and sRGB alike are exact with no
// transcendental in float; NaN reaches none (code 0), as encode_8bit has it.
#version 460

layout(local_size_x = 16, local_size_y = 16) in;

layout(std430, binding = 0) readonly buffer ColourBlock { float colour[]; };
layout(std430, binding = 1) readonly buffer AovBlock { float aov[]; };
layout(std430, binding = 2) readonly buffer ThresholdBlock { float threshold[255]; };
layout(std430, binding = 3) writeonly buffer PackedBlock { uint packed[]; };

// What is shown (presenter.cpp's PackParams, field for field).
layout(push_constant) uniform Pack {
  ivec2 source;  // the rendered image's width and height
  ivec2 shown;   // the packed image's
  // Shown pixel (x, y) reads source pixel first + (x, y) * step: the whole
  // image (step 1), or one pixel behind each lens (a sub-aperture view:
  // step the lens's pixels, first the pixel's place behind the first lens).
  ivec2 first, step;
  int what;             // 0 colour, 1 albedo, 2 depth, 3 normal, 4 object id
  float depth_scale;    // depth shown as depth_scale / (depth_scale + |t|): near bright
} p;

uint code(float v) {
  uint n = 0;
  // Binary search for the number of thresholds <= v (they ascend).
  for (uint half_ = 128u; half_ > 0u; half_ >>= 1u)
    if (n + half_ <= 255u && threshold[n + half_ - 1u] <= v) n += half_;
  return n;
}

uint pack(vec3 c) { return code(c.z) | (code(c.y) << 8) | (code(c.x) << 16) | (255u << 24); }

// A stable colour per object id, background (-1) black.
vec3 id_colour(float id) {
  if (id < 0.0) return vec3(0.0);
  uint h = uint(id) * 2654435761u;
  h ^= h >> 15;
  return vec3(float(h & 255u), float((h >> 8) & 255u), float((h >> 16) & 255u)) / 255.0 * 0.8 + 0.2;
}

void main() {
  const ivec2 xy = ivec2(gl_GlobalInvocationID.xy);
  if (xy.x >= p.shown.x || xy.y >= p.shown.y) return;
  const ivec2 s = p.first + xy * p.step;
  const uint pixel = uint(s.y) * uint(p.source.x) + uint(s.x);
  vec3 c;
  if (p.what == 0) {
    c = vec3(colour[pixel * 3u], colour[pixel * 3u + 1u], colour[pixel * 3u + 2u]);
  } else {
    const uint a = pixel * 8u;
    if (p.what == 1) c = vec3(aov[a], aov[a + 1u], aov[a + 2u]);
    else if (p.what == 2) c = vec3(isnan(aov[a + 3u]) ? 0.0 : p.depth_scale / (p.depth_scale + abs(aov[a + 3u])));
    else if (p.what == 3) c = vec3(aov[a + 4u], aov[a + 5u], aov[a + 6u]) * 0.5 + 0.5;
    else c = id_colour(aov[a + 7u]);
  }
  packed[uint(xy.y) * uint(p.shown.x) + uint(xy.x)] = pack(c);
}
