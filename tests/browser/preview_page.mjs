// Drives the page of `inbetween view` in Debian's chromium through playwright-core (tools/browser)
// for tests/browser/preview_browser_test.cpp, which makes the page, runs this script and checks
// what it prints against `inbetween bake`.  It reads the page only through window.inbetween
// (docs/preview.md) and the canvas pixels.
//
//   node preview_page.mjs PAGE.html --frames F1,F2,… --objects A,B [--overview OUT.png]
//                         [--camera NAME] [--screenshot OUT.png]
//
// --overview saves a screenshot in the free view at the second of the frames (the README's image,
// docs/images/preview.png); --screenshot one through the camera NAME, after the frames.
// Prints one JSON object on standard output: {ready, variance, played: {from, to}, frames: [{asked,
// shown, positions: {A: [x, y, z], …}, rotations: {A: [w, x, y, z], …}, bones: [{parent, child, from, to}, …]}],
// boneCount, trails, bytes, cameras, camera, cameraVariance, errors}.  Exit 77 (with the reason on
// standard error) when playwright-core or chromium is missing or chromium cannot start; 1 on any
// other failure.
import { existsSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const skip = (why) => { process.stderr.write(`SKIP: ${why}\n`); process.exit(77); };

const args = process.argv.slice(2);
const page_path = args[0];
const option = (name) => { const i = args.indexOf(name); return i >= 0 ? args[i + 1] : undefined; };
const frames = (option('--frames') || '').split(',').filter(Boolean).map(Number);
const objects = (option('--objects') || '').split(',').filter(Boolean);
const camera = option('--camera');
const screenshot = option('--screenshot');
const overview = option('--overview');

const module_path = resolve(here, '../../tools/browser/node_modules/playwright-core/index.mjs');
if (!existsSync(module_path)) skip(`playwright-core is not installed (${module_path}); run \`make deps\``);
const { chromium } = await import(pathToFileURL(module_path).href);

// Debian's chromium: the binary itself, not the /usr/bin/chromium wrapper script.
const executable = ['/usr/lib/chromium/chromium', '/usr/bin/chromium'].find((p) => existsSync(p));
if (!executable) skip('chromium is not installed (Debian package chromium; `make deps` installs it)');

let browser;
try {
  browser = await chromium.launch({
    executablePath: executable,
    headless: true,
    // --no-sandbox: chromium refuses its sandbox as root (CI, containers).  SwiftShader: WebGL
    // in software, for machines with no GPU.
    args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist'],
    timeout: 60000,
  });
} catch (e) {
  skip(`chromium (${executable}) cannot start: ${String(e.message || e).split('\n')[0]}`);
}

const errors = [];
try {
  const page = await browser.newPage({ viewport: { width: 1280, height: 720 } });
  page.on('pageerror', (e) => errors.push(String(e)));
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  // Nothing may be fetched: the page is self-contained.
  page.on('request', (r) => { if (!r.url().startsWith('file:') && !r.url().startsWith('data:')) errors.push(`fetched ${r.url()}`); });
  const t0 = Date.now();
  await page.goto(pathToFileURL(resolve(page_path)).href);
  await page.waitForFunction(() => window.inbetween && window.inbetween.ready === true, null, { timeout: 60000 });
  const opened = (Date.now() - t0) / 1000;  // seconds from navigation to the first frame drawn

  // Pixel variance of the 3-D canvas (its drawing buffer is preserved): a blank canvas has 0.
  const variance = () => page.evaluate(() => {
    const gl = document.querySelector('#view canvas');
    const copy = document.createElement('canvas');
    copy.width = gl.width; copy.height = gl.height;
    const g = copy.getContext('2d');
    g.drawImage(gl, 0, 0);
    const px = g.getImageData(0, 0, copy.width, copy.height).data;
    let n = 0, sum = 0, sum2 = 0;
    for (let i = 0; i < px.length; i += 4) {
      const v = 0.299 * px[i] + 0.587 * px[i + 1] + 0.114 * px[i + 2];
      n += 1; sum += v; sum2 += v * v;
    }
    const mean = sum / n;
    return sum2 / n - mean * mean;
  });

  const result = { ready: true, variance: await variance(), frames: [], cameras: await page.evaluate(() => window.inbetween.cameras) };
  result.boneCount = await page.evaluate(() => window.inbetween.boneCount());
  result.trails = await page.evaluate(() => window.inbetween.trails());
  result.openSeconds = opened;
  // The timeline plays: from the first frame, playing moves the frame on (waited for up to 10 s:
  // software WebGL in a headless browser may draw only a few frames a second).
  const start = await page.evaluate(() => window.inbetween.setFrame(window.inbetween.frames[0]));
  await page.evaluate(() => window.inbetween.play());
  await page.waitForFunction((f) => window.inbetween.frame() !== f, start, { timeout: 10000 }).catch(() => {});
  const end = await page.evaluate(() => { window.inbetween.pause(); return window.inbetween.frame(); });
  result.played = { from: start, to: end };
  for (const f of frames) {
    const shown = await page.evaluate((frame) => window.inbetween.setFrame(frame), f);
    const positions = {}, rotations = {};
    for (const name of objects) {
      positions[name] = await page.evaluate((n) => window.inbetween.objectPosition(n), name);
      rotations[name] = await page.evaluate((n) => window.inbetween.objectRotation(n), name);
    }
    const bones = await page.evaluate(() => Array.from({ length: window.inbetween.boneCount() }, (_, k) => window.inbetween.bone(k)));
    result.frames.push({ asked: f, shown, positions, rotations, bones });
  }
  if (overview && frames.length > 0) {
    await page.evaluate((frame) => window.inbetween.setFrame(frame), frames[Math.min(1, frames.length - 1)]);
    await page.screenshot({ path: overview });
  }
  if (camera) {
    result.camera = await page.evaluate((c) => window.inbetween.useCamera(c), camera);
    result.cameraVariance = await variance();
  }
  if (screenshot) await page.screenshot({ path: screenshot });
  result.errors = errors;
  process.stdout.write(JSON.stringify(result) + '\n');
} catch (e) {
  process.stderr.write(`preview_page.mjs: ${e.stack || e}\nerrors on the page: ${errors.join('\n')}\n`);
  process.exitCode = 1;
} finally {
  await browser.close();
}
