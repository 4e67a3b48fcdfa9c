// test_web_h264.cjs — the page's H.264 path: Debian's chromium decodes the daemon's stream with WebCodecs,
// and the picture at rest is the snapshot of the same frame and camera (within the video's loss).
'use strict';
const h = require('./harness.cjs');

h.run(async () => {
  const daemon = await h.startDaemon();
  const producer = h.startProducer(daemon.server, 'video');
  const browser = await h.launchBrowser();
  const page = await h.openPage(browser, daemon.web, '?session=video');
  let s = await h.waitImage(page, 0);
  h.check(s.format === 5, `the page chose H.264 where WebCodecs decodes it (format ${s.format})`);
  await page.evaluate(() => window.fluidcastViewer.setCamera({ eye: [1.2, -1.4, 0.8], target: [0.4, 0.3, 0.2],
    up: [0, 0, 1], fov: 40, width: 0, height: 0 }));
  s = await h.waitImage(page, s.imagesShown, { rest: true });
  h.check(s.lastImage.format === 5 && s.shownByFormat[5] >= 2,
    `the pictures shown are decoded H.264 access units (${JSON.stringify(s.shownByFormat)})`);
  const cmp = await h.compareCanvas(page, h.snapshot(daemon.server, s.camera, s.lastImage.width, s.lastImage.height));
  h.check(cmp.spread > 10 && cmp.meanDiff < 6,
    `the decoded picture is the snapshot at the page's camera (mean difference ${cmp.meanDiff})`);
  h.check(page.consoleErrors.length === 0, `the page logged no error (${page.consoleErrors})`);
  h.check((await producer.release()).status === 0, 'the producer ended normally');
  await browser.close();
  await h.stopDaemon(daemon);
});
