// The agreement check against gravity and a compass (issue 48) from each of the five network
// sources' axis conventions: one recording written here (Body1 hovering level, nose turned 30°
// from mocap +x towards +y, in a z-up world whose +x is north) served by `mocaplink serve
// --protocol vicon|qtm|natnet|vrpn|vicon-udp --from replay:FILE`, read by the real daemon, and a
// scripted ArduCopter whose EKF3 takes yaw and position from ExternalNav (EK3_SRC1_YAW = 6,
// EK3_SRC1_POSXY = 6) with a calibrated compass (COMPASS_ENABLE = 1, offsets not 0), so that it
// sends RAW_IMU (its compass's field) once mocaplink asks for it, as in agreement_axes.test.js.
//
// The vehicle's truth is the recording's pose, turned into NED/FRD here by hand (trueAttitude),
// not by mocaplink: its IMU's roll and pitch (0, 0) and its compass heading (−30°: a yaw of +30°
// about z-up is 30° west of north) are physical, whatever convention a protocol streams them in.
// Per protocol, what reaches mocaplink (each checked below against `station.bodies[].q_wxyz` of
// /api/status, the raw quaternion before any mapping, so that the convention is the one stated):
//   vicon      DataStream: the subject's root segment, translation in mm and rotation matrix in
//              Tracker's world, which is always Z-up (the emulator passes the recording as is).
//   qtm        RT 6D: mm and the 3×3 matrix in QTM's global frame, Z-up (QTM's default L-frame).
//   vicon-udp  Tracker's UDP objects: mm and Euler XYZ (R = Rx·Ry·Rz) of the same Z-up pose.
//   vrpn       Pos_Quat: m and quaternion (x, y, z, w) in the server's world, here Z-up (Vicon
//              Tracker's VRPN output).
//   natnet     Motive with its default Up Axis Y: the emulator turns world and body alike,
//              (x, y, z) → (x, z, −y), q' = Rx(−90°)·q·Rx(90°), as Motive streams a rigid body
//              created level (its local axes aligned with Motive's at creation, so its local +y
//              is up): Body1's q' is 30° about +y. With `up = "+y"`, `north = "+x"`: N = x',
//              E = z', D = −y', i.e. (x, −y, −z) of the recording, the same NED as the others;
//              with `body_up = "+y"`: F = x', D = −y', R = D × F = z', the body's FRD likewise.
// So the right set-up is `up = "+z"` (the defaults) for the four Z-up ones, and `up = "+y"` with
// `body_up = "+y"` for Motive. Per source, each in its own `mocaplink run`:
//   right  → `agree` on tilt and compass, no fix, the reason naming yaw and position as mocap's.
//   up     the source's typical up mistake: `up = "+y"` on a Z-up source (the OptiTrack habit),
//          `up = "+z"` on Motive (the Vicon habit) → tilt offset near 90°, `disagree`, the fix
//          `[mocap] up = …` alone (with the nose 30° off the mocap axes, no body axis lies along
//          the wrong up, so no `body_up` change fits instead: the fix is unique).
//   nose   a rigid body created with its left side as the nose: `body_forward = "+y"` (FLU), on
//          Motive `body_forward = "-z"` (its body is x forward, y up, z right) → tilt agrees, the
//          compass is 90° off (compass − mocap = −30° − (−120°)), `disagree`, the fix
//          `[[vehicle]] body_forward = "+x"`, and beside it `[mocap] north = "+y"` (on Motive
//          `"-z"`: the axis the nose points along), an arena whose north is turned instead: no
//          pose at rest tells the two apart.
// And two more for Motive, the set-ups a user is led to:
//   docs   `up = "+y"` alone (what docs/sources.md and the natnet:// warning ask for) → tilt near
//          90° (the body's +z is horizontal), the fix `[[vehicle]] body_up = "+y"`.
//   vicon-config  a Vicon configuration copied (`up = "+z"`, `body_up` default) → tilt 30° (mocap
//          takes the body's +z, level in Motive's world, for up; it lies 30° from Motive's +z, by
//          the yaw), the fix `[mocap] up = "+y"` and `[[vehicle]] body_up = "+y"`.
// The reason is checked whole once RAW_IMU has arrived (the fix is named again with the heading).
// Sessions run in three batches (vicon and qtm, natnet, vrpn and vicon-udp) on a 2-core machine.
'use strict';

const fs = require('node:fs');
const path = require('node:path');
const h = require('./harness');
const { externalNavVehicle, trueAttitude, verdictPoller } = require('./external_nav_vehicle');

const { assert, ID } = h;
// harness.js adds an exit listener per process started; this test starts about 25.
process.setMaxListeners(40);

