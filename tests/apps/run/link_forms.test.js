// Every mocaplink process on the same PX4 boot hears the vehicle (issue 37; docs/config.md
// "Links"): a scripted PX4 that sends only to its partner — the address given at start (SITL's
// onboard link, `-o 14540`) or else the first that spoke to it — against real processes in turn,
// as a lab runs them: `vehicle setup`, `vehicle setup --apply`, `run`, stop, `run` again.
//
//   udp://PX4?bind=LOCAL   every process sends from LOCAL: one partner for the vehicle
//   udpin://LOCAL          the vehicle sends to LOCAL from boot; every process listens there
//   udp://PX4 (control)    a new ephemeral port per process: the second one hears nothing
//
// And `vehicle setup --apply --json` while `run` owns the udpin link: through the dashboard, one
// JSON document, the link not opened a second time.
'use strict';

const fs = require('node:fs');
const path = require('node:path');
const h = require('./harness');
const { INT32, i32, scriptedPx4, OnePeerVehicle } = require('./scripted_px4');

const { assert } = h;

/// A configuration with one PX4 on `link`, its dashboard on `httpPort` (0: any).
function config(dir, name, link, httpPort = 0) {
  const file = path.join(dir, name);
  fs.writeFileSync(file, `[mocap]\nsource = "sim://?bodies=1&rate_hz=100"\n` +
    `[http]\nlisten = "127.0.0.1:${httpPort}"\n` +
    `[[vehicle]]\nname = "quad"\nbody = "Body1"\nlink = "${link}"\nsystem_id = 1\n` +
    'profile = "px4"\nrate_hz = 30\n');
  return file;
}

/// `vehicle setup` as a process; resolves to {code, stdout, stderr}.
async function setup(file, args, timeoutS = 8) {
  const proc = h.mocaplink(['vehicle', 'setup', '--config', file, 'quad', '--timeout', String(timeoutS), ...args]);
  const { code } = await proc.exited;
  return { code, stdout: proc.stdout, stderr: proc.stderr };
}

