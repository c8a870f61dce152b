// Ground-station endpoints given on the command line (`--vehicle ...,gcs=udpin://...+tcpin://...`,
// issue 38) and what a lab's ground stations do to them:
//   - QGroundControl restarted: the same 255/190 speaks to the udpin endpoint from a new port; the
//     vehicle's frames go to the new address only ("answer where it last spoke from");
//   - a frame damaged on the way (bad CRC) is counted `bad_frames` and not forwarded; a MAVLink 1
//     frame and two frames in one datagram are forwarded as they are;
//   - a TCP ground station (254/190) disconnects and connects again: its frames pass on both
//     connections and the vehicle's reach the second one.
// Throughout, the vehicle receives exactly the valid frames the ground stations sent, in order.
'use strict';

const dgram = require('node:dgram');
const net = require('node:net');
const { MavLinkProtocolV1, MavLinkProtocolV2, minimal } = require('node-mavlink');
const h = require('./harness');
const g38 = require('./gcs_e2e');

const { assert } = h;

/// A ground station `sysid`/190 whose frames may leave from different sockets; `sent` keeps them all.
function station(sysid) {
  const protocol = new MavLinkProtocolV2(sysid, g38.GCS_COMPID);
  let seq = 0;
  const s = { sysid, compid: g38.GCS_COMPID, sent: [] };
  const v1 = new MavLinkProtocolV1(sysid, g38.GCS_COMPID);
  /// One HEARTBEAT (MAVLink 2, or 1 with `v1`; with `corrupt`, its CRC wrong) or, with `twice`,
  /// two in one write (one datagram).
  s.heartbeat = (write, { corrupt = false, version1 = false, twice = false } = {}) => {
    const frame = () => {
      const hb = new minimal.Heartbeat();
      hb.type = 6;
      hb.autopilot = 8;
      hb.mavlinkVersion = 3;
      const buf = (version1 ? v1 : protocol).serialize(hb, seq++ & 255);
      if (corrupt) {
        buf[buf.length - 1] ^= 0x5a;  // the CRC no longer matches
      } else {
        s.sent.push({ buf: Buffer.from(buf), msgid: 0, target: null, t: performance.now() });
      }
      return buf;
    };
    write(twice ? Buffer.concat([frame(), frame()]) : frame());
  };
  return s;
}

async function udpSocket() {
  const socket = dgram.createSocket('udp4');
  const frames = [];
  const decoder = new h.Decoder(() => {});
  decoder.parser.on('data', (p) => frames.push({ sysid: p.header.sysid, buf: Buffer.from(p.buffer) }));
  socket.on('message', (msg) => decoder.write(msg));
  await new Promise((r) => socket.bind(0, '127.0.0.1', r));
  return { socket, frames };
}

async function tcpConnect(port) {
  const frames = [];
  const decoder = new h.Decoder(() => {});
  decoder.parser.on('data', (p) => frames.push({ sysid: p.header.sysid, buf: Buffer.from(p.buffer) }));
  const socket = net.connect(port, '127.0.0.1');
  await new Promise((resolve, reject) => { socket.once('connect', resolve); socket.once('error', reject); });
  socket.on('data', (d) => decoder.write(d));
  socket.on('error', () => {});
  return { socket, frames };
}

