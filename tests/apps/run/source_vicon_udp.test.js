// End to end over the Vicon Tracker UDP object stream: `mocaplink run --config` with
// vicon-udp://127.0.0.1:PORT ← `mocaplink serve --protocol vicon-udp --to 127.0.0.1:PORT --from
// replay:SCENE --set frame_step=2` (a stream at half the camera rate) → two UDP vehicles decoding
// with node-mavlink; poses match scene.js's ground truth in NED. Also `bodies --json` on a second
// port: every scene body tracked and no frame counted as dropped for the step of 2. The scene's
// Body1 hovers perfectly still, so the frozen-object check is off (frozen=0).
//
// Tracker's blocks (issue 27): the emulator's datagrams, caught here on a plain socket and read by
// a decoder written in this file from protocols/vicon-tracker-udp.md, are block_size bytes (256,
// 512, 1024, the default) of items then zeros, objects that do not fit split over datagrams with
// one frame number, or exactly 5 + 75·n bytes with block_size=0; `bodies` reads the padded stream
// with nothing dropped or rejected; hand-built datagrams (the protocol document's golden vector,
// padded to 1024 bytes) are read by `bodies`, and with a stray byte in the padding they are
// refused with the reason in `bodies` (text and JSON) and `record`, and in `run`'s log and
// /api/status.
'use strict';

const dgram = require('node:dgram');
const path = require('node:path');
const h = require('./harness');
const scene = require('./scene');
const e2e = require('./source_e2e');

const { assert, ID } = h;
const SECONDS = 4;
// harness.js adds an exit listener per process started; this test starts about twenty.
process.setMaxListeners(40);

function serve(sceneFile, port) {
  return h.mocaplink(['serve', '--protocol', 'vicon-udp', '--from', `replay:${sceneFile}`,
    '--to', `127.0.0.1:${port}`, '--set', 'frame_step=2']);
}

/// `serve` refuses a vicon-udp emulator without --to, and bad --set values, with exit 1.
async function checkServeErrors() {
  const cases = [
    [['--from', 'sim'], '--to'],
    [['--from', 'sim', '--to', '127.0.0.1:9', '--set', 'rotation=xzy'], 'rotation must be xyz or zyx'],
    [['--from', 'sim', '--to', '127.0.0.1:9', '--set', 'frame_step=0'], 'frame_step'],
    [['--from', 'sim', '--to', '127.0.0.1:9', '--set', 'rotaton=xyz'], 'rotaton'],
    [['--from', 'sim', '--to', '127.0.0.1:9', '--set', 'block_size=79'],
      'block_size must be 0 (no padding) or 80 to 65507 (Tracker: 256, 512, 1024), got "79"'],
    [['--from', 'sim', '--to', '127.0.0.1:9', '--set', 'block_size=65508'],
      'block_size must be an integer from 0 to 65507, got "65508"'],
  ];
  for (const [args, message] of cases) {
    const p = h.mocaplink(['serve', '--protocol', 'vicon-udp', ...args]);
    const { code } = await p.exited;
    assert.equal(code, 1, `serve ${args.join(' ')}: exit ${code}`);
    assert.ok(p.stderr.includes(message), `serve ${args.join(' ')}: ${p.stderr}`);
  }
}

// The golden vector of vicon-tracker-udp.md §6: frame 1234, "Drone1" at (1000, −500, 250) mm,
// rotation (0, 0, π/2); 80 bytes.
const DRONE1 = 'd20400000100480044726f6e6531000000000000000000000000000000000000000000000040' +
  '8f400000000000407fc00000000000406f4000000000000000000000000000000000182d4454fb21f93f';

/// The golden vector with frame number `frame`, zero-padded to `block` bytes.
function drone1Block(frame, block) {
  const bytes = Buffer.alloc(block);
  Buffer.from(DRONE1, 'hex').copy(bytes);
  bytes.writeUInt32LE(frame, 0);
  return bytes;
}

/// Decodes a datagram by the protocol document (§2): frame number, objects (name, six doubles),
/// and the bytes after the last item.
function decodeDatagram(bytes) {
  const frame = bytes.readUInt32LE(0);
  const count = bytes[4];
  const objects = [];
  let at = 5;
  for (let i = 0; i < count; i++) {
    const id = bytes[at];
    const size = bytes.readUInt16LE(at + 1);
    assert.equal(id, 0, `item ${i}: id ${id}`);
    assert.equal(size, 72, `item ${i}: size ${size}`);
    const name = bytes.subarray(at + 3, at + 27).toString('latin1').replace(/\0.*$/s, '');
    objects.push({ name, x: bytes.readDoubleLE(at + 27) });
    at += 75;
  }
  return { frame, objects, tail: bytes.subarray(at) };
}

