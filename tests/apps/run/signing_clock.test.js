// The signing clock of `mocaplink run` (mavlink-wire.md §7.3): a vehicle's persisted timestamp is
// the floor of its next signed frame even when it is ahead of the wall clock, only for that
// vehicle (another signed vehicle and the wall clock are untouched), and a correctly signed frame
// from the vehicle with a later timestamp raises the floor again. Signed frames from the vehicle
// are made by node-mavlink (an independent signer).
'use strict';

const fs = require('node:fs');
const path = require('node:path');
const { MavLinkProtocolV2, minimal } = require('node-mavlink');
const h = require('./harness');

const { assert, ID } = h;
const KEY_HEX = '8432859ef025d9e9cc87af154935c5b92b88b787c9bff024595d45ccf5dca144';
const KEY = Buffer.from(KEY_HEX, 'hex');
const EPOCH_MS = 1420070400000;  // 2015-01-01T00:00:00Z
const to10us = (unixMs) => (unixMs - EPOCH_MS) * 100;

/** Signing timestamps (10 µs units) of the frames `vehicle` received after index `from`. */
const stamps = (vehicle, from = 0) => vehicle.packets.slice(from).map(({ packet }) => {
  assert.ok(packet.signature && packet.signature.matches(KEY), 'unsigned or badly signed frame');
  return packet.signature.timestamp;
});

async function main() {
  const dir = h.tempDir('signing-clock');
  const stateDir = path.join(dir, 'state');
  fs.mkdirSync(stateDir);
  const ahead = to10us(Date.now() + 3600 * 1000);  // one hour ahead of the wall clock
  fs.writeFileSync(path.join(stateDir, 'quad.signing'), `mocaplink-signing-timestamp 1 ${ahead}\n`);
  const quad = await new h.UdpVehicle().bind();
  const other = await new h.UdpVehicle().bind();
  const config = h.writeConfig(path.join(dir, 'run.toml'), 'sim://', [
    { name: 'quad', body: 'Body1', link: `udp://127.0.0.1:${quad.port}`, system_id: 1, profile: 'px4', signing_key: KEY_HEX },
    { name: 'other', body: 'Body2', link: `udp://127.0.0.1:${other.port}`, system_id: 2, profile: 'px4', signing_key: KEY_HEX },
  ]);
  const started = Date.now();
  const run = h.mocaplink(['run', '--config', config], { env: { MOCAPLINK_STATE_DIR: stateDir } });
  await h.waitForLog(run, /signing: vehicle quad: the stored signing timestamp is 3[56]\d\d\.\d+ s ahead/);
  await h.waitFor(() => quad.ofId(ID.ODOMETRY).length >= 10 && other.ofId(ID.ODOMETRY).length >= 10,
    5000, 'poses to both vehicles');

  // quad continues above its stored value; other signs from the wall clock.
  const quadStamps = stamps(quad);
  assert.ok(quadStamps[0] > ahead, `quad's first timestamp ${quadStamps[0]} not above stored ${ahead}`);
  for (const ts of stamps(other)) {
    assert.ok(ts >= to10us(started - 1000) && ts <= to10us(Date.now() + 1000),
      `other's timestamp ${ts} is not the wall clock`);
  }

  // A correctly signed HEARTBEAT from the vehicle, two hours ahead: our next frames go above it.
  const heartbeat = new minimal.Heartbeat();
  heartbeat.type = 2;
  heartbeat.autopilot = 12;
  const protocol = new MavLinkProtocolV2(1, 1, MavLinkProtocolV2.IFLAG_SIGNED);
  const vehicleMs = Date.now() + 2 * 3600 * 1000;
  quad.send(protocol.sign(protocol.serialize(heartbeat, 0), 7, KEY, vehicleMs));
  await h.sleep(200);
  const mark = quad.packets.length;
  await h.waitFor(() => quad.packets.length > mark + 5, 3000, 'frames after the signed heartbeat');
  for (const ts of stamps(quad, mark)) {
    assert.ok(ts > to10us(vehicleMs), `timestamp ${ts} not above the vehicle's ${to10us(vehicleMs)}`);
  }
  // An unsigned or wrongly signed frame raises nothing (it is dropped).
  const wrong = new MavLinkProtocolV2(1, 1, MavLinkProtocolV2.IFLAG_SIGNED);
  quad.send(wrong.sign(wrong.serialize(heartbeat, 1), 7, Buffer.alloc(32, 1), vehicleMs + 3600 * 1000));
  await h.sleep(200);
  const mark2 = quad.packets.length;
  await h.waitFor(() => quad.packets.length > mark2 + 5, 3000, 'frames after the forged heartbeat');
  for (const ts of stamps(quad, mark2)) {
    assert.ok(ts < to10us(vehicleMs + 3600 * 1000), 'a forged frame moved the signing clock');
  }

  await h.stop(run);
  const saved = Number(fs.readFileSync(path.join(stateDir, 'quad.signing'), 'utf8').split(' ')[2]);
  assert.ok(saved > to10us(vehicleMs), `persisted ${saved} is below what was sent`);
  quad.close();
  other.close();
}

main().catch(h.fail);
