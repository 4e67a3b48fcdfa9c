// test_web_ended.cjs — a session whose producer ended keeps its last frame for the page: it says the session
// ended, and a drag still turns the picture, which the daemon renders at the page's camera.
'use strict';
const h = require('./harness.cjs');

h.run(async () => {
  const daemon = await h.startDaemon();
  const producer = h.startProducer(daemon.server, 'finished');
  const browser = await h.launchBrowser();
  const page = await h.openPage(browser, daemon.web, '?session=finished&format=jpeg');
  let s = await h.waitImage(page, 0);
  h.check((await producer.release()).status === 0, 'the producer ended normally');
  s = await h.until(async () => {
    const state = await h.viewerState(page);
    return state.message.includes('ended') ? state : null;
  }, 'the page to say the session ended');
  h.check(await page.$eval('#rejoin', (e) => !e.classList.contains('hidden')), 'the page offers the next run');
  const before = await h.canvasPixels(page);
  const box = await (await page.$('#view')).boundingBox();
  await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  await page.mouse.down();
  for (let i = 1; i <= 10; i++) await page.mouse.move(box.x + box.width / 2 - 15 * i, box.y + box.height / 2);
  await page.mouse.up();
  const moved = await h.waitImage(page, s.imagesShown, { rest: true });
  h.check(h.pixelDifference(before, await h.canvasPixels(page)) > 5, 'after the end a drag still changes the picture');
  const cmp = await h.compareCanvas(page, h.snapshot(daemon.server, moved.camera, moved.lastImage.width,
    moved.lastImage.height));
  h.check(cmp.meanDiff < 4, `the ended frame is rendered at the page's camera (mean difference ${cmp.meanDiff})`);
  h.check(page.consoleErrors.length === 0, `the page logged no error (${page.consoleErrors})`);
  await browser.close();
  await h.stopDaemon(daemon);
});
