// End to end (issue 6): the dashboard of the real daemon, `mocaplink run` with the built-in sim
// source, in Chromium; the vehicle's MAVLink stream is received on a UDP socket and decoded with
// node-mavlink (an independent decoder) to see that the page's controls change what is sent.
import assert from 'node:assert/strict';
import dgram from 'node:dgram';
import { createRequire } from 'node:module';
import path from 'node:path';
import { PassThrough } from 'node:stream';
import { after, before, describe, test } from 'node:test';
import { fileURLToPath } from 'node:url';

import { artifacts, horizontalOverflow, launchBrowser, startProcess, stopProcess } from './support.mjs';

const require = createRequire(import.meta.url);
const here = path.dirname(fileURLToPath(import.meta.url));
const { MavLinkPacketSplitter, MavLinkPacketParser } = require(path.join(here, '../../node_modules/node-mavlink'));

const binary = process.env.MOCAPLINK_BINARY;
assert.ok(binary, 'MOCAPLINK_BINARY must name the mocaplink binary');

const ODOMETRY = 331;
const HEARTBEAT = 0;

/** A UDP "vehicle": records the arrival time of every decoded MAVLink message by msgid. */
function startReceiver() {
  return new Promise((resolve) => {
    const socket = dgram.createSocket('udp4');
    const arrivals = [];  // { t (ms, performance.now), msgid }
    const bytes = new PassThrough();
    bytes.pipe(new MavLinkPacketSplitter()).pipe(new MavLinkPacketParser())
      .on('data', (packet) => arrivals.push({
        t: performance.now(), msgid: packet.header.msgid, sysid: packet.header.sysid,
      }));
    socket.on('message', (datagram) => bytes.write(datagram));
    socket.bind(0, '127.0.0.1', () => resolve({ socket, port: socket.address().port, arrivals }));
  });
}

/** Messages of `msgid` per second over [fromMs, toMs] (performance.now times). */
function rate(arrivals, msgid, fromMs, toMs) {
  const n = arrivals.filter((a) => a.msgid === msgid && a.t >= fromMs && a.t < toMs).length;
  return n / ((toMs - fromMs) / 1000);
}

const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

/** Waits `ms`, then returns the rate of `msgid` over that time. */
async function measure(receiver, msgid, ms) {
  const from = performance.now();
  await sleep(ms);
  return rate(receiver.arrivals, msgid, from, performance.now());
}

