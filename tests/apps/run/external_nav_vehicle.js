// The scripted vehicle of the agreement tests (agreement_axes.test.js, agreement_sources.test.js):
// an ArduCopter whose EKF3 takes yaw and position from ExternalNav, or a PX4 on vision, fed back
// mocaplink's own yaw and position and reporting the body's true roll and pitch (and heading, where
// it has a compass), all computed here by hand from the raw z-up, FLU truth, not by mocaplink.
'use strict';

const { MavLinkProtocolV2, common, minimal } = require('node-mavlink');
const h = require('./harness');

const { assert, ID } = h;
const PARAM_REQUEST_READ = 20;
const EXTERNAL_NAV = ['EK3_SRC1_YAW', 'EK3_SRC1_POSXY'];
// A calibrated compass (SITL's copter.parm offsets), no declination set.
const COMPASS = { COMPASS_ENABLE: 1, COMPASS_OFS_X: 5, COMPASS_OFS_Y: 13, COMPASS_OFS_Z: -18,
  COMPASS_DEC: 0 };
const SET_MESSAGE_INTERVAL = 511;
const RAW_IMU = 27;

/// Roll, pitch and yaw (rad) of the NED/FRD attitude of a raw Z-up, FLU quaternion [w, x, y, z].
function trueAttitude([w, x, y, z]) {
  // Rows of R_raw (body → world), then R = diag(1,−1,−1) · R_raw · diag(1,−1,−1).
  const r = [
    [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
    [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
    [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
  ];
  const s = [1, -1, -1];
  const m = r.map((row, i) => row.map((v, j) => s[i] * v * s[j]));
  return {
    roll: Math.atan2(m[2][1], m[2][2]),
    pitch: -Math.asin(Math.max(-1, Math.min(1, m[2][0]))),
    yaw: Math.atan2(m[1][0], m[0][0]),
  };
}

/// The scripted ArduCopter: heartbeat 2 Hz, ATTITUDE and LOCAL_POSITION_NED at 5 Hz unasked,
/// parameter reads answered (EXTERNAL_NAV 6, COMPASS as above, the rest 0), SET_MESSAGE_INTERVAL
/// accepted, and RAW_IMU (its compass's field in milligauss, as ArduPilot fills it) sent at 5 Hz
/// once asked for. `truth()` gives the body's raw q.
/// With `px4`, a PX4 instead (autopilot 12) whose EKF2 fuses vision position and velocity but takes
/// its yaw from the magnetometer (EKF2_EV_CTRL 7, answered bytewise as PX4 does): its ATTITUDE yaw
/// is then the truth's, and it sends no RAW_IMU. With `visionYaw` as well, EKF2_EV_CTRL 15: its yaw
/// is mocap's fed back, and its magnetometer (SYS_HAS_MAG 1) is sent in HIGHRES_IMU once asked for.
/// Either field: Earth's (0.2 G north, 0.4 G down) turned into the body by the truth's attitude.
const EARTH_FIELD_NED = [0.2, 0, 0.4];
const HIGHRES_IMU = 105;
function externalNavVehicle(vehicle, sysid, truth, { px4 = false, visionYaw = false } = {}) {
  const s = { odometry: null, rawImuAsked: 0, imuAsked: 0 };
  let seq = 0;
  const send = (m) => vehicle.send(new MavLinkProtocolV2(sysid, 1).serialize(m, seq++ & 255));
  const bootStart = performance.now() - 60000;  // up for a minute: settled
  vehicle.decoder.parser.on('data', (packet) => {
    const m = h.decode(packet);
    if (packet.header.msgid === ID.ODOMETRY) s.odometry = m;
    if (packet.header.msgid === ID.COMMAND_LONG && m.command === SET_MESSAGE_INTERVAL
        && m.targetSystem === sysid) {
      const a = new common.CommandAck();
      a.command = SET_MESSAGE_INTERVAL;
      a.result = 0;  // ACCEPTED
      a.targetSystem = packet.header.sysid;
      a.targetComponent = packet.header.compid;
      send(a);
      if (Math.round(m._param1) === RAW_IMU) s.rawImuAsked += 1;
      if (Math.round(m._param1) === HIGHRES_IMU) s.imuAsked += 1;
    }
    if (packet.header.msgid === PARAM_REQUEST_READ && m.targetSystem === sysid) {
      const v = new common.ParamValue();
      v.paramId = m.paramId.replace(/\0+$/, '');
      if (px4) {
        const bits = Buffer.alloc(4);
        const values = { EKF2_EV_CTRL: visionYaw ? 15 : 7, SYS_HAS_MAG: 1 };
        bits.writeInt32LE(values[v.paramId] ?? 0);
        v.paramType = 6;  // INT32, its bytes in the float (PX4's bytewise encoding)
        v.paramValue = bits.readFloatLE(0);
      } else if (v.paramId in COMPASS && v.paramId !== 'COMPASS_ENABLE') {
        v.paramType = 9;  // REAL32
        v.paramValue = COMPASS[v.paramId];
      } else {
        v.paramType = 2;  // INT8, the value cast to float as ArduPilot sends it
        v.paramValue = EXTERNAL_NAV.includes(v.paramId) ? 6 : COMPASS[v.paramId] ?? 0;
      }
      v.paramCount = 1;
      v.paramIndex = 65535;
      send(v);
    }
  });
  const heartbeat = new minimal.Heartbeat();
  heartbeat.type = 2;
  heartbeat.autopilot = px4 ? 12 : 3;
  heartbeat.systemStatus = 3;
  heartbeat.mavlinkVersion = 3;
  let n = 0;
  s.timer = setInterval(() => {
    n += 1;
    if (n % 2 === 0) send(heartbeat);
    const o = s.odometry;
    const q = truth();
    if (!o || !q) return;
    const bootMs = Math.round(performance.now() - bootStart);
    const [w, x, y, z] = o.q;
    const { roll, pitch, yaw } = trueAttitude(q);
    // Body field = Rᵀ · B with R = Rz(yaw) · Ry(pitch) · Rx(roll), by hand.
    const [cr, sr, cp, sp, cy, sy] = [Math.cos(roll), Math.sin(roll), Math.cos(pitch),
      Math.sin(pitch), Math.cos(yaw), Math.sin(yaw)];
    const R = [
      [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
      [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
      [-sp, cp * sr, cp * cr],
    ];
    const b = [0, 1, 2].map((j) => R[0][j] * EARTH_FIELD_NED[0] + R[1][j] * EARTH_FIELD_NED[1]
      + R[2][j] * EARTH_FIELD_NED[2]);
    if (px4 && s.imuAsked > 0) {
      const imu = new common.HighresImu();
      imu.timeUsec = BigInt(Math.round((performance.now() - bootStart) * 1000));
      [imu.xmag, imu.ymag, imu.zmag] = b;
      imu.zacc = -9.81;
      imu.fieldsUpdated = 0x1FF;  // accel, gyro and magnetometer of this sample
      send(imu);
    }
    if (s.rawImuAsked > 0 && !px4) {
      const raw = new common.RawImu();
      raw.timeUsec = BigInt(Math.round((performance.now() - bootStart) * 1000));
      [raw.xmag, raw.ymag, raw.zmag] = b.map((gauss) => Math.round(gauss * 1000));  // mG
      raw.zacc = -1000;
      send(raw);
    }
    const a = new common.Attitude();
    a.timeBootMs = bootMs;
    a.roll = roll;
    a.pitch = pitch;
    // ArduPilot and PX4 on vision yaw: mocap's, fed back; PX4 on its magnetometer: the truth.
    a.yaw = px4 && !visionYaw ? yaw : Math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z));
    send(a);
    const p = new common.LocalPositionNed();
    p.timeBootMs = bootMs;
    p.x = o.x;
    p.y = o.y;
    p.z = o.z;
    send(p);
  }, 200);
  return s;
}

/// Polls /api/status until the first vehicle's agreement has verdict `want` and `also(agreement)`
/// holds (a condition besides the verdict), for at most `ms`; returns that vehicle's status.
function verdictPoller(api, run, label) {
  return async (want, ms, also = () => true) => {
    let q;
    const deadline = Date.now() + ms;
    while (Date.now() < deadline) {
      q = (await api('GET', '/api/status')).json.vehicles[0];
      if (q.agreement.verdict === want && also(q.agreement)) return q;
      await h.sleep(100);
    }
    assert.fail(`${label}: no ${want} (with all it needs) in ${ms} ms: `
      + `${JSON.stringify(q.agreement)}\n${run.stderr}`);
  };
}

module.exports = { externalNavVehicle, trueAttitude, verdictPoller };
