// End to end (issue 15): a fleet big enough to be sent from several threads. sim:// (10 bodies,
// 30 Hz, 150 frames) → `mocaplink run` with 300 UDP vehicles at 30 Hz and MOCAPLINK_SEND_THREADS=3
// (io/send_threads.hpp: one thread per 100 vehicles, so all three send) → 300 sockets decoded by
// node-mavlink. The daemon must say it sends from 3 threads, and the threads must change nothing a
// vehicle sees: each vehicle's frames arrive with consecutive sequence numbers (nothing reordered
// or sent twice), its ODOMETRY in capture order, and every vehicle following a body gets exactly
// the poses the others following it get (frames are never split between vehicles, even when the
// machine is too slow and frames are dropped whole). 30 Hz, not more: node decoding 300 sockets
// under emulation on a busy machine fell behind at 60 Hz and the kernel dropped datagrams at its
// sockets (RcvbufErrors), which this test cannot tell from a bridge that lost them.
'use strict';

const path = require('node:path');
const h = require('./harness');

const { assert, ID } = h;
const VEHICLES = 300;
const BODIES = 10;

async function main() {
  const dir = h.tempDir('sharded');
  const vehicles = [];
  for (let i = 0; i < VEHICLES; i += 1) vehicles.push(await new h.UdpVehicle().bind());
  const config = h.writeConfig(path.join(dir, 'fleet.toml'),
    `sim://?bodies=${BODIES}&rate_hz=30&frames=150&seed=3`,
    vehicles.map((v, i) => ({
      name: `v${i + 1}`, body: `Body${(i % BODIES) + 1}`, link: `udp://127.0.0.1:${v.port}`,
      system_id: (i % 250) + 1, profile: 'px4', rate_hz: 30,
    })));
  const run = h.mocaplink(['run', '--config', config],
    { env: { MOCAPLINK_SEND_THREADS: '3', MOCAPLINK_STATE_DIR: dir } });
  const { code, signal } = await run.exited;  // the sim's 300 frames end the run
  assert.equal(signal, null, run.stderr);
  assert.equal(code, 0, run.stderr);
  assert.match(run.stderr, /sending from 3 threads \(300 vehicles;/);
  await h.sleep(300);  // the last datagrams reach node's sockets

  const posesOfBody = new Map();
  vehicles.forEach((v, i) => {
    assert.equal(v.decoder.invalid, 0, `v${i + 1}: CRC failures`);
    const packets = v.packets.map((p) => p.packet);
    assert.ok(packets.length > 0, `v${i + 1} got nothing`);
    for (let k = 1; k < packets.length; k += 1) {
      assert.equal(packets[k].header.seq, (packets[k - 1].header.seq + 1) % 256,
        `v${i + 1}: frame ${k} out of sequence`);
    }
    const times = v.ofId(ID.ODOMETRY).map((p) => h.decode(p.packet).timeUsec);
    assert.ok(times.length > 50, `v${i + 1}: only ${times.length} ODOMETRY`);
    for (let k = 1; k < times.length; k += 1) {
      assert.ok(times[k] > times[k - 1], `v${i + 1}: ODOMETRY ${k} not after the one before`);
    }
    const body = i % BODIES;
    const key = times.join(',');
    if (!posesOfBody.has(body)) posesOfBody.set(body, key);
    assert.equal(key, posesOfBody.get(body), `v${i + 1} got other poses than v${body + 1}`);
  });
  vehicles.forEach((v) => v.close());
  console.log(`ok: ${VEHICLES} vehicles from 3 threads, ` +
    `${vehicles[0].ofId(ID.ODOMETRY).length} ODOMETRY each, in order`);
}

main().catch(h.fail);
