// The dashboard page in Chromium against the dashboard server over the fake backend
// (tests/adapters/web/fake_backend.cpp: Body1..Body3, vehicles quad1 and rover).
import assert from 'node:assert/strict';
import path from 'node:path';
import { after, before, describe, test } from 'node:test';

import { artifacts, horizontalOverflow, launchBrowser, startProcess, stopProcess } from './support.mjs';

const serverBinary = process.env.MOCAPLINK_FAKE_SERVER;
assert.ok(serverBinary, 'MOCAPLINK_FAKE_SERVER must name the web_fake_server binary');

describe('dashboard against the fake backend', () => {
  let server;
  let base;
  let browser;
  let page;

  before(async () => {
    const started = await startProcess(serverBinary, [], /^listening on (\d+)$/);
    server = started.child;
    base = `http://127.0.0.1:${started.match[1]}`;
    browser = await launchBrowser();
    page = browser.page;
    await page.goto(base);
    await page.locator('#live', { hasText: 'live' }).waitFor();
  });

  after(async () => {
    await browser?.close();
    if (server) await stopProcess(server);
  });

  test('lists every body with its state, position and rejected count', async () => {
    const rows = page.locator('#bodies tbody tr');
    await rows.nth(2).waitFor();
    assert.deepEqual(await page.locator('#bodies tbody tr td:first-child').allTextContents(),
      ['Body1', 'Body2', 'Body3']);
    const body3 = await page.locator('tr[data-body="Body3"] td').allTextContents();
    assert.deepEqual(body3, ['Body3', 'LOST', '-1.000', '2.000', '0.000', '0']);
    assert.equal(await page.locator('tr[data-body="Body2"] td').nth(5).textContent(), '2');
    assert.equal(await page.locator('#st-source').textContent(), 'sim://?bodies=3');
    assert.equal(await page.locator('#st-state').textContent(), 'connected');
    assert.equal(await page.locator('#st-dropped').textContent(), '3');
    assert.equal(await page.locator('#st-late').textContent(), '5');
    assert.equal(await page.locator('#st-late').getAttribute('class'), 'bad');
    assert.equal(await page.locator('#st-superseded').textContent(), '7');
    assert.equal(await page.locator('#st-superseded').getAttribute('class'), 'bad');
    assert.equal(await page.locator('#st-rejected').textContent(), '2');
    assert.equal(await page.locator('#st-rejected').getAttribute('class'), 'bad');
    assert.equal(await page.locator('#st-rejected').getAttribute('title'),
                 'malformed datagram at byte 80: trailing non-zero bytes after 1 item');
    assert.equal(await page.locator('#st-bridge-latency').textContent(), '0.12 ms (p99 0.45 ms)');
  });

  test('shows live updates', async () => {
    const x = page.locator('tr[data-body="Body1"] td').nth(2);
    const first = await x.textContent();
    // Body1 circles at 1.5 m radius: its x changes within a few tenths of a second.
    await page.waitForFunction(
      (before) => document.querySelector('tr[data-body="Body1"] td:nth-child(3)').textContent !== before,
      first, { timeout: 5000 });
    const frames1 = Number((await page.locator('#st-frames').textContent()).replaceAll(',', ''));
    await page.waitForFunction(
      (f) => Number(document.querySelector('#st-frames').textContent.replaceAll(',', '')) > f,
      frames1, { timeout: 5000 });
  });

  test('shows one card per vehicle with heartbeat, timesync, origin and agreement', async () => {
    const quad = page.locator('[data-vehicle="quad1"]');
    const rover = page.locator('[data-vehicle="rover"]');
    assert.equal(await quad.locator('.v-link').textContent(), 'udp://127.0.0.1:14540');
    assert.equal(await quad.locator('.v-sysid').textContent(), '1');
    assert.equal(await quad.locator('.v-profile').textContent(), 'px4');
    assert.match(await quad.locator('.v-heartbeat').textContent(), /quadrotor · px4 · disarmed · POSCTL/);
    assert.match(await quad.locator('.v-timesync').textContent(), /^synced/);
    assert.equal(await quad.locator('.v-origin').textContent(), 'confirmed');
    assert.match(await quad.locator('.v-agreement-box').getAttribute('class'), /\bagree\b/);
    // An agreement says what it was measured on (agreement.checked).
    assert.match(await quad.locator('.v-agreement').textContent(), /^agree on tilt, yaw and position · tilt 1\.5°/);
    // The rover's estimate disagrees: warning colour (class) and text.
    assert.match(await rover.locator('.v-agreement-box').getAttribute('class'), /\bdisagree\b/);
    assert.match(await rover.locator('.v-agreement').textContent(), /DISAGREES · tilt – · yaw 89.7°/);
    const colour = await rover.locator('.v-agreement').evaluate((el) => getComputedStyle(el).color);
    assert.equal(colour, 'rgb(180, 35, 24)');
    assert.equal(await rover.locator('.v-origin').textContent(), 'not confirmed');
    assert.deepEqual(await rover.locator('.v-messages input:checked').evaluateAll((b) => b.map((i) => i.value)),
      ['att_pos_mocap', 'hil_gps', 'local_position_ned']);
  });

  test('shows the alerts', async () => {
    const kinds = await page.locator('#alerts .alert').evaluateAll((a) => a.map((d) => d.dataset.kind));
    assert.deepEqual(kinds.sort(), ['agreement_failing', 'body_lost', 'origin_not_confirmed', 'setup_blocked']);
    assert.match(await page.locator('#alerts .alert.error[data-kind="agreement_failing"]').textContent(), /rover/);
    assert.match(await page.locator('#alerts .alert.error[data-kind="setup_blocked"]').textContent(),
      /quad1: the vehicle will not fuse mocap as set up \(EKF2_EV_CTRL\)/);
  });

  test('moving the rate slider sends PATCH rate_hz at once', async () => {
    const card = page.locator('[data-vehicle="quad1"]');
    const patched = page.waitForRequest((r) => r.method() === 'PATCH');
    await card.locator('.v-rate').fill('120');
    const request = await patched;
    assert.equal(new URL(request.url()).pathname, '/api/vehicles/quad1');
    assert.deepEqual(request.postDataJSON(), { rate_hz: 120 });
    assert.equal(request.headers()['content-type'], 'application/json');
    assert.equal((await request.response()).status(), 200);
    await card.locator('.v-rate-out', { hasText: '120 Hz' }).waitFor();
    // The server now reports it (the page's own view could be stale; ask the API).
    const vehicle = await (await fetch(`${base}/api/vehicles/quad1`)).json();
    assert.equal(vehicle.rate_hz, 120);
    await page.waitForFunction(() => document.querySelector('[data-vehicle="quad1"] .v-actual').textContent.startsWith('119.8'));
  });

  test('unticking a message sends PATCH messages without it', async () => {
    const card = page.locator('[data-vehicle="rover"]');
    const patched = page.waitForRequest((r) => r.method() === 'PATCH');
    await card.locator('.v-messages input[value="hil_gps"]').uncheck();
    const request = await patched;
    assert.equal(new URL(request.url()).pathname, '/api/vehicles/rover');
    assert.deepEqual(request.postDataJSON(), { messages: ['att_pos_mocap', 'local_position_ned'] });
    assert.equal((await request.response()).status(), 200);
    const vehicle = await (await fetch(`${base}/api/vehicles/rover`)).json();
    assert.deepEqual(vehicle.messages, ['att_pos_mocap', 'local_position_ned']);
    assert.equal(vehicle.sent.HIL_GPS, undefined);
  });

  test('pause and resume', async () => {
    const button = page.locator('[data-vehicle="rover"] .v-pause');
    const patched = page.waitForRequest((r) => r.method() === 'PATCH');
    await button.click();
    assert.deepEqual((await patched).postDataJSON(), { paused: true });
    await page.locator('[data-vehicle="rover"] .v-actual', { hasText: 'paused' }).waitFor();
    await page.locator('[data-vehicle="rover"] .v-pause', { hasText: 'Resume' }).click();
    await page.locator('[data-vehicle="rover"] .v-pause', { hasText: 'Pause' }).waitFor();
  });

  test('adding a vehicle: a refused field is marked, a valid one gets a card', async () => {
    const form = page.locator('#add-vehicle');
    await form.locator('[name=name]').fill('hexa');
    await form.locator('[name=body]').fill('Body2');
    await form.locator('[name=link]').fill('udp://10.0.0.7');  // no port: the backend refuses
    await form.locator('[name=rate_hz]').fill('30');
    await form.locator('button[type=submit]').click();
    await page.locator('#add-error', { hasText: 'link: missing port' }).waitFor();
    assert.equal(await form.locator('[name=link]').getAttribute('aria-invalid'), 'true');

    await form.locator('[name=link]').fill('udp://10.0.0.7:14540');
    const posted = page.waitForRequest((r) => r.method() === 'POST');
    await form.locator('button[type=submit]').click();
    assert.deepEqual((await posted).postDataJSON(), {
      name: 'hexa', body: 'Body2', link: 'udp://10.0.0.7:14540', system_id: 1, profile: 'auto', rate_hz: 30,
    });
    await page.locator('[data-vehicle="hexa"] .v-link', { hasText: 'udp://10.0.0.7:14540' }).waitFor();
    assert.equal(await page.locator('#add-error').textContent(), '');
  });

  test('the Set-up list shows what blocks and applies only the shown fixes after confirmation', async () => {
    const quad = page.locator('[data-vehicle="quad1"]');
    assert.equal(await quad.locator('.v-autopilot').textContent(), 'px4 1.14.3 · rules of profile px4');
    assert.equal(await quad.locator('.v-setup-state').textContent(), 'blocked');
    const ev = quad.locator('tr[data-parameter="EKF2_EV_CTRL"] td');
    assert.deepEqual((await ev.allTextContents()).slice(0, 4),
      ['EKF2_EV_CTRL', '0', '15 (horizontal and vertical position, velocity, yaw)', 'blocks']);
    // A blocking wrong item is red (the stylesheet's --bad), an ok one is muted.
    assert.equal(await ev.first().evaluate((el) => getComputedStyle(el).color), 'rgb(180, 35, 24)');
    assert.match(await quad.locator('tr[data-parameter="EKF2_HGT_REF"] td').nth(4).textContent(), /after a reboot/);
    assert.match(await quad.locator('.v-statustext').textContent(), /warning: Preflight Fail: ekf2 missing data/);
    assert.match(await quad.locator('.v-estimator').textContent(), /no horizontal position/);
    assert.match(await quad.locator('.v-delay').textContent(), /recommended EKF2_EV_DELAY = 0 ms/);
    // The rover is armed: nothing can be applied to it.
    assert.equal(await page.locator('[data-vehicle="rover"] .v-apply').isDisabled(), true);
    // Dismissing the confirmation sends nothing.
    const apply = quad.locator('.v-apply');
    assert.equal(await apply.textContent(), 'Apply 2 fixes');
    let posts = 0;
    const count = (r) => { if (r.method() === 'POST' && r.url().endsWith('/setup')) posts += 1; };
    page.on('request', count);
    page.once('dialog', (d) => d.dismiss());
    await apply.click();
    await page.waitForTimeout(300);
    assert.equal(posts, 0);
    // Accepting it names exactly the two wrong parameters the card shows.
    let message = '';
    page.once('dialog', (d) => { message = d.message(); d.accept(); });
    const sent = page.waitForRequest((r) => r.method() === 'POST' && r.url().endsWith('/api/vehicles/quad1/setup'));
    await apply.click();
    assert.deepEqual(JSON.parse((await sent).postData()), { apply: ['EKF2_EV_CTRL', 'EKF2_HGT_REF'] });
    assert.match(message, /EKF2_EV_CTRL = 15\nEKF2_HGT_REF = 3/);
    await quad.locator('.v-setup-state', { hasText: 'ready' }).waitFor();
    page.off('request', count);
    assert.equal(posts, 1);
  });

  test('removing a vehicle takes two clicks and sends DELETE', async () => {
    const remove = page.locator('[data-vehicle="hexa"] .v-remove');
    await remove.click();
    assert.equal(await remove.textContent(), 'Really remove?');
    const deleted = page.waitForRequest((r) => r.method() === 'DELETE');
    await remove.click();
    assert.equal(new URL((await deleted).url()).pathname, '/api/vehicles/hexa');
    await page.locator('[data-vehicle="hexa"]').waitFor({ state: 'detached' });
    assert.equal((await fetch(`${base}/api/vehicles/hexa`)).status, 404);
  });

  test('the plots draw something', async () => {
    await page.selectOption('#plot-body', 'Body2');
    const inked = await page.evaluate(() => ['topdown', 'xyz'].map((id) => {
      const c = document.getElementById(id);
      const data = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
      let n = 0;
      for (let i = 3; i < data.length; i += 4) if (data[i] > 0) n++;
      return n;
    }));
    assert.ok(inked[0] > 1000 && inked[1] > 1000, `pixels drawn: ${inked}`);
  });

  for (const [name, width] of [['phone', 375], ['tablet', 768]]) {
    test(`${name} width (${width} px) has no horizontal overflow`, async () => {
      await page.setViewportSize({ width, height: 900 });
      await page.waitForTimeout(300);  // a couple of status events re-render at the new width
      const o = await horizontalOverflow(page);
      assert.equal(o.scrollWidth, o.width, JSON.stringify(o));
      assert.deepEqual(o.wide, []);
      await page.screenshot({ path: path.join(artifacts, `dashboard-fake-${width}.png`), fullPage: true });
    });
  }

  test('screenshot at desktop width', async () => {
    await page.setViewportSize({ width: 1280, height: 900 });
    await page.waitForTimeout(800);  // trails grow for a moment
    await page.screenshot({ path: path.join(artifacts, 'dashboard-fake.png'), fullPage: true });
    // The one refused request above (a link without a port) is the only expected console error.
    assert.deepEqual(browser.errors.filter((e) => !/status of 422/.test(e)), []);
  });
});

describe('dashboard with a token', () => {
  test('asks for the token, then goes live', async () => {
    const token = 'browser-test-token-0123';
    const { child, match } = await startProcess(serverBinary, ['--token', token], /^listening on (\d+)$/);
    const b = await launchBrowser({ width: 800, height: 700 });
    try {
      await b.page.goto(`http://127.0.0.1:${match[1]}/`);
      await b.page.locator('#token-form').waitFor();
      await b.page.fill('#token-input', token);
      await b.page.click('#token-form button');
      await b.page.locator('#live', { hasText: 'live' }).waitFor();
      await b.page.locator('tr[data-body="Body1"]').waitFor();
      // The token from the URL fragment works too, and leaves the address bar.
      const c = await b.context.newPage();
      await c.goto(`http://127.0.0.1:${match[1]}/#token=${token}`);
      await c.locator('#live', { hasText: 'live' }).waitFor();
      assert.ok(!c.url().includes(token));
    } finally {
      await b.close();
      await stopProcess(child);
    }
  });
});
