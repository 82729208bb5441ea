// A page of haptic_sim view left open with the pointer over the organ, not pressing (the tool
// hovers above the surface: samples at 60 Hz, states drawn as fast as the page can), until the
// scene ends. What the physics loop pays for a page attached: cpp/apps/view/page_cost.py.
//   node view_idle.mjs   (env: VIEW_URL, CHROMIUM, WEB_DIR)
import { createRequire } from 'node:module';
import path from 'node:path';

const require = createRequire(path.resolve(process.env.WEB_DIR, 'package.json'));
const puppeteer = require('puppeteer-core');
const browser = await puppeteer.launch({
  executablePath: process.env.CHROMIUM,
  headless: true,
  args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
  defaultViewport: { width: 1000, height: 700 },
});
let draws = 0, states = 0;
try {
  const page = await browser.newPage();
  await page.goto(process.env.VIEW_URL, { waitUntil: 'load' });
  await page.waitForFunction(() => window.softsimView && window.softsimView.ready, { timeout: 30000 });
  const box = await page.evaluate(() => window.softsimView.box());
  const at = await page.evaluate((p) => window.softsimView.project(p),
    [(box.min[0] + box.max[0]) / 2, (box.min[1] + box.max[1]) / 2, box.max[2]]);
  await page.mouse.move(at.x, at.y);
  // Until the scene closes the connection.
  await page.waitForFunction(() => document.getElementById('status').className === 'error', { timeout: 0, polling: 500 });
  states = await page.evaluate(() => window.softsimView.states);
} finally {
  await browser.close();
}
console.log(JSON.stringify({ states }));
