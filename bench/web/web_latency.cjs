// web_latency.cjs — the web viewer's latency: from a camera change in the page to the new picture drawn on
// its canvas, for the JPEG and the H.264 (WebCodecs) streams, at 960x540, in Debian's headless chromium
// against a real daemon (the dam break, 16k particles), one camera in flight at a time. Prints a Markdown
// table for bench/RESULTS.md.
//
//   node bench/web/web_latency.cjs build/bin/fluidcastd build/bin/fluidcast deploy/demo/dambreak_16k.f32 \
//        build/npm-web/node_modules /tmp/web-latency [SAMPLES]
'use strict';
const h = require('../../tests/web/harness.cjs');

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

h.run(async () => {
  const daemon = await h.startDaemon();
  const producer = h.startProducer(daemon.server, 'bench');
  const browser = await h.launchBrowser();
  const rows = [];
  for (const format of ['jpeg', 'h264']) rows.push(await measure(browser, daemon, format));
  console.log(`| stream | size | camera change to picture on the canvas, ms: median | p90 | samples |`);
  console.log('|---|---|---|---|---|');
  for (const r of rows)
    console.log(`| ${r.format === 'jpeg' ? 'JPEG' : 'H.264 (WebCodecs)'} | ${r.size} | ${median(r.rtt).toFixed(0)} ` +
      `| ${p90(r.rtt).toFixed(0)} | ${r.rtt.length} |`);
  await producer.release();
  await browser.close();
  await h.stopDaemon(daemon);
});
