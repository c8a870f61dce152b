// End to end over VRPN: `mocaplink serve --protocol vrpn --from replay:SCENE` → `mocaplink run
// --config` with vrpn://127.0.0.1:PORT → two UDP vehicles decoding with node-mavlink; poses
// match scene.js's ground truth in NED. Also `bodies --json` on the same server: every scene body
// tracked, and `dropped` null (VRPN has no frame numbers).
'use strict';

const path = require('node:path');
const h = require('./harness');
const scene = require('./scene');
const e2e = require('./source_e2e');

const { assert, ID } = h;
const SECONDS = 4;

async function main() {
  const dir = h.tempDir('vrpn');
  const sceneFile = path.join(dir, 'scene.csv');
  scene.writeScene(sceneFile, SECONDS);
  const server = h.mocaplink(['serve', '--protocol', 'vrpn', '--from', `replay:${sceneFile}`,
    '--listen', '127.0.0.1:0']);
  await h.waitFor(() => /serving vrpn on [^:]+:(\d+)/.test(server.stdout), 10000,
    `serve to start\n${server.stderr}`);
  const port = server.stdout.match(/on [^:]+:(\d+)/)[1];
  const url = `vrpn://127.0.0.1:${port}`;

  const status = await e2e.bodiesJson(url);
  assert.equal(status.dropped, null, 'VRPN frames have no numbers: dropped must be null');
  assert.deepEqual(status.bodies.map((b) => b.name).sort(), ['Body1', 'Body2', 'Body3']);
  assert.ok(status.frame_rate_hz > 100, `rate ${status.frame_rate_hz} Hz`);

  const vehicles = [await new h.UdpVehicle().bind(), await new h.UdpVehicle().bind()];
  const run = h.mocaplink(['run', '--config', e2e.writeRunConfig(dir, url, vehicles)]);
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
