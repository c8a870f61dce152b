// The demo exists only when `run` names no source and no vehicle (issue 11, "no hidden vehicle").
// A listener on 127.0.0.1:14550 — where the demo vehicle sends, and where QGroundControl and
// simulators listen — must hear nothing while `run --source … --vehicle …` runs, and must hear the
// demo's ODOMETRY when `run` gets no vehicle-defining option (so the first check can fail).
'use strict';

const dgram = require('node:dgram');
const h = require('./harness');

const { assert, ID } = h;

const DEMO_PORT = 14550;

async function dashboardPort(run) {
  const [, port] = await h.waitForLog(run, /dashboard: http:\/\/127\.0\.0\.1:(\d+)\//);
  return port;
}

async function vehicleNames(port) {
  const status = await (await fetch(`http://127.0.0.1:${port}/api/status`)).json();
  return status.vehicles.map((v) => v.name);
}

async function main() {
  const demoListener = new h.UdpVehicle();
  await new Promise((resolve, reject) => {
    demoListener.socket.once('error', (e) => reject(new Error(`cannot bind 127.0.0.1:${DEMO_PORT} ` +
      `(something else listens there; stop it to run this test): ${e.message}`)));
    demoListener.socket.bind(DEMO_PORT, '127.0.0.1', resolve);
  });

  // 1. --source and --vehicle: exactly the given vehicle, nothing to the demo's address.
  const quad = await new h.UdpVehicle().bind();
  const given = h.mocaplink(['run', '--http', '127.0.0.1:0', '--source', 'sim://?bodies=2',
    '--vehicle', `quad:body=Body2,link=udp://127.0.0.1:${quad.port},system_id=3,profile=px4`]);
  const givenHttp = await dashboardPort(given);
  await h.waitFor(() => quad.ofId(ID.ODOMETRY).length >= 20, 10000, 'ODOMETRY to quad');
  assert.deepEqual(await vehicleNames(givenHttp), ['quad']);
  assert.ok(quad.packets.every((p) => p.packet.header.sysid === 3), 'only system 3 on quad');
  await h.stop(given);
  assert.equal(demoListener.datagrams, 0, 'a run with --source/--vehicle sent to the demo address');

  // 2. --source alone: no vehicle, said clearly, still nothing to the demo's address.
  const empty = h.mocaplink(['run', '--http', '127.0.0.1:0', '--source', 'sim://']);
  const emptyHttp = await dashboardPort(empty);
  assert.match(empty.stderr, /no vehicle configured: nothing is sent/);
  assert.deepEqual(await vehicleNames(emptyHttp), []);
  await h.sleep(500);
  await h.stop(empty);
  assert.equal(demoListener.datagrams, 0, 'a run with only --source sent to the demo address');

  // 3. --vehicle without a source: refused (exit 1), not filled in from the demo.
  const noSource = h.mocaplink(['run', '--vehicle',
    `quad:body=Body2,link=udp://127.0.0.1:${quad.port},profile=px4`]);
  assert.equal((await noSource.exited).code, 1, noSource.stderr);
  assert.match(noSource.stderr, /--vehicle needs a mocap source: give --source URL or --config FILE/);

  // 4. Only --http: the demo, whose ODOMETRY reaches 127.0.0.1:14550 as documented.
  const demo = h.mocaplink(['run', '--http', '127.0.0.1:0']);
  const demoHttp = await dashboardPort(demo);
  assert.deepEqual(await vehicleNames(demoHttp), ['demo']);
  await h.waitFor(() => demoListener.ofId(ID.ODOMETRY).length >= 10, 10000, 'the demo ODOMETRY');
  await h.stop(demo);

  quad.close();
  demoListener.close();
}

main().then(() => process.exit(0), h.fail);
