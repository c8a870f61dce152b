// Issue 41: a mocap server restart must not move a hovering vehicle. `mocaplink serve --protocol
// vicon` plays the test scene (scene.js: Body1 hovers still, Body3 circles) on a fixed port;
// `mocaplink run --record` sends ODOMETRY for both to two UDP vehicles (node-mavlink decodes).
// After 3 s the server is stopped (connections refused), and started again 1 s later on the same
// port: its scene and its clock start from the beginning. 3 s later it is stopped for 1 s again
// and comes back on a clock 1600 s ahead (its frame numbers from a new base, as issue 49's server
// did): the Bridge must not take that for 1600 s of absence. Checked:
// * the hovering body's reset_counter never moves (a restart is no jump), and its poses resume
//   within the outage plus the reconnect schedule's bound (plus a generous second for the new
//   server process to start; the figures are printed);
// * the circling body, which each restarted scene puts back at its start (tens of centimetres from
//   where it would have been), gets exactly one increment per restart;
// * replaying the recording (replay://…/mocap.csv?speed=1: each restart written as the outage it
//   was, docs/daemon.md, not as the 1600 s the second clock leapt) gives both vehicles the same
//   reset_counter sequence.
'use strict';

const fs = require('node:fs');
const path = require('node:path');
const h = require('./harness');
const scene = require('./scene');

const { assert, ID } = h;
const OUTAGE_MS = 1000;
const AHEAD_S = 1600;

const ORIGIN = '[origin]\nlatitude_deg = 47.397742\nlongitude_deg = 8.545594\naltitude_m = 488.0\n';

/// The scene again, its frame numbers (the Vicon frame ids, hence the client's capture times) and
/// times AHEAD_S later: a server back on a clock ahead of its old one.
function writeSceneAhead(sceneFile, file) {
  const lines = fs.readFileSync(sceneFile, 'utf8').split('\n').map((line) => {
    if (!/^[0-9]/.test(line)) return line;
    const cells = line.split(',');
    cells[0] = (Number(cells[0]) + AHEAD_S).toFixed(6);
    cells[1] = String(Number(cells[1]) + AHEAD_S * scene.RATE_HZ);
    return cells.join(',');
  });
  fs.writeFileSync(file, lines.join('\n'));
}

function serve(sceneFile, port) {
  return h.mocaplink(['serve', '--protocol', 'vicon', '--from', `replay:${sceneFile}`,
    '--listen', `127.0.0.1:${port}`]);
}

async function vehicles() {
  const out = [];
  for (let i = 0; i < 2; i += 1) {
    const v = await new h.UdpVehicle().bind();
    v.socket.setRecvBufferSize(4 << 20);
    out.push(v);
  }
  return out;
}

function config(dir, name, source, vs) {
  const specs = [
    { name: 'hover', body: 'Body1', profile: 'px4', rate_hz: 50 },
    { name: 'circle', body: 'Body3', profile: 'px4', rate_hz: 50 },
  ].map((s, i) => ({ ...s, link: `udp://127.0.0.1:${vs[i].port}`, system_id: i + 1 }));
  return h.writeConfig(path.join(dir, `${name}.toml`), source, specs,
    `up = "+z"\nnorth = "+x"\n${ORIGIN}`);
}

/// ODOMETRY of a vehicle: [{ t (ms, receive), reset }].
function odometry(v) {
  return v.ofId(ID.ODOMETRY).map(({ packet, t }) => ({ t, reset: h.decode(packet).resetCounter }));
}

/// The distinct reset_counter values in order of arrival.
function sequence(odo) {
  const out = [];
  for (const { reset } of odo) if (out[out.length - 1] !== reset) out.push(reset);
  return out;
}

