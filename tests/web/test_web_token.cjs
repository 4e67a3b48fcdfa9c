// test_web_token.cjs — a daemon with a token: the page says it needs one, refuses a wrong one with a
// message, and joins with the right one; the token never appears in the page's URL.
'use strict';
const h = require('./harness.cjs');

const TOKEN = 'web-test-secret-7';

async function submitToken(page, token) {
  await page.$eval('#token', (e) => { e.value = ''; });
  await page.type('#token', token);
  await page.click('#token-form button');
}

h.run(async () => {
  const daemon = await h.startDaemon({ env: { FLUIDCAST_TOKEN: TOKEN } });
  const producer = h.startProducer(daemon.server, 'locked', 0, { FLUIDCAST_TOKEN: TOKEN });
  const browser = await h.launchBrowser();
  const page = await h.openPage(browser, daemon.web, '?session=locked&format=jpeg');
  const visible = () => page.$eval('#token-form', (e) => !e.classList.contains('hidden'));
  await h.until(visible, 'the token form');
  h.check(/needs a token/.test((await h.viewerState(page)).message), 'without a token the page says it needs one');
  await submitToken(page, 'not-the-token');
  await h.until(async () => (await h.viewerState(page)).refusals === 2 && visible(), 'the wrong token refused');
  h.check((await h.viewerState(page)).message.includes('not accepted'), 'the page says the token was not accepted');
  h.check((await h.viewerState(page)).imagesShown === 0, 'a wrong token shows no picture');
  await submitToken(page, TOKEN);
  const s = await h.waitImage(page, 0).catch(async (e) => {
    await page.screenshot({ path: `${h.WORK}/token.png` });
    console.log(JSON.stringify(await h.viewerState(page)));
    throw e;
  });
  h.check(s.connected && s.imagesShown > 0, 'the right token joins the session');
  h.check(!page.url().includes(TOKEN), 'the token is not in the URL');
  h.check((await producer.release()).status === 0, 'the producer ended normally');
  await browser.close();
  await h.stopDaemon(daemon);
});
