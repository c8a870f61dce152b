// Ground stations on a vehicle's link (issue 38; docs/config.md `gcs`), end to end: the pieces the
// gcs_*.test.js files share. A scripted autopilot that records every frame it sends (raw bytes and
// the target it addressed), ground stations that behave as QGroundControl does (HEARTBEAT 1 Hz as
// MAV_TYPE_GCS, PARAM_REQUEST_LIST, COMMAND_LONG arm, MISSION_REQUEST_LIST, one signed frame), the
// three ground-station socket forms (udpin, tcpin, udp), and the exact comparisons: the vehicle must
// receive a ground station's frames byte for byte and in order, and a ground station the vehicle's,
// minus the ones addressed to a system/component never heard on its endpoint.
'use strict';

const dgram = require('node:dgram');
const net = require('node:net');
const path = require('node:path');
const { MavLinkProtocolV2, common, minimal, standard } = require('node-mavlink');
const h = require('./harness');
const { INT32, REAL32, i32, paramValue } = require('./scripted_px4');

const { assert, ID } = h;

const MSG = {
  PARAM_REQUEST_READ: 20, PARAM_REQUEST_LIST: 21, PARAM_VALUE: 22, PARAM_SET: 23,
  MISSION_REQUEST_LIST: 43, MISSION_COUNT: 44, COMMAND_ACK: 77, STATUSTEXT: 253,
  AUTOPILOT_VERSION: 148,
};
const CMD = { ARM_DISARM: 400, REQUEST_MESSAGE: 512, SET_MESSAGE_INTERVAL: 511 };
const MOCAPLINK_COMPID = 197;
const GCS_COMPID = 190;  // MAV_COMP_ID_MISSIONPLANNER, what QGroundControl sends from

/// Every packet `decoder` parses, as {buf (a copy of the raw frame), sysid, compid, msgid, t}.
function recordFrames(parser, into) {
  parser.on('data', (packet) => {
    into.push({ buf: Buffer.from(packet.buffer), sysid: packet.header.sysid,
      compid: packet.header.compid, msgid: packet.header.msgid, packet, t: performance.now() });
  });
}

// --- Vehicle transports: `send(buffer)`, `decoder.parser`, `close()`. -----------------------------

/// A vehicle on UDP (mocaplink's link `udp://127.0.0.1:PORT`): h.UdpVehicle.
async function udpVehicleTransport() {
  const v = await new h.UdpVehicle().bind();
  return { kind: 'udp', transport: v, link: `udp://127.0.0.1:${v.port}`, ready: () => v.peer !== undefined,
    close: () => v.close() };
}

/// A vehicle that is a TCP server (SITL's 5760; mocaplink's link `tcp://127.0.0.1:PORT`).
async function tcpVehicleTransport() {
  const t = { decoder: new h.Decoder(() => {}), socket: null, connections: 0 };
  t.send = (buffer) => { if (t.socket) t.socket.write(buffer); };
  const server = net.createServer((socket) => {
    t.connections += 1;
    t.socket = socket;
    socket.on('data', (d) => t.decoder.write(d));
    socket.on('error', () => {});
  });
  await new Promise((r) => server.listen(0, '127.0.0.1', r));
  return { kind: 'tcp', transport: t, link: `tcp://127.0.0.1:${server.address().port}`,
    ready: () => t.socket !== null,
    close: () => { if (t.socket) t.socket.destroy(); server.close(); } };
}

/// A vehicle on a serial port: a pty pair (pty_relay) whose master side is relayed to UDP here;
/// mocaplink's link is `serial:///dev/pts/N?baud=BAUD`.
async function serialVehicleTransport(baud) {
  const v = await new h.UdpVehicle().bind();
  const relay = h.start([process.env.PTY_RELAY_BIN, String(v.port)]);
  await h.waitFor(() => relay.stdout.includes('\n'), 5000, 'pty_relay');
  const tty = relay.stdout.trim();
  // pty_relay announces its port with an empty datagram: replies can go before mocaplink speaks.
  await h.waitFor(() => v.peer !== undefined, 5000, 'pty_relay datagram');
  return { kind: 'serial', transport: v, link: `serial://${tty}?baud=${baud}`,
    ready: () => v.packets.length > 0,
    close: () => { relay.child.kill('SIGTERM'); v.close(); } };
}