async function main() {
  const v = await g38.udpVehicleTransport();
  const udpinPort = await h.freeUdpPort();
  const tcpinPort = await h.freeTcpPort();
  const udpin = `udpin://127.0.0.1:${udpinPort}`;
  const tcpin = `tcpin://127.0.0.1:${tcpinPort}`;
  const run = h.mocaplink(['run', '--source', 'sim://?bodies=1&rate_hz=100', '--http', '127.0.0.1:0',
    '--vehicle', `quad:body=Body1,link=${v.link},profile=px4,system_id=1,rate_hz=30,gcs=${udpin}+${tcpin}`]);
  const [, port] = await h.waitForLog(run, /dashboard: http:\/\/127\.0\.0\.1:(\d+)\//);
  const api = h.dashboardApi(port);
  const quad = async () => (await api('GET', '/api/vehicles/quad')).json;
  await h.waitFor(v.ready, 10000, `mocaplink reaches the vehicle\n${run.stderr}`);
  const vehicle = g38.scriptedAutopilot(v.transport, 1);
  await h.waitFor(async () => (await quad()).heartbeat, 10000, 'mocaplink hears the vehicle');
  assert.deepEqual((await quad()).gcs.map((e) => e.url), [udpin, tcpin], 'the endpoints of --vehicle ...,gcs=A+B');

  const qgc = station(255);
  const tcp = station(254);
  try {
    // QGroundControl from port A, then (restarted) from port B.
    const a = await udpSocket();
    qgc.heartbeat((b) => a.socket.send(b, udpinPort, '127.0.0.1'));
    await h.waitFor(() => a.frames.length >= 3, 10000, 'vehicle frames at the first address');
    const b = await udpSocket();
    qgc.heartbeat((x) => b.socket.send(x, udpinPort, '127.0.0.1'));
    await h.waitFor(() => b.frames.length >= 4, 10000, 'vehicle frames at the new address');
    // Where in the vehicle's own order each frame was sent: every frame the old address got comes
    // before every frame the new one got (one switch, no copies to both). Order, not a clock: a
    // loaded machine may take any time to read the new address's first datagram.
    const sentIndex = (f) => vehicle.sent.findIndex((x) => x.buf.equals(f.buf));
    const unknown = [...a.frames, ...b.frames].filter((f) => sentIndex(f) < 0).length;
    assert.equal(unknown, 0, `${unknown} frames at the ground station that the vehicle never sent`);
    const lastAtA = Math.max(...a.frames.map(sentIndex));
    const firstAtB = Math.min(...b.frames.map(sentIndex));
    assert.ok(lastAtA < firstAtB, `the old address got the vehicle's frame ${lastAtA} after the new one got ${firstAtB}`);

    // A damaged frame between two good ones; a MAVLink 1 frame (Mission Planner, MAVProxy may
    // send them); two frames in one datagram (as a Wi-Fi bridge batches them).
    const toB = (x) => b.socket.send(x, udpinPort, '127.0.0.1');
    qgc.heartbeat(toB, { corrupt: true });
    qgc.heartbeat(toB);
    qgc.heartbeat(toB, { version1: true });
    qgc.heartbeat(toB, { twice: true });

    // A TCP ground station, twice.
    const first = await tcpConnect(tcpinPort);
    tcp.heartbeat((x) => first.socket.write(x));
    await h.waitFor(() => first.frames.length >= 3, 10000, 'vehicle frames on the first TCP connection');
    first.socket.destroy();
    await h.sleep(300);
    const second = await tcpConnect(tcpinPort);
    tcp.heartbeat((x) => second.socket.write(x));
    await h.waitFor(() => second.frames.length >= 3, 10000, `vehicle frames on the second TCP connection\n${run.stderr}`);
    tcp.heartbeat((x) => second.socket.write(x));

    await h.sleep(500);
    // The vehicle falls silent first, so that no frame is forwarded between reading the counters
    // and closing the sockets that count what arrived.
    vehicle.stop();
    await h.sleep(300);
    const status = await quad();
    await h.stop(run);
    [a, b].forEach((x) => x.socket.close());
    second.socket.destroy();

    g38.assertVehicleGotExactly(vehicle, qgc, 'udpin, two addresses and a damaged frame');
    g38.assertVehicleGotExactly(vehicle, tcp, 'tcpin, two connections');
    const [e0, e1] = status.gcs;
    assert.equal(e0.bad_frames, 1, `udpin: one frame with a bad CRC ${JSON.stringify(e0)}`);
    assert.equal(e0.frames_from_gcs, qgc.sent.length, `udpin: frames_from_gcs ${JSON.stringify(e0)}`);
    assert.equal(e0.frames_to_gcs, a.frames.length + b.frames.length, `udpin: frames_to_gcs ${JSON.stringify(e0)}`);
    assert.equal(e1.bad_frames, 0, JSON.stringify(e1));
    assert.equal(e1.frames_from_gcs, tcp.sent.length, `tcpin: frames_from_gcs ${JSON.stringify(e1)}`);
    // (Frames written as the first connection closed are counted sent and never read here.)
    assert.ok(e1.frames_to_gcs >= first.frames.length + second.frames.length, `tcpin: frames_to_gcs ${JSON.stringify(e1)}`);
    assert.equal(status.link_share.forwarded, qgc.sent.length + tcp.sent.length, JSON.stringify(status.link_share));
    console.log(`ok: udpin ${JSON.stringify(e0)}; tcpin ${JSON.stringify(e1)}`);
  } finally {
    vehicle.stop();
    v.close();
  }
}

main().catch(h.fail);