async function main() {
  const dir = h.tempDir('restart');
  const sceneFile = path.join(dir, 'scene.csv');
  scene.writeScene(sceneFile, 30);
  const port = await h.freeTcpPort();
  let server = serve(sceneFile, port);
  await h.waitFor(() => /serving vicon on/.test(server.stdout), 10000,
    `serve to start\n${server.stderr}`);

  const record = path.join(dir, 'rec');
  const liveVehicles = await vehicles();
  const live = h.mocaplink(['run', '--config', config(dir, 'live', `vicon://127.0.0.1:${port}`,
    liveVehicles), '--record', record], { env: { MOCAPLINK_STATE_DIR: path.join(dir, 'live-state') } });
  await h.waitFor(() => liveVehicles[0].ofId(ID.ODOMETRY).length >= 150, 20000,
    `3 s of poses\n${live.stderr}`);

  // The server goes away: connections refused for OUTAGE_MS, then it is back on the same port.
  const down = performance.now();
  await h.stop(server);
  const killed = performance.now();
  await h.sleep(OUTAGE_MS - (killed - down));
  const restarted = performance.now();
  server = serve(sceneFile, port);
  const before = liveVehicles[0].ofId(ID.ODOMETRY).length;
  await h.waitFor(() => liveVehicles[0].ofId(ID.ODOMETRY).length >= before + 150, 20000,
    `3 s of poses after the restart\n${live.stderr}`);
  // Away 1 s again, back on a clock AHEAD_S ahead.
  const aheadFile = path.join(dir, 'scene-ahead.csv');
  writeSceneAhead(sceneFile, aheadFile);
  await h.stop(server);
  await h.sleep(OUTAGE_MS);
  server = serve(aheadFile, port);
  const beforeAhead = liveVehicles[0].ofId(ID.ODOMETRY).length;
  await h.waitFor(() => liveVehicles[0].ofId(ID.ODOMETRY).length >= beforeAhead + 150, 20000,
    `3 s of poses after the restart on a clock ahead\n${live.stderr}`);
  await h.stop(live);
  await h.stop(server);
  await h.sleep(300);  // let node read what is queued
  liveVehicles.forEach((v) => v.close());

  const hover = odometry(liveVehicles[0]);
  const circle = odometry(liveVehicles[1]);
  // The pose gap at the hovering vehicle across the first restart.
  let gap = 0;
  let gapEnd = 0;
  for (let k = 1; k < beforeAhead; k += 1) {
    if (hover[k].t - hover[k - 1].t > gap) {
      gap = hover[k].t - hover[k - 1].t;
      gapEnd = hover[k].t;
    }
  }
  const outage = restarted - down;
  assert.deepEqual(sequence(hover), [hover[0].reset], `hover reset_counter moved: ${sequence(hover)}`);
  const circleSeq = sequence(circle);
  assert.deepEqual(circleSeq, [0, 1, 2].map((k) => (circle[0].reset + k) % 256),
    `circle: one jump per restart expected, reset_counter ${circleSeq}`);
  // Generous: the reconnect schedule adds at most 0.2 s; the new serve process needs time to start.
  assert.ok(gap < outage + 200 + 1000, `pose gap ${gap.toFixed(0)} ms for an outage of ${outage.toFixed(0)} ms`);

  // The recording, replayed: the same counters.
  const replayVehicles = await vehicles();
  const replay = h.mocaplink(['run', '--config', config(dir, 'replay',
    `replay://${path.join(record, 'mocap.csv')}?speed=1`, replayVehicles)],
  { env: { MOCAPLINK_STATE_DIR: path.join(dir, 'replay-state') } });
  const { code } = await replay.exited;
  assert.equal(code, 0, `replay: exit ${code}\n${replay.stderr}`);
  await h.sleep(300);
  replayVehicles.forEach((v) => v.close());
  const replayHover = sequence(odometry(replayVehicles[0]));
  const replayCircle = sequence(odometry(replayVehicles[1]));
  assert.deepEqual(replayHover, sequence(hover), `replay hover ${replayHover}`);
  assert.deepEqual(replayCircle, circleSeq, `replay circle ${replayCircle}`);
  console.log(`ok: outage ${outage.toFixed(0)} ms (server stopped ${(killed - down).toFixed(0)} ms ` +
    `after the stop began), hover pose gap ${gap.toFixed(0)} ms ending ` +
    `${(gapEnd - restarted).toFixed(0)} ms after the new server was started; reset_counter hover ` +
    `${sequence(hover)}, circle ${circleSeq}; replay the same`);
}

main().catch(h.fail);
