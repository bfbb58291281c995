// What the studio's end-to-end tests and its speed script share: the `rbf` binary serving the
// page, and Debian's Chromium, headless, with software WebGL.

import { spawn } from 'node:child_process';
import { chromium } from 'playwright-core';

export const RBF = process.env.RBF ?? 'target/debug/rbf';

/// Starts `rbf studio` on a free port; resolves to its URL.
export function startStudio(args = []) {
  return new Promise((resolve, reject) => {
    const child = spawn(RBF, ['studio', '--port', '0', ...args], { stdio: ['ignore', 'pipe', 'inherit'] });
    child.stdout.on('data', (data) => {
      const m = /http:\/\/127\.0\.0\.1:\d+\//.exec(String(data));
      if (m) resolve({ child, url: m[0] });
    });
    child.on('exit', (code) => reject(new Error(`rbf studio exited with ${code}`)));
  });
}

/// Debian's Chromium, headless, with software WebGL.
export function launch() {
  return chromium.launch({
    executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium',
    headless: true,
    args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
      '--disable-background-networking', '--disable-component-update', '--disable-sync', '--no-first-run'],
  });
}

