// test_web_reconnect.cjs — the daemon goes away under a watching page: the page says so, and once a daemon
// serves on the same ports again it reconnects and shows the session's pictures; a page that joins a session
// before its producer says that it waits for it.
'use strict';
const h = require('./harness.cjs');

h.run(async () => {
  let daemon = await h.startDaemon({ name: 'first' });
  const browser = await h.launchBrowser();
  const page = await h.openPage(browser, daemon.web, '?session=later&format=jpeg');
  await h.until(async () => (await h.viewerState(page)).message.includes('waiting for session later'),
    'the page to say it waits for the session');
  let producer = h.startProducer(daemon.server, 'later');
  let s = await h.waitImage(page, 0);
  h.check(!s.message.includes('waiting'), 'the waiting message goes once the session has a picture');
  const { server, web } = daemon;
  await h.stopDaemon(daemon);
  await producer.proc.kill('SIGKILL');
  await h.until(async () => (await h.viewerState(page)).message.includes('went away'),
    'the page to say the daemon went away');
  daemon = await h.startDaemon({ name: 'second', listen: server, web: web.split(':')[1] });
  producer = h.startProducer(daemon.server, 'later');
  s = await h.waitImage(page, s.imagesShown);
  h.check(s.connected && !s.message.includes('went away'), 'the page reconnected and shows the session again');
  h.check(page.consoleErrors.every((e) => /WebSocket|ERR_CONNECTION_REFUSED/.test(e)),
    `the page logged nothing but the refused reconnects (${page.consoleErrors})`);
  h.check((await producer.release()).status === 0, 'the producer ended normally');
  await browser.close();
  await h.stopDaemon(daemon);
});
