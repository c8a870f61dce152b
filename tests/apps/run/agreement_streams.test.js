// The agreement check on a vehicle that sends nothing until asked (issue 31), with the real daemon
// and scripted vehicles on real UDP sockets (node-mavlink encodes and decodes). Like ArduCopter
// with its default stream rates, the vehicles send HEARTBEAT and answer TIMESYNC, and send ATTITUDE
// and LOCAL_POSITION_NED only once asked. What they report is the pose mocaplink sends them
// (ODOMETRY), so the yaw offset is the one they are scripted with.
//
//   "quad" (ArduPilot, sysid 1), first boot: refuses SET_MESSAGE_INTERVAL for ATTITUDE
//   (UNSUPPORTED) and streams it once asked with REQUEST_DATA_STREAM EXTRA1; ignores the first two
//   SET_MESSAGE_INTERVAL for LOCAL_POSITION_NED and accepts the third (confirmation 2). It reports
//   its yaw as mocap's, its tilt as the body's, and answers the set-up list's parameter reads as
//   an EKF3 taking yaw and position from ExternalNav (EK3_SRC1_YAW, EK3_SRC1_POSXY 6; the rest 0):
//   the verdict must become `agree` on gravity, its reason naming yaw and position as not
//   checkable (issue 48).
//   Then it reboots (its boot clock starts again, in TIMESYNC and the messages; its rates are
//   gone): mocaplink must ask again (confirmation 0), the vehicle accepts both, and now reports a
//   yaw 90° off (a rigid body defined 90° off): `unknown` while the rebooted vehicle settles, then
//   `disagree` and the `agreement_failing` alert (at 15 s of its uptime plus the 3 s hold).
//   "mute" (ArduPilot, sysid 2): accepts every request and never sends either message: the
//   dashboard must say why the agreement is unknown.
//   Both are also asked, after those two, for EKF_STATUS_REPORT at 1 Hz (issue 28: the set-up
//   list's estimator line); the quad answers as it does LOCAL_POSITION_NED and sends it with
//   "attitude, horizontal velocity and position" good, which /api/status shows in words.
'use strict';

const path = require('node:path');
const { MavLinkProtocolV2, ardupilotmega, common, minimal } = require('node-mavlink');
const h = require('./harness');

const { assert, ID } = h;
const ATTITUDE = 30;
const REQUEST_DATA_STREAM = 66;
const COMMAND_ACK = 77;
const SET_MESSAGE_INTERVAL = 511;
const EKF_STATUS_REPORT = 193;
const PARAM_REQUEST_READ = 20;
const EXTERNAL_NAV = ['EK3_SRC1_YAW', 'EK3_SRC1_POSXY'];

