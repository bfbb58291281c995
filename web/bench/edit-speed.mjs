// How long one edit takes in rbf studio, as a person sees it: the command, the solve, the
// re-polygonization and the next frame drawn, in headless Chromium with software WebGL. Also the
// time from loading the page to ready. Models of 250 and 1000 oriented points on a sphere
// (500 and 2000 rows) are fitted by the `rbf` binary and opened with `rbf studio MODEL`.
//
//   web/build.sh && cargo build --release -p rbf-cli
//   RBF=target/release/rbf node web/bench/edit-speed.mjs [EDITS]

import { execFileSync } from 'node:child_process';
import { mkdtempSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { launch, startStudio, RBF } from '../tests/harness.mjs';

const edits = Number(process.argv[2] ?? 40);
const work = mkdtempSync(join(tmpdir(), 'rbf-speed-'));

function sphereModel(points) {
  const lines = [];
  for (let i = 0; i < points; i++) {
    const z = 1 - 2 * (i + 0.5) / points, r = Math.sqrt(1 - z * z), a = i * 2.399963229728653;
    const p = [r * Math.cos(a), r * Math.sin(a), z];
    lines.push(`${p.join(' ')} ${p.join(' ')}`);
  }
  const text = join(work, `sphere${points}.txt`), model = join(work, `sphere${points}.json`);
  writeFileSync(text, lines.join('\n'));
  execFileSync(RBF, ['fit', text, '-o', model, '-q']);
  return model;
}

const median = (xs) => { const s = [...xs].sort((a, b) => a - b); return s[Math.floor(s.length / 2)]; };
const p90 = (xs) => { const s = [...xs].sort((a, b) => a - b); return s[Math.floor(s.length * 0.9)]; };

const browser = await launch();
console.log(`edits: ${edits} per model; one edit = command + solve + re-mesh (48 cubes across) + next frame`);
for (const points of [250, 1000]) {
  const { child, url } = await startStudio([sphereModel(points)]);
  const page = await browser.newPage({ viewport: { width: 1000, height: 700 } });
  const start = Date.now();
  await page.goto(url);
  await page.waitForFunction(() => window.studio?.ready === true, null, { timeout: 60000 });
  const ready = Date.now() - start;
  const result = await page.evaluate(async (n) => {
    // A boundary item late in the list. If it carries the affine part (a pivot), its first
    // edit refactors the whole system and hands that part to other rows.
    const h = window.studio.handles().filter((x) => x.kind === 0).at(-1);
    const times = [], solve = [], mesh = [];
    for (let k = 0; k < n; k++) {
      const s = 1 + 0.15 * Math.sin(k);
      const t = performance.now();
      const answer = await window.studio.command(`move ${h.index} ${h.position.map((v) => v * s).join(' ')}`);
      times.push(performance.now() - t);
      if (!answer.startsWith('done')) throw new Error(answer);
      const state = window.studio.state();
      solve.push(state.lastSolveMs);
      mesh.push(state.lastMeshMs);
    }
    return { times, solve, mesh, state: window.studio.state() };
  }, edits);
  console.log(`${2 * points} rows (${points} oriented points), ${result.state.triangles} triangles: ` +
    `page ready in ${ready} ms; edit median ${median(result.times).toFixed(1)} ms, 90th percentile ` +
    `${p90(result.times).toFixed(1)} ms (solve median ${median(result.solve).toFixed(1)} ms, re-mesh ${median(result.mesh).toFixed(1)} ms)`);
  await page.close();
  child.kill();
}
await browser.close();
