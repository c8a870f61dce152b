// A fake PX4 vehicle on UDP (node-mavlink encodes and decodes): it sends heartbeats, answers the
// bridge's TIMESYNC requests from a clock 1000 s ahead of the host's steady clock, sends its own
// TIMESYNC request, says it is PX4 1.15.2 when asked for AUTOPILOT_VERSION, and answers
// SET_GPS_GLOBAL_ORIGIN with GPS_GLOBAL_ORIGIN. Expected: the bridge answers our TIMESYNC (ts1
// mirrored, addressed to us), estimates the offset (~1000 s, from its summary line), sends no
// origin before the vehicle has said its version (a PX4 before 1.15 is never sent one:
// docs/setup.md "The origin"), marks the origin confirmed and stops sending SET_GPS_GLOBAL_ORIGIN.
'use strict';

const path = require('node:path');
const { MavLinkProtocolV2, common, minimal, standard } = require('node-mavlink');
const h = require('./harness');

const { assert, ID } = h;
const VEHICLE_SYSID = 1;
const AHEAD_NS = 1000n * 1000000000n;  // the vehicle's clock: host steady clock + 1000 s

function serialize(message, seq) {
  return new MavLinkProtocolV2(VEHICLE_SYSID, 1).serialize(message, seq);
}

async function main() {
  const dir = h.tempDir('fake');
  const vehicle = await new h.UdpVehicle().bind();
  let seq = 0;
  const vehicleNowNs = () => process.hrtime.bigint() + AHEAD_NS;  // CLOCK_MONOTONIC, as the bridge
  const replies = [];
  let originsAnswered = 0;
  let originsBeforeVersion = 0;
  let versionAnswered = false;
  let ourTs1 = null;
  vehicle.decoder.parser.on('data', (packet) => {
    const m = h.decode(packet);
    if (packet.header.msgid === ID.TIMESYNC) {
      if (m.tc1 === 0n) {  // the bridge's request: answer like PX4
        const r = new common.TimeSync();
        r.tc1 = vehicleNowNs();
        r.ts1 = m.ts1;
        r.targetSystem = packet.header.sysid;
        r.targetComponent = packet.header.compid;
        vehicle.send(serialize(r, seq++ & 255));
      } else {
        replies.push(m);
      }
    } else if (packet.header.msgid === ID.COMMAND_LONG && m.command === 512 && Math.round(m._param1) === 148) {
      const v = new standard.AutopilotVersion();  // REQUEST_MESSAGE(AUTOPILOT_VERSION)
      v.capabilities = 2n | 16n;  // PARAM_FLOAT | PARAM_ENCODE_BYTEWISE, as PX4 sets them
      v.flightSwVersion = (1 << 24) | (15 << 16) | (2 << 8) | 255;  // 1.15.2, official
      vehicle.send(serialize(v, seq++ & 255));
      versionAnswered = true;
    } else if (packet.header.msgid === ID.SET_GPS_GLOBAL_ORIGIN) {
      if (!versionAnswered) originsBeforeVersion += 1;
      const r = new common.GpsGlobalOrigin();
      r.latitude = m.latitude;
      r.longitude = m.longitude;
      r.altitude = m.altitude;
      r.timeUsec = 0n;
      vehicle.send(serialize(r, seq++ & 255));
      originsAnswered += 1;
    }
  });

  const config = h.writeConfig(path.join(dir, 'fake.toml'), 'sim://?bodies=1', [{
    name: 'px4', body: 'Body1', link: `udp://127.0.0.1:${vehicle.port}`, profile: 'px4',
    system_id: VEHICLE_SYSID, rate_hz: 20,
  }], '[origin]\nlatitude_deg = 47.397742\nlongitude_deg = 8.545594\naltitude_m = 488.0\n');
  const run = h.mocaplink(['run', '--config', config],
    { env: { MOCAPLINK_STATE_DIR: path.join(dir, 'state') } });
  await h.waitFor(() => vehicle.peer !== undefined, 10000, `first datagram\n${run.stderr}`);

  const heartbeat = new minimal.Heartbeat();
  heartbeat.type = 2;  // MAV_TYPE_QUADROTOR
  heartbeat.autopilot = 12;  // MAV_AUTOPILOT_PX4
  heartbeat.systemStatus = 4;
  heartbeat.mavlinkVersion = 3;
  const beat = setInterval(() => vehicle.send(serialize(heartbeat, seq++ & 255)), 200);
  // Our own TIMESYNC request (PX4 sends them too).
  const request = new common.TimeSync();
  request.tc1 = 0n;
  ourTs1 = vehicleNowNs();
  request.ts1 = ourTs1;
  vehicle.send(serialize(request, seq++ & 255));

  const summary = await h.waitForLog(run,
    /vehicle px4:.*origin confirmed, timesync offset (-?[\d.]+) ms rtt ([\d.]+) ms/, 15000);
  const confirmedAt = vehicle.packets.length;
  const confirmedOrigins = vehicle.ofId(ID.SET_GPS_GLOBAL_ORIGIN).length;
  await h.sleep(2500);
  clearInterval(beat);
  await h.stop(run);
  vehicle.close();

  // TIMESYNC answered: ts1 mirrored, tc1 = bridge time, addressed to the requester.
  assert.ok(replies.length >= 1, 'the bridge did not answer our TIMESYNC request');
  const reply = replies.find((r) => r.ts1 === ourTs1);
  assert.ok(reply, 'no reply mirrors our ts1');
  assert.ok(reply.tc1 > 0n);
  assert.equal(reply.targetSystem, VEHICLE_SYSID);
  // Offset vehicle − host ≈ +1000 s (both clocks are CLOCK_MONOTONIC on this machine).
  // The estimate's error is bounded by half the round trip (NTP-style midpoint assumption).
  const offsetMs = Number(summary[1]);
  const rttMs = Number(summary[2]);
  assert.ok(Math.abs(offsetMs - 1e6) <= rttMs / 2 + 5,
    `timesync offset ${offsetMs} ms (rtt ${rttMs} ms), expected 1e6 ms`);
  // Origin: confirmed, and no SET_GPS_GLOBAL_ORIGIN after the confirmation.
  assert.ok(originsAnswered >= 1);
  assert.ok(versionAnswered, 'never asked for AUTOPILOT_VERSION');
  assert.equal(originsBeforeVersion, 0, 'SET_GPS_GLOBAL_ORIGIN sent before the PX4 said its version');
  assert.match(run.stderr, /origin_state px4: .*confirmed/);
  assert.equal(vehicle.ofId(ID.SET_GPS_GLOBAL_ORIGIN).length, confirmedOrigins,
    'SET_GPS_GLOBAL_ORIGIN still sent after confirmation');
  assert.ok(vehicle.packets.length > confirmedAt, 'the bridge stopped sending altogether');
  console.log(`ok: offset ${offsetMs} ms, ${originsAnswered} origin answers`);
}

main().catch(h.fail);
