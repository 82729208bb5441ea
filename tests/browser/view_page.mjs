// The page of haptic_sim view in a real browser: Debian's Chromium, headless, driven over the
// DevTools protocol by puppeteer-core. It points at the organ, presses it with the pointer and
// checks what a user would see: the force read-out rises above zero and follows the press, the
// picture shows the organ and changes under the press, a blade drag opens a cut, and the console
// shows no error. Screenshots go to OUT_DIR.
//   node view_page.mjs   (env: VIEW_URL, CHROMIUM, WEB_DIR (its node_modules), OUT_DIR, PREFIX)
import { createRequire } from 'node:module';
import path from 'node:path';

const require = createRequire(path.resolve(process.env.WEB_DIR, 'package.json'));
const puppeteer = require('puppeteer-core');
const out = (name) => path.join(process.env.OUT_DIR, `${process.env.PREFIX || 'view'}_${name}.png`);
const checks = [];
const check = (ok, what) => { checks.push([ok, what]); console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`); };
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

const browser = await puppeteer.launch({
  executablePath: process.env.CHROMIUM,
  headless: true,
  args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--window-size=1000,700'],
  defaultViewport: { width: 1000, height: 700 },
});
const consoleErrors = [];
try {
  const page = await browser.newPage();
  page.on('console', (m) => { if (m.type() === 'error') consoleErrors.push(m.text()); });
  page.on('pageerror', (e) => consoleErrors.push(String(e)));
  page.on('requestfailed', (r) => consoleErrors.push(`request failed: ${r.url()}`));
  await page.goto(process.env.VIEW_URL, { waitUntil: 'load' });
  await page.waitForFunction(() => window.softsimView && window.softsimView.ready, { timeout: 30000 });
  const force = () => page.evaluate(() => Math.hypot(...window.softsimView.state.force));
  const frame = () => page.evaluate(() => window.softsimView.state.frame);
  const box = await page.evaluate(() => window.softsimView.box());
  const centre = [0, 1, 2].map((d) => (box.min[d] + box.max[d]) / 2);
  const top = [centre[0], centre[1], box.max[2]];
  const at = await page.evaluate((p) => window.softsimView.project(p), top);

  await sleep(500);
  const organ = await page.evaluate(() => window.softsimView.organPixels());
  check(organ > 0.05, `the organ covers ${(100 * organ).toFixed(1)} % of the picture`);
  await page.evaluate(() => window.softsimView.capture('rest'));
  await page.screenshot({ path: out('rest') });
  const f0 = await force();
  check(f0 < 1e-6, `no force with the tool off the surface (${f0.toExponential(2)} N)`);

  // Press: over the top's centre, left button down at one depth, then deeper.
  await page.mouse.move(at.x, at.y);
  await sleep(200);
  const depth = await page.evaluate(() => window.softsimView.depth);
  await page.mouse.down();
  await sleep(1200);
  const f1 = await force();
  check(f1 > 0.01, `the force rises under the press (${f1.toFixed(4)} N at ${(1e3 * depth).toFixed(2)} mm)`);
  await page.evaluate((d) => { window.softsimView.depth = d; }, 2 * depth);
  await sleep(1200);
  const f2 = await force();
  check(f2 > 1.3 * f1, `and follows it deeper (${f2.toFixed(4)} N at ${(2e3 * depth).toFixed(2)} mm)`);
  await page.evaluate(() => window.softsimView.capture('press'));
  await page.screenshot({ path: out('press') });
  const changed = await page.evaluate(() => window.softsimView.changed('rest', 'press'));
  check(changed > 0.002, `the picture changes under the press (${(100 * changed).toFixed(2)} % of pixels)`);
  await page.mouse.up();
  await sleep(1500);
  const f3 = await force();
  check(f3 < 0.1 * f2, `released, the force falls back (${f3.toExponential(2)} N)`);

  // Cut: the blade dragged across the top.
  const triangles = await page.evaluate(() => window.softsimView.triangles);
  await page.keyboard.press('b');
  // Across the pressed point on the screen, where the pointer met the organ.
  const a = { x: at.x - 120, y: at.y + 10 }, b = { x: at.x + 120, y: at.y - 10 };
  await page.mouse.move(a.x, a.y);
  await sleep(200);
  await page.mouse.down();
  for (let i = 1; i <= 40; ++i) {
    await page.mouse.move(a.x + (b.x - a.x) * i / 40, a.y + (b.y - a.y) * i / 40);
    await sleep(30);
  }
  await page.mouse.up();
  await sleep(1000);
  const cut = await page.evaluate(() => ({ cuts: window.softsimView.state.cuts, triangles: window.softsimView.triangles,
                                           version: window.softsimView.meshVersion }));
  check(cut.cuts > 0 && cut.version > 0 && cut.triangles > triangles,
        `the blade drag opens a cut (${cut.cuts} cut events, surface ${triangles} -> ${cut.triangles} triangles)`);
  await page.keyboard.press('b');
  await page.mouse.move(a.x, a.y - 150);
  await sleep(300);
  await page.screenshot({ path: out('cut') });
  const frames = await frame();
  check(frames > 1000, `the scene ran ${frames} frames`);
  const pageErrors = await page.evaluate(() => window.softsimView.errors);
  check(pageErrors.length === 0, `the scene reported no error to the page (${pageErrors.join('; ')})`);
} finally {
  await browser.close();
}
check(consoleErrors.length === 0, `no console error (${consoleErrors.join('; ')})`);
process.exit(checks.every(([ok]) => ok) ? 0 : 1);
