// holoray's light-field page (docs/guide/web.md): the sub-aperture views of
// an EIA or the views of a quilt, written by `holoray web` beside this file
// as light_field.json and views.png, looked through in WebGL2.
//
// The state lives in the address's fragment, so that a view can be linked
// and the tests can open it: #u=U&v=V&focus=S&aperture=R&show=view|eia|grid.
// u and v count views as `holoray subaperture --u --v` counts them (u the
// column within the elemental image, v the row); fractions between views
// blend the four nearest (bilinear in u, v), in linear light. focus is the
// shift, in lenses per view, of each view before the views are averaged
// (shift-and-add, as a plenoptic camera refocuses); aperture is the radius,
// in views, of the disc of views averaged around (u, v); 0 shows the one
// view. Once the state in the address is drawn, document.body.dataset.drawn
// holds that fragment; a file that cannot be read sets dataset.error and
// shows why in the page.

const VERTEX = `#version 300 es
void main() {
  vec2 corner = vec2(float((gl_VertexID & 1) << 2), float((gl_VertexID & 2) << 1));
  gl_Position = vec4(corner - 1.0, 0.0, 1.0);
}`;

// Shared by both programs: the atlas fetched as linear RGB (an SRGB8_ALPHA8
// texture), the output encoded as sRGB again.
const COMMON = `#version 300 es
precision highp float;
precision highp int;
precision highp sampler2D;
uniform sampler2D atlas;
out vec4 colour;
vec3 encode(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}
// The pixel drawn, counted from the top row down.
ivec2 pixel(int height) { return ivec2(int(gl_FragCoord.x), height - 1 - int(gl_FragCoord.y)); }
`;

const VIEW_SHADER = COMMON + `
uniform ivec2 viewSize;  // one view's pixels: one per lens
uniform ivec2 views;     // views along u and v
uniform ivec2 tiles;     // the atlas's tiles across and down
uniform int quiltOrder;  // 1: view n at column n % C, row R - 1 - n / C (Looking Glass quilts)
uniform vec2 eye;        // (u, v)
uniform float focus;     // lenses of shift per view
uniform float aperture;  // views

ivec2 tileOf(int a, int b) {
  return quiltOrder == 1 ? ivec2(a % tiles.x, tiles.y - 1 - a / tiles.x) : ivec2(a, b);
}
vec3 texel(int a, int b, ivec2 p) {
  p = clamp(p, ivec2(0), viewSize - 1);
  return texelFetch(atlas, tileOf(a, b) * viewSize + p, 0).rgb;
}
// View (a, b) at q, in pixels (pixel centres at whole numbers), bilinear,
// the edge pixels repeated beyond the view.
vec3 sampleView(int a, int b, vec2 q) {
  vec2 f = floor(q);
  ivec2 i = ivec2(f);
  vec2 w = q - f;
  return mix(mix(texel(a, b, i), texel(a, b, i + ivec2(1, 0)), w.x),
             mix(texel(a, b, i + ivec2(0, 1)), texel(a, b, i + ivec2(1, 1)), w.x), w.y);
}
// The four views around e blended (bilinear in u, v) at pixel p.
vec3 between(vec2 e, ivec2 p) {
  e = clamp(e, vec2(0.0), vec2(views - 1));
  ivec2 e0 = ivec2(floor(e));
  ivec2 e1 = min(e0 + 1, views - 1);
  vec2 w = e - vec2(e0);
  return mix(mix(texel(e0.x, e0.y, p), texel(e1.x, e0.y, p), w.x),
             mix(texel(e0.x, e1.y, p), texel(e1.x, e1.y, p), w.x), w.y);
}
void main() {
  ivec2 p = pixel(viewSize.y);
  vec3 c = vec3(0.0);
  float n = 0.0;
  if (aperture > 0.0) {
    for (int b = 0; b < views.y; ++b)
      for (int a = 0; a < views.x; ++a) {
        vec2 d = vec2(a, b) - eye;
        if (dot(d, d) > aperture * aperture) continue;
        c += sampleView(a, b, vec2(p) + focus * d);
        n += 1.0;
      }
  }
  colour = vec4(encode(n > 0.0 ? c / n : between(eye, p)), 1.0);
}`;

const COPY_SHADER = COMMON + `
uniform int height;
void main() { colour = vec4(encode(texelFetch(atlas, pixel(height), 0).rgb), 1.0); }`;

const page = {
  canvas: document.getElementById("view"),
  message: document.getElementById("message"),
  figures: document.getElementById("figures"),
  focus: document.getElementById("focus"),
  aperture: document.getElementById("aperture"),
  zoom: document.getElementById("zoom"),
};

