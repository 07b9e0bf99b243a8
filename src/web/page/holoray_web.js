// holoray's light-field page (docs/guide/web.md): the sub-aperture views of
// an EIA or the views of a quilt, written by `holoray web` beside this file
// as light_field.json and views.png (an animation: views_NNNN.png, played in
// a loop), looked through in WebGL2.
//
// The state lives in the address's fragment, so that a view can be linked
// and the tests can open it: #u=U&v=V&focus=S&aperture=R&show=view|eia|grid
// (&frame=K: an animation held at frame K).
// u and v count views as `holoray subaperture --u --v` counts them (u the
// column within the elemental image, v the row); fractions between views
// blend the four nearest (bilinear in u, v), in linear light. focus is the
// shift, in lenses per view, of each view before the views are averaged
// (shift-and-add, as a plenoptic camera refocuses); aperture is the radius,
// in views, of the disc of views averaged around (u, v); 0 shows the one
// view. show=looking-glass (a quilt with a Looking Glass's calibration,
// given at export or loaded in the page) draws the device's native image,
// one canvas pixel per panel pixel, interlaced as `holoray interlace` does:
// the window the page's button opens, to be moved to the device's screen and
// made full screen (double-click). Once the state in the address is drawn, document.body.dataset.drawn
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
// the edge pixels repeated beyond the view: one filtered read (in linear
// light: the texture is sRGB), q clamped to the view's edge pixels so that
// the filter never reaches the next tile.
vec3 sampleView(int a, int b, vec2 q) {
  q = clamp(q, vec2(0.0), vec2(viewSize - 1));
  return texture(atlas, (vec2(tileOf(a, b) * viewSize) + q + 0.5) / vec2(textureSize(atlas, 0))).rgb;
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

// A Looking Glass's native image from the quilt and the device's
// calibration, as the device's own shader interlaces it and as
// display/looking_glass.cpp's interlace_quilt does: each subpixel's view
// from the lenticular's phase, the two views around it blended. The quilt
// is read as codes (no sRGB decoding: the device shader blends codes),
// filtered, repeating.
const LOOKING_GLASS_SHADER = `#version 300 es
precision highp float;
precision highp int;
precision highp sampler2D;
uniform sampler2D quilt;
uniform ivec2 screen;
uniform int columns, rows;
uniform float lenticules, tilt, center;  // computed in double (the page's script): the shader's atan and cos are not exact enough
uniform bool flipX;
uniform int cellPattern, cellCount;
uniform vec2 cells[30];  // subpixel s of cell k: cells[3 k + s], (dx, dy) in pixels
out vec4 colour;

int cellOf(int i, int j) {  // camera/pixel_lines.h's hr_looking_glass_cell
  if (cellCount == 0) return 0;
  int x = i, y = screen.y - 1 - j, cell = 0;
  if (cellPattern == 1) cell = (y % 2 == 0) == (x % 2 == 0) ? 0 : 1;
  if (cellPattern == 2) cell = x % 2;
  if (cellPattern == 3) cell = (y + (x % 2) * 2) % 4;
  if (cellPattern == 4) cell = y % 2;
  return cell % cellCount;
}
float viewOf(int i, int j, int s) {  // display/looking_glass.cpp's looking_glass_view
  float W = float(screen.x), H = float(screen.y);
  float u = (float(i) + 0.5) / W, v = (H - float(j) - 0.5) / H;
  float flip = flipX ? -1.0 : 1.0;
  float a;
  if (cellCount == 0) {
    a = u + float(s) * (flip / (3.0 * W)) + v * tilt;
  } else {
    vec2 d = cells[3 * cellOf(i, j) + s];
    a = (u + d.x / W) + (v + d.y / H) * tilt;
  }
  a = a * lenticules - center;
  return clamp(1.0 - fract(a), 0.00001, 0.999999);
}
vec4 viewSample(int k, vec2 uv) {  // GetQuiltCoordinates, its 0.00001 included
  float n = float(columns * rows), tx = float(columns) - 0.00001;
  float view = clamp(float(k), 0.0, n);
  float row = floor(view / tx), column = view - tx * row;
  // (s, t) from the quilt's bottom left; its rows are stored top first.
  return texture(quilt, vec2((column + uv.x) / tx, 1.0 - (row + uv.y) / float(rows)));
}
void main() {
  int i = int(gl_FragCoord.x), j = screen.y - 1 - int(gl_FragCoord.y);
  vec2 uv = vec2((float(i) + 0.5) / float(screen.x), (float(screen.y - j) - 0.5) / float(screen.y));
  int n = columns * rows;
  vec3 c;
  for (int s = 0; s < 3; ++s) {
    float x = viewOf(i, j, s), xn = x * float(n);
    int first = min(int(xn), n - 1), second = int((x + 1.0 / float(n)) * float(n));
    if (second >= n) second = 0;
    int next = first == n - 1 ? n : second;  // tile N: the repeating texture's view 0
    c[s] = mix(viewSample(first, uv)[s], viewSample(next, uv)[s], xn - floor(xn));
  }
  colour = vec4(c, 1.0);
}`;

// A calibration file's fields (visual.json: numbers, or {"value": number}),
// checked as display/looking_glass.cpp checks them.
function parseCalibration(text, source) {
  let j;
  try {
    j = JSON.parse(text);
  } catch (e) {
    fail(`${source}: not a Looking Glass calibration (JSON): ${e.message}`);
  }
  const field = (key, fallback) => {
    const raw = j?.[key];
    const x = raw !== null && typeof raw === "object" && "value" in raw ? raw.value : raw;
    if (x === undefined && fallback !== undefined) return fallback;
    if (typeof x !== "number" || !Number.isFinite(x)) fail(`${source}: expected '${key}' to be a finite number, found ${JSON.stringify(x)}`);
    return x;
  };
  const c = {
    pitch: field("pitch"), slope: field("slope"), center: field("center"), dpi: field("DPI"),
    width: field("screenW"), height: field("screenH"), flipX: field("flipImageX", 0) !== 0,
    cellPattern: field("CellPatternMode", 1), cells: [],
  };
  if (!(c.pitch > 0) || c.slope === 0 || !(c.dpi > 0)) fail(`${source}: expected a positive pitch and DPI and a non-zero slope`);
  if (!Number.isInteger(c.width) || !Number.isInteger(c.height) || c.width < 1 || c.height < 1 || c.width > 16384 || c.height > 16384)
    fail(`${source}: expected 'screenW' and 'screenH' whole numbers of pixels from 1 to 16384, found ${c.width}x${c.height}`);
  const cells = j.subpixelCells ?? [];
  if (!Array.isArray(cells) || cells.length > 10) fail(`${source}: expected 'subpixelCells' to be an array of at most 10 cells`);
  for (const cell of cells)
    for (const ch of ["R", "G", "B"]) {
      const at = (k) => (typeof cell?.[k] === "number" ? cell[k] : typeof cell?.[k]?.value === "number" ? cell[k].value : NaN);
      const d = [at(`${ch}OffsetX`), at(`${ch}OffsetY`)];
      if (!d.every(Number.isFinite)) fail(`${source}: expected ${ch}OffsetX and ${ch}OffsetY in every subpixel cell`);
      c.cells.push(...d);
    }
  return c;
}

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
  const lookingGlass = show === "looking-glass" && field.kind === "quilt";
  return {
    u: number("u", Math.floor(field.views[0] / 2)),
    v: number("v", Math.floor(field.views[1] / 2)),
    focus: number("focus", 0),
    aperture: Math.max(0, number("aperture", 0)),
    show: show === "eia" && field.frames[0].eia ? "eia" : show === "grid" ? "grid" : lookingGlass ? "looking-glass" : "view",
    frame: q.has("frame") ? Math.min(field.frames.length - 1, Math.max(0, Math.floor(number("frame", 0)))) : null,
  };
}