/// A scripted ArduPilot on `vehicle` (a h.UdpVehicle) with system id `sysid`. `script` decides
/// the answer to each SET_MESSAGE_INTERVAL: (messageId, confirmation, boot) → MAV_RESULT or null
/// (no answer). With `mute`, it never sends what it was asked for.
function scriptedVehicle(vehicle, sysid, script, { mute = false } = {}) {
  const s = {
    vehicle, sysid, boot: 1, bootStart: performance.now() - 60000,  // boot clock at 60 s
    intervals: new Map(), yawOffsetRad: 0, odometry: null, commands: [], dataStreams: [], acks: 0,
  };
  let seq = 0;
  const send = (m) => vehicle.send(new MavLinkProtocolV2(sysid, 1).serialize(m, seq++ & 255));
  const bootMs = () => Math.max(0, Math.round(performance.now() - s.bootStart));
  const ack = (command, result, packet) => {
    const a = new common.CommandAck();
    a.command = command;
    a.result = result;
    a.targetSystem = packet.header.sysid;
    a.targetComponent = packet.header.compid;
    send(a);
    s.acks += 1;
  };
  vehicle.decoder.parser.on('data', (packet) => {
    const m = h.decode(packet);
    const id = packet.header.msgid;
    if (id === ID.ODOMETRY) {
      s.odometry = m;
    } else if (id === ID.TIMESYNC && m.tc1 === 0n) {  // answer with the boot clock, like ArduPilot
      const r = new common.TimeSync();
      r.tc1 = BigInt(bootMs()) * 1000000n;
      r.ts1 = m.ts1;
      send(r);
    } else if (id === ID.COMMAND_LONG && m.command === SET_MESSAGE_INTERVAL) {
      const messageId = Math.round(m._param1);
      s.commands.push({ boot: s.boot, messageId, intervalUs: m._param2, confirmation: m.confirmation,
        target: [m.targetSystem, m.targetComponent], t: performance.now() });
      const result = script(messageId, m.confirmation, s.boot);
      if (result === null) return;
      ack(SET_MESSAGE_INTERVAL, result, packet);
      if (result === 0 && !mute) s.intervals.set(messageId, m._param2 / 1000);
    } else if (id === PARAM_REQUEST_READ && m.targetSystem === sysid) {
      // EKF3 with yaw and position from ExternalNav (issue 48); every other parameter 0.
      const name = m.paramId.replace(/\0+$/, '');
      const v = new common.ParamValue();
      v.paramId = name;
      v.paramType = 2;  // INT8; ArduPilot sends the value cast to float
      v.paramValue = EXTERNAL_NAV.includes(name) ? 6 : 0;
      v.paramCount = 1;
      v.paramIndex = 65535;
      send(v);
    } else if (id === REQUEST_DATA_STREAM) {
      s.dataStreams.push({ boot: s.boot, stream: m.reqStreamId, rate: m.reqMessageRate, start: m.startStop });
      if (mute) return;
      if (m.reqStreamId === 10 && m.startStop === 1) s.intervals.set(ATTITUDE, 1000 / m.reqMessageRate);
      if (m.reqStreamId === 6 && m.startStop === 1) s.intervals.set(ID.LOCAL_POSITION_NED, 1000 / m.reqMessageRate);
    }
  });
  const heartbeat = new minimal.Heartbeat();
  heartbeat.type = 2;       // quadrotor
  heartbeat.autopilot = 3;  // ArduPilot
  heartbeat.systemStatus = 3;
  heartbeat.mavlinkVersion = 3;
  const last = new Map();
  s.timer = setInterval(() => {
    const now = performance.now();
    if (!last.has('hb') || now - last.get('hb') >= 500) { send(heartbeat); last.set('hb', now); }
    for (const [messageId, periodMs] of s.intervals) {
      if (last.has(messageId) && now - last.get(messageId) < periodMs) continue;
      last.set(messageId, now);
      const o = s.odometry;
      if (!o) continue;
      if (messageId === ATTITUDE) {
        const [w, x, y, z] = o.q;
        const a = new common.Attitude();
        a.timeBootMs = bootMs();
        // Its IMU's tilt is the body's true tilt: what mocap says, when the axes are right.
        a.roll = Math.atan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y));
        a.pitch = Math.asin(Math.max(-1, Math.min(1, 2 * (w * y - z * x))));
        a.yaw = Math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z)) + s.yawOffsetRad;
        send(a);
      } else if (messageId === ID.LOCAL_POSITION_NED) {
        const p = new common.LocalPositionNed();
        p.timeBootMs = bootMs();
        p.x = o.x;
        p.y = o.y;
        p.z = o.z;
        send(p);
      } else if (messageId === EKF_STATUS_REPORT) {
        const e = new ardupilotmega.EkfStatusReport();
        e.flags = 1 | 2 | 8;  // EKF_ATTITUDE, EKF_VELOCITY_HORIZ, EKF_POS_HORIZ_REL
        send(e);
      }
    }
  }, 20);
  s.reboot = () => {  // rates gone, boot clock from 0
    s.boot += 1;
    s.intervals.clear();
    s.bootStart = performance.now();
  };
  return s;
}

