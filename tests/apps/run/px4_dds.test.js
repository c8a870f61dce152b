// Issue 47: PX4s reached over uXRCE-DDS (`link = "ros2://NAMESPACE"`), with the real daemon and
// PX4 stand-ins of another DDS implementation: the Cyclone DDS oracle's --px4 mode
// (tests/adapters/ros2/oracle) reads /NS/fmu/in/vehicle_visual_odometry by PX4's type name,
// writes v1.14's /NS/fmu/out/vehicle_status and an estimator's /NS/fmu/out/vehicle_odometry
// that is the last pose it got (turned by --px4-yaw-offset). One daemon, one participant:
//   a  ros2://px4_1, armed, estimate = pose: heard, armed, POSCTL, agree on gravity (yaw and
//      position assumed to come from mocap); the poses as PX4 reads them, checked against the
//      recording turned into NED/FRD by hand; the set-up list unavailable and said so; then its
//      PX4 stops and the vehicle goes silent.
//   b  ros2://px4_2, disarmed, estimate turned 90°: disagree (the alert), never agree.
//   c  ros2://px4_9, no PX4: silent, never heard, never fine.
// The truth is a recording (Vicon-style Z-up world, north = +x): "Quad1" flies north at 0.2 m/s,
// 2 m west of the origin, 0.5 m up, nose west: NED (0.2 t, −2, −0.5), yaw −90°, body-frame
// velocity (0, +0.2, 0) (north is to the right of a west-facing nose). "Quad2" and "Quad3" rest.
'use strict';

const fs = require('node:fs');
const path = require('node:path');
const h = require('./harness');

const { assert } = h;
const ORACLE = process.env.ROS2_ORACLE;
const RATE_HZ = 100;
const SECONDS = 60;  // longer than the test: it is stopped, never runs out
const DOMAIN = 100 + (process.pid % 80);  // apart from ros2_topics (20..99) and parallel runs

function near(a, b, tol, what) {
  assert.ok(Math.abs(a - b) <= tol, `${what}: ${a} vs ${b} (±${tol})`);
}

function writeRecording(file) {
  const s = Math.SQRT1_2;  // yaw +90° about mocap's up: nose from north to west
  const rows = ['# mocaplink recording 1; source=vicon://test; rate_hz=100',
    'time_s,frame,body,tracked,x_m,y_m,z_m,qw,qx,qy,qz'];
  for (let i = 0; i < RATE_HZ * SECONDS; i += 1) {
    const t = (i / RATE_HZ).toFixed(6);
    rows.push(`${t},${i + 1},Quad1,1,${(0.2 * i / RATE_HZ).toFixed(6)},2.000000,0.500000,${s},0,0,${s}`);
    rows.push(`${t},${i + 1},Quad2,1,-1.000000,0.000000,1.000000,1,0,0,0`);
    rows.push(`${t},${i + 1},Quad3,1,0.000000,0.000000,0.000000,1,0,0,0`);
  }
  fs.writeFileSync(file, `${rows.join('\n')}\n`);
}

function standIn(ns, args) {
  return h.start([ORACLE, '--domain', String(DOMAIN), '--count', '1000000', '--timeout', '90',
    '--px4', ns, ...args]);
}

function samples(proc) {
  return proc.stdout.split('\n').filter((l) => l.startsWith('{')).map((l) => JSON.parse(l))
    .filter((j) => j.event === undefined && j.topic !== undefined);
}

