// test_web_tls.cjs — a daemon with a certificate serves the web viewer over HTTPS and its WebSocket over
// WSS, with the same certificate as its protocol listeners: certificates made by openssl here (a CA and a
// server for localhost and 127.0.0.1), trusted by the browser the way a user's is (the CA in the NSS
// database of the browser's HOME), not by switching certificate checks off. A browser that does not trust
// the CA is refused; plain HTTP on the HTTPS port gets no page.
'use strict';
const { spawnSync } = require('node:child_process');
const crypto = require('node:crypto');
const fs = require('node:fs');
const tls = require('node:tls');
const path = require('node:path');
const h = require('./harness.cjs');

function run(command, args) {
  const r = spawnSync(command, args, { encoding: 'utf8' });
  if (r.status !== 0) throw new Error(`${command} ${args.join(' ')}: ${r.stderr}`);
}

// A CA and two server certificates signed by it (ECDSA P-256, valid for a day): the daemon's files
// (server.pem, server.key) and a second pair to rotate to (next.pem, next.key).
function makeCertificates(dir) {
  const f = (name) => path.join(dir, name);
  fs.writeFileSync(f('server.ext'), 'subjectAltName=DNS:localhost,IP:127.0.0.1\n');
  run('openssl', ['req', '-x509', '-newkey', 'ec', '-pkeyopt', 'ec_paramgen_curve:P-256', '-nodes', '-days', '1',
    '-subj', '/CN=fluidcast web test CA', '-keyout', f('ca.key'), '-out', f('ca.pem')]);
  for (const name of ['server', 'next']) {
    run('openssl', ['req', '-newkey', 'ec', '-pkeyopt', 'ec_paramgen_curve:P-256', '-nodes', '-subj', '/CN=localhost',
      '-keyout', f(`${name}.key`), '-out', f(`${name}.csr`)]);
    run('openssl', ['x509', '-req', '-in', f(`${name}.csr`), '-CA', f('ca.pem'), '-CAkey', f('ca.key'),
      '-CAcreateserial', '-days', '1', '-extfile', f('server.ext'), '-out', f(`${name}.pem`)]);
  }
  return { ca: f('ca.pem'), cert: f('server.pem'), key: f('server.key'), nextCert: f('next.pem'),
    nextKey: f('next.key') };
}

// The serial number of the certificate a TLS server at HOST:PORT presents (verified against ca).
function servedSerial(address, ca) {
  const [host, port] = address.split(':');
  return new Promise((resolve, reject) => {
    const socket = tls.connect({ host, port: Number(port), ca: fs.readFileSync(ca), servername: 'localhost' }, () => {
      resolve(socket.getPeerCertificate().serialNumber);
      socket.destroy();
    });
    socket.on('error', reject);
  });
}

const serialOf = (pem) => new crypto.X509Certificate(fs.readFileSync(pem)).serialNumber;

// A HOME whose NSS database trusts the CA for TLS servers: where chromium on Linux looks.
function homeTrusting(dir, ca) {
  const db = path.join(dir, '.pki', 'nssdb');
  fs.mkdirSync(db, { recursive: true });
  run('certutil', ['-N', '-d', `sql:${db}`, '--empty-password']);
  if (ca) run('certutil', ['-A', '-d', `sql:${db}`, '-n', 'fluidcast web test CA', '-t', 'C,,', '-i', ca]);
  return dir;
}

h.run(async () => {
  const certs = makeCertificates(h.WORK);
  // The CLI (the producer, the snapshots) verifies the daemon against the same CA.
  process.env.SSL_CERT_FILE = certs.ca;
  const daemon = await h.startDaemon({ args: ['--tls-cert', certs.cert, '--tls-key', certs.key] });
  h.check(daemon.origin.startsWith('https://'), `with a certificate the daemon serves ${daemon.origin}`);
  const producer = h.startProducer(daemon.server, 'secure');

  const browser = await h.launchBrowser({ HOME: homeTrusting(path.join(h.WORK, 'home'), certs.ca) });
  const page = await h.openPage(browser, daemon.origin, '?session=secure&format=jpeg');
  let s = await h.waitImage(page, 0).catch(async (e) => {
    console.log(page.url(), JSON.stringify(page.consoleErrors));
    throw e;
  });
  h.check(page.url().startsWith('https://') && s.connected, 'the page loads over HTTPS and joins over WSS');
  await page.evaluate(() => window.fluidcastViewer.setCamera({ eye: [0.4, -1.6, 0.9], target: [0.4, 0.3, 0.2],
    up: [0, 0, 1], fov: 40, width: 0, height: 0 }));
  s = await h.waitImage(page, s.imagesShown, { rest: true });
  const cmp = await h.compareCanvas(page,
    h.snapshot(daemon.server, s.camera, s.lastImage.width, s.lastImage.height));
  h.check(cmp.spread > 10 && cmp.meanDiff < 4,
    `over WSS the canvas shows the snapshot of the same frame and camera (mean difference ${cmp.meanDiff})`);
  h.check(page.consoleErrors.length === 0, `the page logged no error (${page.consoleErrors})`);
  await browser.close();

  // A browser that does not trust the CA gets a certificate error, not the page.
  const stranger = await h.launchBrowser({ HOME: homeTrusting(path.join(h.WORK, 'stranger'), null) });
  const refused = await h.openPage(stranger, daemon.origin).then(() => 'loaded', (e) => e.message);
  h.check(/ERR_CERT_AUTHORITY_INVALID/.test(refused), `a browser without the CA is refused (${refused})`);
  await stranger.close();

  // SIGHUP rotates the web listener's certificate with the protocol listeners': new connections get the
  // new one, and the page still loads and shows the session.
  h.check(await servedSerial(daemon.web, certs.ca) === serialOf(certs.cert), 'the web port serves the certificate');
  fs.copyFileSync(certs.nextCert, certs.cert);
  fs.copyFileSync(certs.nextKey, certs.key);
  daemon.proc.kill('SIGHUP');
  await h.until(() => /TLS certificate and key reloaded/.test(fs.readFileSync(daemon.logPath, 'utf8')), 'the reload');
  h.check(await servedSerial(daemon.web, certs.ca) === serialOf(certs.nextCert),
    'after SIGHUP the web port serves the new certificate');
  const again = await h.launchBrowser({ HOME: path.join(h.WORK, 'home') });
  const reloaded = await h.openPage(again, daemon.origin, '?session=secure&format=jpeg');
  h.check((await h.waitImage(reloaded, 0)).connected, 'after the rotation the page loads and joins over WSS');
  await again.close();

  const plain = await fetch(`http://${daemon.web}/`).then((r) => `HTTP ${r.status}`, (e) => `failed: ${e.cause?.code || e}`);
  h.check(plain.startsWith('failed'), `plain HTTP on the HTTPS port gets no page (${plain})`);
  h.check((await producer.release()).status === 0, 'the producer over TLS ended normally');
  await h.stopDaemon(daemon);
});