async function main() {
  const dir = h.tempDir('agreement');
  const quadLink = await new h.UdpVehicle().bind();
  const muteLink = await new h.UdpVehicle().bind();
  const config = h.writeConfig(path.join(dir, 'run.toml'), 'sim://?bodies=2&rate_hz=100', [
    { name: 'quad', body: 'Body1', link: `udp://127.0.0.1:${quadLink.port}`, system_id: 1,
      profile: 'ardupilot', rate_hz: 30 },
    { name: 'mute', body: 'Body2', link: `udp://127.0.0.1:${muteLink.port}`, system_id: 2,
      profile: 'ardupilot', rate_hz: 30 },
  ]);
  const run = h.mocaplink(['run', '--config', config]);
  const [, port] = await h.waitForLog(run, /dashboard: http:\/\/127\.0\.0\.1:(\d+)\//);
  const api = h.dashboardApi(port);
  const status = async (name) => (await api('GET', '/api/status')).json.vehicles.find((v) => v.name === name);
  await h.waitFor(() => quadLink.peer !== undefined && muteLink.peer !== undefined, 10000, 'first datagrams');

  const quad = scriptedVehicle(quadLink, 1, (messageId, confirmation, boot) => {
    if (boot === 1 && messageId === ATTITUDE) return 3;  // MAV_RESULT_UNSUPPORTED
    if (boot === 1 && confirmation < 2) return null;     // lost, lost, then answered
    return 0;                                            // MAV_RESULT_ACCEPTED
  });
  const mute = scriptedVehicle(muteLink, 2, () => 0, { mute: true });

  try {
    // Before anything was asked, the agreement is unknown and the dashboard says why.
    await h.sleep(500);
    const early = await status('quad');
    assert.equal(early.agreement.verdict, 'unknown');
    assert.match(early.agreement.reason, /ATTITUDE|HEARTBEAT|tracked/);

    // First boot: refused → REQUEST_DATA_STREAM; LOCAL_POSITION_NED retried until accepted.
    await h.waitFor(() => quad.dataStreams.length > 0, 15000, `REQUEST_DATA_STREAM\n${run.stderr}`);
    let q;
    const deadline = Date.now() + 15000;
    while (Date.now() < deadline) {
      q = await status('quad');
      if (q.agreement.verdict !== 'unknown') break;
      await h.sleep(100);
    }
    assert.equal(q.agreement.verdict, 'agree', JSON.stringify(q.agreement));
    assert.ok(Math.abs(q.agreement.yaw_offset_deg) < 10, JSON.stringify(q.agreement));
    // Agreed on gravity; its yaw and position are mocap's own, it has no compass (every other
    // parameter is 0), and the reason says so (issue 48).
    assert.ok(q.agreement.tilt_offset_deg < 15, JSON.stringify(q.agreement));
    assert.equal(q.agreement.reason,
      "yaw not checkable: the vehicle's yaw comes from mocap (EK3_SRC1_YAW = 6), and it has no "
      + "heading of its own (COMPASS_ENABLE = 0: no compass): the nose is "
      + "unchecked; position not checkable: the vehicle's position comes from mocap "
      + "(EK3_SRC1_POSXY = 6)");
    assert.equal(q.streams.RAW_IMU, undefined, JSON.stringify(q.streams));  // not asked for
    assert.equal(q.agreement.fix, null);
    assert.equal(q.streams.ATTITUDE, 'arriving');
    assert.equal(q.streams.LOCAL_POSITION_NED, 'arriving');
    // Then the estimator's health, lost twice and accepted like LOCAL_POSITION_NED, at 1 Hz.
    const estimatorDeadline = Date.now() + 15000;
    while (Date.now() < estimatorDeadline) {
      q = await status('quad');
      if (q.estimator) break;
      await h.sleep(100);
    }
    assert.equal(q.streams.EKF_STATUS_REPORT, 'arriving', JSON.stringify(q.streams));
    assert.equal(q.estimator.source, 'EKF_STATUS_REPORT', JSON.stringify(q.estimator));
    assert.ok(q.estimator.good.length > 0, JSON.stringify(q.estimator));
    const first = quad.commands.filter((c) => c.boot === 1);
    assert.deepEqual(first.map((c) => [c.messageId, c.confirmation]),
      [[ATTITUDE, 0], [ID.LOCAL_POSITION_NED, 0], [ID.LOCAL_POSITION_NED, 1], [ID.LOCAL_POSITION_NED, 2],
        [EKF_STATUS_REPORT, 0], [EKF_STATUS_REPORT, 1], [EKF_STATUS_REPORT, 2]]);
    for (const c of first) {
      assert.equal(c.intervalUs, c.messageId === EKF_STATUS_REPORT ? 1000000 : 200000);
      assert.deepEqual(c.target, [1, 1]);
    }
    const lpn = first.filter((c) => c.messageId === ID.LOCAL_POSITION_NED);
    assert.ok(lpn[1].t - lpn[0].t >= 800 && lpn[2].t - lpn[1].t >= 800, 'retries are paced about 1 s apart');
    assert.ok(quad.dataStreams.every((d) => d.stream === 10 && d.rate === 5 && d.start === 1),
      JSON.stringify(quad.dataStreams));
    // Counted in the dashboard's `sent` (UDP on loopback loses nothing).
    assert.equal(q.sent.SET_MESSAGE_INTERVAL, first.length);
    assert.equal(q.sent.REQUEST_DATA_STREAM, quad.dataStreams.length);
    assert.match(run.stderr, /vehicle_streams quad: asking for ATTITUDE at 5 Hz \(SET_MESSAGE_INTERVAL 30, 200000 us\)/);
    assert.match(run.stderr, /vehicle_streams quad: the vehicle refused SET_MESSAGE_INTERVAL for ATTITUDE \(MAV_RESULT_UNSUPPORTED\); asking with REQUEST_DATA_STREAM EXTRA1 at 5 Hz instead/);
    assert.match(run.stderr, /vehicle_streams quad: ATTITUDE arriving \(after REQUEST_DATA_STREAM\)/);
    assert.match(run.stderr, /vehicle_streams quad: the vehicle accepted SET_MESSAGE_INTERVAL for LOCAL_POSITION_NED/);
    assert.match(run.stderr, /vehicle_streams quad: asking for EKF_STATUS_REPORT at 1 Hz \(SET_MESSAGE_INTERVAL 193, 1000000 us\)/);
    assert.equal((run.stderr.match(/vehicle_streams quad: asking for LOCAL_POSITION_NED/g) || []).length, 1,
      'logged once, not per retry');

    // The mute vehicle: asked, accepted, nothing came: the dashboard says so.
    let m;
    const muteDeadline = Date.now() + 15000;
    while (Date.now() < muteDeadline) {
      m = await status('mute');
      if (m.streams.ATTITUDE === 'silent') break;
      await h.sleep(100);
    }
    assert.equal(m.agreement.verdict, 'unknown');
    assert.equal(m.agreement.reason,
      'no ATTITUDE from the vehicle after asking: is this port\'s MAVLink enabled?');
    assert.match(run.stderr, /no ATTITUDE from the vehicle after asking: is this port's MAVLink enabled\?/);

    // Reboot, now with the body defined 90° off: asked again, and the verdict follows.
    quad.yawOffsetRad = Math.PI / 2;
    quad.reboot();
    await h.waitForLog(run, /vehicle_streams quad: the vehicle rebooted/, 10000);
    await h.waitFor(() => quad.commands.some((c) => c.boot === 2 && c.messageId === ID.LOCAL_POSITION_NED),
      15000, `SET_MESSAGE_INTERVAL after the reboot\n${run.stderr}`);
    const second = quad.commands.filter((c) => c.boot === 2);
    assert.deepEqual(second.slice(0, 2).map((c) => [c.messageId, c.confirmation]),
      [[ATTITUDE, 0], [ID.LOCAL_POSITION_NED, 0]]);
    // A rebooted vehicle's estimate is compared once it has been up 15 s, and a disagreement is
    // the verdict once it has lasted 3 s (docs/messages.md "Agreement check"): not before 18 s of
    // its uptime, and never the first boot's `agree` meanwhile.
    const rebootDeadline = Date.now() + 30000;
    while (Date.now() < rebootDeadline) {
      q = await status('quad');
      if (q.agreement.verdict === 'disagree') break;
      assert.equal(q.agreement.verdict, 'unknown', JSON.stringify(q.agreement));
      await h.sleep(100);
    }
    assert.equal(q.agreement.verdict, 'disagree', JSON.stringify(q.agreement));
    const uptimeMs = performance.now() - quad.bootStart;
    assert.ok(uptimeMs >= 17900, `disagree after ${uptimeMs} ms of uptime`);
    assert.match(run.stderr, /agreement quad: estimate unknown \(the vehicle booted moments ago/);
    assert.ok(Math.abs(Math.abs(q.agreement.yaw_offset_deg) - 90) < 10, JSON.stringify(q.agreement));
    const alerts = (await api('GET', '/api/status')).json.alerts;
    assert.ok(alerts.some((a) => a.kind === 'agreement_failing' && a.subject === 'quad' && a.level === 'error'),
      JSON.stringify(alerts));
    await h.waitForLog(run, /agreement quad: estimate disagrees, tilt offset [0-9.]+ deg, yaw offset/, 5000);
    console.log(`ok: ${quad.commands.length} SET_MESSAGE_INTERVAL, ${quad.dataStreams.length} ` +
      `REQUEST_DATA_STREAM to quad; verdicts agree then disagree (${q.agreement.yaw_offset_deg.toFixed(1)}°)`);
  } finally {
    clearInterval(quad.timer);
    clearInterval(mute.timer);
  }
  await h.stop(run);
  quadLink.close();
  muteLink.close();
}

main().catch(h.fail);
