// End to end over the Vicon Tracker UDP object stream: `mocaplink run --config` with
// vicon-udp://127.0.0.1:PORT ← `mocaplink serve --protocol vicon-udp --to 127.0.0.1:PORT --from
// replay:SCENE --set frame_step=2` (a stream at half the camera rate) → two UDP vehicles decoding
// with node-mavlink; poses match scene.js's ground truth in NED. Also `bodies --json` on a second
// port: every scene body tracked and no frame counted as dropped for the step of 2. The scene's
// Body1 hovers perfectly still, so the frozen-object check is off (frozen=0).
'use strict';

const dgram = require('node:dgram');
const path = require('node:path');
const h = require('./harness');
const scene = require('./scene');
const e2e = require('./source_e2e');

const { assert, ID } = h;
const SECONDS = 4;

/// A UDP port free right now on 127.0.0.1 (the source binds it next).
function freePort() {
  return new Promise((resolve) => {
    const s = dgram.createSocket('udp4');
    s.bind(0, '127.0.0.1', () => {
      const { port } = s.address();
      s.close(() => resolve(port));
    });
  });
}

function serve(sceneFile, port) {
  return h.mocaplink(['serve', '--protocol', 'vicon-udp', '--from', `replay:${sceneFile}`,
    '--to', `127.0.0.1:${port}`, '--set', 'frame_step=2']);
}

/// `serve` refuses a vicon-udp emulator without --to, and bad --set values, with exit 1.
async function checkServeErrors() {
  const cases = [
    [['--from', 'sim'], '--to'],
    [['--from', 'sim', '--to', '127.0.0.1:9', '--set', 'rotation=xzy'], 'rotation must be xyz or zyx'],
    [['--from', 'sim', '--to', '127.0.0.1:9', '--set', 'frame_step=0'], 'frame_step'],
    [['--from', 'sim', '--to', '127.0.0.1:9', '--set', 'rotaton=xyz'], 'rotaton'],
  ];
  for (const [args, message] of cases) {
    const p = h.mocaplink(['serve', '--protocol', 'vicon-udp', ...args]);
    const { code } = await p.exited;
    assert.equal(code, 1, `serve ${args.join(' ')}: exit ${code}`);
    assert.ok(p.stderr.includes(message), `serve ${args.join(' ')}: ${p.stderr}`);
  }
}

async function main() {
  await checkServeErrors();
  const dir = h.tempDir('vicon-udp');
  const sceneFile = path.join(dir, 'scene.csv');
  scene.writeScene(sceneFile, SECONDS);

  const bodiesPort = await freePort();
  const bodies = e2e.bodiesJson(`vicon-udp://127.0.0.1:${bodiesPort}?lost_ms=2000&frozen=0`);
  // Datagrams sent before bodies has bound its port are lost, which is harmless here.
  const first = serve(sceneFile, bodiesPort);
  const status = await bodies;
  first.child.kill('SIGTERM');
  await first.exited;
  assert.equal(status.dropped, 0, `dropped ${status.dropped} with frame_step 2`);
  assert.deepEqual(status.bodies.map((b) => b.name).sort(), ['Body1', 'Body2', 'Body3']);
  assert.ok(status.bodies.every((b) => b.tracked), 'a body untracked');

  const port = await freePort();
  const vehicles = [await new h.UdpVehicle().bind(), await new h.UdpVehicle().bind()];
  const run = h.mocaplink(['run', '--config',
    e2e.writeRunConfig(dir, `vicon-udp://127.0.0.1:${port}?frozen=0`, vehicles)]);
  await h.waitForLog(run, /listening on UDP port/);  // bound: no datagram is lost from now
  const server = serve(sceneFile, port);
  await h.waitFor(() => vehicles[0].ofId(ID.ODOMETRY).length > 0, 10000,
    `first ODOMETRY\n${run.stderr}`);
  await h.sleep(1500);
  await h.stop(run);
  server.child.kill('SIGTERM');
  await server.exited;
  const counts = e2e.checkPoses(vehicles, SECONDS);
  vehicles.forEach((v) => v.close());
  console.log(`ok: ${counts.odometry} ODOMETRY, ${counts.local} LOCAL_POSITION_NED`);
}

main().catch(h.fail);