// --- The scripted autopilot. -------------------------------------------------------------------

/// A PX4-like autopilot with system id `sysid`, component 1, on `transport`. It records every frame
/// it sends in `sent` as {buf, msgid, target: null | [system, component]} and every frame it
/// receives in `received`. It answers: PARAM_REQUEST_LIST with every parameter (PARAM_VALUE, no
/// target), PARAM_REQUEST_READ by name, PARAM_SET; COMMAND_LONG with a COMMAND_ACK addressed back to
/// the sender (ARM_DISARM, REQUEST_MESSAGE and SET_MESSAGE_INTERVAL accepted, others
/// UNSUPPORTED), REQUEST_MESSAGE AUTOPILOT_VERSION also with the message; MISSION_REQUEST_LIST with
/// MISSION_COUNT 0 addressed back; a TIMESYNC request with its answer addressed back (as PX4 1.14
/// fills target_system/target_component). HEARTBEAT every 250 ms. `stop()` silences it.
function scriptedAutopilot(transport, sysid) {
  const s = {
    sysid, sent: [], received: [], armed: false, stopped: false,
    params: new Map([
      ['EKF2_EV_CTRL', [0, INT32]], ['EKF2_HGT_REF', [1, INT32]], ['EKF2_GPS_CTRL', [0, INT32]],
      ['EKF2_MAG_TYPE', [5, INT32]], ['EKF2_EV_DELAY', [0, REAL32]],
      // Read for the agreement's second heading.
      ['SYS_HAS_MAG', [1, INT32]], ['EKF2_MAG_DECL', [0, REAL32]],
      ['MAV_SYS_ID', [sysid, INT32]],
      ['COM_ARM_WO_GPS', [1, INT32]],
    ]),
  };
  const protocol = new MavLinkProtocolV2(sysid, 1);
  let seq = 0;
  const send = (m, target = null) => {
    if (s.stopped) return;
    const buf = protocol.serialize(m, seq++ & 255);
    s.sent.push({ buf: Buffer.from(buf), msgid: m.constructor.MSG_ID, target, t: performance.now() });
    transport.send(buf);
  };
  const names = [...s.params.keys()];
  const value = (name) => paramValue(name, ...s.params.get(name), names.length, names.indexOf(name));
  recordFrames(transport.decoder.parser, s.received);
  transport.decoder.parser.on('data', (packet) => {
    const id = packet.header.msgid;
    const from = [packet.header.sysid, packet.header.compid];
    const m = h.decode(packet);
    if (!m) return;
    const forMe = (ts) => ts === 0 || ts === sysid;
    if (id === MSG.PARAM_REQUEST_LIST && forMe(m.targetSystem)) {
      for (const name of names) send(value(name));
    } else if (id === MSG.PARAM_REQUEST_READ && forMe(m.targetSystem)) {
      const name = m.paramId.replace(/\0+$/, '');
      if (s.params.has(name)) send(value(name));
    } else if (id === MSG.PARAM_SET && forMe(m.targetSystem)) {
      const name = m.paramId.replace(/\0+$/, '');
      if (!s.params.has(name)) return;
      const [, type] = s.params.get(name);
      s.params.set(name, [type === REAL32 ? m.paramValue
        : i32(m.paramValue), type]);
      send(value(name));
    } else if (id === ID.COMMAND_LONG && forMe(m.targetSystem)) {
      const accepted = [CMD.ARM_DISARM, CMD.REQUEST_MESSAGE, CMD.SET_MESSAGE_INTERVAL];
      const ack = new common.CommandAck();
      ack.command = m.command;
      ack.result = accepted.includes(m.command) ? 0 : 3;  // ACCEPTED / UNSUPPORTED
      ack.targetSystem = from[0];
      ack.targetComponent = from[1];
      if (m.command === CMD.ARM_DISARM) s.armed = Math.round(m._param1) === 1;
      send(ack, from);
      if (m.command === CMD.REQUEST_MESSAGE && Math.round(m._param1) === MSG.AUTOPILOT_VERSION) {
        const v = new standard.AutopilotVersion();
        v.capabilities = 2n | 16n;  // PARAM_FLOAT | PARAM_ENCODE_BYTEWISE, as PX4 1.14
        v.flightSwVersion = (1 << 24) | (14 << 16) | (3 << 8) | 255;
        send(v);
      }
    } else if (id === MSG.MISSION_REQUEST_LIST && forMe(m.targetSystem)) {
      const c = new common.MissionCount();
      c.count = 0;
      c.targetSystem = from[0];
      c.targetComponent = from[1];
      c.missionType = m.missionType;
      send(c, from);
    } else if (id === ID.TIMESYNC && m.tc1 === 0n) {
      const r = new common.TimeSync();
      r.tc1 = BigInt(Math.round(performance.now() * 1e6));
      r.ts1 = m.ts1;
      r.targetSystem = from[0];
      r.targetComponent = from[1];
      send(r, from);
    }
  });
  const heartbeat = new minimal.Heartbeat();
  heartbeat.type = 2;        // quadrotor
  heartbeat.autopilot = 12;  // PX4
  heartbeat.systemStatus = 3;
  heartbeat.mavlinkVersion = 3;
  s.timer = setInterval(() => {
    heartbeat.baseMode = s.armed ? 128 : 0;
    send(heartbeat);
  }, 250);
  s.stop = () => { s.stopped = true; clearInterval(s.timer); };
  return s;
}

