// rbf studio: the page. The engine (rbf-web, WebAssembly) holds the session and meshes the
// surface; this module draws it, turns clicks and drags into the command language of
// `rbf sculpt -` (the same lines the command box takes), and offers files in and out.

import init, { WebStudio, coarseCells, fineCells } from './pkg/rbf_web.js';
import { Camera } from './camera.js';
import { Renderer } from './renderer.js';

let COARSE;         // lattice cubes across while dragging (the engine's choice)
let FINE;           // and when an edit is done
const CLICK = 4;     // pixels a press may move and still be a click
const GRAB = 12;     // pixels from a handle that grab it

const $ = (id) => document.getElementById(id);
const canvas = $('view');
const camera = new Camera();
let renderer;
let engine;
let handles = [];
let selected = null;
let drag = null;
let frameQueued = false;

function log(line, refused = false) {
  const entry = document.createElement('div');
  entry.textContent = line;
  if (refused) entry.className = 'refused';
  $('log').prepend(entry);
}

function status(text, error = false) {
  $('status').textContent = text;
  $('status').className = error ? 'error' : '';
}

function readHandles() {
  const flat = engine.handles();
  handles = [];
  for (let k = 0; k < flat.length; k += 8) {
    handles.push({
      index: flat[k], kind: flat[k + 1],
      position: [flat[k + 2], flat[k + 3], flat[k + 4]],
      base: [flat[k + 5], flat[k + 6], flat[k + 7]],
    });
  }
  if (!handles.some((h) => h.index === selected)) selected = null;
}

function upload() {
  renderer.setSurface(engine.positions(), engine.normals(), engine.indices());
  renderer.setDiscs(engine.floaters());
  readHandles();
  renderer.setHandles(handles, selected);
  const triangles = renderer.count / 3;
  status(`${handles.length} constraints · ${triangles} triangles · solve ${engine.lastSolveMs.toFixed(1)} ms · mesh ${engine.lastMeshMs.toFixed(1)} ms`);
  redraw();
}

function redraw() {
  if (frameQueued) return;
  frameQueued = true;
  requestAnimationFrame(() => {
    frameQueued = false;
    renderer.draw(camera, $('show-handles').checked);
  });
}

/// The next frame drawn: what a caller awaits to know the surface it sees is the new one. The
/// draw queued by `redraw` runs first in that frame, this callback right after it.
function nextFrame() {
  return new Promise((resolve) => requestAnimationFrame(() => resolve()));
}

/// Applies a command line, re-meshes, redraws; resolves to the answer once drawn.
async function command(line, cells = FINE, quiet = false) {
  const answer = engine.command(line, cells);
  const refused = answer.startsWith('refused');
  if (answer && (!quiet || refused)) log(`> ${line}\n${answer}`, refused);
  upload();
  await nextFrame();
  return answer;
}

const fmt = (p) => p.map((v) => Number(v.toFixed(6))).join(' ');

function frameSurface() {
  const p = engine.positions();
  if (p.length === 0) return;
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < p.length; i++) {
    lo[i % 3] = Math.min(lo[i % 3], p[i]);
    hi[i % 3] = Math.max(hi[i % 3], p[i]);
  }
  camera.frame(lo, hi);
}

function resize() {
  const ratio = window.devicePixelRatio || 1;
  canvas.width = Math.max(1, Math.round(canvas.clientWidth * ratio));
  canvas.height = Math.max(1, Math.round(canvas.clientHeight * ratio));
  camera.width = canvas.clientWidth;
  camera.height = canvas.clientHeight;
  redraw();
}

function handleAt(x, y) {
  let best = null, bestDistance = GRAB;
  for (const h of handles) {
    const s = camera.project(h.position);
    if (s.z <= 0) continue;
    const d = Math.hypot(s.x - x, s.y - y);
    if (d < bestDistance) { best = h; bestDistance = d; }
  }
  return best;
}

function mode() {
  return document.querySelector('input[name=mode]:checked').value;
}

