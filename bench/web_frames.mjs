// bench/web_frames.mjs: frames per second of the light-field page's
// parallax and refocus, and its load time, in headless Chromium (Debian's,
// through tests/web's playwright-core; WebGL2 on SwiftShader where there is
// no GPU). For bench/run_web_bench.sh.
// Usage: node bench/web_frames.mjs URL LOADS FRAMES APERTURE
import { createRequire } from "node:module";
import { fileURLToPath } from "node:url";
import { dirname, join } from "node:path";

const require = createRequire(join(dirname(fileURLToPath(import.meta.url)), "..", "tests", "web", "package.json"));
const { chromium } = require("playwright-core");
const [url, loads, frames, aperture] = process.argv.slice(2);
const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || "/usr/bin/chromium",
  args: ["--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--no-sandbox"],
});
const median = (xs) => xs.sort((a, b) => a - b)[Math.floor(xs.length / 2)];
try {
  const loadMs = [];
  for (let k = 0; k < Number(loads); ++k) {
    const page = await browser.newPage({ viewport: { width: 1100, height: 900 } });
    const t0 = Date.now();
    await page.goto(url);
    await page.waitForFunction(() => "drawn" in document.body.dataset || "error" in document.body.dataset, null, { timeout: 120000 });
    loadMs.push(Date.now() - t0);
    if (k + 1 < Number(loads)) await page.close();
    else {
      // Frames as a reader makes them: pointer moves (parallax), then the
      // focus slider with the aperture open (refocus); each run of frames
      // ends with the canvas read back, so that the GPU's work is counted.
      const run = (kind, n, open) => page.evaluate(({ kind, n, open }) => {
        const canvas = document.getElementById("view");
        const focus = document.getElementById("focus"), aperture = document.getElementById("aperture");
        aperture.value = String(open);
        aperture.dispatchEvent(new Event("input"));
        canvas.toDataURL();
        const r = canvas.getBoundingClientRect();
        const t0 = performance.now();
        for (let f = 0; f < n; ++f) {
          if (kind === "parallax") {
            canvas.dispatchEvent(new PointerEvent("pointermove", { clientX: r.left + r.width * ((f % 50) / 49), clientY: r.top + r.height / 2 }));
          } else {
            focus.value = String(-1 + 2 * ((f % 20) / 19));
            focus.dispatchEvent(new Event("input"));
          }
          if (f % 10 === 9 || f === n - 1) canvas.toDataURL();
        }
        return performance.now() - t0;
      }, { kind, n, open });
      const parallax = await run("parallax", Number(frames), 0);
      const refocus = await run("refocus", Math.max(3, Math.floor(Number(frames) / 10)), Number(aperture));
      const views = await page.evaluate(() => document.getElementById("figures").textContent);
      console.log(JSON.stringify({
        load_ms_median: median(loadMs), load_ms: loadMs, parallax_fps: (1000 * Number(frames)) / parallax,
        refocus_fps: (1000 * Math.max(3, Math.floor(Number(frames) / 10))) / refocus, figures: views,
      }));
    }
  }
} finally {
  await browser.close();
}
