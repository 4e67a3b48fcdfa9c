// test_web_page.cjs — the page served by fluidcastd --web-listen, in headless chromium, against a real
// daemon fed by `fluidcast stream`: the files and their headers, the session list, the JPEG stream's
// picture against a snapshot of the same frame and camera, and a drag that turns the view (the daemon's
// picture then matches a snapshot at the camera the page sent).
'use strict';
const net = require('node:net');
const h = require('./harness.cjs');

// A WebSocket upgrade request with the given Origin, answered with the status line.
function upgradeStatus(web, origin) {
  const [host, port] = web.split(':');
  return new Promise((resolve) => {
    const socket = net.connect(Number(port), host, () => {
      socket.write(`GET /ws HTTP/1.1\r\nHost: ${web}\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n` +
        `Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n` +
        `Sec-WebSocket-Protocol: fluidcast.v1\r\nOrigin: ${origin}\r\n\r\n`);
    });
    let reply = '';
    socket.on('data', (d) => {
      reply += d;
      if (reply.includes('\r\n')) {
        socket.destroy();
        resolve(reply.split('\r\n')[0]);
      }
    });
    socket.on('close', () => resolve(reply.split('\r\n')[0] || 'closed'));
    socket.on('error', () => resolve('error'));
  });
}

h.run(async () => {
  const daemon = await h.startDaemon();
  const browser = await h.launchBrowser();
  const index = await fetch(`http://${daemon.web}/`);
  const csp = index.headers.get('content-security-policy') || '';
  h.check(index.status === 200 && /script-src 'self'/.test(csp) && /default-src 'none'/.test(csp),
    `GET / is the page with a strict Content-Security-Policy (${csp})`);
  h.check((await fetch(`http://${daemon.web}/viewer.js`)).headers.get('content-type').startsWith('text/javascript'),
    'the scripts are served as JavaScript');
  h.check((await fetch(`http://${daemon.web}/no-such-file`)).status === 404, 'an unknown path is 404');
  h.check(/ 101 /.test(await upgradeStatus(daemon.web, `http://${daemon.web}`)), 'a same-origin WebSocket opens');
  h.check(!/ 101 /.test(await upgradeStatus(daemon.web, 'http://elsewhere.example')),
    'a WebSocket from another origin is refused');

  // The mapping (PROTOCOL.md 13) from a page: one protocol message per binary WebSocket message.
  const listPage = await h.openPage(browser, daemon.web);
  const mapping = await listPage.evaluate(async () => {
    const fc = await import('/protocol.js');
    // Sends each message on a fresh WebSocket; resolves with the types received and the close code.
    const exchange = (...messages) => new Promise((resolve) => {
      const ws = new WebSocket(`ws://${location.host}/ws`, 'fluidcast.v1');
      ws.binaryType = 'arraybuffer';
      const types = [];
      ws.onopen = () => messages.forEach((m) => ws.send(m));
      ws.onmessage = (e) => types.push(fc.parse(e.data).type);
      ws.onclose = (e) => resolve({ types, code: e.code });
    });
    const hello = fc.hello(1, 'web-test', '');
    const short = hello.slice(0, hello.length - 1);   // its header names one byte more than follows
    const badMagic = fc.message(fc.MSG.GOODBYE, 2);
    badMagic[0] = 0x58;
    return {
      hello: await exchange(hello, fc.goodbye()),
      text: await exchange('hello'),
      short: await exchange(short),
      badMagic: await exchange(badMagic),
    };
  });
  h.check(JSON.stringify(mapping.hello.types) === '[2]' && mapping.hello.code === 1000,
    `HELLO then GOODBYE: WELCOME, then the daemon closes (${JSON.stringify(mapping.hello)})`);
  h.check(mapping.text.types.length === 0 && mapping.text.code === 1002, 'a text message closes the WebSocket (1002)');
  h.check(mapping.short.types.length === 0 && mapping.short.code === 1002,
    'a message shorter than its header says closes the WebSocket (1002)');
  h.check(JSON.stringify(mapping.badMagic.types) === '[8]' && mapping.badMagic.code === 1000,
    `a bad magic is the daemon's to answer: ERROR, then closed (${JSON.stringify(mapping.badMagic)})`);
  await listPage.close();

  const producer = h.startProducer(daemon.server, 'tank');
  const list = await h.openPage(browser, daemon.web);
  await h.until(() => list.$('#session-list a'), 'the session list');
  const href = await list.$eval('#session-list a', (a) => a.getAttribute('href'));
  h.check(href === '?session=tank', `the session list links the session (${href})`);
  h.check(list.consoleErrors.length === 0, `the list page logged no error (${list.consoleErrors})`);

  const page = await h.openPage(browser, daemon.web, '?session=tank&format=jpeg');
  let s = await h.waitImage(page, 0);
  h.check(s.format === 2 && s.lastImage.format === 2, 'the stream is JPEG when asked for');
  // A camera set through the page reaches the daemon: its picture is the snapshot at that camera.
  await page.evaluate(() => window.fluidcastViewer.setCamera({ eye: [0.4, -1.6, 0.9], target: [0.4, 0.3, 0.2],
    up: [0, 0, 1], fov: 40, width: 0, height: 0 }));
  s = await h.waitImage(page, s.imagesShown, { rest: true });
  let cmp = await h.compareCanvas(page, h.snapshot(daemon.server, s.camera, s.lastImage.width, s.lastImage.height));
  h.check(cmp.spread > 10 && cmp.meanDiff < 4,
    `the canvas shows the snapshot of the same frame and camera (mean difference ${cmp.meanDiff}, ` +
    `spread ${cmp.spread})`);

  const before = await h.canvasPixels(page);
  const box = await (await page.$('#view')).boundingBox();
  await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  await page.mouse.down();
  for (let i = 1; i <= 10; i++) await page.mouse.move(box.x + box.width / 2 + 15 * i, box.y + box.height / 2 + 4 * i);
  await page.mouse.up();
  const moved = await h.waitImage(page, s.imagesShown, { rest: true });
  h.check(JSON.stringify(moved.camera.eye) !== JSON.stringify(s.camera.eye), 'the drag moved the page\'s camera');
  h.check(h.pixelDifference(before, await h.canvasPixels(page)) > 5, 'the drag changed the picture');
  cmp = await h.compareCanvas(page,
    h.snapshot(daemon.server, moved.camera, moved.lastImage.width, moved.lastImage.height));
  h.check(cmp.meanDiff < 4, `after the drag the daemon rendered the page's camera (mean difference ${cmp.meanDiff})`);
  h.check(/fps · round trip \d+ ms/.test(await page.$eval('#hud', (e) => e.textContent)),
    'the HUD shows the frame rate and the round trip');
  // Save PNG: a full-size lossless render of the current view.
  await page.click('#save');
  const saved = await h.until(() => page.evaluate(() => window.fluidcastViewer.state.saved), 'the saved PNG');
  h.check(saved.width === moved.lastImage.width && saved.height === moved.lastImage.height &&
    saved.signature.join(',') === '137,80,78,71,13,10,26,10',
  `Save PNG renders the view full size as PNG (${JSON.stringify(saved)})`);
  // A double-click on the fluid makes the point under it the pivot: the camera's new target.
  await page.mouse.click(box.x + box.width / 2, box.y + box.height / 2, { count: 2 });
  const picked = await h.until(async () => {
    const state = await page.evaluate(() => window.fluidcastViewer.state);
    return state.picked && JSON.stringify(state.camera.target) === JSON.stringify(state.picked) ? state : null;
  }, 'the pivot picked', 30).catch(async (e) => {
    console.log(JSON.stringify(await h.viewerState(page)), await page.evaluate(() =>
      JSON.stringify({ picked: window.fluidcastViewer.state.picked, errors: window.fluidcastViewer.state.errors })));
    throw e;
  });
  const shift = Math.hypot(...picked.picked.map((x, i) => x - moved.camera.target[i]));
  h.check(shift > 1e-3, `a double-click on the fluid recentres on the point under it (moved ${shift})`);
  await h.waitImage(page, (await h.viewerState(page)).imagesShown - 1, { rest: true });
  const beforeReset = await h.canvasPixels(page);
  await page.click('#reset');
  const reset = await h.until(async () => {
    const state = await h.viewerState(page);
    // the first image of the new subscription: a new-frame image, not a VIEW of the old camera
    return state.imagesShown > moved.imagesShown && state.lastImage.flags === 0 ? state : null;
  }, 'the picture after Reset view');
  const resetDiff = h.pixelDifference(beforeReset, await h.canvasPixels(page));
  h.check(reset.camera === null && resetDiff > 5,
    `Reset view rejoins the session framed by the daemon (camera ${JSON.stringify(reset.camera)}, ` +
    `difference ${resetDiff})`);
  h.check(page.consoleErrors.length === 0, `the viewer page logged no error (${page.consoleErrors})`);

  const ended = await producer.release();
  h.check(ended.status === 0, 'the producer ended normally');
  await browser.close();
  await h.stopDaemon(daemon);
});
