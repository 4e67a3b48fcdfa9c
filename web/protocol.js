// protocol.js — the viewer's side of the fluidcast wire protocol (proto/PROTOCOL.md) in the browser:
// each binary WebSocket message is one protocol message, header and payload (PROTOCOL.md section 14).
// Little-endian throughout; strings are a u16 length and UTF-8 bytes.

export const HEADER_SIZE = 16;
export const MSG = {
  HELLO: 1, WELCOME: 2, CAMERA: 4, SETTINGS: 5, RENDER: 6, IMAGE: 7, ERROR: 8, GOODBYE: 9,
  SUBSCRIBE: 17, SESSION_STATE: 18, SESSION_END: 19, STREAM_IMAGE: 20, LIST_SESSIONS: 23, SESSION_LIST: 24,
};
export const CAP_SESSIONS = 1;
export const FORMAT = { PNG: 1, JPEG: 2, RAW: 4, H264: 5 };
export const AOV = { COLOR: 0, DEPTH: 1 };
export const FLAG = { REFRESH: 1, VIEW: 2, KEYFRAME: 4 };
export const STAGE_NAMES = ['upload', 'depth', 'thickness', 'smoothing', 'composite', 'readback', 'encode',
  'total', 'receive', 'decode', 'queue'];
export const ERROR_NAMES = ['', 'BAD_MAGIC', 'VERSION', 'UNKNOWN_TYPE', 'TOO_LARGE', 'MALFORMED', 'BAD_STATE',
  'INVALID_VALUE', 'LIMIT', 'RENDER', 'ENCODE', 'INTERNAL', 'UNAUTHORIZED', 'DUPLICATE', 'INCONSISTENT',
  'INCOMPLETE'];
export const ERR_UNAUTHORIZED = 12;
// Setting keys of the table in PROTOCOL.md section 7.5 that the page changes.
export const SETTING = { COLOR_BY: 22, COLORMAP: 23, COLOR_RANGE: 24, JPEG_SUBSAMPLING: 32 };

const MAGIC = [0x46, 0x43, 0x53, 0x54];
const encoder = new TextEncoder();
const decoder = new TextDecoder();

// Builds payloads field by field.
class Writer {
  constructor() { this.bytes = []; }
  u16(v) { this.bytes.push(v & 255, (v >>> 8) & 255); return this; }
  u32(v) { this.u16(v & 0xffff); return this.u16(v >>> 16); }
  f32(v) { new Uint8Array(new Float32Array([v]).buffer).forEach((b) => this.bytes.push(b)); return this; }
  str(s) { const b = encoder.encode(s); this.u16(b.length); b.forEach((x) => this.bytes.push(x)); return this; }
  payload() { return new Uint8Array(this.bytes); }
}

export function message(type, requestId, payload = new Uint8Array(0)) {
  const out = new Uint8Array(HEADER_SIZE + payload.length);
  const view = new DataView(out.buffer);
  out.set(MAGIC, 0);
  view.setUint16(4, type, true);
  view.setUint16(6, 0, true);
  view.setUint32(8, requestId, true);
  view.setUint32(12, payload.length, true);
  out.set(payload, HEADER_SIZE);
  return out;
}

export function hello(requestId, clientName, token) {
  const w = new Writer().u32(1).u32(1).u32(CAP_SESSIONS).str(clientName);
  if (token) w.str(token);
  return message(MSG.HELLO, requestId, w.payload());
}

export function subscribe(requestId, name, format, quality, width, height) {
  const w = new Writer().u32(format).u32(quality).u32(AOV.COLOR).u32(width).u32(height).str(name);
  return message(MSG.SUBSCRIBE, requestId, w.payload());
}

export function camera(requestId, cam) {
  const w = new Writer();
  [...cam.eye, ...cam.target, ...cam.up, cam.fov].forEach((x) => w.f32(x));
  w.u32(cam.width).u32(cam.height);
  return message(MSG.CAMERA, requestId, w.payload());
}