/// `serve --from sim://?bodies=7` caught on a plain socket for every block size: each datagram is
/// block_size bytes (5 + 75·n for 0), items then zeros, at most what fits per datagram, and every
/// frame number's datagrams together hold the seven bodies once.
async function checkEmulatorBlocks() {
  const fits = { 0: 7, 256: 3, 512: 6, 1024: 7 };
  for (const block of [1024, 512, 256, 0]) {
    const socket = dgram.createSocket('udp4');
    await new Promise((resolve) => socket.bind(0, '127.0.0.1', resolve));
    const datagrams = [];
    socket.on('message', (m) => datagrams.push(m));
    const args = ['serve', '--protocol', 'vicon-udp', '--from', 'sim://?bodies=7', '--to',
      `127.0.0.1:${socket.address().port}`];
    // The default is 1024: the first round gives no --set.
    const server = h.mocaplink(block === 1024 ? args : [...args, '--set', `block_size=${block}`]);
    await h.waitFor(() => datagrams.length >= 60, 10000, `datagrams with block_size=${block}`);
    server.child.kill('SIGTERM');
    await server.exited;
    socket.close();
    const names = new Map();  // frame → names, in arrival order
    for (const d of datagrams) {
      const { frame, objects, tail } = decodeDatagram(d);
      assert.equal(d.length, block === 0 ? 5 + 75 * objects.length : block,
        `block_size=${block}: a datagram of ${d.length} bytes`);
      assert.ok(tail.every((b) => b === 0), `block_size=${block}: non-zero padding`);
      assert.ok(objects.length <= fits[block], `block_size=${block}: ${objects.length} objects`);
      if (!names.has(frame)) names.set(frame, []);
      names.get(frame).push(...objects.map((o) => o.name));
    }
    // Every frame but the last (perhaps cut by the kill) holds the seven bodies once.
    const frames = [...names.values()].slice(0, -1);
    assert.ok(frames.length > 10, `block_size=${block}: ${frames.length} frames`);
    for (const n of frames) {
      assert.deepEqual([...n].sort(), ['Body1', 'Body2', 'Body3', 'Body4', 'Body5', 'Body6',
        'Body7'], `block_size=${block}: a frame of ${n}`);
    }
  }
}

/// Sends `make(i)` to 127.0.0.1:port every 10 ms until stop() is called.
function sendEvery10ms(port, make) {
  const socket = dgram.createSocket('udp4');
  let i = 0;
  const timer = setInterval(() => socket.send(make(i++), port, '127.0.0.1'), 10);
  return () => { clearInterval(timer); socket.close(); };
}

