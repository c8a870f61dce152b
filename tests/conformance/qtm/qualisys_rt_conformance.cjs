#!/usr/bin/env node
// Our QTM RT emulator (`mocaplink serve --protocol qtm`) read by the official Qualisys client,
// npm qualisys-rt 0.3.1 (pinned in package-lock.json; an implementation written by Qualisys):
//   A. TCP, protocol 1.19 (its default; ≤ 1.20 XML), components 6D + 6DRes: body names from
//      getParameters('6D'), and every frame's positions (mm) and column-by-column matrices equal
//      the scene's ground truth (tests/apps/run/scene.js, computed here, not by our decoder);
//      occluded bodies arrive as NaN;
//   B. UDP (streamFrames udpPort), protocol 1.25 (§5.2 XML), 6DEuler + 6DEulerRes: positions and
//      the Euler angles of QTM's default definition (roll x, pitch y, yaw z, rotated axes),
//      recomputed here from the truth quaternion;
//   C. body list changes (sim://?churn_s): event 11 arrives, getParameters('6D') then lists the new
//      bodies, and the frames after it carry that many.
// qualisys-rt quirks minded (not our server's): it lower-cases the whole XML text before parsing
// (names arrive as "body1"), and its 64-bit timestamp reader is wrong (timestamps not compared).
// Usage (CTest): node qualisys_rt_conformance.cjs PATH_TO_MOCAPLINK
'use strict';

const assert = require('node:assert/strict');
const { spawn } = require('node:child_process');
const fs = require('node:fs');
const os = require('node:os');
const path = require('node:path');
const { Api } = require('qualisys-rt');
const scene = require('../../apps/run/scene');

const bin = process.argv[2];
if (!bin) throw new Error('usage: qualisys_rt_conformance.cjs PATH_TO_MOCAPLINK');
const SECONDS = 5.6;  // covers the scene's occlusion (5.0–5.3 s)
const BODIES = ['Body1', 'Body2', 'Body3'];
const tmp = fs.mkdtempSync(path.join(os.tmpdir(), 'mocaplink-qtm-'));
const children = [];
process.on('exit', () => {
  for (const c of children) if (c.exitCode === null) c.kill('SIGKILL');
  fs.rmSync(tmp, { recursive: true, force: true });
});

function serve(args) {
  const child = spawn(bin, ['serve', '--protocol', 'qtm', '--listen', '127.0.0.1:0', ...args],
    { stdio: ['ignore', 'pipe', 'pipe'] });
  children.push(child);
  let out = '';
  let err = '';
  child.stderr.on('data', (d) => { err += d; });
  return new Promise((resolve, reject) => {
    child.stdout.on('data', (d) => {
      out += d;
      const m = out.match(/serving qtm on [^:]+:(\d+)/);
      if (m) resolve({ child, port: Number(m[1]), stderr: () => err });
    });
    child.on('exit', (code) => reject(new Error(`serve exited ${code}: ${err}`)));
  });
}

const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