const DEG = Math.PI / 180;

// ---- The recording: the scene's truth ----

const RATE_HZ = 100;
const SECONDS = 120;  // longer than any batch: the emulators serve it from their start
const YAW_RAD = 30 * DEG;
/// Body1's raw pose as recorded (z-up world, x north; FLU body): level, turned +30° about +z.
const Q_RECORDED = [Math.cos(YAW_RAD / 2), 0, 0, Math.sin(YAW_RAD / 2)];
const P_RECORDED = [1, 2, 0.5];

/// Writes the recording (docs/cli.md "The recording format"). The position wobbles by 0.2 mm
/// (never bit-identical, so vicon-udp's frozen-object check stays at its default); the attitude
/// is exact.
function writeRecording(file) {
  const lines = [`# mocaplink recording 1; source=agreement-sources; rate_hz=${RATE_HZ}`,
    'time_s,frame,body,tracked,x_m,y_m,z_m,qw,qx,qy,qz'];
  for (let i = 0; i < SECONDS * RATE_HZ; i += 1) {
    const p = P_RECORDED.map((v, k) => v + 0.0002 * Math.sin(0.7 * i + k));
    lines.push([(i / RATE_HZ).toFixed(6), i + 1, 'Body1', 1, ...p.map((v) => v.toFixed(6)),
      ...Q_RECORDED.map((v) => v.toFixed(9))].join(','));
  }
  fs.writeFileSync(file, `${lines.join('\n')}\n`);
}

// The vehicle's roll, pitch and compass heading: the recorded pose in NED/FRD, by hand.
const TRUTH = trueAttitude(Q_RECORDED);
// Motive's raw quaternion of the same pose: Rx(−90°)·Rz(30°)·Rx(90°) = 30° about +y.
const Q_MOTIVE = [Math.cos(YAW_RAD / 2), 0, Math.sin(YAW_RAD / 2), 0];

// ---- The emulators ----

/// `mocaplink serve --protocol P --from replay:FILE ARGS...`, once it prints where it serves.
async function serve(recording, protocol, args) {
  const server = h.mocaplink(['serve', '--protocol', protocol, '--from', `replay:${recording}`,
    '--rate', String(RATE_HZ), ...args]);
  const re = new RegExp(`serving ${protocol} on [^:]+:(\\d+)|serving ${protocol} to `);
  await h.waitFor(() => re.test(server.stdout), 15000, `serve ${protocol} to start\n${server.stderr}`);
  const m = server.stdout.match(/serving \S+ on [^:]+:(\d+)/);
  return { server, port: m ? m[1] : null };
}

/// A TCP-served protocol: one emulator for every session of its batch (each its own client).
async function sharedSource(recording, protocol, url, args = []) {
  const { server, port } = await serve(recording, protocol, ['--listen', '127.0.0.1:0', ...args]);
  return {
    protocol,
    server,
    url: url(port),
    stop: async () => { await h.stop(server); },
  };
}

// ---- A session: one `mocaplink run` with one vehicle ----

