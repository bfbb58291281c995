// End-to-end tests of rbf studio: the built `rbf` binary serves the built page, Debian's
// Chromium (headless, software WebGL) loads it, and the tests click, drag, type and download as
// a person would. Run by .ci/run: `RBF=target/debug/rbf node --test web/tests/`.

import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { launch, startStudio, RBF } from './harness.mjs';

const work = mkdtempSync(join(tmpdir(), 'rbf-studio-'));
let server, browser, page, url;
const problems = [];

before(async () => {
  ({ child: server, url } = await startStudio());
  browser = await launch();
  page = await browser.newPage({ viewport: { width: 1000, height: 700 }, acceptDownloads: true });
  page.on('console', (m) => { if (m.type() === 'error' || m.type() === 'warning') problems.push(`console ${m.type()}: ${m.text()}`); });
  page.on('pageerror', (e) => problems.push(`page error: ${e.message}`));
  page.on('requestfailed', (r) => problems.push(`request failed: ${r.url()}`));
  page.on('response', (r) => { if (r.status() >= 400) problems.push(`HTTP ${r.status()}: ${r.url()}`); });
  await page.goto(url);
  await page.waitForFunction(() => window.studio?.ready === true, null, { timeout: 30000 });
});

after(async () => {
  await browser?.close();
  server?.kill();
});

const state = () => page.evaluate(() => window.studio.state());
const bounds = () => page.evaluate(() => window.studio.bounds());
const handles = () => page.evaluate(() => window.studio.handles());
const canvasBox = () => page.locator('#view').boundingBox();

/// Distinct colours in the drawn canvas (sampled every 7 pixels).
async function colours() {
  return page.evaluate(() => {
    const source = document.getElementById('view');
    const copy = document.createElement('canvas');
    copy.width = source.width; copy.height = source.height;
    const c = copy.getContext('2d');
    c.drawImage(source, 0, 0);
    const data = c.getImageData(0, 0, copy.width, copy.height).data;
    const seen = new Set();
    for (let i = 0; i < data.length; i += 4 * 7) seen.add((data[i] << 16) | (data[i + 1] << 8) | data[i + 2]);
    return seen.size;
  });
}

const close = (a, b, tolerance) => a.every((v, i) => Math.abs(v - b[i]) <= tolerance);

test('the page has WebGL2 and draws the surface', async () => {
  const webgl2 = await page.evaluate(() => !!document.createElement('canvas').getContext('webgl2'));
  assert.ok(webgl2, 'no WebGL2 context: the page cannot draw');
  const s = await state();
  assert.equal(s.constraints, 12);
  assert.ok(s.triangles > 1000, `${s.triangles} triangles`);
  assert.ok(await colours() > 50, 'the canvas is uniform: nothing was drawn');
});

test('software WebGL is recognized and draws without multisampling', async () => {
  // Headless Chromium here has no graphics card: WebGL is SwiftShader's.
  const name = await page.evaluate(() => {
    const gl = document.createElement('canvas').getContext('webgl2');
    const info = gl.getExtension('WEBGL_debug_renderer_info');
    return gl.getParameter(info.UNMASKED_RENDERER_WEBGL);
  });
  assert.match(name, /SwiftShader/i, `renderer ${name}`);
  const s = await state();
  assert.equal(s.softwareWebGL, true);
  assert.equal(s.multisampled, false);
});