function fail(text) {
  page.message.textContent = text;
  document.body.dataset.error = text;
  throw new Error(text);
}

// The state in the address, with the manifest's defaults: the middle view
// (P / 2, as `holoray subaperture` takes it), the lens plane in focus, one view.
function readState(field) {
  const q = new URLSearchParams(location.hash.slice(1));
  const number = (name, fallback) => {
    const x = Number.parseFloat(q.get(name));
    return Number.isFinite(x) ? x : fallback;
  };
  const show = q.get("show");
  return {
    u: number("u", Math.floor(field.views[0] / 2)),
    v: number("v", Math.floor(field.views[1] / 2)),
    focus: number("focus", 0),
    aperture: Math.max(0, number("aperture", 0)),
    show: show === "eia" && field.eia_image ? "eia" : show === "grid" ? "grid" : "view",
  };
}

function writeState(s) {
  const hash = `#u=${+s.u.toFixed(3)}&v=${+s.v.toFixed(3)}&focus=${+s.focus.toFixed(3)}&aperture=${+s.aperture.toFixed(2)}&show=${s.show}`;
  history.replaceState(null, "", hash);
}

async function fetchOk(name) {
  let response;
  try {
    response = await fetch(name);
  } catch (e) {
    fail(`${name}: could not be fetched (${e.message})`);
  }
  if (!response.ok) fail(`${name}: the server answered ${response.status} ${response.statusText}`);
  return response;
}

async function loadBitmap(name) {
  const blob = await (await fetchOk(name)).blob();
  try {
    // The file's codes as they are: no colour management, no premultiplication.
    return await createImageBitmap(blob, { colorSpaceConversion: "none", premultiplyAlpha: "none" });
  } catch (e) {
    fail(`${name}: not an image this browser can decode (${e.message || e.name})`);
  }
}

function compile(gl, vertex, fragment) {
  const program = gl.createProgram();
  for (const [type, text] of [[gl.VERTEX_SHADER, vertex], [gl.FRAGMENT_SHADER, fragment]]) {
    const shader = gl.createShader(type);
    gl.shaderSource(shader, text);
    gl.compileShader(shader);
    if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS)) fail(`shader: ${gl.getShaderInfoLog(shader)}`);
    gl.attachShader(program, shader);
  }
  gl.linkProgram(program);
  if (!gl.getProgramParameter(program, gl.LINK_STATUS)) fail(`shader: ${gl.getProgramInfoLog(program)}`);
  return program;
}

function texture(gl, bitmap) {
  const t = gl.createTexture();
  gl.bindTexture(gl.TEXTURE_2D, t);
  gl.pixelStorei(gl.UNPACK_FLIP_Y_WEBGL, false);
  gl.texImage2D(gl.TEXTURE_2D, 0, gl.SRGB8_ALPHA8, gl.RGBA, gl.UNSIGNED_BYTE, bitmap);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
  return t;
}

function checkManifest(f) {
  const pair = (x) => Array.isArray(x) && x.length === 2 && x.every((n) => Number.isInteger(n) && n > 0);
  if (f.format !== "holoray-web 1") fail(`light_field.json: expected "format": "holoray-web 1", got ${JSON.stringify(f.format)}`);
  for (const key of ["views", "view_size", "tiles"])
    if (!pair(f[key])) fail(`light_field.json: "${key}" must be two positive whole numbers, got ${JSON.stringify(f[key])}`);
  if (typeof f.views_image !== "string") fail(`light_field.json: "views_image" must name the views' image`);
}

