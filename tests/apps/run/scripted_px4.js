// A scripted PX4 1.14 for the end-to-end tests: it answers as PX4's mavlink_parameters.cpp does
// (PARAM_REQUEST_READ by name with the int32's bytes in the float — PARAM_ENCODE_BYTEWISE, which its
// AUTOPILOT_VERSION capabilities announce —, silence for a name it does not have, PARAM_SET with
// the new PARAM_VALUE) and sends a heartbeat every 250 ms. It is left at PX4's defaults for GPS
// flight: vision fusion off (EKF2_EV_CTRL 0), height from the barometer (EKF2_HGT_REF 1).
// `vehicle` is the transport: `vehicle.decoder.parser` emits the packets it receives and
// `vehicle.send(buffer)` sends (harness.UdpVehicle, OnePeerVehicle below, a TCP connection).
'use strict';

const dgram = require('node:dgram');
const { MavLinkProtocolV2, common, minimal, standard } = require('node-mavlink');
const h = require('./harness');

const { ID } = h;
const PARAM_REQUEST_READ = 20;
const PARAM_SET = 23;
const REQUEST_MESSAGE = 512;
const INT32 = 6;
const REAL32 = 9;

/** float whose bytes are the int32 `bits` (PARAM_ENCODE_BYTEWISE) */
const f32 = (bits) => new Float32Array(new Int32Array([bits]).buffer)[0];
const i32 = (float) => new Int32Array(new Float32Array([float]).buffer)[0];

/// PARAM_VALUE `name` = `value` of `type` as PX4 sends it (an INT32's bits in the float).
function paramValue(name, value, type, count, index) {
  const m = new common.ParamValue();
  m.paramId = name;
  m.paramType = type;
  m.paramValue = type === REAL32 ? value : f32(value);
  m.paramCount = count;
  m.paramIndex = index;
  return m;
}

function scriptedPx4(vehicle, sysid) {
  const s = {
    params: new Map([
      ['EKF2_EV_CTRL', [0, INT32]], ['EKF2_HGT_REF', [1, INT32]], ['EKF2_GPS_CTRL', [0, INT32]],
      ['EKF2_MAG_TYPE', [5, INT32]], ['EKF2_EV_DELAY', [0, REAL32]],
      // Read for the agreement's second heading.
      ['SYS_HAS_MAG', [1, INT32]], ['EKF2_MAG_DECL', [0, REAL32]],
    ]),
    reads: [], sets: [], versionRequests: 0, armed: false,
  };
  let seq = 0;
  const send = (m) => vehicle.send(new MavLinkProtocolV2(sysid, 1).serialize(m, seq++ & 255));
  const value = (name) => paramValue(name, ...s.params.get(name), 1000, 42);
  vehicle.decoder.parser.on('data', (packet) => {
    const m = h.decode(packet);
    const id = packet.header.msgid;
    if (id === ID.COMMAND_LONG && m.command === REQUEST_MESSAGE && Math.round(m._param1) === 148) {
      s.versionRequests += 1;
      const v = new standard.AutopilotVersion();
      v.capabilities = 2n | 16n;  // PARAM_FLOAT | PARAM_ENCODE_BYTEWISE, as PX4 1.14 sets them
      v.flightSwVersion = (1 << 24) | (14 << 16) | (3 << 8) | 255;
      send(v);
    } else if (id === PARAM_REQUEST_READ) {
      const name = m.paramId.replace(/\0+$/, '');
      s.reads.push({ name, target: [m.targetSystem, m.targetComponent], index: m.paramIndex });
      if (s.params.has(name)) send(value(name));
    } else if (id === PARAM_SET) {
      const name = m.paramId.replace(/\0+$/, '');
      s.sets.push({ name, raw: m.paramValue, type: m.paramType, target: [m.targetSystem, m.targetComponent] });
      const [, type] = s.params.get(name);
      s.params.set(name, [type === REAL32 ? m.paramValue : i32(m.paramValue), type]);
      send(value(name));
    }
  });
  const heartbeat = new minimal.Heartbeat();
  heartbeat.type = 2;        // quadrotor
  heartbeat.autopilot = 12;  // PX4
  heartbeat.systemStatus = 3;
  heartbeat.mavlinkVersion = 3;
  let beats = 0;
  s.timer = setInterval(() => {
    heartbeat.baseMode = s.armed ? 128 : 0;
    send(heartbeat);
    beats += 1;
    if (beats === 4) {
      const t = new common.StatusText();
      t.severity = 4;  // warning
      t.text = 'Preflight Fail: ekf2 missing data';
      send(t);
    }
  }, 250);
  return s;
}

/// PX4's UDP MAVLink link seen from outside (mavlink_main / mavlink_receiver, 1.14): it reads and
/// handles every datagram that reaches its port, but sends — heartbeats and every answer — only to
/// its partner: the address given at start (`-o PORT`, SITL's onboard link: 127.0.0.1:14540), or
/// else the first address that sent it a datagram since it booted. That is why a second process
/// speaking from another port hears nothing.
class OnePeerVehicle {
  constructor({ partner } = {}) {
    this.packets = [];
    this.heardFrom = [];
    this.partner = partner;  // {address, port}
    this.socket = dgram.createSocket('udp4');
    this.decoder = new h.Decoder((packet, t) => this.packets.push({ packet, t }));
    this.socket.on('message', (msg, rinfo) => {
      this.heardFrom.push(`${rinfo.address}:${rinfo.port}`);
      if (!this.partner) this.partner = { address: rinfo.address, port: rinfo.port };
      this.decoder.write(msg);
    });
  }
  async bind(port = 0) {
    await new Promise((r) => this.socket.bind(port, '127.0.0.1', r));
    this.port = this.socket.address().port;
    return this;
  }
  get peer() { return this.partner; }
  send(buffer) {
    if (this.partner) this.socket.send(buffer, this.partner.port, this.partner.address);
  }
  close() { this.socket.close(); }
  ofId(msgid) { return this.packets.filter((p) => p.packet.header.msgid === msgid); }
}

module.exports = { INT32, REAL32, f32, i32, paramValue, scriptedPx4, OnePeerVehicle, MavLinkProtocolV2, ID };
