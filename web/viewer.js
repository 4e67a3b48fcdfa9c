// viewer.js — the web viewer: the daemon's live sessions, and one session watched with a camera of its own
// (docs/web.md). Speaks the viewer side of the protocol over the WebSocket the daemon serves next to this
// page (protocol.js); no build step, no library.
import * as fc from './protocol.js';
import * as cam from './camera.js';

const REST_MS = 300;          // still this long: the full-size image follows the half-size previews
const LIST_REFRESH_MS = 2000; // the session list is asked for again this often
const RECONNECT_MS = [500, 1000, 2000, 5000];
const TOKEN_KEY = 'fluidcast-token';

const $ = (id) => document.getElementById(id);
const params = new URLSearchParams(location.search);
const sessionName = params.get('session');

// Everything the page knows; window.fluidcastViewer exposes it to the tests (tests/web/).
const state = {
  connected: false, welcome: null, requestId: 0, subscribeId: 0, format: null,
  camera: null,            // the page's own camera; null while the server frames the view
  cameraSentAt: 0, cameraRequestId: 0, cameraInFlight: false, cameraQueued: false, moving: false, restTimer: 0,
  imagesShown: 0, shownByFormat: {}, imagesDecoding: 0, lastImage: null, lastRttMs: null, fpsTimes: [],
  ended: false, resetting: false, unauthorized: false, refusals: 0,
  reconnects: 0, errors: [], pending: new Map(), decoder: null, decoderReady: false, colormaps: null,
};
window.fluidcastViewer = { state, setCamera: (c) => applyCamera(c, false), requestKeyFrame, viewSize };

let ws = null;
let listTimer = 0;

function nextId() { state.requestId = (state.requestId % 0xfffffff0) + 1; return state.requestId; }

function send(bytes) { if (ws && ws.readyState === WebSocket.OPEN) ws.send(bytes); }

function say(text, kind = 'info') {
  const box = $('message');
  box.textContent = text;
  box.className = text ? kind : 'hidden';
}

// ---- connection -----------------------------------------------------------------------------------------

function connect() {
  const scheme = location.protocol === 'https:' ? 'wss:' : 'ws:';
  ws = new WebSocket(`${scheme}//${location.host}/ws`, 'fluidcast.v1');
  ws.binaryType = 'arraybuffer';
  ws.onopen = () => {
    send(fc.hello(nextId(), 'fluidcast-web 0.1.0', sessionStorage.getItem(TOKEN_KEY) || ''));
  };
  ws.onmessage = (event) => {
    try {
      dispatch(fc.parse(event.data));
    } catch (e) {
      say(`the daemon sent something this page cannot read: ${e.message}`, 'error');
      ws.close();
    }
  };
  ws.onclose = () => {
    state.connected = false;
    clearInterval(listTimer);
    closeDecoder();
    if (state.unauthorized) return;
    if (state.resetting) {
      state.resetting = false;
      connect();
      return;
    }
    const delay = RECONNECT_MS[Math.min(state.reconnects, RECONNECT_MS.length - 1)];
    state.reconnects++;
    say(`the daemon at ${location.host} went away; reconnecting in ${(delay / 1000).toFixed(1)} s…`, 'error');
    setTimeout(connect, delay);
  };
}

function dispatch(msg) {
  switch (msg.type) {
    case fc.MSG.WELCOME: return onWelcome(fc.readWelcome(msg.payload));
    case fc.MSG.ERROR: return onError(msg.requestId, fc.readError(msg.payload));
    case fc.MSG.SESSION_LIST: return showSessions(fc.readSessionList(msg.payload));
    case fc.MSG.SESSION_STATE: return onSessionState(fc.readSessionState(msg.payload));
    case fc.MSG.SESSION_END: return onSessionEnd(msg.requestId, fc.readSessionEnd(msg.payload));
    case fc.MSG.STREAM_IMAGE: return onStreamImage(fc.readStreamImage(msg.payload));
    case fc.MSG.IMAGE: return onImage(msg.requestId, fc.readImage(msg.payload));
    case fc.MSG.GOODBYE: return ws.close();
    default: return undefined;
  }
}