async function main() {
  assert.ok(ORACLE, 'ROS2_ORACLE is not set');
  const dir = h.tempDir('px4-dds');
  const recording = path.join(dir, 'flight.csv');
  writeRecording(recording);
  const port = await h.freeTcpPort();
  const config = path.join(dir, 'lab.toml');
  const vehicle = (name, body, ns, id) => `[[vehicle]]\nname = "${name}"\nbody = "${body}"\n` +
    `link = "ros2://${ns}"\nsystem_id = ${id}\nprofile = "px4"\n`;
  fs.writeFileSync(config, `[mocap]\nsource = "replay://${recording}?speed=1"\nup = "+z"\n` +
    `[ros2]\ndomain_id = ${DOMAIN}\ninterface = "loopback"\npublish = []\n` +
    `[http]\nlisten = "127.0.0.1:${port}"\n` +
    vehicle('a', 'Quad1', 'px4_1', 1) + vehicle('b', 'Quad2', 'px4_2', 2) +
    vehicle('c', 'Quad3', 'px4_9', 3));

  // Parameters never go over DDS: `vehicle setup` says where they do, before anything runs.
  const setup = h.mocaplink(['vehicle', 'setup', '--config', config, 'a', '--timeout', '5']);
  const setupExit = await setup.exited;
  assert.equal(setupExit.code, 2, setup.stderr);
  assert.match(setup.stderr + setup.stdout, /MAVLink link/);

  const a = standIn('px4_1', ['--px4-armed', '1']);
  const b = standIn('px4_2', ['--px4-yaw-offset', '90']);
  await h.waitFor(() => a.stdout.includes('"ready"') && b.stdout.includes('"ready"'), 10000,
    'stand-ins ready');
  const run = h.mocaplink(['run', '--config', config],
    { env: { MOCAPLINK_STATE_DIR: path.join(dir, 'state') } });
  const api = h.dashboardApi(port);
  const status = async () => (await api('GET', '/api/status')).json;
  const byName = (s) => Object.fromEntries(s.vehicles.map((v) => [v.name, v]));

  // The verdicts: agreement waits out the 15 s a vehicle settles (from its first status here)
  // and a disagreement holds 3 s.
  let v;
  await h.waitFor(async () => {
    try { v = byName(await status()); } catch { return false; }
    return v.a.agreement.verdict === 'agree' && v.b.agreement.verdict === 'disagree';
  }, 30000, 'the agreement verdicts');
  const s = await status();
  v = byName(s);

  assert.equal(v.a.link_state, 'up');
  assert.equal(v.a.heartbeat.autopilot, 'px4');
  assert.equal(v.a.heartbeat.armed, true);
  assert.equal(v.a.heartbeat.mode, 'POSCTL');
  assert.equal(v.b.heartbeat.armed, false);
  // The agreement rests on gravity: yaw and position are taken to be mocap's own.
  assert.match(v.a.agreement.reason, /yaw not checkable: .*assumed: PX4 fuses the poses it is sent over uXRCE-DDS/);
  assert.ok(v.a.agreement.tilt_offset_deg < 1, `tilt ${v.a.agreement.tilt_offset_deg}`);
  near(Math.abs(v.b.agreement.yaw_offset_deg), 90, 1, 'b: the turned estimate');
  assert.ok(s.alerts.some((x) => x.kind === 'agreement_failing' && x.subject === 'b'));
  // Only poses go: no HEARTBEAT, TIMESYNC or requests of ours over DDS.
  for (const name of ['a', 'b', 'c']) {
    assert.deepEqual(Object.keys(v[name].sent), ['ODOMETRY'], `${name}: ${JSON.stringify(v[name].sent)}`);
    assert.equal(v[name].timesync.state, 'off');
    assert.equal(v[name].clock.verdict, null);
  }
  // The stand-ins stamp on this host's clock, as a PX4 whose time sync is right: after 5 s of it,
  // the capture time goes (before, 0: PX4 stamps on arrival).
  for (const name of ['a', 'b']) {
    assert.equal(v[name].clock.pose_stamps, 'capture', JSON.stringify(v[name].clock));
    assert.match(v[name].clock.text, /^PX4's uXRCE-DDS time sync within [-+][0-9.]+ ms of this host's clock/);
  }
  // The set-up list cannot be read over DDS, and the dashboard says so.
  for (const name of ['a', 'b']) {
    assert.equal(v[name].setup.state, 'unavailable');
    assert.match(v[name].setup.note, /parameters do not go over uXRCE-DDS: check this list over a MAVLink link/);
    assert.ok(v[name].setup.items.length > 0 && v[name].setup.items.every((i) => i.status === 'unread'));
    assert.equal(v[name].delay_ms.recommended, 0);
    assert.match(v[name].delay_ms.basis, /uXRCE-DDS time sync/);
  }
  assert.ok(!s.alerts.some((x) => x.kind === 'setup_no_answer'), JSON.stringify(s.alerts));
  const refused = await api('POST', '/api/vehicles/a/setup', { reboot: true });
  assert.equal(refused.status, 409);
  // No PX4 on px4_9: silent, never fine.
  assert.equal(v.c.link_state, 'silent');
  assert.equal(v.c.heartbeat, null);
  assert.equal(v.c.agreement.verdict, 'unknown');
  assert.ok(s.alerts.some((x) => x.kind === 'vehicle_silent' && x.subject === 'c'));
  assert.ok(!s.alerts.some((x) => x.subject === 'a'), JSON.stringify(s.alerts));

  // PX4 a stops: its vehicle goes silent.
  a.child.kill('SIGTERM');
  await a.exited;
  await h.waitFor(async () => byName(await status()).a.link_state === 'silent', 10000,
    'a silent after its PX4 stopped');
  b.child.kill('SIGTERM');
  await b.exited;
  await h.stop(run);
  assert.match(run.stderr, /vehicle_setup a: set-up unavailable: PX4's parameters do not go over uXRCE-DDS/);

  // The poses as PX4 read them (Cyclone decoding the 114 bytes by PX4's field list).
  const got = samples(a).filter((x) => x.topic === 'rt/px4_1/fmu/in/vehicle_visual_odometry');
  assert.ok(got.length > 500, `${got.length} poses at PX4`);
  assert.ok(samples(b).length > 500, 'poses at the second PX4');
  const offsets = [];
  let settled = 0;
  let arrival = 0;
  for (const x of got) {
    if (x.timestamp_sample === 0) {  // PX4's sync not judged yet: stamped on arrival
      assert.equal(x.timestamp, 0);
      assert.equal(offsets.length + settled, 0, 'arrival stamps after capture stamps began');
      arrival += 1;
      continue;
    }
    const t = x.position[0] / 0.2;  // the recording's time, read back from the pose
    assert.equal(x.pose_frame, 2, 'FRD pose frame');
    assert.equal(x.velocity_frame, 3, 'body-frame velocity');
    near(x.position[1], -2, 0.002, 'east');
    near(x.position[2], -0.5, 0.002, 'down');
    const [qw, qx, qy, qz] = x.q;
    near(Math.abs(qw * Math.SQRT1_2 - qz * Math.SQRT1_2), 1, 1e-4, `yaw −90°: q ${x.q}`);
    near(qx, 0, 1e-4, 'qx');
    near(qy, 0, 1e-4, 'qy');
    assert.ok(x.position_variance.every((c) => c > 0), `variances ${x.position_variance}`);
    assert.ok(x.timestamp_sample <= x.timestamp, 'capture after send');
    assert.ok(x.timestamp * 1000 <= x.receive_time_ns + 1e6, 'sent after it arrived');
    assert.ok(x.receive_time_ns / 1000 - x.timestamp_sample < 500e3, 'a pose half a second old');
    assert.equal(x.reset_counter, 0);
    if (t > 1.0) {
      offsets.push(x.timestamp_sample - t * 1e6);
      near(x.velocity[0], 0, 0.01, 'forward velocity');
      near(x.velocity[1], 0.2, 0.01, 'right velocity');
      near(x.velocity[2], 0, 0.01, 'down velocity');
      settled += 1;
    }
  }
  // Capture times: the same offset from the recording's clock for every pose.
  const spreadMs = (Math.max(...offsets) - Math.min(...offsets)) / 1e3;
  assert.ok(settled > 400 && spreadMs < 3, `${settled} poses, timestamp_sample − t spread ${spreadMs} ms`);
  assert.ok(arrival > 100 && arrival < 500, `${arrival} poses stamped on arrival first`);
  console.log(`px4_1: ${got.length} poses read by PX4's type (${arrival} first stamped on arrival), ` +
    'timestamp_sample − capture spread ' +
    `${spreadMs.toFixed(3)} ms; px4_2 disagrees by ${v.b.agreement.yaw_offset_deg.toFixed(1)}°; ` +
    'px4_9 silent');
}

main().catch(h.fail);
