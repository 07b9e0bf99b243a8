// Opens each address in headless Chromium (Debian's, through playwright-core)
// and saves what the light-field page drew: OUT/N.png, the view canvas as
// canvas.toDataURL() reads it, once the page has drawn the state in its
// address (document.body.dataset.drawn), or OUT/N.error.txt with the
// message the page shows when it could not; OUT/N.figures.txt, the figures
// under the view; with SCREENSHOT=FILE, the first page as a reader sees it
// (1100x900 CSS pixels). For tests/web/test_web_page.py.
// Usage: node capture.mjs OUT URL... (CHROMIUM=path, default /usr/bin/chromium)
import { chromium } from "playwright-core";
import { writeFileSync } from "node:fs";
import { join } from "node:path";

const [out, ...urls] = process.argv.slice(2);
if (!out || urls.length === 0) {
  console.error("usage: node capture.mjs OUT URL...");
  process.exit(2);
}
const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || "/usr/bin/chromium",
  // SwiftShader's WebGL2 where there is no GPU, as on the test machines.
  args: ["--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--no-sandbox"],
});
try {
  for (const [k, url] of urls.entries()) {
    const page = await browser.newPage({ viewport: { width: 1100, height: 900 } });
    const logs = [];
    page.on("console", (m) => logs.push(`${m.type()}: ${m.text()}`));
    page.on("pageerror", (e) => logs.push(`pageerror: ${e.message}`));
    await page.goto(url);
    await page.waitForFunction(() => "drawn" in document.body.dataset || "error" in document.body.dataset, null, { timeout: 60000 });
    const state = await page.evaluate(() => ({
      error: document.body.dataset.error ?? null,
      shown: document.getElementById("message").textContent,
      png: "drawn" in document.body.dataset ? document.getElementById("view").toDataURL("image/png") : null,
      figures: document.getElementById("figures").textContent,
    }));
    writeFileSync(join(out, `${k}.figures.txt`), `${state.figures}\n`);
    if (k === 0 && process.env.SCREENSHOT) await page.screenshot({ path: process.env.SCREENSHOT });
    if (state.error !== null) {
      writeFileSync(join(out, `${k}.error.txt`), `${state.shown}\n`);
    } else {
      writeFileSync(join(out, `${k}.png`), Buffer.from(state.png.split(",")[1], "base64"));
    }
    if (logs.length) writeFileSync(join(out, `${k}.log`), logs.join("\n") + "\n");
    await page.close();
  }
} finally {
  await browser.close();
}
