// Shared by the end-to-end tests of one source (source_vrpn.test.js, source_vicon_udp.test.js):
// scene.js's recording served by `mocaplink serve --protocol P`, read by `mocaplink run` with two
// vehicles, decoded by node-mavlink; the poses must match the scene's ground truth after the
// z-up → NED mapping (up = "+z", north = "+x").
'use strict';

const fs = require('node:fs');
const path = require('node:path');
const h = require('./harness');
const scene = require('./scene');

const { assert, ID } = h;

/// Writes the run configuration for `source` with quad1 ← Body1 (px4, 50 Hz) and rover3 ← Body3
/// (classic, 20 Hz) at the two vehicles' ports; returns its path.
function writeRunConfig(dir, source, vehicles) {
  const file = path.join(dir, 'run.toml');
  fs.writeFileSync(file, `
[mocap]
source = "${source}"
up = "+z"
north = "+x"
[origin]
latitude_deg = 47.397742
longitude_deg = 8.545594
altitude_m = 488.0
[http]
listen = "127.0.0.1:0"
[[vehicle]]
name = "quad1"
body = "Body1"
link = "udp://127.0.0.1:${vehicles[0].port}"
system_id = 1
profile = "px4"
rate_hz = 50
[[vehicle]]
name = "rover3"
body = "Body3"
link = "udp://127.0.0.1:${vehicles[1].port}"
system_id = 3
profile = "classic"
rate_hz = 20
`);
  return file;
}

/// Checks what the two vehicles received against the scene over `seconds`.
function checkPoses(vehicles, seconds) {
  const odometry = vehicles[0].ofId(ID.ODOMETRY).map(({ packet }) => h.decode(packet));
  assert.ok(odometry.length > 20, `quad1: only ${odometry.length} ODOMETRY`);
  const expected1 = scene.toNed(scene.truth('Body1', 0).p);
  const half = -scene.YAW1_RAD / 2;  // NED heading −30°
  for (const m of odometry) {
    const dp = Math.hypot(m.x - expected1[0], m.y - expected1[1], m.z - expected1[2]);
    assert.ok(dp < 0.005, `quad1 position off by ${dp} m`);
    const s = m.q[0] < 0 ? -1 : 1;
    const dq = Math.max(Math.abs(s * m.q[0] - Math.cos(half)), Math.abs(m.q[1]),
      Math.abs(m.q[2]), Math.abs(s * m.q[3] - Math.sin(half)));
    assert.ok(dq < 0.002, `quad1 attitude off: ${m.q}`);
  }
  const classic = vehicles[1].ofId(ID.LOCAL_POSITION_NED).map(({ packet }) => h.decode(packet));
  assert.ok(classic.length > 10, `rover3: only ${classic.length} LOCAL_POSITION_NED`);
  for (const m of classic) {
    const d = scene.distanceToTrajectory('Body3', [m.x, m.y, m.z], seconds);
    assert.ok(d < 0.02, `rover3 LOCAL_POSITION_NED ${d} m from Body3's path`);
  }
  for (const v of vehicles) assert.equal(v.decoder.invalid, 0, 'CRC failures');
  return { odometry: odometry.length, local: classic.length };
}

/// `mocaplink bodies --source URL --seconds 1 --json`, parsed.
async function bodiesJson(url) {
  const bodies = h.mocaplink(['bodies', '--source', url, '--seconds', '1', '--json']);
  const { code } = await bodies.exited;
  assert.equal(code, 0, `bodies exited ${code}: ${bodies.stderr}`);
  return JSON.parse(bodies.stdout);
}

module.exports = { bodiesJson, checkPoses, writeRunConfig };
