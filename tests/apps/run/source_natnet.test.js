// End to end through NatNet: `mocaplink serve --protocol natnet --from replay:SCENE` (multicast on
// the loopback interface, frames turned into Motive's Y-up world as Motive streams them) →
// `mocaplink run` with `natnet://…?local=127.0.0.1` and `up = "+y"` → a UDP vehicle decoding with
// node-mavlink. Checks: ODOMETRY positions and attitude against scene.js's ground truth after the
// Y-up → NED mapping (N = x, E = z, D = −y), the gap while Body1 is occluded (tracking-valid bit
// clear), then the same over unicast with the bitstream 3.0 layout and the emulator keeping z-up.
'use strict';

const path = require('node:path');
const h = require('./harness');
const scene = require('./scene');

const { assert, ID } = h;
const SECONDS = 6.5;

async function runOnce(dir, sceneFile, { serveSettings, query, up, label }) {
  const serveArgs = ['serve', '--protocol', 'natnet', '--from', `replay:${sceneFile}`,
    '--listen', '127.0.0.1:0'];
  for (const s of serveSettings) serveArgs.push('--set', s);
  const server = h.mocaplink(serveArgs);
  await h.waitFor(() => /serving natnet on [^:]+:(\d+)/.test(server.stdout), 10000,
    `serve to start\n${server.stderr}`);
  const port = server.stdout.match(/on [^:]+:(\d+)/)[1];

  const vehicle = await new h.UdpVehicle().bind();
  const configFile = h.writeConfig(path.join(dir, `${label}.toml`),
    `natnet://127.0.0.1:${port}${query}`,
    [{ name: 'quad1', body: 'Body1', link: `udp://127.0.0.1:${vehicle.port}`, system_id: 1,
      profile: 'px4', rate_hz: 50 }],
    `up = "${up}"\nnorth = "+x"\nbody_up = "${up}"\nbody_forward = "+x"\n` +
      '[tracking]\nloss_timeout_ms = 100\nreset_after_ms = 200\n');
  const run = h.mocaplink(['run', '--config', configFile],
    { env: { MOCAPLINK_STATE_DIR: path.join(dir, `${label}-state`) } });
  await h.waitFor(() => vehicle.ofId(ID.ODOMETRY).length > 0, 10000,
    `${label}: first ODOMETRY\n${run.stderr}\n${server.stderr}`);
  await h.sleep((SECONDS - 1) * 1000);
  await h.stop(run);
  server.child.kill('SIGTERM');
  await server.exited;
  vehicle.close();
  assert.ok(!/Motive streams Y-up/.test(run.stderr), `${label}: ${run.stderr}`);  // up is written

  const odometry = vehicle.ofId(ID.ODOMETRY).map((p) => h.decode(p.packet));
  assert.ok(odometry.length > 100, `${label}: only ${odometry.length} ODOMETRY`);
  const expected = scene.toNed(scene.truth('Body1', 0).p);
  const half = -scene.YAW1_RAD / 2;  // NED heading −30°
  for (const m of odometry) {
    const dp = Math.hypot(m.x - expected[0], m.y - expected[1], m.z - expected[2]);
    assert.ok(dp < 0.005, `${label}: position off by ${dp} m (${m.x}, ${m.y}, ${m.z})`);
    const s = m.q[0] < 0 ? -1 : 1;
    const dq = Math.max(Math.abs(s * m.q[0] - Math.cos(half)), Math.abs(m.q[1]),
      Math.abs(m.q[2]), Math.abs(s * m.q[3] - Math.sin(half)));
    assert.ok(dq < 0.002, `${label}: attitude off: ${m.q}`);
  }
  // Body1 untracked for 300 ms (scene.js): no pose sent then; back in place, so reset_counter
  // stays (a gap is no jump, issue 41).
  let gapIndex = -1;
  for (let k = 1; k < odometry.length; k += 1) {
    if (Number(odometry[k].timeUsec - odometry[k - 1].timeUsec) > 200000) gapIndex = k;
  }
  assert.ok(gapIndex > 0, `${label}: no gap while Body1 was occluded`);
  assert.equal(odometry[gapIndex].resetCounter, odometry[gapIndex - 1].resetCounter);
  return odometry.length;
}

async function main() {
  const dir = h.tempDir('natnet');
  const sceneFile = path.join(dir, 'scene.csv');
  scene.writeScene(sceneFile, SECONDS);
  const dataPort = await h.freeUdpPort();
  const multicast = await runOnce(dir, sceneFile, {
    label: 'multicast',
    serveSettings: ['transport=multicast', 'group=239.255.42.98', `data_port=${dataPort}`,
      'interface=127.0.0.1', 'version=4.2'],
    query: '?local=127.0.0.1',
    up: '+y',
  });
  const unicast = await runOnce(dir, sceneFile, {
    label: 'unicast',
    serveSettings: ['transport=unicast', 'version=3.0', 'up=z', `data_port=${await h.freeUdpPort()}`],
    query: '?local=127.0.0.1',
    up: '+z',
  });
  console.log(`ok: ${multicast} ODOMETRY over multicast (4.2, Y-up), ${unicast} over unicast ` +
    '(3.0, z-up)');
}

main().catch(h.fail);
