// SIGTERM under load with --record: the process exits 0 and leaves complete, readable files —
// mocap.csv parses row by row (DESIGN.md "Recording format") and every .tlog record (8-byte
// big-endian Unix µs + one frame) decodes with node-mavlink, with times inside the run.
'use strict';

const fs = require('node:fs');
const path = require('node:path');
const h = require('./harness');

const { assert } = h;
const VEHICLES = 3;

function checkCsv(file) {
  const lines = fs.readFileSync(file, 'utf8').split('\n');
  assert.equal(lines.pop(), '', 'mocap.csv does not end with a newline (cut short?)');
  assert.match(lines[0], /^# mocaplink recording 1; source=sim:\/\/.*; rate_hz=500$/);
  assert.equal(lines[1], 'time_s,frame,body,tracked,x_m,y_m,z_m,qw,qx,qy,qz');
  let lastTime = -1;
  const frames = new Set();
  for (const written of lines.slice(2)) {
    // A frame the bridge took but did not send (late, or superseded by a newer one waiting: under
    // load) is its rows as comments; they are checked as rows.
    const line = written.replace(/^# (late|superseded), not sent: /, '');
    const f = line.split(',');
    assert.equal(f.length, 11, `bad row: ${line}`);
    const t = Number(f[0]);
    assert.ok(Number.isFinite(t) && t >= lastTime, `time_s goes back: ${line}`);
    lastTime = t;
    assert.match(f[2], /^Body[1-3]$/);
    if (f[3] === '1') {
      const values = f.slice(4).map(Number);
      assert.ok(values.every(Number.isFinite), `bad pose: ${line}`);
      assert.ok(Math.abs(Math.hypot(...values.slice(3)) - 1) < 1e-3, `quaternion norm: ${line}`);
    } else {
      assert.equal(f[3], '0');
    }
    frames.add(f[1]);
  }
  return frames.size;
}

function checkTlog(file, startUs, endUs) {
  const bytes = fs.readFileSync(file);
  const frames = [];
  let at = 0;
  while (at < bytes.length) {
    assert.ok(at + 8 + 3 <= bytes.length, `${file}: truncated record at ${at}`);
    const t = bytes.readBigUInt64BE(at);
    assert.ok(t >= startUs && t <= endUs, `${file}: time ${t} outside the run`);
    const magic = bytes[at + 8];
    assert.equal(magic, 0xfd, `${file}: record at ${at} is not a MAVLink 2 frame`);
    const len = bytes[at + 9];
    const signed = (bytes[at + 10] & 1) !== 0;
    const size = 12 + len + (signed ? 13 : 0);
    assert.ok(at + 8 + size <= bytes.length, `${file}: frame cut short at ${at}`);
    frames.push(bytes.subarray(at + 8, at + 8 + size));
    at += 8 + size;
  }
  let decoded = 0;
  const decoder = new h.Decoder(() => { decoded += 1; });
  for (const frame of frames) decoder.write(frame);
  return new Promise((resolve) => setImmediate(() => {
    assert.equal(decoder.invalid, 0, `${file}: frames with bad CRC`);
    assert.equal(decoded, frames.length, `${file}: ${frames.length - decoded} frames undecodable`);
    resolve(frames.length);
  }));
}

async function main() {
  const dir = h.tempDir('shutdown');
  const record = path.join(dir, 'rec');
  const vehicles = [];
  const specs = [];
  for (let i = 0; i < VEHICLES; i += 1) {
    vehicles.push(await new h.UdpVehicle().bind());
    specs.push({ name: `v${i + 1}`, body: `Body${i + 1}`,
      link: `udp://127.0.0.1:${vehicles[i].port}`, profile: 'classic', system_id: i + 1,
      rate_hz: 200 });
  }
  const config = h.writeConfig(path.join(dir, 'load.toml'), 'sim://?bodies=3&rate_hz=500', specs,
    '[origin]\nlatitude_deg = 47.397742\nlongitude_deg = 8.545594\naltitude_m = 488.0\n');
  const args = ['run', '--config', config, '--record', record];
  const startUs = BigInt(Date.now()) * 1000n;
  const run = h.mocaplink(args, { env: { MOCAPLINK_STATE_DIR: path.join(dir, 'state') } });
  await h.waitFor(() => vehicles.every((v) => v.packets.length > 300), 10000,
    `traffic\n${run.stderr}`);
  // Frames are flowing at full rate: stop now, mid-stream.
  await h.stop(run);
  const endUs = BigInt(Date.now()) * 1000n;
  assert.match(run.stderr, /stopping: SIGTERM/);
  assert.match(run.stderr, /recording: \d+ frames in/);
  assert.doesNotMatch(run.stderr, /WRITE ERRORS/);

  const frames = checkCsv(path.join(record, 'mocap.csv'));
  assert.ok(frames > 100, `only ${frames} frames recorded`);
  for (let i = 0; i < VEHICLES; i += 1) {
    const n = await checkTlog(path.join(record, `v${i + 1}.tlog`), startUs, endUs);
    // Everything the vehicle received was logged (the tlog may hold more: frames in flight).
    assert.ok(n >= vehicles[i].packets.length, `v${i + 1}.tlog: ${n} < ${vehicles[i].packets.length}`);
  }
  vehicles.forEach((v) => v.close());
  console.log(`ok: ${frames} mocap frames recorded`);
}

main().catch(h.fail);