/// A padded stream read at full rate, and trailing garbage refused with its reason.
async function checkPaddedAndGarbage(dir) {
  // The emulator's default (1024-byte blocks) at 100 Hz: nothing dropped, nothing rejected.
  let port = await h.freeUdpPort();
  let bodies = h.mocaplink(['bodies', '--source', `vicon-udp://127.0.0.1:${port}?frozen=0`,
    '--seconds', '2', '--json']);
  let server = h.mocaplink(['serve', '--protocol', 'vicon-udp', '--from', 'sim', '--rate', '100',
    '--to', `127.0.0.1:${port}`]);
  let { code } = await bodies.exited;
  server.child.kill('SIGTERM');
  await server.exited;
  assert.equal(code, 0, `bodies: ${bodies.stderr}`);
  let status = JSON.parse(bodies.stdout);
  assert.equal(status.rejected, 0, `padded stream: ${status.rejected_reason}`);
  assert.equal(status.rejected_reason, null);
  assert.equal(status.dropped, 0, 'padded stream: frames dropped');
  // Every frame number from the first to the last (dropped 0) and no rejection is the full rate;
  // the count only shows that the stream ran (the emulator starts after bodies).
  assert.ok(status.frames >= 50, `padded stream: ${status.frames} frames in 2 s at 100 Hz`);

  // The golden vector in 1024-byte blocks, built here: read as the document says.
  port = await h.freeUdpPort();
  bodies = h.mocaplink(['bodies', '--source', `vicon-udp://127.0.0.1:${port}?frozen=0`,
    '--seconds', '1', '--json']);
  await h.sleep(300);  // bound by then; earlier datagrams are simply lost
  let stop = sendEvery10ms(port, (i) => drone1Block(1234 + i, 1024));
  ({ code } = await bodies.exited);
  stop();
  assert.equal(code, 0, `bodies: ${bodies.stderr}`);
  status = JSON.parse(bodies.stdout);
  assert.equal(status.rejected, 0);
  assert.equal(status.bodies.length, 1);
  assert.equal(status.bodies[0].name, 'Drone1');
  assert.ok(status.bodies[0].tracked);
  assert.deepEqual(status.bodies[0].p_m, [1, -0.5, 0.25]);

  // One stray byte in the padding: every datagram refused, the reason shown.
  const garbage = (i) => {
    const b = drone1Block(1234 + i, 1024);
    b[300] = 0x41;
    return b;
  };
  const reason = 'malformed datagram at byte 300: trailing non-zero bytes after 1 item ' +
    '(0x41 in a 1024-byte datagram)';
  port = await h.freeUdpPort();
  bodies = h.mocaplink(['bodies', '--source', `vicon-udp://127.0.0.1:${port}`, '--seconds', '1']);
  await h.sleep(300);
  stop = sendEvery10ms(port, garbage);
  ({ code } = await bodies.exited);
  stop();
  assert.equal(code, 2, `bodies with garbage: exit ${code}`);
  assert.match(bodies.stdout, new RegExp(`^rejected  \\d+   last: ${reason.replace(/[()]/g, '\\$&')}$`, 'm'),
    bodies.stdout);
  assert.ok(bodies.stderr.includes('no frame arrived from') &&
    /packets? rejected: /.test(bodies.stderr) && bodies.stderr.includes(reason), bodies.stderr);

  port = await h.freeUdpPort();
  const out = path.join(dir, 'garbage.csv');
  const record = h.mocaplink(['record', '--source', `vicon-udp://127.0.0.1:${port}`, '--out', out,
    '--seconds', '1']);
  await h.sleep(300);
  stop = sendEvery10ms(port, garbage);
  ({ code } = await record.exited);
  stop();
  assert.equal(code, 2, `record with garbage: exit ${code}`);
  assert.ok(record.stderr.includes(`rejected: ${reason}`), record.stderr);

  // run: the log says it from the first tick (at the count then, and again past 10, 100, ...),
  // /api/status has the count and the reason.
  port = await h.freeUdpPort();
  const vehicles = [await new h.UdpVehicle().bind(), await new h.UdpVehicle().bind()];
  const run = h.mocaplink(['run', '--config',
    e2e.writeRunConfig(dir, `vicon-udp://127.0.0.1:${port}`, vehicles)]);
  const [, http] = await h.waitForLog(run, /dashboard: http:\/\/127\.0\.0\.1:(\d+)\//);
  await h.waitForLog(run, /listening on UDP port/);
  stop = sendEvery10ms(port, garbage);
  await h.waitForLog(run, new RegExp(`warning source vicon-udp://127\\.0\\.0\\.1:${port}: \\d+ ` +
    'packets? rejected: malformed datagram at byte 300: trailing non-zero bytes after 1 item'));
  const api = h.dashboardApi(http);
  let json;
  for (let tries = 0; ; tries++) {
    ({ json } = await api('GET', '/api/status'));
    if (json.station.rejected >= 10) break;
    assert.ok(tries < 500, `station.rejected ${json.station.rejected}`);
    await h.sleep(20);
  }
  stop();
  assert.equal(json.station.rejected_reason, reason);
  assert.equal(json.station.frames, 0);
  await h.waitForLog(run, /: \d{2,} packets rejected: malformed/);  // again, past 10
  await h.stop(run);
  vehicles.forEach((v) => v.close());
}

async function main() {
  await checkServeErrors();
  await checkEmulatorBlocks();
  const dir = h.tempDir('vicon-udp');
  await checkPaddedAndGarbage(dir);
  const sceneFile = path.join(dir, 'scene.csv');
  scene.writeScene(sceneFile, SECONDS);

  const bodiesPort = await h.freeUdpPort();
  const bodies = e2e.bodiesJson(`vicon-udp://127.0.0.1:${bodiesPort}?lost_ms=2000&frozen=0`);
  // Datagrams sent before bodies has bound its port are lost, which is harmless here.
  const first = serve(sceneFile, bodiesPort);
  const status = await bodies;
  first.child.kill('SIGTERM');
  await first.exited;
  assert.equal(status.dropped, 0, `dropped ${status.dropped} with frame_step 2`);
  assert.deepEqual(status.bodies.map((b) => b.name).sort(), ['Body1', 'Body2', 'Body3']);
  assert.ok(status.bodies.every((b) => b.tracked), 'a body untracked');

  const port = await h.freeUdpPort();
  const vehicles = [await new h.UdpVehicle().bind(), await new h.UdpVehicle().bind()];
  const run = h.mocaplink(['run', '--config',
    e2e.writeRunConfig(dir, `vicon-udp://127.0.0.1:${port}?frozen=0`, vehicles)]);
  await h.waitForLog(run, /listening on UDP port/);  // bound: no datagram is lost from now
  const server = serve(sceneFile, port);
  await h.waitFor(() => vehicles[0].ofId(ID.ODOMETRY).length > 0, 10000,
    `first ODOMETRY\n${run.stderr}`);
  await h.sleep(1500);
  await h.stop(run);
  server.child.kill('SIGTERM');
  await server.exited;
  const counts = e2e.checkPoses(vehicles, SECONDS);
  vehicles.forEach((v) => v.close());
  console.log(`ok: ${counts.odometry} ODOMETRY, ${counts.local} LOCAL_POSITION_NED`);
}

main().catch(h.fail);