// --- Ground stations. --------------------------------------------------------------------------

/// A ground station's socket for one `gcs` form. `url` is what goes into the vehicle's `gcs` list;
/// `open()` connects (after mocaplink started), `send(buffer)`, frames received in `received`.
/// udpin:  mocaplink listens on a UDP port; the ground station sends to it from its own port.
/// tcpin:  mocaplink serves TCP; the ground station connects.
/// udp:    the ground station listens (QGroundControl's 14550) and answers where mocaplink sent from;
///         it can speak only once mocaplink has sent it something.
async function groundStationSocket(form) {
  const g = { form, received: [], decoder: new h.Decoder(() => {}) };
  recordFrames(g.decoder.parser, g.received);
  if (form === 'udpin') {
    const port = await h.freeUdpPort();
    g.url = `udpin://127.0.0.1:${port}`;
    g.socket = dgram.createSocket({ type: 'udp4', recvBufferSize: 8 << 20 });
    g.socket.on('message', (msg) => g.decoder.write(msg));
    await new Promise((r) => g.socket.bind(0, '127.0.0.1', r));
    g.open = async () => {};
    g.canSend = () => true;
    g.send = (buf) => g.socket.send(buf, port, '127.0.0.1');
    g.close = () => g.socket.close();
  } else if (form === 'tcpin') {
    const port = await h.freeTcpPort();
    g.url = `tcpin://127.0.0.1:${port}`;
    g.open = async () => {
      await h.waitFor(() => new Promise((resolve) => {
        const socket = net.connect(port, '127.0.0.1');
        socket.once('connect', () => { g.socket = socket; resolve(true); });
        socket.once('error', () => resolve(false));
      }), 10000, `connecting to ${g.url}`);
      g.socket.on('data', (d) => g.decoder.write(d));
      g.socket.on('error', () => {});
    };
    g.canSend = () => g.socket !== undefined;
    g.send = (buf) => g.socket.write(buf);
    g.close = () => { if (g.socket) g.socket.destroy(); };
  } else if (form === 'udp') {
    g.socket = dgram.createSocket({ type: 'udp4', recvBufferSize: 8 << 20 });
    g.socket.on('message', (msg, rinfo) => { g.peer = rinfo; g.decoder.write(msg); });
    await new Promise((r) => g.socket.bind(0, '127.0.0.1', r));
    g.url = `udp://127.0.0.1:${g.socket.address().port}`;
    g.open = async () => {
      await h.waitFor(() => g.peer !== undefined, 10000, `a first datagram on ${g.url}`);
    };
    g.canSend = () => g.peer !== undefined;
    g.send = (buf) => g.socket.send(buf, g.peer.port, g.peer.address);
    g.close = () => g.socket.close();
  } else {
    throw new Error(`unknown form ${form}`);
  }
  return g;
}

const SIGNING_KEY = Buffer.from('3f1b0c9e7d6a5b4c3d2e1f00112233445566778899aabbccddeeff0011223344', 'hex');

