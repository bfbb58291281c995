// Where the time of a studio edit goes, in headless Chromium: a CPU profile (Chrome DevTools
// protocol) over 60 edits of the model given, as edit-speed.mjs makes them, summed by function
// (the engine's Rust functions by name, the page's JavaScript, idle time).
//
//   web/build.sh && cargo build --release -p rbf-cli
//   RBF=target/release/rbf node web/bench/profile-edit.mjs MODEL.json

import { launch, startStudio } from '../tests/harness.mjs';

const model = process.argv[2];
if (!model) {
  console.error('usage: node web/bench/profile-edit.mjs MODEL.json');
  process.exit(2);
}
const browser = await launch();
const { child, url } = await startStudio([model]);
const page = await browser.newPage({ viewport: { width: 1000, height: 700 } });
await page.goto(url);
await page.waitForFunction(() => window.studio?.ready === true, null, { timeout: 60000 });
const cdp = await page.context().newCDPSession(page);
await cdp.send('Profiler.enable');
await cdp.send('Profiler.setSamplingInterval', { interval: 200 });
await cdp.send('Profiler.start');
const r = await page.evaluate(async (n) => {
  const h = window.studio.handles().filter((x) => x.kind === 0).at(-1);
  const times = [];
  for (let k = 0; k < n; k++) {
    const s = 1 + 0.15 * Math.sin(k);
    const t = performance.now();
    await window.studio.command(`move ${h.index} ${h.position.map((v) => v * s).join(' ')}`);
    times.push(performance.now() - t);
  }
  return times;
}, 60);
const { profile } = await cdp.send('Profiler.stop');
const self = new Map();
const byId = new Map(profile.nodes.map((n) => [n.id, n]));
const dt = profile.timeDeltas; let total = 0;
profile.samples.forEach((id, i) => { const n = byId.get(id); const k = n.callFrame.functionName || '(anon ' + n.callFrame.url.split('/').pop() + ')'; self.set(k, (self.get(k) ?? 0) + dt[i] / 1000); total += dt[i] / 1000; });
console.log('edits median', r.sort((a, b) => a - b)[30].toFixed(1), 'total ms', total.toFixed(0));
[...self.entries()].sort((a, b) => b[1] - a[1]).slice(0, 35).forEach(([k, v]) => console.log(v.toFixed(1).padStart(8), k.slice(0, 120)));
await browser.close(); child.kill();