// Rotation matrix (row-major 3×3) of a w-first quaternion.
function matrix([w, x, y, z]) {
  return [
    [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
    [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
    [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
  ];
}

// QTM's default Euler angles (degrees): R = Rx(roll)·Ry(pitch)·Rz(yaw).
function euler(q) {
  const r = matrix(q);
  const deg = 180 / Math.PI;
  return [Math.atan2(-r[1][2], r[2][2]) * deg, Math.asin(Math.max(-1, Math.min(1, r[0][2]))) * deg,
    Math.atan2(-r[0][1], r[0][0]) * deg];
}

const angleDiff = (a, b) => Math.abs(((a - b + 540) % 360) - 180);

// Checks one frame's component against the truth at the frame's scene time; returns 1 if checked.
function checkComponent(frame, component, kind) {
  const t = (frame.frame - 1) / scene.RATE_HZ;
  assert.equal(component.rigidBodyCount, 3, `frame ${frame.frame}: body count`);
  component.rigidBodies.forEach((b, i) => {
    const body = BODIES[i];
    const what = `frame ${frame.frame} ${body} ${kind}`;
    if (scene.occluded(body, t)) {
      assert.ok(Number.isNaN(b.x) || b.x === null, `${what}: occluded body not NaN (${b.x})`);
      return;
    }
    const { p, q } = scene.truth(body, t);
    for (const [k, axis] of ['x', 'y', 'z'].entries()) {
      assert.ok(Math.abs(b[axis] / 1000 - p[k]) < 3e-6, `${what}: ${axis} ${b[axis]} mm vs ${p[k]} m`);
    }
    if (kind.includes('Euler')) {
      const want = euler(q);
      [b.euler1, b.euler2, b.euler3].forEach((a, k) => {
        assert.ok(angleDiff(a, want[k]) < 1e-3, `${what}: euler${k + 1} ${a} vs ${want[k]}`);
      });
    } else {
      const r = matrix(q);
      for (let col = 0; col < 3; col += 1) {
        for (let row = 0; row < 3; row += 1) {
          const got = b.rotation[col * 3 + row];
          assert.ok(Math.abs(got - r[row][col]) < 1e-5, `${what}: R${row}${col} ${got} vs ${r[row][col]}`);
        }
      }
    }
    if (kind.endsWith('Res')) {
      const res = kind.includes('Euler') ? b.residuals : b.residual;
      assert.ok(Number.isFinite(res), `${what}: residual ${res}`);
    }
  });
  return 1;
}

// connect → version → getParameters('6D') → streamFrames; resolves with the frames after `ms`.
async function readScene(port, minor, components, udpPort) {
  const api = new Api();
  await api.connect(port, '127.0.0.1', 1, minor);
  const params = await api.getParameters('6D');
  const list = minor <= 20 ? params.the6d.rigidBodies : params.the6d.body;
  assert.deepEqual(list.map((b) => b.name), BODIES.map((n) => n.toLowerCase()),
    `1.${minor}: body names`);
  if (minor <= 20) assert.equal(params.the6d.euler.first, 'roll');
  const frames = [];
  api.on('frame', (f) => frames.push(f));
  await api.streamFrames({ frequency: 'AllFrames', components, udpPort });
  return { api, frames };
}

async function main() {
  const sceneFile = path.join(tmp, 'scene.csv');
  scene.writeScene(sceneFile, SECONDS);
  const server = await serve(['--from', `replay:${sceneFile}`, '--rate', String(scene.RATE_HZ)]);
  const udpPort = await new Promise((resolve) => {
    const s = require('node:dgram').createSocket('udp4');
    s.bind(0, '127.0.0.1', () => { const p = s.address().port; s.close(() => resolve(p)); });
  });
  const [tcp, udp] = await Promise.all([
    readScene(server.port, 19, ['6D', '6DRes']),
    readScene(server.port, 25, ['6DEuler', '6DEulerRes'], udpPort),
  ]);
  // The replay lasts SECONDS from serve's start; wait for its end.
  const last = Math.round(SECONDS * scene.RATE_HZ);
  const deadline = Date.now() + (SECONDS + 20) * 1000;
  while ((tcp.frames.length === 0 || tcp.frames[tcp.frames.length - 1].frame < last - 1 ||
          udp.frames.length === 0 || udp.frames[udp.frames.length - 1].frame < last - 20) &&
         Date.now() < deadline) {
    await sleep(50);
  }
  let checked = 0;
  let occludedSeen = 0;
  for (const [run, kinds] of [[tcp, ['6d', '6dRes']], [udp, ['6dEuler', '6dEulerRes']]]) {
    assert.ok(run.frames.length > SECONDS * scene.RATE_HZ * 0.5, `only ${run.frames.length} frames`);
    for (const f of run.frames) {
      for (const kind of kinds) {
        assert.ok(f.components[kind], `frame ${f.frame}: no ${kind} component`);
        checked += checkComponent(f, f.components[kind], kind);
      }
      if (scene.occluded('Body1', (f.frame - 1) / scene.RATE_HZ)) occludedSeen += 1;
    }
  }
  assert.ok(occludedSeen > 0, 'no frame inside the occlusion was read');
  tcp.api.disconnect();
  udp.api.disconnect();
  server.child.kill('SIGTERM');

  // C. Body list changes.
  const churn = await serve(['--from', 'sim://?bodies=3&churn_s=0.4', '--rate', '50']);
  const api = new Api();
  await api.connect(churn.port, '127.0.0.1', 1, 25);
  const count = (list) => (list === undefined ? 0 : [].concat(list).length);
  const seen = new Set();
  let expected = 0;
  let events = 0;
  let mismatched = 0;
  let rereading = 0;  // reads in flight
  const reread = async () => {
    rereading += 1;
    const n = count((await api.getParameters('6D')).the6d.body);
    rereading -= 1;
    expected = n;
    seen.add(n);
  };
  // In place before the first read, so that no change passes unseen.
  api.on('event', (e) => {
    if (e.id !== 11) return;
    events += 1;
    reread();
  });
  await reread();  // the emulator welcomes a client only once it has a body list: never empty
  let framesAfter = 0;
  api.on('frame', (f) => {
    if (rereading > 0) return;  // between the event and the new list, frames may carry either
    if (f.components['6d'].rigidBodyCount !== expected) mismatched += 1;
    framesAfter += 1;
  });
  await api.streamFrames({ frequency: 'AllFrames', components: ['6D'] });
  const churnDeadline = Date.now() + 20000;
  while ((events < 3 || framesAfter < 50) && Date.now() < churnDeadline) await sleep(50);
  api.disconnect();
  churn.child.kill('SIGTERM');
  assert.ok(events >= 3, `only ${events} parameter-change events`);
  assert.deepEqual([...seen].sort(), [2, 3], `body counts listed: ${[...seen]}`);
  // A frame may cross the event on the wire; more than a couple would mean stale lists.
  assert.ok(mismatched <= events * 2, `${mismatched} frames disagree with the body list`);
  console.log(`ok: ${checked} components checked against the scene (TCP 1.19 and UDP 1.25), ` +
    `${events} body list changes`);
}

main().then(() => process.exit(0)).catch((e) => {
  console.error(e);
  process.exit(1);
});