/// QGroundControl's first seconds with vehicle `target`, as ground station `sysid`/190 on socket
/// `g`: HEARTBEAT (MAV_TYPE_GCS) every second for `beats` beats; after the first, PARAM_REQUEST_LIST,
/// COMMAND_LONG ARM_DISARM(1), MISSION_REQUEST_LIST and one signed HEARTBEAT, 200 ms apart. Every
/// frame sent is kept in `g.sent` (raw bytes, in order). Resolves after the last beat.
async function qgcSession(g, sysid, target, { beats = 4, extra = [] } = {}) {
  g.sysid = sysid;
  g.compid = GCS_COMPID;
  g.sent = [];
  const protocol = new MavLinkProtocolV2(sysid, GCS_COMPID);
  const signer = new MavLinkProtocolV2(sysid, GCS_COMPID, MavLinkProtocolV2.IFLAG_SIGNED);
  let seq = 0;
  const send = (m, { signed = false } = {}) => {
    let buf = (signed ? signer : protocol).serialize(m, seq++ & 255);
    if (signed) buf = signer.sign(buf, 1, SIGNING_KEY);
    g.sent.push({ buf: Buffer.from(buf), msgid: m.constructor.MSG_ID, target: targetOf(m), t: performance.now() });
    g.send(buf);
  };
  const heartbeat = () => {
    const hb = new minimal.Heartbeat();
    hb.type = 6;        // MAV_TYPE_GCS
    hb.autopilot = 8;   // MAV_AUTOPILOT_INVALID
    hb.baseMode = 192;  // as QGroundControl sends
    hb.systemStatus = 4;
    hb.mavlinkVersion = 3;
    return hb;
  };
  const paramList = new common.ParamRequestList();
  paramList.targetSystem = target;
  paramList.targetComponent = 0;
  const arm = new common.CommandLong();
  arm.command = CMD.ARM_DISARM;
  arm._param1 = 1;
  arm.targetSystem = target;
  arm.targetComponent = 1;
  const missions = new common.MissionRequestList();
  missions.targetSystem = target;
  missions.targetComponent = 1;
  missions.missionType = 0;
  const steps = [
    () => send(paramList), () => send(arm), () => send(missions),
    () => send(heartbeat(), { signed: true }), ...extra.map((m) => () => send(m)),
  ];
  g.start = performance.now();
  for (let beat = 0; beat < beats; beat += 1) {
    send(heartbeat());
    if (beat === 0) {
      for (const step of steps) {
        await h.sleep(200);
        step();
      }
      await h.sleep(1000 - 200 * steps.length);
    } else {
      await h.sleep(1000);
    }
  }
}

/// The [system, component] a message (node-mavlink instance) is addressed to, or null.
function targetOf(m) {
  return 'targetSystem' in m ? [m.targetSystem, 'targetComponent' in m ? m.targetComponent : 0] : null;
}

/// Whether a vehicle frame addressed to `target` belongs to ground station `g` (mavlink-router's
/// rule: no target or system 0 → everyone; else the system, and the component unless it is 0).
function forGroundStation(target, g) {
  if (target === null || target[0] === 0) return true;
  return target[0] === g.sysid && (target[1] === 0 || target[1] === g.compid);
}

const hex = (b) => b.toString('hex');
const describe = (f) => `msgid ${f.msgid}${f.target ? ` to ${f.target.join('/')}` : ''} ${hex(f.buf)}`;

/// The ground station's frames for this vehicle arrived at it exactly: the same bytes, in order,
/// none more. A frame is for the vehicle when it has no target, targets system 0 or the vehicle's.
function assertVehicleGotExactly(vehicle, g, what) {
  const got = vehicle.received.filter((f) => f.sysid === g.sysid && f.compid === g.compid);
  const want = g.sent.filter((f) => f.target === null || f.target[0] === 0 || f.target[0] === vehicle.sysid);
  let firstDiff = want.findIndex((f, i) => !got[i] || !got[i].buf.equals(f.buf));
  if (firstDiff === -1 && got.length !== want.length) firstDiff = want.length;
  assert.ok(firstDiff === -1,
    `${what}: the vehicle received ${got.length} frames from ${g.sysid}/${g.compid}, it sent ` +
    `${want.length}; first difference at ${firstDiff}:\n  sent     ${want[firstDiff] ? describe(want[firstDiff]) : '-'}` +
    `\n  received ${got[firstDiff] ? hex(got[firstDiff].buf) : '-'}`);
}

