// camera.js — the page's look-at camera moved as the SDL viewer moves its own (client/viewer/view_camera.c):
// a turntable orbit about the target (the pivot) that keeps the horizon level, a pan that keeps the point
// under the cursor under it, a dolly towards the pivot, and recentring on a picked point.

const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const add = (a, b) => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
const scale = (a, k) => [a[0] * k, a[1] * k, a[2] * k];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const norm = (a) => Math.hypot(a[0], a[1], a[2]);
const unit = (a) => scale(a, 1 / norm(a));

// Rotates v about the unit axis by angle radians (Rodrigues).
function rotate(v, axis, angle) {
  const c = Math.cos(angle), s = Math.sin(angle);
  return add(add(scale(v, c), scale(cross(axis, v), s)), scale(axis, dot(axis, v) * (1 - c)));
}

// Where the session's frames are unknown to the page (they live on the server), the first move starts
// from this view of the unit box about the origin, as the SDL viewer's does.
export function homeCamera(width, height) {
  return { eye: [1.8, -2.6, 1.6], target: [0, 0, 0], up: [0, 0, 1], fov: 45, width, height };
}

// The view's right and true-up axes and its forward direction.
function basis(cam) {
  const forward = unit(sub(cam.target, cam.eye));
  const right = unit(cross(forward, cam.up));
  return { forward, right, up: cross(right, forward) };
}

// A drag by (dx, dy) CSS pixels in a view `viewHeight` pixels high: half a turn per view height. A tilt
// that would look straight along up is refused (the camera is returned unchanged).
export function orbit(cam, dx, dy, viewHeight) {
  const k = Math.PI / Math.max(1, viewHeight);
  const up = unit(cam.up);
  let offset = rotate(sub(cam.eye, cam.target), up, -dx * k);
  const right = unit(cross(scale(offset, -1), up));
  const tilted = rotate(offset, right, -dy * k);
  if (Math.abs(dot(unit(tilted), up)) < 0.999) offset = tilted;
  return { ...cam, eye: add(cam.target, offset) };
}

// Moves eye and target together so that the point under the cursor stays under it.
export function pan(cam, dx, dy, viewHeight) {
  const { right, up } = basis(cam);
  const distance = norm(sub(cam.eye, cam.target));
  const perPixel = (2 * distance * Math.tan((cam.fov * Math.PI) / 360)) / Math.max(1, viewHeight);
  const move = add(scale(right, -dx * perPixel), scale(up, dy * perPixel));
  return { ...cam, eye: add(cam.eye, move), target: add(cam.target, move) };
}

// Wheel clicks: positive moves towards the pivot, by a factor of exp(-0.1) each.
export function dolly(cam, clicks) {
  const offset = scale(sub(cam.eye, cam.target), Math.exp(-0.1 * clicks));
  return { ...cam, eye: add(cam.target, offset) };
}

// The world point at linear view depth `depth` under (u, v) in [0, 1], v down, in an image of this aspect
// ratio (width / height).
export function unproject(cam, u, v, depth, aspect) {
  const { forward, right, up } = basis(cam);
  const tanY = Math.tan((cam.fov * Math.PI) / 360);
  const tanX = tanY * aspect;
  const x = (2 * u - 1) * tanX * depth, y = (1 - 2 * v) * tanY * depth;
  return add(add(add(cam.eye, scale(forward, depth)), scale(right, x)), scale(up, y));
}

// The view recentred on pivot, at the same distance and direction.
export function setPivot(cam, pivot) {
  const move = sub(pivot, cam.target);
  return { ...cam, eye: add(cam.eye, move), target: pivot };
}