function onWelcome(welcome) {
  state.welcome = welcome;
  state.connected = true;
  state.reconnects = 0;
  $('server').textContent = `${welcome.serverVersion} · ${welcome.renderer}`;
  $('token-form').classList.add('hidden');
  if (!sessionName) {
    say('');
    send(fc.listSessions(nextId()));
    listTimer = setInterval(() => send(fc.listSessions(nextId())), LIST_REFRESH_MS);
    return;
  }
  subscribe();
}

function onError(requestId, error) {
  if (error.code === fc.ERR_UNAUTHORIZED) {
    state.unauthorized = true;
    state.refusals++;
    say('this daemon needs a token, and the one given was not accepted: enter it below', 'error');
    $('token-form').classList.remove('hidden');
    return;
  }
  state.errors.push(error);
  if (requestId === state.cameraRequestId) cameraAnswered();   // a refused CAMERA brings no image
  const pick = state.pending.get(requestId);
  state.pending.delete(requestId);
  say(`${pick ? pick.what : 'the daemon'}: ${error.name}: ${error.message}`, 'error');
  if (requestId === state.subscribeId && state.format === fc.FORMAT.H264) requestKeyFrame();
}

// ---- the session list -----------------------------------------------------------------------------------

function showSessions(sessions) {
  $('sessions').classList.remove('hidden');
  const list = $('session-list');
  list.replaceChildren(...sessions.map((s) => {
    const item = document.createElement('li');
    const link = document.createElement('a');
    link.href = `?session=${encodeURIComponent(s.name)}`;
    link.textContent = s.name;
    item.append(link, ` — ${s.producers} producer(s), ${s.viewers} viewer(s), ${s.frames} frame(s)`);
    return item;
  }));
  $('no-sessions').classList.toggle('hidden', sessions.length > 0);
}

// ---- one session ----------------------------------------------------------------------------------------

function chooseFormat() {
  const asked = params.get('format') || 'auto';
  if (asked === 'jpeg') return Promise.resolve(fc.FORMAT.JPEG);
  if (!('VideoDecoder' in window)) return Promise.resolve(fc.FORMAT.JPEG);
  return VideoDecoder.isConfigSupported({ codec: 'avc1.42E01F', optimizeForLatency: true })
    .then((r) => (r.supported ? fc.FORMAT.H264 : fc.FORMAT.JPEG), () => fc.FORMAT.JPEG);
}

// The render size: the view's CSS pixels, halved while the camera moves, within the daemon's limits and
// even (H.264's 4:2:0 halves both sides).
function viewSize(half) {
  const rect = $('view').getBoundingClientRect();
  const k = half ? 0.5 : 1;
  const even = (x, max) => Math.max(2, Math.min(max, Math.floor((x * k) / 2) * 2));
  const w = state.welcome;
  return { width: even(rect.width, w ? w.maxWidth : 8192), height: even(rect.height, w ? w.maxHeight : 8192) };
}

async function subscribe() {
  state.format = await chooseFormat();
  $('format').textContent = state.format === fc.FORMAT.H264 ? 'H.264 (WebCodecs)' : 'JPEG';
  $('viewer').classList.remove('hidden');
  const size = viewSize(false);
  state.subscribeId = nextId();
  state.ended = false;
  if (state.format === fc.FORMAT.H264) openDecoder();
  sendColorSettings();
  send(fc.subscribe(state.subscribeId, sessionName, state.format, 0, size.width, size.height));
  if (state.camera) sendCamera();
}

function onSessionState(s) {
  $('session-name').textContent = s.name;
  if (s.lastFrame === 0) say(`waiting for session ${s.name}: no producer has published a frame yet`);
  else say('');
}

function onSessionEnd(requestId, name) {
  if (requestId !== state.subscribeId) return;
  // The viewer stays on the ended session's last frame (PROTOCOL.md 10.1): the camera still turns it. A
  // new run under the same name is a new session, joined when asked.
  state.ended = true;
  say(`session ${name} ended: its last frame stays, and the view still turns it`);
  $('rejoin').classList.remove('hidden');
}

function rejoin() {
  $('rejoin').classList.add('hidden');
  closeDecoder();
  subscribe();
}

// ---- images ---------------------------------------------------------------------------------------------