test('a click on the surface adds a constraint there and the surface does not move', async () => {
  const before = await state();
  const { lo, hi } = await bounds();
  const box = await canvasBox();
  const centre = await page.evaluate((p) => window.studio.screen(p), lo.map((v, i) => (v + hi[i]) / 2));
  // Away from every handle, so that the click is not a selection.
  let at = { x: centre.x, y: centre.y };
  for (const h of await handles()) {
    if (Math.hypot(h.screen.x - at.x, h.screen.y - at.y) < 20) at = { x: at.x + 25, y: at.y };
  }
  await page.mouse.click(box.x + at.x, box.y + at.y);
  await page.waitForFunction((n) => window.studio.state().constraints === n, before.constraints + 1);
  const after = await bounds();
  const size = Math.max(...hi.map((v, i) => v - lo[i]));
  // Knot insertion: the surface is the same; only its meshing may differ by a lattice cell.
  assert.ok(close(after.lo, lo, size / 30) && close(after.hi, hi, size / 30),
    `the surface moved: ${JSON.stringify({ lo, hi })} → ${JSON.stringify(after)}`);
});

test('dragging a handle moves it and the surface follows; undo puts both back', async () => {
  const start = await bounds();
  const before = await state();
  const list = await handles();
  // The boundary handle farthest to the right on screen, dragged further right.
  const h = list.filter((x) => x.kind === 0).sort((a, b) => b.screen.x - a.screen.x)[0];
  const box = await canvasBox();
  await page.mouse.move(box.x + h.screen.x, box.y + h.screen.y);
  await page.mouse.down();
  for (let k = 1; k <= 8; k++) await page.mouse.move(box.x + h.screen.x + 10 * k, box.y + h.screen.y, { steps: 1 });
  await page.mouse.up();
  const moved = (await handles()).find((x) => x.index === h.index);
  assert.ok(moved.screen.x > h.screen.x + 40, `the handle stayed at ${h.screen.x} → ${moved.screen.x}`);
  const after = await bounds();
  const grew = after.hi.some((v, i) => v > start.hi[i] + 0.05) || after.lo.some((v, i) => v < start.lo[i] - 0.05);
  assert.ok(grew, `the surface did not follow: ${JSON.stringify(start)} → ${JSON.stringify(after)}`);
  assert.equal((await state()).constraints, before.constraints);
  // One Ctrl+Z undoes the whole drag.
  await page.locator('#view').focus();
  await page.keyboard.press('Control+z');
  await page.waitForFunction((p) => {
    const x = window.studio.handles().find((q) => q.index === p.index);
    return Math.hypot(x.position[0] - p.position[0], x.position[1] - p.position[1], x.position[2] - p.position[2]) < 1e-6;
  }, h);
  const back = await bounds();
  assert.ok(close(back.lo, start.lo, 1e-6) && close(back.hi, start.hi, 1e-6), 'undo did not restore the surface');
  assert.equal((await state()).constraints, before.constraints);
});

test('undo and redo restore the constraint count', async () => {
  const n = (await state()).constraints;
  await page.evaluate(() => window.studio.command('add 0 1.4 0'));
  assert.equal((await state()).constraints, n + 1);
  await page.click('#undo');
  await page.waitForFunction((k) => window.studio.state().constraints === k, n);
  await page.click('#redo');
  await page.waitForFunction((k) => window.studio.state().constraints === k, n + 1);
  await page.evaluate(() => window.studio.command('undo'));
  assert.equal((await state()).constraints, n);
});

test('the command box answers, and refuses a bad command leaving the session as it was', async () => {
  const n = (await state()).constraints;
  await page.fill('#command', 'add 0 0 1.6');
  await page.press('#command', 'Enter');
  await page.waitForFunction((k) => window.studio.state().constraints === k, n + 1);
  assert.match(await page.locator('#log div').first().textContent(), /item \d+ added; \d+ items; solved in/);
  for (const bad of ['add 0 0', 'smooth 3', 'move 999 0 0 0', 'add 0 0 nan']) {
    const answer = await page.evaluate((line) => window.studio.command(line), bad);
    assert.match(answer, /^refused: /, bad);
  }
  assert.equal((await state()).constraints, n + 1);
  await page.evaluate(() => window.studio.command('undo'));
});

test('a coincident point is refused and changes nothing', async () => {
  const n = (await state()).constraints;
  const corner = (await handles()).find((h) => h.kind === 0).position;
  const answer = await page.evaluate((p) => window.studio.command(`add ${p.join(' ')}`), corner);
  assert.match(answer, /^refused: /);
  assert.equal((await state()).constraints, n);
});

