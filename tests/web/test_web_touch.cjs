// test_web_touch.cjs — the viewer on a touch screen: real touch events dispatched through the DevTools
// protocol (Input.dispatchTouchEvent, as a finger on a phone or tablet): one finger orbits, two fingers
// spreading apart dolly in, and the daemon renders the camera the page sent.
'use strict';
const h = require('./harness.cjs');

const distance = (cam) => Math.hypot(...cam.eye.map((x, i) => x - cam.target[i]));

// One gesture: `frames` steps from the fingers' start points to their end points, then lifted.
async function gesture(client, fingers, frames = 10) {
  const at = (t) => fingers.map(([x0, y0, x1, y1], id) => ({ x: x0 + (x1 - x0) * t, y: y0 + (y1 - y0) * t, id }));
  await client.send('Input.dispatchTouchEvent', { type: 'touchStart', touchPoints: at(0) });
  for (let i = 1; i <= frames; i++)
    await client.send('Input.dispatchTouchEvent', { type: 'touchMove', touchPoints: at(i / frames) });
  await client.send('Input.dispatchTouchEvent', { type: 'touchEnd', touchPoints: [] });
}

h.run(async () => {
  const daemon = await h.startDaemon();
  const producer = h.startProducer(daemon.server, 'touch');
  const browser = await h.launchBrowser();
  const page = await h.openPage(browser, daemon.web, '?session=touch&format=jpeg',
    { width: 640, height: 480, hasTouch: true, isMobile: true });
  const client = await page.target().createCDPSession();
  await page.evaluate(() => window.fluidcastViewer.setCamera({ eye: [0.4, -1.6, 0.9], target: [0.4, 0.3, 0.2],
    up: [0, 0, 1], fov: 40, width: 0, height: 0 }));
  const start = await h.waitImage(page, 0, { rest: true });
  const box = await (await page.$('#view')).boundingBox();
  const cx = box.x + box.width / 2, cy = box.y + box.height / 2;

  const before = await h.canvasPixels(page);
  await gesture(client, [[cx, cy, cx + 120, cy + 20]]);
  const orbited = await h.waitImage(page, start.imagesShown, { rest: true });
  h.check(JSON.stringify(orbited.camera.eye) !== JSON.stringify(start.camera.eye) &&
    Math.abs(distance(orbited.camera) - distance(start.camera)) < 1e-3 * distance(start.camera),
  'one finger orbits: the eye moves around the target at the same distance');
  h.check(h.pixelDifference(before, await h.canvasPixels(page)) > 5, 'the orbit changed the picture');
  let cmp = await h.compareCanvas(page,
    h.snapshot(daemon.server, orbited.camera, orbited.lastImage.width, orbited.lastImage.height));
  h.check(cmp.meanDiff < 4, `the daemon rendered the camera the finger set (mean difference ${cmp.meanDiff})`);

  await gesture(client, [[cx - 30, cy, cx - 150, cy], [cx + 30, cy, cx + 150, cy]]);
  const pinched = await h.waitImage(page, orbited.imagesShown, { rest: true });
  h.check(distance(pinched.camera) < 0.9 * distance(orbited.camera),
    `two fingers spreading apart dolly in (distance ${distance(orbited.camera)} -> ${distance(pinched.camera)})`);
  cmp = await h.compareCanvas(page,
    h.snapshot(daemon.server, pinched.camera, pinched.lastImage.width, pinched.lastImage.height));
  h.check(cmp.meanDiff < 4, `after the pinch the daemon rendered the page's camera (mean difference ${cmp.meanDiff})`);
  h.check(page.consoleErrors.length === 0, `the page logged no error (${page.consoleErrors})`);
  h.check((await producer.release()).status === 0, 'the producer ended normally');
  await browser.close();
  await h.stopDaemon(daemon);
});
