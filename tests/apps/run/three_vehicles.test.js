// End to end: mocap emulator (`mocaplink serve --protocol vicon --from replay:SCENE`) →
// `mocaplink run` with three vehicles (different bodies, profiles, rates, one signed) → three UDP
// listeners decoding with node-mavlink. Checks per vehicle: only its own body and sysid, the
// profile's messages and nothing else, valid CRCs and signatures, the rate (±5 % over ≥ 3 s), the
// pose against the scene's ground truth after the z-up → NED mapping; and the loss behaviour when
// two bodies are occluded for 300 ms (vision stops, HIL_GPS fix_type 0; back in place, so
// reset_counter stays, issue 41, although the gap exceeds reset_after_ms).
'use strict';

const fs = require('node:fs');
const path = require('node:path');
const { MavLinkPacketSignature } = require('node-mavlink');
const h = require('./harness');
const scene = require('./scene');

const { assert, ID } = h;
const SECONDS = 8;
const KEY_HEX = '8432859ef025d9e9cc87af154935c5b92b88b787c9bff024595d45ccf5dca144';
const ORIGIN = { latitude_deg: 47.397742, longitude_deg: 8.545594, altitude_m: 488.0 };
const COMPID = 197;

async function main() {
  const dir = h.tempDir('e2e');
  const sceneFile = path.join(dir, 'scene.csv');
  scene.writeScene(sceneFile, SECONDS);

  const server = h.mocaplink(['serve', '--protocol', 'vicon', '--from', `replay:${sceneFile}`,
    '--listen', '127.0.0.1:0']);
  const served = await h.waitFor(() => /serving vicon on [^:]+:(\d+)/.test(server.stdout), 10000,
    `serve to start\n${server.stderr}`).then(() => server.stdout.match(/on [^:]+:(\d+)/)[1]);

  const vehicles = [await new h.UdpVehicle().bind(), await new h.UdpVehicle().bind(),
    await new h.UdpVehicle().bind()];
  const configFile = path.join(dir, 'three.toml');
  fs.writeFileSync(configFile, `
[mocap]
source = "vicon://127.0.0.1:${served}"
up = "+z"
north = "+x"
[origin]
latitude_deg = ${ORIGIN.latitude_deg}
longitude_deg = ${ORIGIN.longitude_deg}
altitude_m = ${ORIGIN.altitude_m}
[http]
listen = "127.0.0.1:0"
[tracking]
loss_timeout_ms = 100
reset_after_ms = 200
[[vehicle]]
name = "quad1"
body = "Body1"
link = "udp://127.0.0.1:${vehicles[0].port}"
system_id = 1
profile = "px4"
rate_hz = 50
signing_key = "${KEY_HEX}"
[[vehicle]]
name = "quad2"
body = "Body2"
link = "udp://127.0.0.1:${vehicles[1].port}"
system_id = 2
profile = "px4-gps"
rate_hz = 10
[[vehicle]]
name = "rover3"
body = "Body3"
link = "udp://127.0.0.1:${vehicles[2].port}"
system_id = 3
profile = "classic"
rate_hz = 20
`);
  const stateDir = path.join(dir, 'state');
  const run = h.mocaplink(['run', '--config', configFile], { env: { MOCAPLINK_STATE_DIR: stateDir } });
  // The scene lasts SECONDS; the emulator stops sending after it (or loops): wait for the end.
  await h.waitFor(() => vehicles[0].ofId(ID.ODOMETRY).length > 0, 10000,
    `first ODOMETRY\n${run.stderr}`);
  await h.sleep((SECONDS - 1) * 1000);
  await h.stop(run);
  server.child.kill('SIGTERM');
  await server.exited;

  // --- every vehicle: own sysid, compid 197, valid CRC, expected message set -------------------
  const allowed = {
    0: [ID.HEARTBEAT, ID.TIMESYNC, ID.SET_GPS_GLOBAL_ORIGIN, ID.COMMAND_LONG, ID.ODOMETRY],
    1: [ID.HEARTBEAT, ID.TIMESYNC, ID.HIL_GPS],
    2: [ID.HEARTBEAT, ID.TIMESYNC, ID.HIL_GPS, ID.LOCAL_POSITION_NED, ID.ATT_POS_MOCAP],
  };
  const required = { 0: [ID.ODOMETRY, ID.HEARTBEAT], 1: [ID.HIL_GPS, ID.HEARTBEAT],
    2: [ID.HIL_GPS, ID.LOCAL_POSITION_NED, ID.ATT_POS_MOCAP, ID.HEARTBEAT] };
  vehicles.forEach((v, i) => {
    assert.equal(v.decoder.invalid, 0, `vehicle ${i + 1}: CRC failures`);
    assert.ok(v.packets.length > 50, `vehicle ${i + 1}: only ${v.packets.length} packets`);
    for (const { packet } of v.packets) {
      assert.equal(packet.header.sysid, i + 1, `vehicle ${i + 1} got sysid ${packet.header.sysid}`);
      assert.equal(packet.header.compid, COMPID);
      assert.ok(allowed[i].includes(packet.header.msgid),
        `vehicle ${i + 1}: unexpected message ${packet.header.msgid}`);
    }
    for (const id of required[i]) assert.ok(v.ofId(id).length > 0, `vehicle ${i + 1}: no ${id}`);
  });

  // --- signing: every frame to quad1 signed with the key, link id 1, strictly increasing -------
  const key = Buffer.from(KEY_HEX, 'hex');
  let lastTs = -1;
  for (const { packet } of vehicles[0].packets) {
    assert.ok(packet.signature, 'quad1 got an unsigned frame');
    assert.ok(packet.signature.matches(key), 'quad1: signature does not match the key');
    assert.equal(packet.signature.linkId, 1);
    assert.ok(packet.signature.timestamp > lastTs, 'signing timestamp not increasing');
    lastTs = packet.signature.timestamp;
  }
  for (const v of vehicles.slice(1)) {
    assert.ok(v.packets.every(({ packet }) => !packet.signature), 'unexpected signature');
  }
  assert.ok(fs.existsSync(path.join(stateDir, 'quad1.signing')), 'signing timestamp not persisted');

  // --- rates: ±5 % over ≥ 3 s of uninterrupted tracking -----------------------------------------
  const odometry = vehicles[0].ofId(ID.ODOMETRY).map((p) => ({ ...p, m: h.decode(p.packet) }));
  const gapIndex = odometry.findIndex((p, k) => k > 0 &&
    Number(p.m.timeUsec - odometry[k - 1].m.timeUsec) > 200000);
  assert.ok(gapIndex > 0, 'no gap in ODOMETRY while Body1 was occluded');
  // Rates are measured on the messages' own capture timestamps (time_usec): decimation follows
  // the mocap clock (DESIGN.md), so a loaded test machine that delivers frames late does not
  // change the count per second of capture time.
  const checkRate = (samples, expectedHz, what) => {
    const us = (p) => Number(p.m.timeUsec);
    const t0 = us(samples[0]) + 500000;  // skip start-up
    const window = samples.filter((p) => us(p) >= t0 && us(p) <= t0 + 3200000);
    const span = (us(window[window.length - 1]) - us(window[0])) / 1000;
    assert.ok(span >= 3000, `${what}: only ${span} ms of samples`);
    const hz = ((window.length - 1) * 1000) / span;
    assert.ok(Math.abs(hz - expectedHz) <= 0.05 * expectedHz, `${what}: ${hz.toFixed(2)} Hz`);
    return hz;
  };
  checkRate(odometry.slice(0, gapIndex), 50, 'quad1 ODOMETRY');
  const hil2 = vehicles[1].ofId(ID.HIL_GPS).map((p) => ({ ...p, m: h.decode(p.packet) }));
  checkRate(hil2, 10, 'quad2 HIL_GPS');
  const classic = vehicles[2].ofId(ID.ATT_POS_MOCAP).map((p) => ({ ...p, m: h.decode(p.packet) }));
  checkRate(classic, 20, 'rover3 ATT_POS_MOCAP');

  // --- poses against the ground truth ------------------------------------------------------------
  const expected1 = scene.toNed(scene.truth('Body1', 0).p);
  const half = -scene.YAW1_RAD / 2;  // NED heading −30°: q = (cos(−15°), 0, 0, sin(−15°))
  for (const { m } of odometry) {
    assert.equal(m.frameId, 20);  // MAV_FRAME_LOCAL_FRD
    assert.equal(m.childFrameId, 12);  // MAV_FRAME_BODY_FRD
    assert.equal(m.estimatorType, 2);  // MAV_ESTIMATOR_TYPE_VISION
    const dp = Math.hypot(m.x - expected1[0], m.y - expected1[1], m.z - expected1[2]);
    assert.ok(dp < 0.005, `quad1 position off by ${dp} m`);
    const s = m.q[0] < 0 ? -1 : 1;  // q and −q are the same rotation
    const dq = Math.max(Math.abs(s * m.q[0] - Math.cos(half)), Math.abs(m.q[1]),
      Math.abs(m.q[2]), Math.abs(s * m.q[3] - Math.sin(half)));
    assert.ok(dq < 0.002, `quad1 attitude off: ${m.q}`);
  }
  for (const { m } of classic) {
    const d = scene.distanceToTrajectory('Body3', [m.x, m.y, m.z], SECONDS);
    assert.ok(d < 0.02, `rover3 ATT_POS_MOCAP ${d} m from Body3's path`);
    assert.ok(Math.abs(m.q[0]) > 0.999, `rover3 attitude ${m.q}`);
  }
  for (const { packet } of vehicles[2].ofId(ID.LOCAL_POSITION_NED)) {
    const m = h.decode(packet);
    const d = scene.distanceToTrajectory('Body3', [m.x, m.y, m.z], SECONDS);
    assert.ok(d < 0.02, `rover3 LOCAL_POSITION_NED ${d} m from Body3's path`);
  }
  const fixed = hil2.filter(({ m }) => m.fixType === 3);
  assert.ok(fixed.length > 20);
  // Body2 flies north along NED (n, 0, -1) for n from -1 to -1 + 0.1 * SECONDS.
  const south = scene.nedToGeodetic(ORIGIN, [-1.02, 0, -1]);
  const north = scene.nedToGeodetic(ORIGIN, [-1 + 0.1 * SECONDS + 0.02, 0, -1]);
  for (const { m } of fixed) {
    const lat = m.lat / 1e7;
    assert.ok(lat > south.latitude_deg && lat < north.latitude_deg, `quad2 lat ${lat}`);
    assert.ok(Math.abs(m.lon / 1e7 - south.longitude_deg) < 3e-7, `quad2 lon ${m.lon}`);
    assert.ok(Math.abs(m.alt / 1000 - south.altitude_m) < 0.02, `quad2 alt ${m.alt}`);
    assert.ok(m.satellitesVisible >= 10);
  }

  // --- loss: 300 ms occlusion ---------------------------------------------------------------------
  const gap = Number(odometry[gapIndex].m.timeUsec - odometry[gapIndex - 1].m.timeUsec) / 1000;
  assert.ok(gap >= 200 && gap < 600, `ODOMETRY gap ${gap} ms`);
  const before = odometry[gapIndex - 1].m.resetCounter;
  const after = odometry[gapIndex].m.resetCounter;
  assert.equal(after, before, `reset_counter ${before} -> ${after}: a gap is no jump`);
  const lost = hil2.filter(({ m }) => m.fixType === 0);
  assert.ok(lost.length >= 1, 'quad2 HIL_GPS never reported fix_type 0 while Body2 was occluded');
  const lastLost = lost[lost.length - 1].m.timeUsec;
  assert.ok(hil2.some(({ m }) => m.timeUsec > lastLost && m.fixType === 3),
    'no fix after reacquisition');
  // The unoccluded body keeps going without a gap.
  for (let k = 1; k < classic.length; k += 1) {
    const dt = Number(classic[k].m.timeUsec - classic[k - 1].m.timeUsec) / 1000;
    assert.ok(dt < 100, `rover3 stream interrupted for ${dt} ms`);
  }
  vehicles.forEach((v) => v.close());
  console.log(`ok: ${vehicles.map((v) => v.packets.length).join('/')} packets, ` +
    `quad1 gap ${gap.toFixed(0)} ms, reset_counter ${before}->${after}`);
}

main().catch(h.fail);