test('a malformed model or mesh file is refused and the session stays', async () => {
  const n = (await state()).constraints;
  for (const [name, text] of [['broken.json', '{"format": "rbf-model", '], ['flat.json', '{"constraints": []}'], ['bad.obj', 'v 0 0 0\nf 1 2 3\n']]) {
    const opened = await page.evaluate(([a, b]) => window.studio.open(a, b), [name, text]);
    assert.equal(opened, false, name);
    assert.match(await page.locator('#log div').first().textContent(), new RegExp(name.replace('.', '\\.')));
  }
  assert.equal((await state()).constraints, n);
});

test('a saved model reads back with rbf info', async () => {
  await page.evaluate(() => window.studio.command('add 0 0 1.2'));
  const [download] = await Promise.all([page.waitForEvent('download'), page.click('#save')]);
  const path = join(work, 'saved.json');
  await download.saveAs(path);
  assert.equal(readFileSync(path, 'utf8'), await page.evaluate(() => window.studio.modelJson()));
  const info = execFileSync(RBF, ['info', path], { encoding: 'utf8' });
  const n = (await state()).constraints;
  assert.match(info, /3D model, kernel cubic/);
  assert.match(info, new RegExp(`\\(${n} centres\\)`), info);
  for (const format of ['obj', 'ply', 'stl']) {
    const [mesh] = await Promise.all([page.waitForEvent('download'), page.click(`#${format}`)]);
    const file = join(work, `surface.${format}`);
    await mesh.saveAs(file);
    const check = execFileSync(RBF, ['check', file, '--json'], { encoding: 'utf8' });
    assert.equal(JSON.parse(check).boundary_edges, 0, `${format} is not closed`);
  }
});

test('a dropped mesh opens as normal constraints', async () => {
  const obj = 'v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n' +
    'f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\nf 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6\n';
  const opened = await page.evaluate((text) => window.studio.open('octahedron.obj', text), obj);
  assert.equal(opened, true);
  const s = await state();
  assert.equal(s.constraints, 12); // six vertices and six normal handles
  assert.ok(s.triangles > 500);
});

test('rbf studio opens a model given on its command line', async () => {
  const points = join(work, 'sphere.txt');
  const lines = [];
  for (let i = 0; i < 40; i++) {
    const z = 1 - 2 * (i + 0.5) / 40, r = Math.sqrt(1 - z * z), a = i * 2.399963;
    lines.push(`${r * Math.cos(a)} ${r * Math.sin(a)} ${z} ${r * Math.cos(a)} ${r * Math.sin(a)} ${z}`);
  }
  writeFileSync(points, lines.join('\n'));
  const model = join(work, 'sphere.json');
  execFileSync(RBF, ['fit', points, '-o', model, '-q']);
  const second = await startStudio([model]);
  try {
    const other = await browser.newPage();
    await other.goto(second.url);
    await other.waitForFunction(() => window.studio?.ready === true, null, { timeout: 30000 });
    assert.equal((await other.evaluate(() => window.studio.state())).constraints, 80);
    await other.close();
  } finally {
    second.child.kill();
  }
});

test('floaters spread over the surface, follow an edit, and go when turned off', async () => {
  await page.check('#show-floaters');
  await page.waitForFunction(() => window.studio.state().floaters > 20);
  const before = (await state()).floaters;
  await page.evaluate(() => window.studio.command('add 0 0 1.7'));
  const after = (await state()).floaters;
  assert.ok(after > 20, `${before} → ${after} floaters`);
  await page.uncheck('#show-floaters');
  await page.waitForFunction(() => window.studio.state().floaters === 0);
  await page.evaluate(() => window.studio.command('undo'));
});

test('no console errors and no failed requests', () => {
  assert.deepEqual(problems, []);
});