// entries: [[key, [values...], 'f32' | 'u32'], ...]
export function settings(requestId, entries) {
  const w = new Writer().u32(entries.length);
  for (const [key, values, type] of entries) {
    w.u16(key).u16(values.length);
    values.forEach((v) => (type === 'f32' ? w.f32(v) : w.u32(v)));
  }
  return message(MSG.SETTINGS, requestId, w.payload());
}

export function render(requestId, format, quality, aov) {
  return message(MSG.RENDER, requestId, new Writer().u32(format).u32(quality).u32(aov).payload());
}

export const listSessions = (requestId) => message(MSG.LIST_SESSIONS, requestId);
export const goodbye = () => message(MSG.GOODBYE, 0);

// Reads fields in order from one payload.
class Reader {
  constructor(bytes) {
    this.bytes = bytes;
    this.view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
    this.at = 0;
  }
  need(n) { if (this.at + n > this.bytes.length) throw new Error('malformed message from the server'); }
  u32() { this.need(4); const v = this.view.getUint32(this.at, true); this.at += 4; return v; }
  u64() { const lo = this.u32(); const hi = this.u32(); return hi * 4294967296 + lo; }
  f32() { this.need(4); const v = this.view.getFloat32(this.at, true); this.at += 4; return v; }
  str() {
    this.need(2);
    const n = this.view.getUint16(this.at, true);
    this.at += 2;
    this.need(n);
    const s = decoder.decode(this.bytes.subarray(this.at, this.at + n));
    this.at += n;
    return s;
  }
  bytesOf(n) { this.need(n); const b = this.bytes.subarray(this.at, this.at + n); this.at += n; return b; }
}

// One whole message (an ArrayBuffer) into {type, requestId, payload}.
export function parse(buffer) {
  const bytes = new Uint8Array(buffer);
  if (bytes.length < HEADER_SIZE || MAGIC.some((b, i) => bytes[i] !== b)) throw new Error('not a fluidcast message');
  const view = new DataView(buffer);
  const length = view.getUint32(12, true);
  if (bytes.length !== HEADER_SIZE + length) throw new Error('message length disagrees with its header');
  return { type: view.getUint16(4, true), requestId: view.getUint32(8, true), payload: bytes.subarray(HEADER_SIZE) };
}

export function readWelcome(payload) {
  const r = new Reader(payload);
  const welcome = { version: r.u32(), capabilities: r.u32(), maxParticles: r.u64(), maxWidth: r.u32(),
    maxHeight: r.u32(), maxMessage: r.u32() };
  welcome.serverVersion = r.str();
  welcome.renderer = r.str();
  return welcome;
}

export function readError(payload) {
  const r = new Reader(payload);
  const code = r.u32();
  return { code, name: ERROR_NAMES[code] || `code ${code}`, message: r.str() };
}

function readState(r) {
  return { producers: r.u32(), viewers: r.u32(), frames: r.u64(), lastFrame: r.u64(), name: r.str() };
}

export const readSessionState = (payload) => readState(new Reader(payload));

export function readSessionList(payload) {
  const r = new Reader(payload);
  const sessions = [];
  for (let n = r.u32(); n > 0; n--) sessions.push(readState(r));
  return sessions;
}

export function readSessionEnd(payload) {
  return new Reader(payload).str();
}

function readImageFields(r) {
  const image = { width: r.u32(), height: r.u32(), format: r.u32(), aov: r.u32(), stages: {} };
  for (let n = r.u32(); n > 0; n--) {
    const stage = r.u32();
    image.stages[STAGE_NAMES[stage] || `stage ${stage}`] = r.f32();
  }
  const size = r.u64();
  image.data = r.bytesOf(size);
  return image;
}

export const readImage = (payload) => readImageFields(new Reader(payload));

export function readStreamImage(payload) {
  const r = new Reader(payload);
  const tag = { frameNumber: r.u64(), sequence: r.u64(), missed: r.u32(), flags: r.u32() };
  return { ...tag, ...readImageFields(r) };
}
