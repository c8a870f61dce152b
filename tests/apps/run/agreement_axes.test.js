// The agreement check against gravity (issue 48), with the real daemon and a scripted ArduCopter
// whose EKF3 takes yaw and position from ExternalNav (EK3_SRC1_YAW = 6, EK3_SRC1_POSXY = 6): it
// reports back mocaplink's own yaw and position (from the ODOMETRY it is sent), so they always
// match, and its IMU's roll and pitch from the body's true attitude. The truth is the sim's Z-up
// world with FLU bodies: the raw quaternion /api/status shows (`station.bodies[].q_wxyz`, before
// any mapping) turned into NED/FRD here by hand (R = Rx(180°) · R_raw · Rx(180°)), not by mocaplink.
//   right   `up = "+z"`: `agree` on gravity, the reason naming yaw and position as not checkable.
//   mistake `up = "+y"` (the OptiTrack habit): tilt offset near 90°, `disagree`, the
//           agreement_failing alert, and the fix `[mocap] up = "+z"` in agreement.fix, the reason
//           and the log line; poses keep flowing.
//   nose    `body_forward = "+y"` (a body created nose-left): tilt and the fed-back yaw agree,
//           the compass does not: the vehicle has a calibrated one (COMPASS_ENABLE = 1, offsets
//           not 0), so mocaplink asks for RAW_IMU with SET_MESSAGE_INTERVAL, which this vehicle
//           then sends with Earth's field turned into the body by its true attitude: heading offset
//           near 90°, `disagree`, and the fix `[[vehicle]] body_forward = "+x"`.
// The heading, like the tilt, is the raw quaternion turned into NED here by hand.
'use strict';

const fs = require('node:fs');
const path = require('node:path');
const h = require('./harness');
const { externalNavVehicle, verdictPoller } = require('./external_nav_vehicle');

const { assert, ID } = h;

