// web_latency.cjs — the viewers' latency, in one run against one daemon and session (the dam break, 16k
// particles, 960x540, one camera in flight at a time): the web viewer in Debian's headless chromium, from a
// camera change in the page to the new picture drawn on its canvas, JPEG and H.264 (WebCodecs); and the SDL
// viewer (`fluidcast view` under xvfb-run), from the request of a drag's camera at rest to its image decoded
// (its --test-script's `rtt`), raw, JPEG and H.264. Prints a Markdown table for bench/RESULTS.md.
//
//   node bench/web/web_latency.cjs build/bin/fluidcastd build/bin/fluidcast deploy/demo/dambreak_16k.f32 \
//        build/npm-web/node_modules /tmp/web-latency [SAMPLES]
'use strict';
const { spawnSync } = require('node:child_process');
const h = require('../../tests/web/harness.cjs');

const CLI = process.argv[3];

const SAMPLES = Number(process.argv[7] || 15);
// 960x540 canvas: the page's view is the window's width less 2em (14 px each), 9/16 of it high.
const VIEWPORT = { width: 988, height: 800 };

const median = (xs) => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)];
const p90 = (xs) => [...xs].sort((a, b) => a - b)[Math.min(xs.length - 1, Math.floor(xs.length * 0.9))];

async function measure(browser, daemon, format) {
  const page = await h.openPage(browser, daemon.web, `?session=bench&format=${format}`, VIEWPORT);
  let s = await h.waitImage(page, 0);
  const rtt = [], size = [];
  for (let i = 0; i <= SAMPLES; i++) {
    const angle = (i * 2 * Math.PI) / (SAMPLES + 1);
    await page.evaluate((a) => window.fluidcastViewer.setCamera({
      eye: [0.5 + 1.8 * Math.cos(a), 0.3 + 1.8 * Math.sin(a), 1.0], target: [0.5, 0.3, 0.2], up: [0, 0, 1], fov: 40,
      width: 0, height: 0 }), angle);
    s = await h.waitImage(page, s.imagesShown, { rest: true });
    const { lastRttMs } = await page.evaluate(() => window.fluidcastViewer.state);
    if (i === 0) continue;   // the first one builds the encoder (H.264) and warms the caches
    rtt.push(lastRttMs);
    size.push(`${s.lastImage.width}x${s.lastImage.height}`);
  }
  await page.close();
  return { format, size: size[0], rtt };
}

// The SDL viewer under Xvfb: once the session's picture is up (sleep), SAMPLES + 1 drags, each followed by `wait` (the image at rest, full size) and
// `rtt`; the first is dropped as above.
function measureSdl(daemon, format) {
  const script = ['sleep 2000', ...Array(SAMPLES + 1).fill('drag 40 0; wait; rtt'), 'quit'].join('; ');
  const r = spawnSync('xvfb-run', ['-a', '-s', '-screen 0 1280x800x24', CLI, 'view', '--session', 'bench',
    '--server', daemon.server, '--size', '960x540', '--format', format, '--no-spacemouse', '--test-script', script],
  { encoding: 'utf8', timeout: 600000 });
  const samples = [...r.stdout.matchAll(/round trip: ([0-9.]+) ms (\d+x\d+)/g)];
  if (r.status !== 0 || samples.length !== SAMPLES + 1)
    throw new Error(`fluidcast view --format ${format}: status ${r.status}, ${samples.length} samples: ${r.stderr}`);
  return { format, size: samples[1][2], rtt: samples.slice(1).map((m) => Number(m[1])) };
}

h.run(async () => {
  const daemon = await h.startDaemon();
  const producer = h.startProducer(daemon.server, 'bench');
  const browser = await h.launchBrowser();
  const rows = [];
  for (const format of ['jpeg', 'h264']) rows.push({ viewer: 'web', ...(await measure(browser, daemon, format)) });
  for (const format of ['raw', 'jpeg', 'h264']) rows.push({ viewer: 'SDL', ...measureSdl(daemon, format) });
  const names = { raw: 'raw RGBA', jpeg: 'JPEG', h264: 'H.264' };
  console.log(`| viewer | stream | size | camera change to new picture, ms: median | p90 | samples |`);
  console.log('|---|---|---|---|---|---|');
  for (const r of rows)
    console.log(`| ${r.viewer} | ${names[r.format]}${r.viewer === 'web' && r.format === 'h264' ? ' (WebCodecs)' : ''} ` +
      `| ${r.size} | ${median(r.rtt).toFixed(0)} | ${p90(r.rtt).toFixed(0)} | ${r.rtt.length} |`);
  await producer.release();
  await browser.close();
  await h.stopDaemon(daemon);
});