// An ImageBitmap or a decoded VideoFrame, at its own size.
function drawPicture(picture, width, height) {
  const canvas = $('view');
  if (canvas.width !== width || canvas.height !== height) {
    canvas.width = width;
    canvas.height = height;
  }
  canvas.getContext('2d').drawImage(picture, 0, 0, width, height);
}

function countShown(image) {
  const now = performance.now();
  state.imagesShown++;
  state.shownByFormat[image.format] = (state.shownByFormat[image.format] || 0) + 1;
  state.lastImage = { width: image.width, height: image.height, format: image.format, frame: image.frameNumber,
    flags: image.flags, missed: image.missed, stages: image.stages };
  state.fpsTimes.push(now);
  while (state.fpsTimes.length && state.fpsTimes[0] < now - 1000) state.fpsTimes.shift();
  if (image.flags & fc.FLAG.VIEW && state.cameraSentAt) {
    state.lastRttMs = now - state.cameraSentAt;
    state.cameraSentAt = 0;
  }
  updateHud();
}

function onStreamImage(image) {
  // Any image frees the camera slot: a VIEW answers it, and a new frame's image (a session that had no frame
  // when the camera went out sends no VIEW) is rendered with the newest camera the daemon has.
  cameraAnswered();
  if ($('message').textContent.startsWith('waiting for session')) say('');
  if (image.format === fc.FORMAT.H264) return decodeAccessUnit(image);
  const type = image.format === fc.FORMAT.PNG ? 'image/png' : 'image/jpeg';
  state.imagesDecoding++;
  createImageBitmap(new Blob([image.data], { type })).then((bitmap) => {
    drawPicture(bitmap, bitmap.width, bitmap.height);
    bitmap.close();
    countShown(image);
  }, (e) => say(`cannot decode an image: ${e.message}`, 'error')).finally(() => { state.imagesDecoding--; });
  return undefined;
}

// H.264 (PROTOCOL.md 10.7): Annex B access units, decoded in order from an IDR on; an undecodable one asks
// the daemon for a key frame.
function openDecoder() {
  closeDecoder();
  state.decoderReady = false;
  state.decoder = new VideoDecoder({
    output: (frame) => {
      drawPicture(frame, frame.displayWidth, frame.displayHeight);
      frame.close();
      const image = state.decoding.shift();
      state.imagesDecoding--;
      if (image) countShown(image);
    },
    error: (e) => {
      say(`H.264 decoding failed (${e.message}); asking for a key frame`, 'error');
      state.decoder = null;
      openDecoder();
      requestKeyFrame();
    },
  });
  state.decoding = [];
}

function closeDecoder() {
  if (state.decoder && state.decoder.state !== 'closed') state.decoder.close();
  state.decoder = null;
}

// avc1.PPCCLL from the stream's SPS (NAL type 7): profile, constraints and level.
function codecOf(data) {
  for (let i = 0; i + 7 < data.length; i++) {
    if (data[i] === 0 && data[i + 1] === 0 && data[i + 2] === 1 && (data[i + 3] & 31) === 7) {
      const hex = (b) => b.toString(16).padStart(2, '0');
      return `avc1.${hex(data[i + 4])}${hex(data[i + 5])}${hex(data[i + 6])}`;
    }
  }
  return null;
}

function decodeAccessUnit(image) {
  if (!state.decoder) openDecoder();
  const key = (image.flags & fc.FLAG.KEYFRAME) !== 0;
  if (key) {
    const codec = codecOf(image.data);
    if (codec) {
      state.decoder.configure({ codec, optimizeForLatency: true });
      state.decoderReady = true;
    }
  }
  if (!state.decoderReady) return;
  state.decoding.push(image);
  state.imagesDecoding++;
  state.decoder.decode(new EncodedVideoChunk({ type: key ? 'key' : 'delta', timestamp: image.sequence * 1000,
    data: image.data }));
}

function requestKeyFrame() {
  send(fc.settings(nextId(), []));
}

// RENDER replies: the saved PNG and the depth under a double-click.
function onImage(requestId, image) {
  const pick = state.pending.get(requestId);
  state.pending.delete(requestId);
  if (pick) pick.done(image);
}