/// The ground station received exactly the vehicle's frames meant for it, byte for byte, in order,
/// from some point on (before its endpoint knew it, nothing could reach it) to the end: a suffix of
/// the expected list, with nothing else (no frame of mocaplink's own, none addressed elsewhere).
function assertGroundStationGotExactly(vehicle, g, what, { fromSystem = vehicle.sysid } = {}) {
  const got = g.received.filter((f) => f.sysid === fromSystem);
  const others = g.received.filter((f) => f.sysid !== fromSystem && f.sysid !== undefined);
  const want = vehicle.sent.filter((f) => forGroundStation(f.target, g));
  const tail = want.slice(Math.max(0, want.length - got.length));
  let firstDiff = got.findIndex((f, i) => !tail[i] || !tail[i].buf.equals(f.buf));
  if (firstDiff === -1 && got.length > want.length) firstDiff = want.length;
  assert.ok(got.length > 0, `${what}: the ground station received nothing from system ${fromSystem}`);
  assert.ok(firstDiff === -1,
    `${what}: the ground station's ${got.length} frames from system ${fromSystem} are not the last ` +
    `${got.length} of the ${want.length} the vehicle sent for it; first difference at ${firstDiff}:` +
    `\n  expected ${tail[firstDiff] ? describe(tail[firstDiff]) : '-'}` +
    `\n  received ${got[firstDiff] ? `msgid ${got[firstDiff].msgid} ${hex(got[firstDiff].buf)}` : '-'}` +
    `\n  (the vehicle's frames it must not get: ${vehicle.sent.filter((f) => !forGroundStation(f.target, g))
      .filter((f) => got.some((x) => x.buf.equals(f.buf))).map(describe).slice(0, 3).join('; ') || 'none of them arrived'})`);
  return { got, others, want, skipped: want.length - got.length };
}