async function main() {
  const field = await (await fetchOk("light_field.json")).json().catch((e) => fail(`light_field.json: not JSON (${e.message})`));
  checkManifest(field);
  const atlas = await loadBitmap(field.views_image);
  const [tw, th] = [field.tiles[0] * field.view_size[0], field.tiles[1] * field.view_size[1]];
  if (atlas.width !== tw || atlas.height !== th)
    fail(`${field.views_image}: ${atlas.width}x${atlas.height} pixels, but light_field.json describes ${field.tiles[0]}x${field.tiles[1]} views of ${field.view_size[0]}x${field.view_size[1]} (${tw}x${th})`);
  const eia = field.eia_image ? await loadBitmap(field.eia_image) : null;

  const gl = page.canvas.getContext("webgl2", { preserveDrawingBuffer: true, antialias: false, alpha: false });
  if (!gl) fail("this browser has no WebGL2: the page needs it");
  const viewProgram = compile(gl, VERTEX, VIEW_SHADER);
  const copyProgram = compile(gl, VERTEX, COPY_SHADER);
  const atlasTexture = texture(gl, atlas);
  const eiaTexture = eia ? texture(gl, eia) : null;
  gl.bindVertexArray(gl.createVertexArray());

  const lenses = field.kind === "quilt" ? `${field.views[0]} views of ${field.view_size[0]}x${field.view_size[1]} pixels (a quilt)`
    : `${field.lenses[0]}x${field.lenses[1]} lenses (${field.grid}), ${field.pixels_per_lens} pixels per lens, ${field.views[0]}x${field.views[1]} views`;
  page.figures.textContent = `${field.name}: ${lenses}`;
  page.aperture.max = String(Math.max(field.views[0], field.views[1]));

  let state = readState(field);
  const draw = () => {
    const s = state;
    const [w, h] = s.show === "eia" ? [eia.width, eia.height] : s.show === "grid" ? [tw, th] : field.view_size;
    page.canvas.width = w, page.canvas.height = h;
    page.canvas.classList.toggle("zoomed", s.show !== "view" || Number(page.zoom.value) > 1);
    page.canvas.style.width = page.canvas.classList.contains("zoomed") ? `${w * Number(page.zoom.value)}px` : "";
    gl.viewport(0, 0, w, h);
    if (s.show === "view") {
      gl.useProgram(viewProgram);
      gl.bindTexture(gl.TEXTURE_2D, atlasTexture);
      const at = (name) => gl.getUniformLocation(viewProgram, name);
      gl.uniform2i(at("viewSize"), ...field.view_size);
      gl.uniform2i(at("views"), ...field.views);
      gl.uniform2i(at("tiles"), ...field.tiles);
      gl.uniform1i(at("quiltOrder"), field.tile_order === "quilt" ? 1 : 0);
      gl.uniform2f(at("eye"), s.u, s.v);
      gl.uniform1f(at("focus"), s.focus);
      gl.uniform1f(at("aperture"), s.aperture);
    } else {
      gl.useProgram(copyProgram);
      gl.bindTexture(gl.TEXTURE_2D, s.show === "eia" ? eiaTexture : atlasTexture);
      gl.uniform1i(gl.getUniformLocation(copyProgram, "height"), h);
    }
    gl.drawArrays(gl.TRIANGLES, 0, 3);
    page.focus.value = String(s.focus), page.aperture.value = String(s.aperture);
    document.getElementById("focus-value").textContent = s.focus.toFixed(2);
    document.getElementById("aperture-value").textContent = s.aperture.toFixed(1);
    for (const b of document.querySelectorAll("button[data-show]")) b.setAttribute("aria-pressed", String(b.dataset.show === s.show));
    document.body.dataset.drawn = location.hash;
  };
  const change = (fields) => {
    state = { ...state, ...fields };
    writeState(state);
    draw();
  };

  // Parallax: the pointer (or a touch) across the view moves the eye across
  // the array's aperture; a device's tilt does the same.
  page.canvas.addEventListener("pointermove", (e) => {
    if (state.show !== "view") return;
    const r = page.canvas.getBoundingClientRect();
    const fx = Math.min(1, Math.max(0, (e.clientX - r.left) / r.width));
    const fy = Math.min(1, Math.max(0, (e.clientY - r.top) / r.height));
    change({ u: fx * (field.views[0] - 1), v: fy * (field.views[1] - 1) });
  });
  window.addEventListener("deviceorientation", (e) => {
    if (state.show !== "view" || e.gamma === null || e.beta === null) return;
    const t = (deg) => Math.min(1, Math.max(0, 0.5 + deg / 60));
    change({ u: t(e.gamma) * (field.views[0] - 1), v: t(e.beta - 45) * (field.views[1] - 1) });
  });
  page.focus.addEventListener("input", () => change({ focus: Number(page.focus.value) }));
  page.aperture.addEventListener("input", () => change({ aperture: Number(page.aperture.value) }));
  page.zoom.addEventListener("input", draw);
  for (const b of document.querySelectorAll("button[data-show]"))
    b.addEventListener("click", () => change({ show: b.dataset.show === "eia" && !eia ? "view" : b.dataset.show }));
  window.addEventListener("hashchange", () => {
    state = readState(field);
    draw();
  });
  draw();
}

main().catch((e) => {
  if (!document.body.dataset.error) {
    page.message.textContent = e.message;
    document.body.dataset.error = e.message;
  }
});
