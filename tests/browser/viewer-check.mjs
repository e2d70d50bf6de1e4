// Drives viewer.html in Debian's Chromium (headless) with playwright-core and prints one JSON line of what it read.
// usage: node viewer-check.mjs URL_OR_FILE '{"hover":[x,y],"light":"NAME","preset":"PRESET","intensity":F,"read":[x,y],"canvas":true,"timeRuns":N,
//   "logDrag":K,"logTo":F,"readout":[x,y],"view":"luminance"}'
// Fails (exit 1) on any console error or page error.
import { chromium } from "playwright-core";
import { pathToFileURL } from "node:url";
import { existsSync } from "node:fs";

const [target, plan = "{}"] = process.argv.slice(2);
const p = JSON.parse(plan);
const url = /^https?:/.test(target) ? target : pathToFileURL(target).href;
const executablePath = process.env.CHROMIUM ?? ["/usr/bin/chromium", "/usr/bin/chromium-browser"].find(existsSync);
const browser = await chromium.launch({ executablePath, headless: true, args: ["--no-sandbox", "--disable-gpu"] });
const errors = [];
try {
  const page = await browser.newPage({ viewport: { width: 1800, height: 1100 } });
  page.on("console", m => { if (m.type() === "error") errors.push(m.text()); });
  page.on("pageerror", e => errors.push(String(e)));
  await page.goto(url);
  await page.waitForFunction(() => window.viewer !== undefined, null, { timeout: 60000 });
  const out = { title: await page.title(), lights: await page.evaluate(() => viewer.lights()) };
  if (p.hover) {
    // Hover the pixel's centre on the (zoomed) canvas and read the plotted spectrum back from the SVG.
    const box = await page.locator("#image").boundingBox();
    const zoom = box.width / (await page.evaluate(() => viewer.width));
    await page.mouse.move(box.x + (p.hover[0] + 0.5) * zoom, box.y + (p.hover[1] + 0.5) * zoom);
    out.plotted = (await page.locator("#spectrum-line").getAttribute("data-values")).split(",").map(Number);
    const refl = page.locator("#reflectance-line");
    out.reflectance = (await refl.count()) ? (await refl.getAttribute("data-values")).split(",").map(Number) : null;
    out.where = await page.locator("#where").textContent();
  }
  if (p.light) {
    if (p.storeA) await page.evaluate(() => viewer.storeA());
    if (p.storeA && p.read) out.xyzA = await page.evaluate(([x, y]) => viewer.pixelXyz(x, y), p.read);
    await page.evaluate(([l, pr, f]) => viewer.setLight(l, pr, f), [p.light, p.preset, p.intensity]);
    if (p.drag !== undefined) {
      // Drag light p.drag's intensity slider from its thumb to the right end of its track, as a person would.
      const slider = page.locator(`#intensity-${p.drag}`);
      const box = await slider.boundingBox();
      const [value, max] = await slider.evaluate(e => [+e.value, +e.max]);
      await page.mouse.move(box.x + box.width * value / max, box.y + box.height / 2);
      await page.mouse.down();
      await page.mouse.move(box.x + box.width + 20, box.y + box.height / 2, { steps: 5 });
      await page.mouse.up();
      out.dragged = await slider.evaluate(e => +e.value);
      out.sliderMax = max;
    }
    if (p.read) out.rgb = await page.evaluate(([x, y]) => viewer.pixelRgb(x, y), p.read);
    if (p.read) out.xyz = await page.evaluate(([x, y]) => viewer.pixelXyz(x, y), p.read);
    // Every pixel the page drew (RGBA, row by row), to compare with the preview a relight writes.
    if (p.canvas) out.canvas = await page.evaluate(() => { const c = document.getElementById("image"); return Array.from(c.getContext("2d").getImageData(0, 0, c.width, c.height).data); });
    if (p.storeA) { await page.evaluate(() => viewer.setMode("de")); out.de = await page.evaluate(() => viewer.deStats()); }
    if (p.storeA && p.read) out.pixelDe = await page.evaluate(([x, y]) => viewer.pixelDe(x, y), p.read);
  }
  if (p.logDrag !== undefined) {
    // Drag light p.logDrag's logarithmic slider from its thumb to p.logTo (0 … 1) of its track; read the slider, the
    // intensity the page took and the text beside it.
    const slider = page.locator(`#logIntensity-${p.logDrag}`);
    const box = await slider.boundingBox();
    const [value, min, max] = await slider.evaluate(e => [+e.value, +e.min, +e.max]);
    await page.mouse.move(box.x + box.width * (value - min) / (max - min), box.y + box.height / 2);
    await page.mouse.down();
    await page.mouse.move(box.x + box.width * p.logTo, box.y + box.height / 2, { steps: 5 });
    await page.mouse.up();
    out.logSlider = await slider.evaluate(e => [+e.value, +e.min, +e.max]);
    out.linearSlider = await page.locator(`#intensity-${p.logDrag}`).evaluate(e => +e.value);
    out.intensity = await page.evaluate(k => viewer.intensity(viewer.lights()[k]), p.logDrag);
    out.intensityText = await page.locator(`#intensityText-${p.logDrag}`).textContent();
    if (p.read) out.rgb = await page.evaluate(([x, y]) => viewer.pixelRgb(x, y), p.read);
  }
  if (p.readout) {
    // Hover the pixel and read the luminance and illuminance readout under the cursor.
    const box = await page.locator("#image").boundingBox();
    const zoom = box.width / (await page.evaluate(() => viewer.width));
    await page.mouse.move(box.x + (p.readout[0] + 0.5) * zoom, box.y + (p.readout[1] + 0.5) * zoom);
    out.luminance = +(await page.locator("#luminance-readout").getAttribute("data-value"));
    out.illuminance = +(await page.locator("#illuminance-readout").getAttribute("data-value"));
    out.readoutText = await page.locator("#photometry-readout").textContent();
  }
  if (p.view) {
    // Switch the view (luminance, illuminance) and read the canvas and the legend shown beside it.
    await page.selectOption("#mode", p.view);
    out.viewCanvas = await page.evaluate(() => { const c = document.getElementById("image"); return Array.from(c.getContext("2d").getImageData(0, 0, c.width, c.height).data); });
    out.legend = await page.locator("#legend").innerHTML();
  }
  if (p.timeRuns) {
    await page.evaluate(() => viewer.setMode("colour"));
    out.relightMs = await page.evaluate(n => viewer.timeRelight(n), p.timeRuns);
    out.drawMs = await page.evaluate(n => viewer.timeDraw(n), p.timeRuns);
    out.size = await page.evaluate(() => [viewer.width, viewer.height, viewer.bands]);
  }
  // CIEDE2000 of given L*a*b* pairs ([L1, a1, b1, L2, a2, b2] each), by the page's own formula.
  if (p.dePairs) out.dePairs = await page.evaluate(pairs => pairs.map(q => viewer.de2000(...q)), p.dePairs);
  out.errors = errors;
  console.log(JSON.stringify(out));
} finally {
  await browser.close();
}
process.exit(errors.length ? 1 : 0);