describe('dashboard of mocaplink run (sim source)', () => {
  let daemon;
  let receiver;
  let browser;
  let page;
  const log = [];

  before(async () => {
    receiver = await startReceiver();
    // The demo's source and vehicle (sim, "demo" following Body1 with px4 at 50 Hz), the link
    // pointed at our receiver and the dashboard on a free port. Given in full: any --source or
    // --vehicle starts from what the options say, not from the demo.
    const started = await startProcess(binary, ['run', '--http', '127.0.0.1:0', '--source', 'sim://',
      '--vehicle', `demo:body=Body1,link=udp://127.0.0.1:${receiver.port},system_id=1,profile=px4`],
    /dashboard: http:\/\/127\.0\.0\.1:(\d+)\//, log);
    daemon = started.child;
    browser = await launchBrowser();
    page = browser.page;
    await page.goto(`http://127.0.0.1:${started.match[1]}/`);
    await page.locator('#live', { hasText: 'live' }).waitFor();
  });

  after(async () => {
    await browser?.close();
    if (daemon) await stopProcess(daemon, 'SIGINT');
    receiver?.socket.close();
  });

  test('lists the simulated bodies and the demo vehicle', async () => {
    await page.locator('#bodies tbody tr').nth(2).waitFor();
    const names = await page.locator('#bodies tbody tr td:first-child').allTextContents();
    assert.deepEqual(names.slice(0, 3), ['Body1', 'Body2', 'Body3']);
    assert.match(await page.locator('#st-source').textContent(), /^sim:/);
    await page.locator('#st-state', { hasText: 'connected' }).waitFor();
    // The bridge's own latency, measured by the daemon: "0.05 ms (p99 0.31 ms)".
    await page.locator('#st-bridge-latency', { hasText: /^\d+\.\d\d ms \(p99 \d+\.\d\d ms\)$/ }).waitFor();
    const card = page.locator('[data-vehicle="demo"]');
    assert.equal(await card.locator('.v-link').textContent(), `udp://127.0.0.1:${receiver.port}`);
    assert.equal(await card.locator('.v-profile').textContent(), 'px4');
    // The demo's receiver never answers: the agreement card says why it has no verdict (issue 31).
    await card.locator('.v-agreement', { hasText: 'unknown: no HEARTBEAT from the vehicle yet' }).waitFor();
  });

  test('shows live updates', async () => {
    const frames = async () => Number((await page.locator('#st-frames').textContent()).replaceAll(',', ''));
    const first = await frames();
    await page.waitForFunction(
      (f) => Number(document.querySelector('#st-frames').textContent.replaceAll(',', '')) > f + 50,
      first, { timeout: 5000 });
    const x = await page.locator('tr[data-body="Body1"] td').nth(2).textContent();
    await page.waitForFunction(
      (before) => document.querySelector('tr[data-body="Body1"] td:nth-child(3)').textContent !== before,
      x, { timeout: 5000 });
  });

  test('the rate slider changes the send rate the vehicle receives', async () => {
    const before50 = await measure(receiver, ODOMETRY, 2000);
    assert.ok(before50 > 40 && before50 < 60, `ODOMETRY at ${before50} Hz before, configured 50`);

    const card = page.locator('[data-vehicle="demo"]');
    const patched = page.waitForResponse((r) => r.request().method() === 'PATCH');
    await card.locator('.v-rate').fill('20');
    const response = await patched;
    assert.equal(response.status(), 200);
    assert.deepEqual(response.request().postDataJSON(), { rate_hz: 20 });
    await sleep(300);  // frames already in flight
    const after20 = await measure(receiver, ODOMETRY, 2000);
    assert.ok(after20 > 15 && after20 < 25, `ODOMETRY at ${after20} Hz after the slider went to 20`);
    // The card's measured rate follows.
    await page.waitForFunction(() => {
      const v = parseFloat(document.querySelector('[data-vehicle="demo"] .v-actual').textContent);
      return v > 15 && v < 25;
    }, null, { timeout: 5000 });
  });

  test('unticking a message stops it', async () => {
    const card = page.locator('[data-vehicle="demo"]');
    const patched = page.waitForResponse((r) => r.request().method() === 'PATCH');
    await card.locator('.v-messages input[value="odometry"]').uncheck();
    const response = await patched;
    assert.equal(response.status(), 200);
    assert.deepEqual(response.request().postDataJSON(), { messages: [] });
    await sleep(300);
    const from = performance.now();
    await sleep(2500);
    const to = performance.now();
    assert.equal(rate(receiver.arrivals, ODOMETRY, from, to), 0, 'ODOMETRY still arriving');
    assert.ok(rate(receiver.arrivals, HEARTBEAT, from, to) > 0, 'HEARTBEAT stopped too');

    // Ticking it again brings it back.
    await card.locator('.v-messages input[value="odometry"]').check();
    await sleep(300);
    assert.ok(await measure(receiver, ODOMETRY, 1000) > 10);
  });

  test('a vehicle added in the form gets its own stream; removing it stops everything', async () => {
    const second = await startReceiver();
    try {
      const form = page.locator('#add-vehicle');
      await form.locator('[name=name]').fill('rover');
      await form.locator('[name=body]').fill('Body2');
      // First the demo's own link and system id: refused by the daemon, the field marked.
      await form.locator('[name=link]').fill(`udp://127.0.0.1:${receiver.port}`);
      await form.locator('[name=system_id]').fill('1');
      await form.locator('[name=rate_hz]').fill('25');
      const errorsBefore = browser.errors.length;
      await form.locator('button[type=submit]').click();
      await page.locator('#add-error', { hasText: 'system_id 1 is already used' }).waitFor();
      assert.equal(await form.locator('[name=system_id]').getAttribute('aria-invalid'), 'true');
      // Chromium logs the refused request itself; that one is expected, nothing else.
      const logged = browser.errors.splice(errorsBefore);
      assert.ok(logged.every((e) => /status of 422/.test(e)), JSON.stringify(logged));

      await form.locator('[name=link]').fill(`udp://127.0.0.1:${second.port}`);
      await form.locator('[name=system_id]').fill('2');
      const posted = page.waitForResponse((r) => r.request().method() === 'POST');
      await form.locator('button[type=submit]').click();
      assert.equal((await posted).status(), 201);
      const card = page.locator('[data-vehicle="rover"]');
      await card.locator('.v-link', { hasText: `udp://127.0.0.1:${second.port}` }).waitFor();
      await sleep(500);
      const from = performance.now();
      await sleep(2000);
      const got = second.arrivals.filter((a) => a.msgid === ODOMETRY && a.t >= from);
      const hz = got.length / 2;
      assert.ok(hz > 20 && hz < 30, `rover ODOMETRY at ${hz} Hz, added at 25`);
      assert.deepEqual([...new Set(got.map((a) => a.sysid))], [2]);
      // The card shows the measured rate like any configured vehicle's.
      await page.waitForFunction(() => {
        const v = parseFloat(document.querySelector('[data-vehicle="rover"] .v-actual').textContent);
        return v > 20 && v < 30;
      }, null, { timeout: 5000 });

      const remove = card.locator('.v-remove');
      await remove.click();
      const deleted = page.waitForResponse((r) => r.request().method() === 'DELETE');
      await remove.click();
      assert.equal((await deleted).status(), 204);
      await card.waitFor({ state: 'detached' });
      await sleep(300);
      const silentFrom = second.arrivals.length;
      await sleep(1500);
      assert.equal(second.arrivals.length, silentFrom, 'the removed vehicle still gets MAVLink');
      assert.ok(await measure(receiver, ODOMETRY, 1000) > 10, 'the demo vehicle stopped too');
    } finally {
      second.socket.close();
    }
  });

  test('phone width has no horizontal overflow; screenshot', async () => {
    await page.setViewportSize({ width: 375, height: 800 });
    await sleep(300);
    const o = await horizontalOverflow(page);
    assert.equal(o.scrollWidth, o.width, JSON.stringify(o));
    await page.screenshot({ path: path.join(artifacts, 'dashboard-run-375.png'), fullPage: true });
    await page.setViewportSize({ width: 1280, height: 900 });
    await sleep(1500);
    await page.screenshot({ path: path.join(artifacts, 'dashboard-run.png'), fullPage: true });
    assert.deepEqual(browser.errors, []);
  });
});

// Issue 26: DNS rebinding as a real browser does it. Chromium resolves evil.example to 127.0.0.1
// (--host-resolver-rules, as an attacker's DNS would after the page loaded), so a page of
// evil.example on the dashboard's port talks to the dashboard same-origin, with Host and Origin
// both evil.example. Without a token, every request it makes is refused and changes nothing; the
// same browser still runs the dashboard from localhost.
describe('a page on another site cannot drive the dashboard (DNS rebinding)', () => {
  let daemon;
  let receiver;
  let bystander;
  let browser;
  let port;
  const log = [];

  /** GET /api/status from this test (Node, Host 127.0.0.1:PORT), parsed. */
  async function status() {
    const res = await fetch(`http://127.0.0.1:${port}/api/status`);
    assert.equal(res.status, 200);
    return res.json();
  }

  before(async () => {
    receiver = await startReceiver();
    bystander = await startReceiver();
    const started = await startProcess(binary, ['run', '--http', '127.0.0.1:0', '--source', 'sim://',
      '--vehicle', `q:body=Body1,link=udp://127.0.0.1:${receiver.port},system_id=1,profile=px4`],
    /dashboard: http:\/\/127\.0\.0\.1:(\d+)\//, log);
    daemon = started.child;
    port = started.match[1];
    browser = await launchBrowser(undefined, ['--host-resolver-rules=MAP evil.example 127.0.0.1']);
  });

  after(async () => {
    await browser?.close();
    if (daemon) await stopProcess(daemon, 'SIGINT');
    receiver?.socket.close();
    bystander?.socket.close();
  });

  test('the five requests of a rebinding page are refused and change nothing', async () => {
    const before = await status();
    const page = browser.page;
    const loaded = await page.goto(`http://evil.example:${port}/`);
    assert.equal(loaded.status(), 403);
    const refusal = await page.textContent('body');
    assert.ok(refusal.includes(`Host \\"evil.example:${port}\\"`), refusal);
    // The attacker's script, running in its own page (same origin as the dashboard now).
    const answers = await page.evaluate(async (link) => {
      const json = { 'Content-Type': 'application/json' };
      const requests = [
        ['GET', '/api/status'],
        ['GET', '/api/events'],
        ['PATCH', '/api/vehicles/q', { paused: true }],
        ['POST', '/api/vehicles', { name: 'evil', body: 'Body2', link, system_id: 9 }],
        ['DELETE', '/api/vehicles/q'],
      ];
      const out = [];
      for (const [method, path, body] of requests) {
        const res = await fetch(path, {
          method, headers: body ? json : {}, body: body ? JSON.stringify(body) : undefined,
        });
        out.push({ method, path, status: res.status, text: await res.text() });
      }
      return out;
    }, `udp://127.0.0.1:${bystander.port}`);
    for (const a of answers) {
      assert.equal(a.status, 403, `${a.method} ${a.path}: ${a.text}`);
      assert.ok(!a.text.includes('"vehicles"'), `${a.method} ${a.path} leaked the status`);
    }
    const after = await status();
    assert.deepEqual(after.vehicles.map((v) => [v.name, v.paused]), [['q', false]]);
    assert.deepEqual(after.vehicles.map((v) => v.name), before.vehicles.map((v) => v.name));
    assert.ok(after.http.requests_host_refused >= 6, JSON.stringify(after.http));
    assert.ok(await measure(receiver, ODOMETRY, 1000) > 40, 'the vehicle stopped getting poses');
    assert.equal(bystander.arrivals.length, 0, 'the page made mocaplink send to its address');
    assert.ok(log.some((l) => /dashboard: refused: Host "evil.example:\d+"/.test(l)), log.join('\n'));
  });

  test('the same browser runs the dashboard from localhost', async () => {
    const page = await browser.context.newPage();
    await page.goto(`http://localhost:${port}/`);
    await page.locator('#live', { hasText: 'live' }).waitFor();
    const card = page.locator('[data-vehicle="q"]');
    await card.waitFor();
    const patched = page.waitForResponse((r) => r.request().method() === 'PATCH');
    await card.locator('.v-pause').click();
    assert.equal((await patched).status(), 200);
    await card.locator('.v-actual', { hasText: 'paused' }).waitFor();
    await sleep(300);
    assert.equal(await measure(receiver, ODOMETRY, 1000), 0, 'ODOMETRY still arriving when paused');
    const resumed = page.waitForResponse((r) => r.request().method() === 'PATCH');
    await card.locator('.v-pause').click();
    assert.equal((await resumed).status(), 200);
    await sleep(300);
    assert.ok(await measure(receiver, ODOMETRY, 1000) > 40);
    await page.screenshot({ path: path.join(artifacts, 'dashboard-localhost.png') });
    await page.close();
  });
});