function writeState(s) {
  const hash = `#u=${+s.u.toFixed(3)}&v=${+s.v.toFixed(3)}&focus=${+s.focus.toFixed(3)}&aperture=${+s.aperture.toFixed(2)}&show=${s.show}` +
    (s.frame === null ? "" : `&frame=${s.frame}`);
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

// The views as linear light, fetched texel by texel; or (codes) as the
// Looking Glass shader reads its quilt: codes, filtered, repeating. Rows
// top first either way (an ImageBitmap ignores UNPACK_FLIP_Y_WEBGL).
function texture(gl, bitmap, codes = false) {
  const t = gl.createTexture();
  gl.bindTexture(gl.TEXTURE_2D, t);
  gl.texImage2D(gl.TEXTURE_2D, 0, codes ? gl.RGBA8 : gl.SRGB8_ALPHA8, gl.RGBA, gl.UNSIGNED_BYTE, bitmap);
  // Filtered for refocus's shifted reads (texelFetch ignores the filter).
  const filter = gl.LINEAR, wrap = codes ? gl.REPEAT : gl.CLAMP_TO_EDGE;
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, filter);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, filter);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_S, wrap);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_T, wrap);
  return t;
}

const CALIBRATION_KEY = "holoray-looking-glass";

// The quilt's Looking Glass calibration: the exported one, else the last
// loaded in a page of this site (kept for the window the button opens).
async function loadCalibration(field) {
  if (field.looking_glass) return parseCalibration(await (await fetchOk(field.looking_glass)).text(), field.looking_glass);
  const kept = localStorage.getItem(CALIBRATION_KEY);
  if (!kept) return null;
  try {
    return parseCalibration(kept, "the calibration loaded before");
  } catch {
    delete document.body.dataset.error;
    page.message.textContent = "";
    return null;
  }
}