/// `run` until the vehicle's set-up list is read through it (it hears the vehicle); then stopped.
async function runHears(file, what) {
  const run = h.mocaplink(['run', '--config', file]);
  try {
    const [, port] = await h.waitForLog(run, /dashboard: http:\/\/127\.0\.0\.1:(\d+)\//);
    const api = h.dashboardApi(port);
    let v;
    await h.waitFor(async () => {
      v = (await api('GET', '/api/vehicles/quad')).json;
      return v.heartbeat && (v.setup.state === 'ready' || v.setup.state === 'blocked');
    }, 10000, `${what}: run hears the vehicle\n${JSON.stringify(v)}`);
    return v;
  } finally {
    await h.stop(run);
  }
}

/// The lab's sequence on one boot of `px4`: list, apply, run, run again.
async function sequence(px4, vehicle, file, what) {
  const listed = await setup(file, ['--json']);
  assert.equal(listed.code, 3, `${what}: list\n${listed.stdout}\n${listed.stderr}`);
  assert.deepEqual(JSON.parse(listed.stdout).setup.items.filter((i) => i.status === 'wrong')
    .map((i) => i.parameter).sort(), ['EKF2_EV_CTRL', 'EKF2_HGT_REF']);

  const applied = await setup(file, ['--apply', '--json']);
  assert.equal(applied.code, 0, `${what}: apply\n${applied.stdout}\n${applied.stderr}`);
  const doc = JSON.parse(applied.stdout);  // exactly one JSON document
  assert.deepEqual(doc.applied.sort(), ['EKF2_EV_CTRL', 'EKF2_HGT_REF']);
  assert.equal(doc.setup.state, 'ready');
  assert.deepEqual(px4.sets.map((x) => [x.name, i32(x.raw)]).sort(),
    [['EKF2_EV_CTRL', 15], ['EKF2_HGT_REF', 3]]);

  await runHears(file, `${what}, first run`);
  await runHears(file, `${what}, run restarted`);
  // One partner for the whole boot, and every datagram came from it.
  const partner = `${vehicle.partner.address}:${vehicle.partner.port}`;
  assert.deepEqual([...new Set(vehicle.heardFrom)], [partner], `${what}: one address`);
}

async function bound(dir) {
  const vehicle = await new OnePeerVehicle().bind();
  const px4 = scriptedPx4(vehicle, 1);
  try {
    const local = await h.freeUdpPort();
    await sequence(px4, vehicle,
      config(dir, 'bind.toml', `udp://127.0.0.1:${vehicle.port}?bind=127.0.0.1:${local}`), 'bind');
    assert.equal(vehicle.partner.port, local);
  } finally {
    clearInterval(px4.timer);
    vehicle.close();
  }
}

async function listening(dir) {
  // SITL's onboard link: PX4 sends to a fixed port (14540) from boot.
  const local = await h.freeUdpPort();
  const vehicle = await new OnePeerVehicle({ partner: { address: '127.0.0.1', port: local } }).bind();
  const px4 = scriptedPx4(vehicle, 1);
  try {
    const file = config(dir, 'udpin.toml', `udpin://127.0.0.1:${local}`);
    await sequence(px4, vehicle, file, 'udpin');

    // `vehicle setup` while `run` owns the link: through the dashboard.
    const httpPort = await h.freeTcpPort();
    const owned = config(dir, 'owned.toml', `udpin://127.0.0.1:${local}`, httpPort);
    px4.params.set('EKF2_EV_CTRL', [0, INT32]);  // undone by a ground station meanwhile
    const run = h.mocaplink(['run', '--config', owned]);
    try {
      await h.waitForLog(run, /dashboard: http:\/\/127\.0\.0\.1:\d+\//);
      const before = px4.sets.length;
      const through = await setup(owned, ['--apply', '--json']);
      assert.equal(through.code, 0, `through run\n${through.stdout}\n${through.stderr}`);
      assert.match(through.stderr, /mocaplink run owns the link of quad: reading and applying through its dashboard at http:\/\/127\.0\.0\.1:\d+/);
      const doc = JSON.parse(through.stdout);
      assert.deepEqual(doc.applied, ['EKF2_EV_CTRL']);
      assert.equal(doc.setup.state, 'ready');
      assert.deepEqual(px4.sets.slice(before).map((x) => [x.name, i32(x.raw)]), [['EKF2_EV_CTRL', 15]]);
      assert.match(run.stderr, /EKF2_EV_CTRL set to 15 \(confirmed by the vehicle\)/);
      // The same config's `check` does not warn about the link.
      const check = h.mocaplink(['check', owned]);
      assert.equal((await check.exited).code, 0);
      assert.doesNotMatch(check.stderr + check.stdout, /answers only the first address/);
    } finally {
      await h.stop(run);
    }
  } finally {
    clearInterval(px4.timer);
    vehicle.close();
  }
}

async function control(dir) {
  // A plain udp:// link: the first process becomes the partner, the second hears nothing, and
  // the command says which forms avoid it. (`check`'s warning on a PX4 port: parse_test.cpp.)
  const vehicle = await new OnePeerVehicle().bind();
  const px4 = scriptedPx4(vehicle, 1);
  try {
    const file = config(dir, 'plain.toml', `udp://127.0.0.1:${vehicle.port}`);
    const first = await setup(file, ['--json']);
    assert.equal(first.code, 3, first.stderr);
    const second = await setup(file, ['--json'], 2);
    assert.equal(second.code, 2, `the second process must not hear it\n${second.stderr}`);
    assert.match(second.stderr, /no HEARTBEAT from the vehicle within 2 s.*\?bind=.*udpin:\/\//);
  } finally {
    clearInterval(px4.timer);
    vehicle.close();
  }
}

async function strangerOnTheDashboardPort(dir) {
  // Another program answers at the configuration's [http] listen with something that is not a
  // vehicle: said, exit 2, never a crash, and the link is not opened behind its back.
  const http = require('node:http');
  const server = http.createServer((req, res) => {
    res.writeHead(200, { 'Content-Type': 'application/json' });
    res.end(JSON.stringify({ setup: { state: 7 } }));
  });
  await new Promise((r) => server.listen(0, '127.0.0.1', r));
  try {
    const file = config(dir, 'stranger.toml', 'udpin://127.0.0.1:9', server.address().port);
    const out = await setup(file, ['--json'], 2);
    assert.equal(out.code, 2, out.stderr);
    assert.match(out.stderr, /answered GET \/api\/vehicles\/quad with a vehicle this version cannot read/);
    assert.equal(out.stdout, '');
  } finally {
    server.close();
  }
}

async function main() {
  const dir = h.tempDir('link-forms');
  await bound(dir);
  await listening(dir);
  await control(dir);
  await strangerOnTheDashboardPort(dir);
}

main().catch(h.fail);