/// Test 1 of issue 38 for one vehicle transport: one PX4-like vehicle (system 1) on `makeVehicle()`'s
/// link with three ground stations at once, one per form — QGroundControl on udpin (255/190), a
/// second on tcpin (254/190), a listening one on udp (253/190) —, each playing QGroundControl's
/// first seconds. Checked: bytes both ways (exact, in order), mocaplink's own traffic still reaching
/// the vehicle and the answers to it staying with it, /api/status's `gcs` and `link_share`, the log.
async function forwardingMatrix(makeVehicle, label) {
  const dir = h.tempDir(`gcs-${label.replace(/\W+/g, '-')}`);
  const v = await makeVehicle();
  const gcs = [];
  for (const [form, sysid] of [['udpin', 255], ['tcpin', 254], ['udp', 253]]) {
    const g = await groundStationSocket(form);
    g.sysid = sysid;
    gcs.push(g);
  }
  const config = h.writeConfig(path.join(dir, 'run.toml'), 'sim://?bodies=1&rate_hz=100', [
    { name: 'quad', body: 'Body1', link: v.link, system_id: 1, profile: 'px4', rate_hz: 30,
      gcs: gcs.map((g) => g.url) },
  ]);
  const run = h.mocaplink(['run', '--config', config]);
  let autopilot;
  try {
    const [, port] = await h.waitForLog(run, /dashboard: http:\/\/127\.0\.0\.1:(\d+)\//);
    const api = h.dashboardApi(port);
    const quad = async () => (await api('GET', '/api/vehicles/quad')).json;
    await h.waitFor(v.ready, 10000, `${label}: mocaplink reaches the vehicle\n${run.stderr}`);
    autopilot = scriptedAutopilot(v.transport, 1);
    // mocaplink's set-up list read first (its parameter reads, by name), so that they cannot be
    // answered by the ground stations' parameter lists instead.
    await h.waitFor(async () => ['ready', 'blocked'].includes((await quad()).setup.state), 15000,
      `${label}: mocaplink reads the vehicle's set-up list\n${run.stderr}`);
    await Promise.all(gcs.map((g) => g.open()));

    // The three sessions at once; the endpoints' peers in the middle of them.
    const sessions = gcs.map((g) => qgcSession(g, g.sysid, 1));
    await h.sleep(2500);
    const during = await quad();
    await Promise.all(sessions);
    const sessionEnd = performance.now();
    for (const g of gcs) {
      await h.waitFor(() => {
        const mine = (msgid) => g.received.filter((f) => f.msgid === msgid && f.t > g.start);
        return mine(MSG.COMMAND_ACK).length > 0 && mine(MSG.MISSION_COUNT).length > 0 &&
          mine(MSG.PARAM_VALUE).length >= autopilot.params.size;
      }, 5000, `${label}: ${g.url} gets the answers to its arm command, mission and parameter lists ` +
        `(received ${g.received.map((f) => f.msgid).join(',')})`);
    }
    autopilot.stop();
    await h.sleep(600);  // what is on its way arrives
    const after = await quad();
    await h.stop(run);

    // Bytes, both ways, for each ground station.
    for (const g of gcs) {
      const what = `${label}, ${g.url} (${g.sysid}/190)`;
      assertVehicleGotExactly(autopilot, g, what);
      const { got, skipped } = assertGroundStationGotExactly(autopilot, g, what);
      assert.deepEqual(g.received.filter((f) => f.sysid !== 1 || f.compid !== 1).map((f) => `${f.sysid}/${f.compid} msgid ${f.msgid}`),
        [], `${what}: frames that are not the vehicle's (mocaplink's own, another ground station's)`);
      const from = (msgid) => got.filter((f) => f.msgid === msgid).map((f) => h.decode(f.packet));
      const acks = from(MSG.COMMAND_ACK);
      assert.deepEqual(acks.map((a) => [a.command, a.result, a.targetSystem, a.targetComponent]),
        [[CMD.ARM_DISARM, 0, g.sysid, GCS_COMPID]], `${what}: the COMMAND_ACKs it received`);
      assert.deepEqual(from(MSG.MISSION_COUNT).map((c) => [c.count, c.targetSystem, c.targetComponent]),
        [[0, g.sysid, GCS_COMPID]], `${what}: MISSION_COUNT`);
      const params = new Set(from(MSG.PARAM_VALUE).map((p) => p.paramId.replace(/\0+$/, '')));
      for (const name of autopilot.params.keys()) assert.ok(params.has(name), `${what}: PARAM_VALUE ${name} missing`);
      // Answers to mocaplink (1/197) the vehicle sent while this ground station was listening:
      // there were some, and none reached it (the exact comparison above says so too).
      const firstHeard = g.received[0].t;
      const toMocaplink = autopilot.sent.filter((f) => f.target && f.target[0] === 1 &&
        f.target[1] === MOCAPLINK_COMPID && f.t >= firstHeard);
      assert.ok(toMocaplink.length > 0, `${what}: the vehicle answered mocaplink nothing while the ground station listened`);
      assert.ok(!g.received.some((r) => toMocaplink.some((f) => f.buf.equals(r.buf))), `${what}: an answer to mocaplink reached it`);
      if (g.form === 'udp') {
        // Listening before mocaplink started: it has had everything meant for it since.
        assert.equal(skipped, 0, `${what}: frames the vehicle sent before it was reached`);
        assert.ok(autopilot.sent.some((f) => f.msgid === MSG.COMMAND_ACK && f.target[1] === MOCAPLINK_COMPID),
          `${what}: the vehicle never acknowledged a command of mocaplink's`);
      }
    }

    // mocaplink's own traffic still reaches the vehicle, during the sessions as before them.
    const own = (msgid, from = 0, to = Infinity) => autopilot.received.filter((f) => f.sysid === 1 &&
      f.compid === MOCAPLINK_COMPID && f.msgid === msgid && f.t >= from && f.t <= to);
    const start = Math.min(...gcs.map((g) => g.start));
    const odometry = own(ID.ODOMETRY, start, sessionEnd).length;
    const seconds = (sessionEnd - start) / 1000;
    assert.ok(odometry >= 0.8 * 30 * seconds, `${label}: ${odometry} ODOMETRY in the ${seconds.toFixed(1)} s of the sessions (30 Hz)`);
    assert.ok(own(ID.HEARTBEAT, start, sessionEnd).length >= Math.floor(seconds) - 1, `${label}: mocaplink's HEARTBEAT`);
    assert.ok(own(ID.TIMESYNC).length > 0, `${label}: mocaplink's TIMESYNC`);
    const ownIds = {};
    for (const f of autopilot.received) if (f.compid === MOCAPLINK_COMPID) ownIds[f.msgid] = (ownIds[f.msgid] || 0) + 1;
    assert.ok(own(MSG.PARAM_REQUEST_READ).length > 0,
      `${label}: mocaplink's parameter reads (its frames by message id: ${JSON.stringify(ownIds)})`);
    assert.ok(autopilot.received.every((f) => (f.sysid === 1 && f.compid === MOCAPLINK_COMPID) ||
      gcs.some((g) => g.sysid === f.sysid && g.compid === f.compid)), `${label}: a frame from nobody`);

    // /api/status (the vehicle's view): one entry per endpoint, counted.
    assert.deepEqual(after.gcs.map((e) => e.url), gcs.map((g) => g.url), `${label}: gcs urls`);
    for (const [i, g] of gcs.entries()) {
      const e = after.gcs[i];
      const what = `${label}, ${g.url}: /api/vehicles/quad gcs[${i}] ${JSON.stringify(e)}`;
      assert.equal(during.gcs[i].peers, 1, `${what}: peers while it beats (${JSON.stringify(during.gcs[i])})`);
      assert.equal(typeof e.state, 'string', what);
      assert.equal(e.frames_from_gcs, g.sent.length, `${what}: frames_from_gcs (it sent ${g.sent.length})`);
      // Sent to it: what it received. What could not be sent before it connected (udpin: no
      // address to answer yet; tcpin: no connection) is counted `dropped`; none once connected.
      const got = g.received.length;
      assert.equal(e.frames_to_gcs, got, `${what}: frames_to_gcs (it received ${got})`);
      assert.equal(e.dropped, during.gcs[i].dropped, `${what}: dropped while connected`);
      if (g.form === 'udp') assert.equal(e.dropped, 0, `${what}: dropped (it listened from the start)`);
      assert.equal(e.no_route, 0, what);
      assert.equal(e.bad_frames, 0, what);
      assert.match(run.stderr, new RegExp(`ground station ${g.sysid}/190 on ${g.url.replace(/[.:/]/g, '\\$&')} connected`),
        `${label}: log of ${g.url}`);
    }
    const share = after.link_share;
    const forwarded = gcs.reduce((n, g) => n + g.sent.length, 0);
    if (v.kind === 'serial') assert.ok(typeof share.capacity_bytes_per_s === 'number' && share.capacity_bytes_per_s > 0, JSON.stringify(share));
    else assert.equal(share.capacity_bytes_per_s, null, JSON.stringify(share));
    assert.equal(share.forwarded, forwarded, `${label}: link_share.forwarded (the ground stations sent ${forwarded}) ${JSON.stringify(share)}`);
    assert.equal(share.forwarded_dropped, 0, JSON.stringify(share));
    for (const key of ['own_bytes_per_s', 'forwarded_bytes_per_s', 'queued_bytes']) assert.equal(typeof share[key], 'number', `${key}: ${JSON.stringify(share)}`);
    return { gcs, autopilot, odometry, seconds, after };
  } finally {
    if (autopilot) autopilot.stop();
    if (run.child.exitCode === null) run.child.kill('SIGTERM');
    for (const g of gcs) g.close();
    v.close();
  }
}

/// The body of gcs_{udp,tcp,serial}_vehicle.test.js: the matrix on one transport, a summary line.
function runMatrix(makeVehicle, label) {
  forwardingMatrix(makeVehicle, label).then((r) => {
    console.log(`ok: ${label}, ${r.gcs.map((g) => `${g.url} ${g.sent.length} sent/${g.received.length} received`).join('; ')}; ` +
      `${r.odometry} ODOMETRY in ${r.seconds.toFixed(1)} s`);
    console.log(JSON.stringify({ gcs: r.after.gcs, link_share: r.after.link_share }));
  }).catch(h.fail);
}

module.exports = {
  forwardingMatrix, runMatrix,
  CMD, GCS_COMPID, MOCAPLINK_COMPID, MSG, SIGNING_KEY, assertGroundStationGotExactly,
  assertVehicleGotExactly, forGroundStation, groundStationSocket, qgcSession,
  scriptedAutopilot, serialVehicleTransport, tcpVehicleTransport, udpVehicleTransport,
};
