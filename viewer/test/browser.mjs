// What the viewer's browser scripts share: `tumble view` as a child process, and Debian's
// chromium, headless with software WebGL, in a fresh profile (nothing fetched: no component
// updates, no sync, no QUIC).
import { spawn } from 'node:child_process';
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { chromium } from 'playwright-core';

/// Starts `tumble view REPLAY` and resolves with the process and the address it prints.
export function serve(tumble, replay) {
  const server = spawn(tumble, ['view', replay], { stdio: ['ignore', 'pipe', 'inherit'] });
  return new Promise((resolve, reject) => {
    let out = '';
    server.stdout.on('data', (d) => {
      out += d;
      const m = out.match(/http:\/\/127\.0\.0\.1:\d+\//);
      if (m) resolve({ server, url: m[0] });
    });
    server.on('exit', (code) => reject(new Error(`tumble view exited with ${code}`)));
  });
}

export async function openBrowser(viewport = { width: 1200, height: 800 }) {
  const profile = mkdtempSync(join(tmpdir(), 'tumble-chromium-'));
  const context = await chromium.launchPersistentContext(profile, {
    executablePath: '/usr/bin/chromium',
    headless: true,
    viewport,
    args: ['--headless', '--no-sandbox', '--disable-gpu', '--use-angle=swiftshader',
      '--enable-unsafe-swiftshader', '--disable-quic', '--no-first-run',
      '--disable-background-networking', '--disable-component-update', '--disable-sync'],
  });
  const close = async () => {
    await context.close();
    rmSync(profile, { recursive: true, force: true });
  };
  return { context, close };
}

/// Opens the viewer and waits until it has drawn the replay or given up; returns the state
/// the page reports ('ready' or 'error').
export async function load(page, url) {
  await page.goto(url);
  await page.waitForFunction(() => document.body.dataset.state !== 'loading', null, { timeout: 20000 });
  return page.evaluate(() => document.body.dataset.state);
}
