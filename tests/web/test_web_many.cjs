// test_web_many.cjs — 8 pages watch one session while its producer publishes at full speed: the producer
// streams every frame and ends normally (latest wins: pages are not queued frames they cannot keep up
// with), and every page keeps receiving, up to the newest frame.
'use strict';
const h = require('./harness.cjs');

const PAGES = 8, FRAMES = 24;

h.run(async () => {
  const daemon = await h.startDaemon();
  const producer = h.startProducer(daemon.server, 'crowd', FRAMES);
  const browser = await h.launchBrowser();
  const pages = [];
  for (let i = 0; i < PAGES; i++)
    pages.push(await h.openPage(browser, daemon.web, '?session=crowd&format=jpeg', { width: 360, height: 300 }));
  for (const page of pages) await h.waitImage(page, 0);
  await producer.proceed();
  const newest = FRAMES + 2;   // the first file, the one read from the first FIFO, then FRAMES more
  for (const [i, page] of pages.entries()) {
    const s = await h.until(async () => {
      const state = await h.viewerState(page);
      return state.lastImage && state.lastImage.frame === newest ? state : null;
    }, `page ${i + 1} to show frame ${newest}`, 120);
    h.check(s.lastImage.frame === newest, `page ${i + 1} kept receiving up to frame ${newest}`);
    h.check(page.consoleErrors.length === 0, `page ${i + 1} logged no error (${page.consoleErrors})`);
  }
  const ended = await producer.release();
  h.check(ended.status === 0 && ended.output.includes(`streamed ${FRAMES + 3} frames`),
    `the producer streamed all ${FRAMES + 3} frames and ended normally`);
  await browser.close();
  await h.stopDaemon(daemon);
});