// A RENDER of the session's newest frame with this viewer's camera, answered by an IMAGE.
function renderOnce(format, aov, what, done) {
  const id = nextId();
  state.pending.set(id, { what, done });
  send(fc.render(id, format, 0, aov));
}

// ---- the camera -----------------------------------------------------------------------------------------

// One CAMERA in flight: the next goes out when the image for the previous has come, so a fast drag never
// queues renders and the newest camera wins.
function sendCamera() {
  if (state.cameraInFlight) { state.cameraQueued = true; return; }
  state.cameraInFlight = true;
  state.cameraQueued = false;
  state.cameraSentAt = performance.now();
  state.cameraRequestId = nextId();
  send(fc.camera(state.cameraRequestId, { ...state.camera, ...viewSize(state.moving) }));
}

function cameraAnswered() {
  state.cameraInFlight = false;
  if (state.cameraQueued) sendCamera();
}

function applyCamera(next, moving) {
  state.camera = next;
  state.moving = moving;
  clearTimeout(state.restTimer);
  if (moving) state.restTimer = setTimeout(() => { state.moving = false; sendCamera(); }, REST_MS);
  sendCamera();
}

function startCamera() {
  if (!state.camera) state.camera = cam.homeCamera(...Object.values(viewSize(false)));
  return state.camera;
}

function installControls() {
  const canvas = $('view');
  const pointers = new Map();
  let pinch = null;
  canvas.addEventListener('pointerdown', (e) => {
    canvas.setPointerCapture(e.pointerId);
    pointers.set(e.pointerId, { x: e.clientX, y: e.clientY, button: e.button });
  });
  const release = (e) => { pointers.delete(e.pointerId); pinch = null; };
  canvas.addEventListener('pointerup', release);
  canvas.addEventListener('pointercancel', release);
  canvas.addEventListener('pointermove', (e) => {
    const p = pointers.get(e.pointerId);
    if (!p) return;
    const dx = e.clientX - p.x, dy = e.clientY - p.y;
    p.x = e.clientX;
    p.y = e.clientY;
    const height = canvas.getBoundingClientRect().height;
    const c = startCamera();
    if (pointers.size === 2) {   // two fingers: pinch dollies, moving both pans
      const [a, b] = [...pointers.values()];
      const spread = Math.hypot(a.x - b.x, a.y - b.y);
      if (pinch) applyCamera(cam.pan(cam.dolly(c, 10 * Math.log(spread / pinch)), dx / 2, dy / 2, height), true);
      pinch = spread;
      return;
    }
    applyCamera(p.button === 0 && !e.shiftKey ? cam.orbit(c, dx, dy, height) : cam.pan(c, dx, dy, height), true);
  });
  canvas.addEventListener('contextmenu', (e) => e.preventDefault());
  canvas.addEventListener('wheel', (e) => {
    e.preventDefault();
    applyCamera(cam.dolly(startCamera(), -e.deltaY / 100), true);
  }, { passive: false });
  canvas.addEventListener('dblclick', (e) => pickPivot(e));
  $('reset').addEventListener('click', () => {
    // A connection keeps its camera across subscriptions: a new one is framed by the server again.
    state.camera = null;
    state.cameraInFlight = state.cameraQueued = false;
    state.resetting = true;
    ws.close();
  });
  $('save').addEventListener('click', savePng);
  $('rejoin').addEventListener('click', rejoin);
  for (const id of ['color-by', 'colormap', 'range-min', 'range-max'])
    $(id).addEventListener('change', sendColorSettings);
  window.addEventListener('resize', () => { if (state.camera) applyCamera(state.camera, true); });
}

// The fluid under the cursor becomes the pivot: its depth read from a depth image of the current view.
// The server's own framing is unknown to the page, so a first double-click moves to the page's camera.
function pickPivot(e) {
  const rect = $('view').getBoundingClientRect();
  const u = (e.clientX - rect.left) / rect.width, v = (e.clientY - rect.top) / rect.height;
  if (!state.camera) { applyCamera(startCamera(), false); return; }
  renderOnce(fc.FORMAT.RAW, fc.AOV.DEPTH, 'picking the pivot', (image) => {
    const x = Math.min(image.width - 1, Math.floor(u * image.width));
    const y = Math.min(image.height - 1, Math.floor(v * image.height));
    const depth = new DataView(image.data.buffer, image.data.byteOffset).getFloat32((y * image.width + x) * 4, true);
    if (!(depth > 0)) { say('no fluid under the cursor'); return; }
    state.picked = cam.unproject(state.camera, u, v, depth, image.width / image.height);
    applyCamera(cam.setPivot(state.camera, state.picked), false);
  });
}

