// End to end through QTM RT: the emulator (`mocaplink serve --protocol qtm --from replay:SCENE`) →
// `mocaplink bodies` and `mocaplink run --source qtm://…` → two UDP vehicles decoding with
// node-mavlink. Checks: bodies lists the scene's bodies; quad1 (Body1, px4) gets ODOMETRY at the
// scene's pose after the z-up → NED mapping (mm on the wire → m), with a gap over the scene's
// 300 ms occlusion and reset_counter unchanged after it (back in place: no jump, issue 41);
// rover3 (Body3, classic) stays on Body3's NED path.
'use strict';

const path = require('node:path');
const h = require('./harness');
const scene = require('./scene');

const { assert, ID } = h;
const SECONDS = 6.5;

async function main() {
  const dir = h.tempDir('qtm');
  const sceneFile = path.join(dir, 'scene.csv');
  scene.writeScene(sceneFile, SECONDS);
  const server = h.mocaplink(['serve', '--protocol', 'qtm', '--from', `replay:${sceneFile}`,
    '--rate', String(scene.RATE_HZ), '--listen', '127.0.0.1:0']);
  await h.waitFor(() => /serving qtm on [^:]+:\d+/.test(server.stdout), 10000,
    `serve to start\n${server.stderr}`);
  const port = server.stdout.match(/serving qtm on [^:]+:(\d+)/)[1];
  const source = `qtm://127.0.0.1:${port}`;

  const vehicles = [await new h.UdpVehicle().bind(), await new h.UdpVehicle().bind()];
  const config = h.writeConfig(path.join(dir, 'qtm.toml'), source, [
    { name: 'quad1', body: 'Body1', link: `udp://127.0.0.1:${vehicles[0].port}`, system_id: 1,
      profile: 'px4', rate_hz: 50 },
    { name: 'rover3', body: 'Body3', link: `udp://127.0.0.1:${vehicles[1].port}`, system_id: 3,
      profile: 'classic', rate_hz: 20 },
  ], 'up = "+z"\nnorth = "+x"\n[origin]\nlatitude_deg = 47.397742\nlongitude_deg = 8.545594\n' +
    'altitude_m = 488.0\n[tracking]\nloss_timeout_ms = 100\nreset_after_ms = 200\n');
  const run = h.mocaplink(['run', '--config', config]);

  // `bodies` reads the same emulator through the registry, next to `run`.
  const bodies = h.mocaplink(['bodies', '--source', source, '--seconds', '1', '--json']);
  const { code } = await bodies.exited;
  assert.equal(code, 0, bodies.stderr);
  const summary = JSON.parse(bodies.stdout);
  assert.equal(summary.connected, true);
  assert.deepEqual(summary.bodies.map((b) => b.name), ['Body1', 'Body2', 'Body3']);

  await h.waitFor(() => vehicles[0].ofId(ID.ODOMETRY).length > 0, 10000,
    `first ODOMETRY\n${run.stderr}`);
  // The replay lasts SECONDS from serve's start (the occlusion is at 5.0–5.3 s): wait for its end.
  await h.waitForLog(server, /replay finished/, (SECONDS + 20) * 1000);
  await h.sleep(200);
  await h.stop(run);
  await h.stop(server);

  const odometry = vehicles[0].ofId(ID.ODOMETRY).map((p) => h.decode(p.packet));
  assert.ok(odometry.length > 50, `only ${odometry.length} ODOMETRY`);
  const expected = scene.toNed(scene.truth('Body1', 0).p);
  const half = -scene.YAW1_RAD / 2;  // NED heading −30°
  for (const m of odometry) {
    const dp = Math.hypot(m.x - expected[0], m.y - expected[1], m.z - expected[2]);
    assert.ok(dp < 0.005, `quad1 position off by ${dp} m`);
    const s = m.q[0] < 0 ? -1 : 1;
    const dq = Math.max(Math.abs(s * m.q[0] - Math.cos(half)), Math.abs(m.q[1]), Math.abs(m.q[2]),
      Math.abs(s * m.q[3] - Math.sin(half)));
    assert.ok(dq < 0.002, `quad1 attitude off: ${m.q}`);
  }
  // The longest gap is the occlusion (300 ms of capture time).
  let gapIndex = 0;
  const dt = (k) => Number(odometry[k].timeUsec - odometry[k - 1].timeUsec) / 1000;
  for (let k = 1; k < odometry.length; k += 1) if (gapIndex === 0 || dt(k) > dt(gapIndex)) gapIndex = k;
  assert.ok(dt(gapIndex) >= 200 && dt(gapIndex) < 600, `ODOMETRY gap ${dt(gapIndex)} ms`);
  assert.equal(odometry[gapIndex].resetCounter, odometry[gapIndex - 1].resetCounter);

  const classic = vehicles[1].ofId(ID.ATT_POS_MOCAP).map((p) => h.decode(p.packet));
  assert.ok(classic.length > 20, `only ${classic.length} ATT_POS_MOCAP`);
  for (const m of classic) {
    const d = scene.distanceToTrajectory('Body3', [m.x, m.y, m.z], SECONDS);
    assert.ok(d < 0.02, `rover3 ${d} m from Body3's path`);
  }
  for (const v of vehicles) {
    assert.equal(v.decoder.invalid, 0);
    v.close();
  }
  console.log(`ok: ${odometry.length} ODOMETRY, ${classic.length} ATT_POS_MOCAP over qtm://; occlusion gap ` +
    `${dt(gapIndex).toFixed(0)} ms`);
}

main().catch(h.fail);