async function session(dir, name, up, vehicleKeys = {}, { px4 = false, visionYaw = false } = {}) {
  const link = await new h.UdpVehicle().bind();
  const config = h.writeConfig(path.join(dir, `${name}.toml`),
    'sim://?bodies=1&rate_hz=100', [{ name: 'quad', body: 'Body1',
      link: `udp://127.0.0.1:${link.port}`, system_id: 1, profile: px4 ? 'px4' : 'ardupilot', rate_hz: 30,
      ...vehicleKeys }],
    `up = "${up}"`);
  // A fixed dashboard port: `vehicle setup` with this configuration asks the running daemon.
  const httpPort = await h.freeTcpPort();
  fs.writeFileSync(config, fs.readFileSync(config, 'utf8').replace('127.0.0.1:0', `127.0.0.1:${httpPort}`));
  const run = h.mocaplink(['run', '--config', config]);
  const [, port] = await h.waitForLog(run, /dashboard: http:\/\/127\.0\.0\.1:(\d+)\//);
  const api = h.dashboardApi(port);
  let truth = null;
  const poll = setInterval(async () => {
    try {
      const body = (await api('GET', '/api/status')).json.station.bodies.find((b) => b.name === 'Body1');
      if (body && body.q_wxyz) truth = body.q_wxyz;
    } catch { /* the daemon stopping */ }
  }, 50);
  await h.waitFor(() => link.peer !== undefined, 10000, 'first datagrams');
  const quad = externalNavVehicle(link, 1, () => truth, { px4, visionYaw });
  const done = async () => {
    clearInterval(quad.timer);
    clearInterval(poll);
    await h.stop(run);
    link.close();
  };
  // A disagreement by tilt comes before the source parameters are read (on a loaded machine well
  // before): the cases wait for what they check with `also`.
  const verdict = verdictPoller(api, run, name);
  return { run, api, verdict, done, config, quad };
}

const NOT_CHECKABLE = 'yaw compared with its compass only (its compass in RAW_IMU: '
  + "COMPASS_ENABLE = 1, calibrated), 45° allowed: the vehicle's yaw comes from mocap (EK3_SRC1_YAW = 6); position "
  + "not checkable: the vehicle's position comes from mocap (EK3_SRC1_POSXY = 6)";

async function main() {
  const dir = h.tempDir('agreement-axes');
  const right = await session(dir, 'right', '+z');
  const mistake = await session(dir, 'up', '+y');
  const nose = await session(dir, 'nose', '+z', { body_forward: '+y' });
  const bodyUp = await session(dir, 'bodyup', '+z', { body_up: '+y' });
  const px4Nose = await session(dir, 'px4nose', '+z', { body_forward: '+y' }, { px4: true });
  const px4VisionNose = await session(dir, 'px4visionnose', '+z', { body_forward: '+y' },
    { px4: true, visionYaw: true });
  try {
    const ok = await right.verdict('agree', 20000);
    assert.ok(ok.agreement.tilt_offset_deg < 5, JSON.stringify(ok.agreement));
    assert.ok(Math.abs(ok.agreement.heading_offset_deg) < 10, JSON.stringify(ok.agreement));
    assert.equal(ok.agreement.reason, NOT_CHECKABLE);
    assert.equal(ok.agreement.fix, null);
    assert.equal(ok.streams.RAW_IMU, 'arriving', JSON.stringify(ok.streams));
    assert.ok(right.quad.rawImuAsked >= 1);
    assert.deepEqual(ok.agreement.checked, ['tilt', 'compass'], JSON.stringify(ok.agreement));
    const rightSetup = h.mocaplink(['vehicle', 'setup', '--config', right.config, 'quad', '--timeout', '20']);
    await rightSetup.exited;
    assert.match(rightSetup.stdout, /^ {2}agreement: agree on tilt and compass \(tilt [0-9.]+ deg, .*compass -?[0-9.]+ deg\)$/m,
      `${rightSetup.stdout}\n${rightSetup.stderr}`);

    const bad = await mistake.verdict('disagree', 25000,
      (ag) => typeof ag.reason === 'string' && ag.reason.endsWith(NOT_CHECKABLE));
    const a = bad.agreement;
    assert.ok(Math.abs(a.tilt_offset_deg - 90) < 10, JSON.stringify(a));
    assert.ok(Math.abs(a.yaw_offset_deg) < 5, JSON.stringify(a));  // mocap against itself
    assert.equal(a.fix.kind, 'fix', JSON.stringify(a.fix));
    assert.deepEqual(a.fix.lines, ['[mocap] up = "+z"'], JSON.stringify(a.fix));
    assert.ok(a.fix.tilt_residual_deg < 5, JSON.stringify(a.fix));
    // Named again once RAW_IMU arrived: the nose is checked too (a wrong `up` leaves it right).
    await mistake.verdict('disagree', 5000, (ag) => ag.fix && ag.fix.heading_residual_deg !== null);
    const withHeading = (await mistake.api('GET', '/api/status')).json.vehicles[0].agreement.fix;
    assert.deepEqual(withHeading.lines, ['[mocap] up = "+z"'], JSON.stringify(withHeading));
    assert.ok(withHeading.heading_residual_deg < 10, JSON.stringify(withHeading));
    assert.ok(a.reason.startsWith('fix: [mocap] up = "+z" (then tilt '), a.reason);
    assert.ok(a.reason.endsWith(NOT_CHECKABLE), a.reason);
    const alerts = (await mistake.api('GET', '/api/status')).json.alerts;
    assert.ok(alerts.some((x) => x.kind === 'agreement_failing' && x.subject === 'quad'), JSON.stringify(alerts));
    await h.waitForLog(mistake.run, /agreement quad: estimate disagrees, tilt offset [0-9.]+ deg.*; fix: \[mocap\] up = "\+z"/, 5000);
    // `vehicle setup` names the same fix, through the running daemon.
    const setup = h.mocaplink(['vehicle', 'setup', '--config', mistake.config, 'quad', '--timeout', '20']);
    await setup.exited;
    assert.match(setup.stdout, /^ {2}agreement: disagree \(tilt [0-9.]+ deg, yaw -?[0-9.e-]+ deg, position [0-9.e-]+ m, compass -?[0-9.]+ deg\)\n {4}fix: \[mocap\] up = "\+z" \(then tilt [0-9.]+°, heading [0-9.]+°\)\n {12}yaw compared with its compass only /m,
      `${setup.stdout}\n${setup.stderr}`);
    // The fix once, not again in the reason below it.
    assert.equal(setup.stdout.split('up = "+z"').length - 1, 1, setup.stdout);
    console.log(setup.stdout.split('\n').filter((l) => /agreement:|fix:/.test(l)).join('\n'));
    // It refuses nothing new: poses keep flowing.
    const sent = bad.sent.ODOMETRY;
    await h.sleep(500);
    const later = (await mistake.api('GET', '/api/status')).json.vehicles[0].sent.ODOMETRY;
    assert.ok(later > sent, `ODOMETRY ${sent} → ${later}`);
    // The nose: only the compass sees it.
    const turned = await nose.verdict('disagree', 25000,
      (ag) => ag.fix !== null && typeof ag.reason === 'string' && ag.reason.endsWith(NOT_CHECKABLE));
    const n = turned.agreement;
    assert.ok(n.tilt_offset_deg < 5, JSON.stringify(n));
    assert.ok(Math.abs(n.yaw_offset_deg) < 5, JSON.stringify(n));  // mocap against itself
    assert.ok(Math.abs(Math.abs(n.heading_offset_deg) - 90) < 10, JSON.stringify(n));
    assert.equal(n.fix.kind, 'fix', JSON.stringify(n.fix));
    assert.deepEqual(n.fix.lines, ['[[vehicle]] body_forward = "+x"'], JSON.stringify(n.fix));
    assert.ok(n.fix.heading_residual_deg < 10, JSON.stringify(n.fix));
    await h.waitForLog(nose.run, /agreement quad: estimate disagrees, tilt offset [0-9.]+ deg, yaw offset -?[0-9.e-]+ deg, position offset [0-9.e-]+ m, compass offset -?[0-9.]+ deg; fix: \[\[vehicle\]\] body_forward = "\+x"/, 5000);
    // The log's last word on the agreement is the fix the dashboard shows: a line re-judged
    // within a second of the one before is held back and logged once the second has passed, not
    // dropped (core::EventLimiter).
    await h.sleep(1200);
    const lines = nose.run.stderr.split('\n').filter((l) => /agreement quad: /.test(l));
    assert.match(lines[lines.length - 1], /body_forward = "\+x"/, lines.join('\n'));
    // A body defined lying on its side: gravity sees it.
    const side = (await bodyUp.verdict('disagree', 25000, (ag) => ag.fix !== null
      && ag.fix.heading_residual_deg !== null)).agreement;
    assert.ok(Math.abs(side.tilt_offset_deg - 90) < 10, JSON.stringify(side));
    assert.deepEqual(side.fix.lines, ['[[vehicle]] body_up = "+z"'], JSON.stringify(side.fix));
    // PX4 with magnetometer yaw: its own yaw is the heading, the nose mistake is a yaw offset.
    const px4Turned = (await px4Nose.verdict('disagree', 25000, (ag) => ag.fix !== null)).agreement;
    assert.ok(Math.abs(Math.abs(px4Turned.yaw_offset_deg) - 90) < 10, JSON.stringify(px4Turned));
    assert.equal(px4Turned.heading_offset_deg, null, JSON.stringify(px4Turned));
    assert.deepEqual(px4Turned.fix.lines, ['[[vehicle]] body_forward = "+x"'], JSON.stringify(px4Turned.fix));
    assert.ok(px4Turned.reason.endsWith('position not checkable: the vehicle\'s position comes from '
      + 'mocap (EKF2_EV_CTRL = 7)'), px4Turned.reason);
    assert.equal(px4Nose.quad.rawImuAsked, 0);  // never asked of PX4
    assert.deepEqual(px4Turned.checked, ['tilt', 'yaw'], JSON.stringify(px4Turned));
    // PX4 on vision yaw: only its magnetometer (HIGHRES_IMU, asked for) sees the nose.
    const px4Blind = (await px4VisionNose.verdict('disagree', 25000, (ag) => ag.fix !== null
      && ag.fix.heading_residual_deg !== null)).agreement;
    assert.ok(Math.abs(px4Blind.yaw_offset_deg) < 5, JSON.stringify(px4Blind));
    assert.ok(Math.abs(Math.abs(px4Blind.heading_offset_deg) - 90) < 10, JSON.stringify(px4Blind));
    assert.deepEqual(px4Blind.fix.lines, ['[[vehicle]] body_forward = "+x"'], JSON.stringify(px4Blind.fix));
    assert.deepEqual(px4Blind.checked, ['tilt', 'compass'], JSON.stringify(px4Blind));
    assert.ok(px4VisionNose.quad.imuAsked >= 1);
    assert.equal(px4VisionNose.quad.rawImuAsked, 0);
    console.log(`ok: right axes agree (tilt ${ok.agreement.tilt_offset_deg.toFixed(1)}°, compass `
      + `${ok.agreement.heading_offset_deg.toFixed(1)}°); up = "+y" disagrees (tilt `
      + `${a.tilt_offset_deg.toFixed(1)}°) with ${a.fix.text}; body_forward = "+y" disagrees `
      + `(compass ${n.heading_offset_deg.toFixed(1)}°) with ${n.fix.text}`);
  } finally {
    await right.done();
    await mistake.done();
    await nose.done();
    await bodyUp.done();
    await px4Nose.done();
    await px4VisionNose.done();
  }
}

main().catch(h.fail);