function savePng() {
  renderOnce(fc.FORMAT.PNG, fc.AOV.COLOR, 'saving the PNG', (image) => {
    state.saved = { width: image.width, height: image.height, signature: Array.from(image.data.subarray(0, 8)) };
    const link = document.createElement('a');
    link.href = URL.createObjectURL(new Blob([image.data], { type: 'image/png' }));
    link.download = `fluidcast-${sessionName}-${state.lastImage ? state.lastImage.frame : 0}.png`;
    link.click();
    setTimeout(() => URL.revokeObjectURL(link.href), 10000);
  });
}

// ---- colour by attribute and the legend ------------------------------------------------------------------

function colorControls() {
  return { by: Number($('color-by').value), map: Number($('colormap').value), lo: Number($('range-min').value),
    hi: Number($('range-max').value) };
}

// Sent before SUBSCRIBE and when a control changes, never on its own: on a viewer each SETTINGS brings a VIEW
// image, which the one-camera-in-flight accounting would take for the camera's.
function sendColorSettings() {
  const { by, map, lo, hi } = colorControls();
  const entries = [[fc.SETTING.COLOR_BY, [by], 'u32'], [fc.SETTING.COLORMAP, [map], 'u32']];
  if (Number.isFinite(lo) && Number.isFinite(hi) && lo < hi) entries.push([fc.SETTING.COLOR_RANGE, [lo, hi], 'f32']);
  if (state.connected) send(fc.settings(nextId(), entries));
  drawLegend(by, map, lo, hi);
}

function drawLegend(by, map, lo, hi) {
  $('legend').classList.toggle('hidden', by === 0 || !state.colormaps);
  if (by === 0 || !state.colormaps) return;
  const table = state.colormaps[map].colors;
  const canvas = $('legend-bar');
  const ctx = canvas.getContext('2d');
  for (let x = 0; x < canvas.width; x++) {
    const [r, g, b] = table[Math.round((x / (canvas.width - 1)) * (table.length - 1))];
    ctx.fillStyle = `rgb(${r * 255},${g * 255},${b * 255})`;
    ctx.fillRect(x, 0, 1, canvas.height);
  }
  $('legend-min').textContent = String(lo);
  $('legend-max').textContent = `${hi} ${by === 1 ? '(speed)' : '(density)'}`;
}

async function loadColormaps() {
  const maps = await (await fetch('colormaps.json')).json();
  state.colormaps = maps;
  $('colormap').replaceChildren(...maps.map((m, i) => new Option(m.name, String(i))));
}

// ---- HUD ------------------------------------------------------------------------------------------------

function updateHud() {
  const img = state.lastImage;
  const stages = Object.entries(img.stages).filter(([name]) => name !== 'total')
    .map(([name, ms]) => `${name} ${ms.toFixed(1)}`).join(' · ');
  $('hud').textContent = `${state.fpsTimes.length} fps · round trip ${state.lastRttMs === null ? '–' :
    `${state.lastRttMs.toFixed(0)} ms`} · ${img.width}×${img.height} · frame ${img.frame}` +
    (img.missed ? ` (${img.missed} missed)` : '') + (stages ? ` · server ms: ${stages}` : '') +
    (img.stages.total !== undefined ? ` · total ${img.stages.total.toFixed(1)}` : '');
}

// ---- start ----------------------------------------------------------------------------------------------

$('token-form').addEventListener('submit', (e) => {
  e.preventDefault();
  sessionStorage.setItem(TOKEN_KEY, $('token').value);
  state.unauthorized = false;
  say('connecting…');
  connect();
});
if (sessionName) document.title = `${sessionName} — fluidcast`;
installControls();
loadColormaps().then(() => {
  const { by, map, lo, hi } = colorControls();
  drawLegend(by, map, lo, hi);
}, (e) => say(`cannot load the colormaps: ${e.message}`, 'error'));
connect();
