// Shared by the browser tests: start a server process and wait for its readiness line, launch
// Debian's Chromium through playwright-core (never a downloaded browser) with a fresh profile.
import { spawn } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import readline from 'node:readline';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const { chromium } = await import(path.join(here, '../../node_modules/playwright-core/index.mjs'));

export const artifacts = process.env.MOCAPLINK_ARTIFACTS || path.join(os.tmpdir(), 'mocaplink-browser');
fs.mkdirSync(artifacts, { recursive: true });

/**
 * Starts `command args`, resolves with { child, match } once a stdout or stderr line matches
 * `ready` (a RegExp), rejects if the process exits first. Lines are echoed to `log` (an array).
 */
export function startProcess(command, args, ready, log = []) {
  return new Promise((resolve, reject) => {
    const child = spawn(command, args, { stdio: ['pipe', 'pipe', 'pipe'] });
    let done = false;
    const onLine = (line) => {
      log.push(line);
      const match = ready.exec(line);
      if (match && !done) {
        done = true;
        resolve({ child, match });
      }
    };
    readline.createInterface({ input: child.stdout }).on('line', onLine);
    readline.createInterface({ input: child.stderr }).on('line', onLine);
    child.on('exit', (code, signal) => {
      if (!done) reject(new Error(`${command} exited (${code ?? signal}) before ready:\n${log.join('\n')}`));
    });
  });
}

/** Ends a process started by startProcess and waits for it. */
export async function stopProcess(child, signal = 'SIGTERM') {
  if (child.exitCode !== null || child.signalCode !== null) return;
  const exited = new Promise((resolve) => child.once('exit', resolve));
  child.stdin.end();
  child.kill(signal);
  await exited;
}

/**
 * A browser context with a fresh profile directory, and its first page. `extraArgs` are more
 * Chromium switches (e.g. --host-resolver-rules to point a name at 127.0.0.1).
 */
export async function launchBrowser(viewport = { width: 1280, height: 900 }, extraArgs = []) {
  const userDataDir = fs.mkdtempSync(path.join(os.tmpdir(), 'mocaplink-chromium-'));
  const context = await chromium.launchPersistentContext(userDataDir, {
    executablePath: process.env.MOCAPLINK_CHROMIUM || '/usr/bin/chromium',
    headless: true,
    viewport,
    args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
      '--disable-background-networking', '--disable-component-update', '--disable-sync',
      ...extraArgs],
  });
  const page = context.pages()[0] || (await context.newPage());
  const errors = [];
  page.on('pageerror', (e) => errors.push(String(e)));
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  return {
    context, page, errors,
    async close() {
      await context.close();
      fs.rmSync(userDataDir, { recursive: true, force: true });
    },
  };
}

/** True when nothing on the page is wider than the viewport (no horizontal scrolling). */
export async function horizontalOverflow(page) {
  return page.evaluate(() => {
    const width = document.documentElement.clientWidth;
    const wide = [...document.querySelectorAll('body *')]
      .filter((el) => el.getBoundingClientRect().right > width + 0.5 && el.closest('.table-wrap') === null)
      .map((el) => `${el.tagName.toLowerCase()}.${el.className} right=${el.getBoundingClientRect().right}`);
    return { scrollWidth: document.documentElement.scrollWidth, width, wide };
  });
}
