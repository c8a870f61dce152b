// Issue 46: every body on ROS 2 topics, received by a subscriber of another DDS implementation.
// `mocaplink run` replays a recording this test writes (a Vicon-style Z-up world, north = +x) with
// [ros2] on loopback; two Cyclone DDS readers built from IDL (tests/adapters/ros2/oracle), one
// reliable and one best effort, take /mocap/<body>/pose, /mocap/<body>/odom and /tf by ROS's DDS
// names and types. The truth is the recording, turned into REP 103 frames here by hand:
//   "Rigid Body 1" (published as Rigid_Body_1) flies north at 0.2 m/s, 1 m west of the origin,
//   1.5 m up, nose west: ENU (−1, 0.2 t, 1.5), yaw 180° (q = (0, 0, ±1, 0)), body-frame
//   velocity (0, −0.2, 0) (north is to the right of a west-facing nose);
//   "Quad2" rests at mocap (1, 2, 0.5) rolled 10° about north: ENU (−2, 1, 0.5), q = Rz(90°)·Rx(10°);
//   "???" has no ROS name and is not published.
// The stamps must be capture times: stamp − t is the same for every sample of the moving body
// (t read back from its position), and every stamp precedes its arrival.
'use strict';

const fs = require('node:fs');
const path = require('node:path');
const h = require('./harness');

const { assert } = h;
const ORACLE = process.env.ROS2_ORACLE;
const RATE_HZ = 100;
const SECONDS = 5;
const DOMAIN = 20 + (process.pid % 80);  // parallel runs on one machine keep apart

function qmul(a, b) {  // Hamilton product of {w, x, y, z}
  return {
    w: a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z,
    x: a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
    y: a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
    z: a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w,
  };
}
function about(axis, deg) {
  const r = (deg * Math.PI) / 360;
  return { w: Math.cos(r), x: axis[0] * Math.sin(r), y: axis[1] * Math.sin(r), z: axis[2] * Math.sin(r) };
}
function sameRotation(q, e, what) {
  const dot = Math.abs(q.w * e.w + q.x * e.x + q.y * e.y + q.z * e.z);
  assert.ok(dot > 1 - 1e-6, `${what}: ${JSON.stringify(q)} is not ${JSON.stringify(e)}`);
}
function near(a, b, tol, what) {
  assert.ok(Math.abs(a - b) <= tol, `${what}: ${a} vs ${b} (±${tol})`);
}

function writeRecording(file) {
  const yaw90 = about([0, 0, 1], 90);
  const roll10 = about([1, 0, 0], 10);
  const rows = ['# mocaplink recording 1; source=vicon://test; rate_hz=100',
    'time_s,frame,body,tracked,x_m,y_m,z_m,qw,qx,qy,qz'];
  const q = (v) => [v.w, v.x, v.y, v.z].map((c) => c.toFixed(9)).join(',');
  for (let i = 0; i < RATE_HZ * SECONDS; i += 1) {
    const t = (i / RATE_HZ).toFixed(6);
    rows.push(`${t},${i + 1},Rigid Body 1,1,${(0.2 * i / RATE_HZ).toFixed(6)},1.000000,1.500000,${q(yaw90)}`);
    rows.push(`${t},${i + 1},Quad2,1,1.000000,2.000000,0.500000,${q(roll10)}`);
    rows.push(`${t},${i + 1},???,1,0.000000,0.000000,0.000000,1,0,0,0`);
  }
  fs.writeFileSync(file, `${rows.join('\n')}\n`);
}

function oracle(reliability) {
  return h.start([ORACLE, '--domain', String(DOMAIN), '--reliability', reliability,
    '--count', '350', '--timeout', '30',
    '--sub', 'pose:rt/mocap/Rigid_Body_1/pose', '--sub', 'odom:rt/mocap/Rigid_Body_1/odom',
    '--sub', 'pose:rt/mocap/Quad2/pose', '--sub', 'tf:rt/tf']);
}

function samples(proc) {
  return proc.stdout.split('\n').filter((l) => l.startsWith('{')).map((l) => JSON.parse(l))
    .filter((j) => j.event === undefined && j.topic !== undefined);
}

