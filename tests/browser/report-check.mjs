// Opens a `spectral validate` report.html in Debian's Chromium (headless) with playwright-core and prints one JSON line:
// the page's title, the summary table's case names and results, and per case section its id, result, whether its
// heading is visible, and its plots (count and rendered size).
// usage: node report-check.mjs REPORT.html
// Fails (exit 1) on any console error, page error or failed request (the page must need nothing beyond itself).
import { chromium } from "playwright-core";
import { pathToFileURL } from "node:url";
import { existsSync } from "node:fs";

const [target] = process.argv.slice(2);
const executablePath = process.env.CHROMIUM ?? ["/usr/bin/chromium", "/usr/bin/chromium-browser"].find(existsSync);
const browser = await chromium.launch({ executablePath, headless: true, args: ["--no-sandbox", "--disable-gpu"] });
const errors = [];
try {
  const page = await browser.newPage({ viewport: { width: 1400, height: 1000 } });
  page.on("console", m => { if (m.type() === "error") errors.push(m.text()); });
  page.on("pageerror", e => errors.push(String(e)));
  page.on("requestfailed", r => errors.push(`request failed: ${r.url()}`));
  const requests = [];
  page.on("request", r => requests.push(r.url()));
  await page.goto(pathToFileURL(target).href);
  const out = { title: await page.title() };
  out.summary = await page.evaluate(() => Array.from(document.querySelectorAll("#cases tr")).slice(1)
    .map(r => ({ name: r.cells[0].textContent, result: r.cells[r.cells.length - 1].textContent })));
  out.sections = [];
  for (const id of await page.evaluate(() => Array.from(document.querySelectorAll("section.case")).map(s => s.id))) {
    const section = page.locator(`section[id="${id}"]`);
    await section.scrollIntoViewIfNeeded();
    const heading = await section.locator("h2").boundingBox();
    const plots = [];
    for (const svg of await section.locator("svg").all()) {
      const box = await svg.boundingBox();
      plots.push({ width: box?.width ?? 0, height: box?.height ?? 0, lines: await svg.locator("polyline").count() });
    }
    out.sections.push({ id, result: await section.locator("h2 span").textContent(), visible: heading !== null && heading.height > 0,
      plots, points: await section.locator("table.points tr").count() - 1 });
  }
  out.requests = requests.filter(u => u !== pathToFileURL(target).href);
  out.errors = errors;
  console.log(JSON.stringify(out));
} finally {
  await browser.close();
}
process.exit(errors.length ? 1 : 0);