function checkManifest(f) {
  const pair = (x) => Array.isArray(x) && x.length === 2 && x.every((n) => Number.isInteger(n) && n > 0);
  if (f.format !== "holoray-web 1") fail(`light_field.json: expected "format": "holoray-web 1", got ${JSON.stringify(f.format)}`);
  for (const key of ["views", "view_size", "tiles"])
    if (!pair(f[key])) fail(`light_field.json: "${key}" must be two positive whole numbers, got ${JSON.stringify(f[key])}`);
  if (!Array.isArray(f.frames) || f.frames.length === 0 || !f.frames.every((x) => typeof x?.views === "string"))
    fail(`light_field.json: "frames" must list each frame's views image`);
  if (!(f.fps > 0)) fail(`light_field.json: "fps" must be a positive number, got ${JSON.stringify(f.fps)}`);
  if (f.looking_glass != null && typeof f.looking_glass !== "string") fail(`light_field.json: "looking_glass" must name a calibration file`);
}

async function main() {
  const field = await (await fetchOk("light_field.json")).json().catch((e) => fail(`light_field.json: not JSON (${e.message})`));
  checkManifest(field);
  const [tw, th] = [field.tiles[0] * field.view_size[0], field.tiles[1] * field.view_size[1]];
  const loaded = await Promise.all(field.frames.map(async (f) => {
    const atlas = await loadBitmap(f.views);
    if (atlas.width !== tw || atlas.height !== th)
      fail(`${f.views}: ${atlas.width}x${atlas.height} pixels, but light_field.json describes ${field.tiles[0]}x${field.tiles[1]} views of ${field.view_size[0]}x${field.view_size[1]} (${tw}x${th})`);
    return { atlas, eia: f.eia ? await loadBitmap(f.eia) : null };
  }));
  const eia = loaded[0].eia;  // its size: every frame's
  let calibration = field.kind === "quilt" ? await loadCalibration(field) : null;

  const gl = page.canvas.getContext("webgl2", { preserveDrawingBuffer: true, antialias: false, alpha: false });
  if (!gl) fail("this browser has no WebGL2: the page needs it");
  const viewProgram = compile(gl, VERTEX, VIEW_SHADER);
  const copyProgram = compile(gl, VERTEX, COPY_SHADER);
  const frames = loaded.map((f) => ({ atlas: f.atlas, views: texture(gl, f.atlas), eia: f.eia ? texture(gl, f.eia) : null, codes: null }));
  let lookingGlassProgram = null;  // made when first shown
  let playing = 0;  // the frame shown while the animation plays (state.frame null)
  gl.bindVertexArray(gl.createVertexArray());

  const lenses = field.kind === "quilt" ? `${field.views[0]} views of ${field.view_size[0]}x${field.view_size[1]} pixels (a quilt)`
    : `${field.lenses[0]}x${field.lenses[1]} lenses (${field.grid}), ${field.pixels_per_lens} pixels per lens, ${field.views[0]}x${field.views[1]} views`;
  const animation = field.frames.length > 1 ? `; ${field.frames.length} frames at ${field.fps} fps` : "";
  page.figures.textContent = `${field.name}: ${lenses}${animation}`;
  page.aperture.max = String(Math.max(field.views[0], field.views[1]));

  let state = readState(field);
  const draw = () => {
    const s = state;
    const frame = frames[s.frame ?? playing];
    if (s.show === "looking-glass" && !calibration) {
      page.message.textContent = "no Looking Glass calibration: write the page with --looking-glass visual.json, or load the device's visual.json below";
      s.show = "view";
    }
    const [w, h] = s.show === "eia" ? [eia.width, eia.height] : s.show === "grid" ? [tw, th]
      : s.show === "looking-glass" ? [calibration.width, calibration.height] : field.view_size;
    page.canvas.width = w, page.canvas.height = h;
    page.canvas.classList.toggle("zoomed", s.show !== "view" || Number(page.zoom.value) > 1);
    page.canvas.style.width = s.show === "looking-glass" ? `${w / devicePixelRatio}px`  // a canvas pixel a panel pixel
      : page.canvas.classList.contains("zoomed") ? `${w * Number(page.zoom.value)}px` : "";
    gl.viewport(0, 0, w, h);
    if (s.show === "looking-glass") {
      lookingGlassProgram ??= compile(gl, VERTEX, LOOKING_GLASS_SHADER);
      frame.codes ??= texture(gl, frame.atlas, true);
      gl.useProgram(lookingGlassProgram);
      gl.bindTexture(gl.TEXTURE_2D, frame.codes);
      const at = (name) => gl.getUniformLocation(lookingGlassProgram, name);
      const c = calibration;
      gl.uniform2i(at("screen"), c.width, c.height);
      gl.uniform1i(at("columns"), field.tiles[0]);
      gl.uniform1i(at("rows"), field.tiles[1]);
      // The phase's scale, in double: a relative error of 1e-5 in it moved
      // the views by 2 % at the panel's far corner (SwiftShader's cos(atan())).
      gl.uniform1f(at("lenticules"), c.pitch * c.width / c.dpi * Math.cos(Math.atan(1 / c.slope)));
      gl.uniform1f(at("tilt"), (c.height / (c.width * c.slope)) * (c.flipX ? -1 : 1));
      gl.uniform1f(at("center"), c.center);
      gl.uniform1i(at("flipX"), c.flipX ? 1 : 0);
      gl.uniform1i(at("cellPattern"), c.cellPattern);
      gl.uniform1i(at("cellCount"), c.cells.length / 6);
      if (c.cells.length) gl.uniform2fv(at("cells"), new Float32Array(c.cells));
    } else if (s.show === "view") {
      gl.useProgram(viewProgram);
      gl.bindTexture(gl.TEXTURE_2D, frame.views);
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
      gl.bindTexture(gl.TEXTURE_2D, s.show === "eia" ? frame.eia : frame.views);
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
  // The Looking Glass: a window of its own for the device's screen.
  document.getElementById("looking-glass-controls").hidden = field.kind !== "quilt";
  document.getElementById("looking-glass").addEventListener("click", () =>
    window.open(`${location.pathname}#show=looking-glass`, "holoray-looking-glass", "popup"));
  document.getElementById("calibration").addEventListener("change", async (e) => {
    const file = e.target.files[0];
    if (!file) return;
    const text = await file.text();
    try {
      calibration = parseCalibration(text, file.name);
    } catch {
      return;  // fail() has shown why
    }
    page.message.textContent = "";
    delete document.body.dataset.error;
    localStorage.setItem(CALIBRATION_KEY, text);
  });
  page.canvas.addEventListener("dblclick", () => {
    if (state.show === "looking-glass") page.canvas.requestFullscreen?.();
  });
  for (const b of document.querySelectorAll("button[data-show]"))
    b.addEventListener("click", () => change({ show: b.dataset.show === "eia" && !eia ? "view" : b.dataset.show }));
  window.addEventListener("hashchange", () => {
    state = readState(field);
    draw();
  });
  // An animation plays in a loop unless the address holds it at a frame;
  // the play button holds it or lets it go.
  const play = document.getElementById("play");
  play.hidden = frames.length < 2;
  play.addEventListener("click", () => change({ frame: state.frame === null ? playing : null }));
  if (frames.length > 1)
    setInterval(() => {
      play.textContent = state.frame === null ? "pause" : "play";
      if (state.frame !== null) return;
      playing = (playing + 1) % frames.length;
      draw();
    }, 1000 / field.fps);
  draw();
}

main().catch((e) => {
  if (!document.body.dataset.error) {
    page.message.textContent = e.message;
    document.body.dataset.error = e.message;
  }
});