async function main() {
  assert.ok(ORACLE, 'ROS2_ORACLE is not set');
  const dir = h.tempDir('ros2');
  const recording = path.join(dir, 'flight.csv');
  writeRecording(recording);
  const config = path.join(dir, 'lab.toml');
  fs.writeFileSync(config, `[mocap]\nsource = "replay://${recording}?speed=1"\nup = "+z"\n` +
    `[ros2]\ndomain_id = ${DOMAIN}\ninterface = "loopback"\n[http]\nlisten = "127.0.0.1:0"\n`);
  const reliable = oracle('reliable');
  const bestEffort = oracle('best_effort');
  await h.waitFor(() => reliable.stdout.includes('"ready"') && bestEffort.stdout.includes('"ready"'),
    10000, 'oracles ready');
  const run = h.mocaplink(['run', '--config', config],
    { env: { MOCAPLINK_STATE_DIR: path.join(dir, 'state') } });
  const [r, b] = [await reliable.exited, await bestEffort.exited];
  assert.equal(r.code, 0, `reliable oracle exit ${r.code}\n${reliable.stdout.slice(-2000)}`);
  assert.equal(b.code, 0, `best-effort oracle exit ${b.code}\n${bestEffort.stdout.slice(-2000)}`);
  const { code } = await run.exited;  // the replay ends: a clean exit
  assert.equal(code, 0, run.stderr);
  assert.match(run.stderr, /ros2: body "\?\?\?" has no letter or digit to make a ROS name of/);
  assert.match(run.stderr, /ros2: \/mocap\/Rigid_Body_1\/pose: a subscriber matched/);

  for (const [proc, what] of [[reliable, 'reliable'], [bestEffort, 'best effort']]) {
    const got = samples(proc);
    const offsets = [];
    let velocities = 0;
    for (const s of got) {
      const stampNs = s.header ? s.header.stamp.sec * 1e9 + s.header.stamp.nanosec : undefined;
      if (s.header) {
        assert.ok(stampNs < s.receive_time_ns, `${what}: a stamp after its arrival`);
        assert.ok(s.receive_time_ns - stampNs < 0.5e9, `${what}: a stamp ${(s.receive_time_ns - stampNs) / 1e6} ms old`);
        assert.equal(s.header.frame_id, 'world');
      }
      if (s.topic === 'rt/mocap/Rigid_Body_1/pose') {
        const p = s.pose.position;
        near(p.x, -1.0, 0.002, `${what}: east`);
        near(p.z, 1.5, 0.002, `${what}: up`);
        sameRotation(s.pose.orientation, { w: 0, x: 0, y: 0, z: 1 }, `${what}: nose west`);
        // After the first second: the capture-time mapping has seen its least-delayed frames.
        if (p.y / 0.2 > 1.0) offsets.push(stampNs - (p.y / 0.2) * 1e9);
      } else if (s.topic === 'rt/mocap/Rigid_Body_1/odom') {
        assert.equal(s.child_frame_id, 'Rigid_Body_1');
        const p = s.pose.pose.position;
        if (p.y / 0.2 > 1.0) {  // the velocity filter has settled
          const v = s.twist.twist.linear;
          near(v.x, 0, 0.01, `${what}: forward velocity`);
          near(v.y, -0.2, 0.01, `${what}: left velocity`);
          near(v.z, 0, 0.01, `${what}: up velocity`);
          velocities += 1;
        }
        const c = s.pose.covariance;
        assert.equal(c.length, 36);
        assert.ok(c[0] > 0 && c[7] > 0 && c[14] > 0 && c[21] > 0, `${what}: variances ${c}`);
      } else if (s.topic === 'rt/mocap/Quad2/pose') {
        const p = s.pose.position;
        near(p.x, -2.0, 0.001, `${what}: Quad2 east`);
        near(p.y, 1.0, 0.001, `${what}: Quad2 north`);
        near(p.z, 0.5, 0.001, `${what}: Quad2 up`);
        sameRotation(s.pose.orientation, qmul(about([0, 0, 1], 90), about([1, 0, 0], 10)),
          `${what}: Quad2 rolled`);
      } else if (s.topic === 'rt/tf') {
        const children = s.transforms.map((t) => t.child_frame_id).sort();
        assert.deepEqual(children, ['Quad2', 'Rigid_Body_1']);
        for (const t of s.transforms) assert.equal(t.header.frame_id, 'world');
      }
    }
    assert.ok(velocities > 150, `${what}: ${velocities} settled velocities`);
    // Capture times: the same offset from the recording's clock for every sample (a publish-time
    // stamp would wander by the loop's and the thread's scheduling).
    const spreadMs = (Math.max(...offsets) - Math.min(...offsets)) / 1e6;
    assert.ok(offsets.length >= 200 && spreadMs < 3, `${what}: ${offsets.length} poses, stamp − t spread ${spreadMs} ms`);
    console.log(`${what}: ${got.length} samples, stamp − capture spread ${spreadMs.toFixed(3)} ms`);
  }
}

/// A participant that cannot start is an error on the dashboard, and the vehicles go on.
async function participantRefused() {
  const dir = h.tempDir('ros2-refused');
  const vehicle = await new h.UdpVehicle().bind();
  const port = await h.freeTcpPort();
  const config = path.join(dir, 'lab.toml');
  // 192.0.2.1 (TEST-NET-1) is no address of this machine's: Fast DDS would fall back to every
  // interface, mocaplink refuses the participant instead.
  fs.writeFileSync(config, '[mocap]\nsource = "sim://?bodies=1&rate_hz=100"\n' +
    `[ros2]\ndomain_id = ${DOMAIN}\ninterface = "192.0.2.1"\n[http]\nlisten = "127.0.0.1:${port}"\n` +
    `[[vehicle]]\nname = "quad"\nbody = "Body1"\nlink = "udp://127.0.0.1:${vehicle.port}"\n` +
    'system_id = 1\nprofile = "px4"\n');
  const run = h.mocaplink(['run', '--config', config],
    { env: { MOCAPLINK_STATE_DIR: path.join(dir, 'state') } });
  await h.waitForLog(run, /ros2: no DDS participant, nothing is published: 192\.0\.2\.1 is not an address of this machine/);
  const api = h.dashboardApi(port);
  let status;
  await h.waitFor(async () => {
    try { status = (await api('GET', '/api/status')).json; } catch { return false; }
    return status && status.ros2;
  }, 10000, 'the status');
  assert.equal(status.ros2.running, false);
  assert.match(status.ros2.error, /^192\.0\.2\.1 is not an address of this machine/);
  assert.ok(status.alerts.some((a) => a.kind === 'ros2_failing' && a.level === 'error'));
  await h.waitFor(() => vehicle.ofId(h.ID.ODOMETRY).length > 10, 10000, 'the vehicle\'s poses');
  await h.stop(run);
  vehicle.close();
  console.log('a refused participant: an error on the dashboard, the vehicle\'s poses go on');
}

main().then(participantRefused).catch(h.fail);
