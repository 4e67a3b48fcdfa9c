// harness.cjs — what the web viewer's browser tests share: a real fluidcastd with --web-listen, producers
// fed by `fluidcast stream`, Debian's headless chromium driven by puppeteer-core, and pixel comparisons
// made inside the page (the canvas against a PNG from `fluidcast snapshot`).
'use strict';
const { spawn, spawnSync } = require('node:child_process');
const fs = require('node:fs');
const path = require('node:path');

const [, , DAEMON, CLI, SCENE, NODE_MODULES, WORK] = process.argv;
const puppeteer = require(path.resolve(NODE_MODULES, 'puppeteer-core'));

let failures = 0;
function check(ok, what) {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
  if (!ok) failures++;
}

const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

// Waits until probe() is truthy, for at most `seconds`; the reason names what was waited for.
async function until(probe, what, seconds = 60) {
  for (let waited = 0; waited < seconds * 10; waited++) {
    const value = await probe();
    if (value) return value;
    await sleep(100);
  }
  throw new Error(`timed out waiting for ${what}`);
}

fs.rmSync(WORK, { recursive: true, force: true });
fs.mkdirSync(WORK, { recursive: true });
const children = [];

// A daemon on free ports (or the ports given, to restart one in place); resolves once it serves.
async function startDaemon({ name = 'daemon', env = {}, listen = '127.0.0.1:0', web = '0', args = [] } = {}) {
  const logPath = path.join(WORK, `${name}.log`);
  const portFile = path.join(WORK, `${name}.port`);
  fs.rmSync(portFile, { force: true });
  const out = fs.openSync(logPath, 'a');
  const proc = spawn(DAEMON, ['--listen', listen, '--port-file', portFile, '--web-listen', web, '--refresh-ms', '0',
    ...args], { env: { ...process.env, ...env }, stdio: ['ignore', out, out] });
  children.push(proc);
  const [scheme, address] = await until(() => {
    const log = fs.readFileSync(logPath, 'utf8');
    const m = [...log.matchAll(/web viewer on (https?):\/\/([^/]+)\//g)];
    return m.length && fs.existsSync(portFile) ? [m[m.length - 1][1], m[m.length - 1][2]] : null;
  }, `${name} to serve`);
  // With a certificate every TCP listener speaks TLS: the page is https:// and the protocol port tls://.
  const port = fs.readFileSync(portFile, 'utf8').trim();
  return { proc, web: address, origin: `${scheme}://${address}`,
    server: scheme === 'https' ? `tls://127.0.0.1:${port}` : `127.0.0.1:${port}`, logPath };
}

async function stopDaemon(daemon) {
  daemon.proc.kill('SIGTERM');
  await until(() => daemon.proc.exitCode !== null, 'the daemon to stop', 20);
}

// `fluidcast stream` publishing the scene once, waiting on a FIFO, publishing it `frames` more times at full
// speed, then waiting on a second FIFO: the session stays live, with its frames, until the test lets the
// producer go on (proceed()) and end (release()).
function startProducer(server, session, frames = 0, env = {}) {
  const fifo = (n) => {
    const p = path.join(WORK, `hold-${session}-${n}-${process.hrtime.bigint()}.f32`);
    spawnSync('mkfifo', [p]);
    return p;
  };
  const first = fifo(1), last = fifo(2);
  const files = [SCENE, ...(frames ? [first, ...Array(frames).fill(SCENE)] : []), last];
  const proc = spawn(CLI, ['stream', ...files, '--server', server, '--session', session],
    { stdio: ['ignore', 'pipe', 'pipe'], env: { ...process.env, ...env } });
  children.push(proc);
  let output = '';
  proc.stdout.on('data', (d) => { output += d; });
  proc.stderr.on('data', (d) => { output += d; });
  const proceed = () => fs.promises.writeFile(first, fs.readFileSync(SCENE));
  const release = async () => {
    await fs.promises.writeFile(last, fs.readFileSync(SCENE));
    await until(() => proc.exitCode !== null, 'the producer to end', 120);
    return { status: proc.exitCode, output };
  };
  return { proc, proceed, release, output: () => output };
}

// A snapshot of the scene at the page's camera and size, as base64 PNG.
function snapshot(server, camera, width, height) {
  const out = path.join(WORK, `snap-${Date.now()}.png`);
  const v = (a) => a.map((x) => x.toPrecision(9)).join(',');
  const r = spawnSync(CLI, ['snapshot', SCENE, '--server', server, '--size', `${width}x${height}`,
    '--eye', v(camera.eye), '--target', v(camera.target), '--up', v(camera.up), '--fov', String(camera.fov),
    '-o', out], { encoding: 'utf8' });
  if (r.status !== 0) throw new Error(`snapshot failed: ${r.stderr}`);
  return fs.readFileSync(out).toString('base64');
}

// env: e.g. a HOME whose NSS database (~/.pki/nssdb) trusts a test CA, as a user's browser would.
async function launchBrowser(env = {}) {
  return puppeteer.launch({ executablePath: '/usr/bin/chromium', headless: true, env: { ...process.env, ...env },
    args: ['--no-sandbox', '--use-gl=swiftshader', '--enable-unsafe-swiftshader', '--disable-gpu-sandbox'] });
}

// A page of the viewer at web (HOST:PORT, http, or a daemon's origin such as https://HOST:PORT);
// page.consoleErrors collects what the page logs as errors and throws.
async function openPage(browser, web, query = '', viewport = { width: 640, height: 480 }) {
  const page = await browser.newPage();
  await page.setViewport(viewport);
  page.consoleErrors = [];
  page.on('console', (m) => { if (m.type() === 'error') page.consoleErrors.push(m.text()); });
  page.on('pageerror', (e) => page.consoleErrors.push(e.message));
  await page.goto(`${web.includes('://') ? web : `http://${web}`}/${query}`);
  return page;
}

const viewerState = (page) => page.evaluate(() => {
  const s = window.fluidcastViewer.state;
  return { imagesShown: s.imagesShown, lastImage: s.lastImage, camera: s.camera, format: s.format,
    cameraInFlight: s.cameraInFlight, cameraQueued: s.cameraQueued, moving: s.moving, connected: s.connected,
    reconnects: s.reconnects, refusals: s.refusals, shownByFormat: s.shownByFormat, decoding: s.imagesDecoding,
    full: window.fluidcastViewer.viewSize(false), message: document.getElementById('message').textContent };
});

// Waits for an image shown after `after` images, at rest (full size, no camera pending) if asked.
async function waitImage(page, after, { rest = false, seconds = 60 } = {}) {
  return until(async () => {
    const s = await viewerState(page);
    if (s.imagesShown <= after) return null;
    const full = s.lastImage.width === s.full.width && s.lastImage.height === s.full.height;
    if (rest && (s.moving || s.cameraInFlight || s.cameraQueued || s.decoding || !full || !(s.lastImage.flags & 2)))
      return null;
    return s;
  }, `an image${rest ? ' at rest' : ''} after ${after}`, seconds);
}

// Mean absolute difference (0..255, RGB) between the canvas and a PNG, and the PNG's spread of luminance
// (a picture with something in it, not a flat background).
const compareCanvas = (page, pngBase64) => page.evaluate(async (b64) => {
  const bytes = Uint8Array.from(atob(b64), (c) => c.charCodeAt(0));
  const bitmap = await createImageBitmap(new Blob([bytes], { type: 'image/png' }));
  const canvas = document.getElementById('view');
  const off = new OffscreenCanvas(bitmap.width, bitmap.height);
  off.getContext('2d').drawImage(bitmap, 0, 0);
  const want = off.getContext('2d').getImageData(0, 0, bitmap.width, bitmap.height).data;
  if (canvas.width !== bitmap.width || canvas.height !== bitmap.height)
    return { sizeMismatch: `${canvas.width}x${canvas.height} vs ${bitmap.width}x${bitmap.height}` };
  const got = canvas.getContext('2d').getImageData(0, 0, canvas.width, canvas.height).data;
  let diff = 0, sum = 0, sum2 = 0;
  const n = want.length / 4;
  for (let i = 0; i < want.length; i += 4) {
    for (let c = 0; c < 3; c++) diff += Math.abs(want[i + c] - got[i + c]);
    const y = (want[i] + want[i + 1] + want[i + 2]) / 3;
    sum += y;
    sum2 += y * y;
  }
  return { meanDiff: diff / (3 * n), spread: Math.sqrt(sum2 / n - (sum / n) ** 2) };
}, pngBase64);

// The canvas's pixels as one array, to tell two pictures apart.
const canvasPixels = (page) => page.evaluate(() => {
  const c = document.getElementById('view');
  return Array.from(c.getContext('2d').getImageData(0, 0, c.width, c.height).data);
});

function pixelDifference(a, b) {
  if (a.length !== b.length) return 255;
  let diff = 0;
  for (let i = 0; i < a.length; i++) diff += Math.abs(a[i] - b[i]);
  return diff / a.length;
}

// Runs the test body; ends every process it started and exits 0 only when every check held.
async function run(body) {
  let status = 1;
  try {
    await body();
    status = failures === 0 ? 0 : 1;
  } catch (e) {
    console.log(`FAIL ${e.stack || e}`);
  } finally {
    for (const child of children) if (child.exitCode === null) child.kill('SIGKILL');
  }
  console.log(status === 0 ? 'all checks held' : `${failures} check(s) failed`);
  process.exit(status);
}

module.exports = { check, until, sleep, startDaemon, stopDaemon, startProducer, snapshot, launchBrowser, openPage,
  viewerState, waitImage, compareCanvas, canvasPixels, pixelDifference, run, WORK, SCENE };