/// A click on the canvas: on a handle selects it; on the surface adds a constraint there.
async function click(x, y) {
  const h = handleAt(x, y);
  if (h) {
    selected = h.index;
    renderer.setHandles(handles, selected);
    redraw();
    return;
  }
  const { origin, direction } = camera.ray(x, y);
  const hit = engine.hit(origin, direction);
  if (!hit) { selected = null; renderer.setHandles(handles, selected); redraw(); return; }
  const depth = camera.distance * 0.04;
  switch (mode()) {
    case 'boundary': await command(`pick ${fmt(origin)} ${fmt(direction)}`); break;
    case 'interior': await command(`interior ${fmt(hit.map((v, i) => v + depth * direction[i]))}`); break;
    case 'exterior': await command(`exterior ${fmt(hit.map((v, i) => v - depth * direction[i]))}`); break;
  }
}

function pointer(event) {
  const r = canvas.getBoundingClientRect();
  return { x: event.clientX - r.left, y: event.clientY - r.top };
}

canvas.addEventListener('pointerdown', (event) => {
  canvas.focus();
  const { x, y } = pointer(event);
  const h = event.button === 0 && !event.shiftKey ? handleAt(x, y) : null;
  drag = { x, y, startX: x, startY: y, handle: h, moved: false, pan: event.shiftKey || event.button !== 0 };
  if (h) {
    selected = h.index;
    renderer.setHandles(handles, selected);
    engine.beginGesture();
  }
  canvas.setPointerCapture(event.pointerId);
});

canvas.addEventListener('pointermove', (event) => {
  if (!drag) return;
  if (event.buttons === 0) { finishDrag(); return; }  // the release was lost
  const { x, y } = pointer(event);
  if (Math.hypot(x - drag.startX, y - drag.startY) > CLICK) drag.moved = true;
  if (!drag.moved) return;
  if (drag.handle) {
    const to = camera.onPlaneFacing(drag.handle.position, x, y);
    const verb = drag.handle.kind === 3 ? 'tip' : 'move';
    command(`${verb} ${drag.handle.index} ${fmt(to)}`, COARSE, true);
  } else if (drag.pan) {
    camera.pan(x - drag.x, y - drag.y);
    redraw();
  } else {
    camera.orbit(x - drag.x, y - drag.y);
    redraw();
  }
  drag.x = x; drag.y = y;
});

/// Ends a drag: a moved handle's surface is re-meshed finely and its moves become one edit.
function finishDrag() {
  const d = drag;
  drag = null;
  if (!d?.handle) return;
  try {
    if (d.moved) {
      log(`moved item ${d.handle.index}`);
      engine.remesh(FINE);
      upload();
    }
  } catch (e) {
    log(`${e.message}`, true);
  } finally {
    engine.endGesture();
  }
}

canvas.addEventListener('pointerup', async (event) => {
  if (!drag) return;
  const { x, y } = pointer(event);
  const isClick = !drag.moved && event.button === 0;
  finishDrag();
  if (isClick) await click(x, y);
});
canvas.addEventListener('pointercancel', finishDrag);
canvas.addEventListener('lostpointercapture', () => { if (drag) finishDrag(); });
canvas.addEventListener('contextmenu', (event) => event.preventDefault());

canvas.addEventListener('wheel', (event) => {
  event.preventDefault();
  camera.zoom(Math.sign(event.deltaY));
  redraw();
}, { passive: false });

function download(name, bytes, type) {
  const url = URL.createObjectURL(new Blob([bytes], { type }));
  const a = document.createElement('a');
  a.href = url;
  a.download = name;
  a.click();
  setTimeout(() => URL.revokeObjectURL(url), 1000);
}

function exportMesh(extension) {
  try {
    download(`surface.${extension}`, engine.export(`surface.${extension}`), 'application/octet-stream');
  } catch (e) {
    log(`export: ${e.message}`, true);
  }
}

async function undo() { if (!drag) await command('undo'); }
async function redo() { if (!drag) await command('redo'); }
async function addNormal() {
  if (selected === null) { log('select a boundary handle first', true); return; }
  await command(`normal ${selected}`);
}
async function remove() {
  if (selected === null) { log('select a handle first', true); return; }
  await command(`delete ${selected}`);
}

