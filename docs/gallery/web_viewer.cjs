// web_viewer.cjs — docs/gallery/web.png: the web viewer (docs/web.md) in Debian's headless chromium watching a
// session of the dam break through a daemon of its own, after a camera change. Run by make_gallery.sh:
//   node docs/gallery/web_viewer.cjs build/bin/fluidcastd build/bin/fluidcast deploy/demo/dambreak_16k.f32 \
//        build/npm-web/node_modules WORK_DIR OUT.png
'use strict';
const h = require('../../tests/web/harness.cjs');

h.run(async () => {
  const daemon = await h.startDaemon();
  const producer = h.startProducer(daemon.server, 'dambreak');
  const browser = await h.launchBrowser();
  const page = await h.openPage(browser, daemon.web, '?session=dambreak&format=jpeg', { width: 1000, height: 700 });
  const s = await h.waitImage(page, 0);
  await page.evaluate(() => window.fluidcastViewer.setCamera({ eye: [-1.9, -2.6, 2.0], target: [0.6, 0.5, 0.25],
    up: [0, 0, 1], fov: 40, width: 0, height: 0 }));
  await h.waitImage(page, s.imagesShown, { rest: true });
  await page.screenshot({ path: process.argv[7] });
  await producer.release();
  await browser.close();
  await h.stopDaemon(daemon);
});