async function session(dir, label, source, mocapKeys, vehicleKeys = {}) {
  const link = await new h.UdpVehicle().bind();
  // vicon-udp: the emulator sends to the port `run` binds, so one emulator per session.
  const url = source.protocol === 'vicon-udp'
    ? `vicon-udp://127.0.0.1:${await h.freeUdpPort()}` : source.url;
  const config = h.writeConfig(path.join(dir, `${label}.toml`), url, [{ name: 'quad', body: 'Body1',
    link: `udp://127.0.0.1:${link.port}`, system_id: 1, profile: 'ardupilot', rate_hz: 30,
    ...vehicleKeys }], Object.entries(mocapKeys).map(([k, v]) => `${k} = "${v}"`).join('\n'));
  const run = h.mocaplink(['run', '--config', config],
    { env: { MOCAPLINK_STATE_DIR: path.join(dir, `${label}-state`) } });
  const [, port] = await h.waitForLog(run, /dashboard: http:\/\/127\.0\.0\.1:(\d+)\//, 15000);
  let own = null;
  if (source.protocol === 'vicon-udp') {
    await h.waitForLog(run, /listening on UDP port/, 15000);  // bound: nothing sent is lost
    ({ server: own } = await serve(source.recording, 'vicon-udp',
      ['--to', url.replace('vicon-udp://', '')]));
  }
  const api = h.dashboardApi(port);
  await h.waitFor(() => link.peer !== undefined, 15000, `${label}: first datagrams\n${run.stderr}`);
  const quad = externalNavVehicle(link, 1, () => Q_RECORDED);
  const done = async () => {
    clearInterval(quad.timer);
    await h.stop(run);
    if (own) await h.stop(own);
    link.close();
  };
  // The raw quaternion (station.bodies[].q_wxyz) once Body1 is tracked.
  const raw = async () => {
    let body;
    const deadline = Date.now() + 20000;
    while (Date.now() < deadline) {
      body = (await api('GET', '/api/status')).json.station.bodies.find((b) => b.name === 'Body1');
      if (body && body.q_wxyz) return body.q_wxyz;
      await h.sleep(100);
    }
    assert.fail(`${label}: Body1 never tracked: ${JSON.stringify(body)}\n${run.stderr}`);
  };
  const verdict = verdictPoller(api, run, label);
  return { label, run, api, raw, verdict, done, quad };
}

const NOT_CHECKABLE = 'yaw compared with its compass only (its compass in RAW_IMU: '
  + "COMPASS_ENABLE = 1, calibrated), 45° allowed: the vehicle's yaw comes from mocap (EK3_SRC1_YAW = 6); position "
  + "not checkable: the vehicle's position comes from mocap (EK3_SRC1_POSXY = 6)";
const TURNED = "; or, if it is the arena's north that is turned (no pose at rest tells the two "
  + 'apart): ';

/// The fix's sentence with the heading (axis_fix.cpp's wording; the pose is exact, so 0.0°).
const fixText = (lines, alternative) => `fix: ${lines.join(', ')} (then tilt 0.0°, heading 0.0°)`
  + (alternative ? `${TURNED}${alternative.join(', ')}` : '');

/// Equal up to sign (q and −q are one rotation), within `tol`.
function sameRotation(a, b, tol) {
  const d = (s) => Math.max(...a.map((v, i) => Math.abs(v - s * b[i])));
  return Math.min(d(1), d(-1)) < tol;
}

// ---- The cases ----

/// Each case: `want` is what a user needs to read; `check` the offsets that prove why.
function cases(zUp) {
  const upRight = zUp ? { up: '+z' } : { up: '+y', body_up: '+y' };
  return [
    { name: 'right', mocap: upRight, want: 'agree' },
    {
      name: 'up',
      mocap: zUp ? { up: '+y' } : { up: '+z', body_up: '+y' },
      want: 'disagree',
      lines: [`[mocap] up = "${upRight.up}"`],
      tilt: 90,
    },
    {
      name: 'nose',
      mocap: upRight,
      vehicle: { body_forward: zUp ? '+y' : '-z' },
      want: 'disagree',
      lines: ['[[vehicle]] body_forward = "+x"'],
      alternative: [`[mocap] north = "${zUp ? '+y' : '-z'}"`],
      tilt: 0,
      heading: 90,
    },
    ...(zUp ? [] : [
      {
        name: 'docs',
        mocap: { up: '+y' },
        want: 'disagree',
        lines: ['[[vehicle]] body_up = "+y"'],
        tilt: 90,
      },
      {
        name: 'vicon-config',
        mocap: { up: '+z' },
        want: 'disagree',
        lines: ['[mocap] up = "+y"', '[[vehicle]] body_up = "+y"'],
        tilt: 30,
      },
    ]),
  ];
}

/// Runs one case on its session; resolves to a line for the report.
async function check(s, c, wire) {
  const q = await s.raw();
  assert.ok(sameRotation(q, wire, 2e-3), `${s.label}: raw q ${JSON.stringify(q)}, expected `
    + `${JSON.stringify(wire)} (the convention stated at the top)`);
  if (c.want === 'agree') {
    const ok = (await s.verdict('agree', 30000, (ag) => ag.checked.includes('compass'))).agreement;
    assert.deepEqual(ok.checked, ['tilt', 'compass'], `${s.label}: ${JSON.stringify(ok)}`);
    assert.equal(ok.fix, null, `${s.label}: ${JSON.stringify(ok)}`);
    assert.equal(ok.reason, NOT_CHECKABLE, `${s.label}: ${JSON.stringify(ok)}`);
    assert.ok(ok.tilt_offset_deg < 5, `${s.label}: ${JSON.stringify(ok)}`);
    assert.ok(Math.abs(ok.heading_offset_deg) < 10, `${s.label}: ${JSON.stringify(ok)}`);
    assert.ok(s.quad.rawImuAsked >= 1, `${s.label}: RAW_IMU never asked for`);
    return `${s.label}: agree (tilt ${ok.tilt_offset_deg.toFixed(1)}°, compass `
      + `${ok.heading_offset_deg.toFixed(1)}°)`;
  }
  // A disagreement by tilt is named before RAW_IMU arrives, and again with its heading.
  const bad = (await s.verdict('disagree', 30000, (ag) => ag.fix !== null
    && ag.fix.heading_residual_deg !== null && typeof ag.reason === 'string'
    && ag.reason.endsWith(NOT_CHECKABLE))).agreement;
  const said = JSON.stringify(bad);
  assert.ok(Math.abs(bad.tilt_offset_deg - c.tilt) < 5, `${s.label}: tilt, expected ${c.tilt}°: ${said}`);
  assert.ok(Math.abs(bad.yaw_offset_deg) < 5, `${s.label}: ${said}`);  // mocap against itself
  if (c.heading !== undefined) {
    assert.ok(Math.abs(bad.heading_offset_deg - c.heading) < 10,
      `${s.label}: compass, expected ${c.heading}°: ${said}`);
  }
  assert.deepEqual(bad.checked, ['tilt', 'compass'], `${s.label}: ${said}`);
  assert.equal(bad.fix.kind, 'fix', `${s.label}: ${said}`);
  assert.deepEqual(bad.fix.lines, c.lines, `${s.label}: fix: ${said}`);
  assert.deepEqual(bad.fix.alternative_lines, c.alternative ?? [], `${s.label}: alternative: ${said}`);
  assert.equal(bad.reason, `${fixText(c.lines, c.alternative)}; ${NOT_CHECKABLE}`, `${s.label}: reason`);
  const logged = c.lines.join(', ').replace(/[[\]+"]/g, '\\$&');
  await h.waitForLog(s.run, new RegExp(`agreement quad: .*fix: ${logged} \\(then tilt`), 5000);
  return `${s.label}: disagree (tilt ${bad.tilt_offset_deg.toFixed(1)}°, compass `
    + `${bad.heading_offset_deg?.toFixed(1)}°) with ${bad.fix.text}`;
}

/// Starts every case of `sources` at once, checks them all, stops them; failures collected.
async function batch(dir, sources, failures, report) {
  const sessions = [];
  try {
    await Promise.all(sources.flatMap((src) => cases(src.zUp).map(async (c) => {
      const s = await session(dir, `${src.protocol}-${c.name}`, src, c.mocap, c.vehicle);
      sessions.push(s);
      s.case = c;
      s.wire = src.zUp ? Q_RECORDED : Q_MOTIVE;
    })));
    const results = await Promise.allSettled(sessions.map((s) => check(s, s.case, s.wire)));
    results.forEach((r) => (r.status === 'fulfilled' ? report.push(r.value) : failures.push(r.reason)));
  } finally {
    for (const s of sessions) await s.done();
    for (const src of sources) if (src.stop) await src.stop();
  }
}

async function main() {
  const t0 = Date.now();
  assert.ok(Math.abs(TRUTH.roll) < 1e-12 && Math.abs(TRUTH.pitch) < 1e-12
    && Math.abs(TRUTH.yaw + YAW_RAD) < 1e-12, JSON.stringify(TRUTH));  // level, heading −30°
  const dir = h.tempDir('agreement-sources');
  const recording = path.join(dir, 'body1.csv');
  writeRecording(recording);
  const failures = [];
  const report = [];

  const vicon = { ...await sharedSource(recording, 'vicon', (p) => `vicon://127.0.0.1:${p}`), zUp: true };
  const qtm = { ...await sharedSource(recording, 'qtm', (p) => `qtm://127.0.0.1:${p}`), zUp: true };
  await batch(dir, [vicon, qtm], failures, report);

  // Unicast (Motive's other transport): each client its own stream, no multicast group shared
  // with other tests on this host.
  const natnet = {
    ...await sharedSource(recording, 'natnet', (p) => `natnet://127.0.0.1:${p}?local=127.0.0.1`,
      ['--set', 'transport=unicast', '--set', `data_port=${await h.freeUdpPort()}`]),
    zUp: false,
  };
  await batch(dir, [natnet], failures, report);

  const vrpn = { ...await sharedSource(recording, 'vrpn', (p) => `vrpn://Body1@127.0.0.1:${p}`), zUp: true };
  const viconUdp = { protocol: 'vicon-udp', recording, zUp: true };
  await batch(dir, [vrpn, viconUdp], failures, report);

  console.log(report.join('\n'));
  if (failures.length > 0) {
    throw new Error(`${failures.length} case(s) failed:\n${failures.map((e) => e.message).join('\n\n')}`);
  }
  console.log(`ok: ${report.length} cases from vicon, qtm, natnet, vrpn and vicon-udp in `
    + `${((Date.now() - t0) / 1000).toFixed(1)} s`);
}

main().catch(h.fail);