$('undo').onclick = undo;
$('redo').onclick = redo;
$('normal').onclick = addNormal;
$('delete').onclick = remove;
$('save').onclick = () => download('model.json', engine.modelJson(), 'application/json');
$('obj').onclick = () => exportMesh('obj');
$('ply').onclick = () => exportMesh('ply');
$('stl').onclick = () => exportMesh('stl');
$('show-handles').onchange = redraw;
$('show-floaters').onchange = () => {
  engine.setFloaters($('show-floaters').checked);
  upload();
};
$('frame').onclick = () => { frameSurface(); redraw(); };

$('command-form').addEventListener('submit', async (event) => {
  event.preventDefault();
  const line = $('command').value;
  $('command').value = '';
  if (line.trim()) await command(line);
});

window.addEventListener('keydown', async (event) => {
  // Not in the command box, and not while a handle is held: its drag is one edit.
  if (event.target === $('command') || drag) return;
  const key = event.key.toLowerCase();
  if ((event.ctrlKey || event.metaKey) && key === 'z') {
    event.preventDefault();
    await (event.shiftKey ? redo() : undo());
  } else if (key === 'delete' || key === 'backspace') {
    await remove();
  } else if (key === 'n') {
    await addNormal();
  } else if (key === 'f') {
    frameSurface();
    redraw();
  }
});

/// Replaces the session by one read from a dropped or served file; a bad file leaves the
/// session as it was and says why.
async function open(name, bytes) {
  if (drag) finishDrag();
  try {
    const next = name.toLowerCase().endsWith('.json')
      ? WebStudio.fromModel(name, new TextDecoder().decode(bytes))
      : WebStudio.fromMesh(name, new Uint8Array(bytes));
    engine.free();
    engine = next;
    engine.setFloaters($('show-floaters').checked);
    selected = null;
    frameSurface();
    upload();
    log(`opened ${name}: ${handles.length} constraints`);
    return true;
  } catch (e) {
    log(`${e.message}`, true);
    return false;
  }
}

window.addEventListener('dragover', (event) => { event.preventDefault(); document.body.classList.add('dragover'); });
window.addEventListener('dragleave', () => document.body.classList.remove('dragover'));
window.addEventListener('drop', async (event) => {
  event.preventDefault();
  document.body.classList.remove('dragover');
  const file = event.dataTransfer.files[0];
  if (file) await open(file.name, await file.arrayBuffer());
});
window.addEventListener('resize', resize);

/// What tests and scripts drive: see the README.
window.studio = {
  ready: false,
  command: (line) => command(line),
  open: (name, text) => open(name, new TextEncoder().encode(text)),
  state: () => ({
    floaters: renderer.discVertices / 24,
    constraints: handles.length,
    triangles: renderer.count / 3,
    lastSolveMs: engine.lastSolveMs,
    lastMeshMs: engine.lastMeshMs,
    // WebGL on the processor: drawn without multisampling (see renderer.js).
    softwareWebGL: renderer.software,
    multisampled: renderer.gl.getContextAttributes().antialias,
  }),
  handles: () => handles.map((h) => ({ ...h, screen: camera.project(h.position) })),
  modelJson: () => engine.modelJson(),
  bounds: () => {
    const p = engine.positions();
    const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
    for (let i = 0; i < p.length; i++) { lo[i % 3] = Math.min(lo[i % 3], p[i]); hi[i % 3] = Math.max(hi[i % 3], p[i]); }
    return { lo, hi };
  },
  screen: (p) => camera.project(p),
};

async function start() {
  try {
    renderer = new Renderer(canvas);
    await init();
    COARSE = coarseCells();
    FINE = fineCells();
    engine = new WebStudio();
    resize();
    frameSurface();
    upload();
    // A model given to `rbf studio MODEL` is served with the page.
    const config = await (await fetch('studio.json')).json().catch(() => ({}));
    if (config.model) {
      const response = await fetch(config.model);
      await open(config.model, await response.arrayBuffer());
    }
    await nextFrame();
    window.studio.ready = true;
  } catch (e) {
    status(`the studio could not start: ${e.message}`, true);
    throw e;
  }
}

start();
