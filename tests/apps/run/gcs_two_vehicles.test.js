// Two vehicles behind one ground-station endpoint (issue 38; docs/config.md `gcs`): vehicles 1 and 2
// on their own UDP links, both with `gcs = ["udpin://127.0.0.1:P"]` — one endpoint, shared. A
// ground station (255/190) talks to system 2 as QGroundControl would, and also sends a COMMAND_LONG
// to system 1, a PARAM_REQUEST_LIST to system 0 (broadcast) and a COMMAND_LONG to system 7 (no such
// vehicle). Checked: each vehicle receives exactly the frames for it (HEARTBEAT and broadcast to
// both, targeted ones only to their system), byte for byte; the ground station receives each
// vehicle's frames; the command to 7 is dropped and counted `no_route`; /api/status shows the shared
// endpoint on both vehicles with its counts, `peers` 1 while the ground station beats and 0 once it
// has been silent 5 s, and the log says when it came and went.
'use strict';

const path = require('node:path');
const { common } = require('node-mavlink');
const h = require('./harness');
const g38 = require('./gcs_e2e');

const { assert } = h;

function command(target, cmd, param1) {
  const c = new common.CommandLong();
  c.command = cmd;
  c._param1 = param1;
  c.targetSystem = target;
  c.targetComponent = 1;
  return c;
}

async function main() {
  const dir = h.tempDir('gcs-two');
  const links = [await g38.udpVehicleTransport(), await g38.udpVehicleTransport()];
  const g = await g38.groundStationSocket('udpin');
  const config = h.writeConfig(path.join(dir, 'run.toml'), 'sim://?bodies=2&rate_hz=100', [
    { name: 'one', body: 'Body1', link: links[0].link, system_id: 1, profile: 'px4', rate_hz: 30, gcs: [g.url] },
    { name: 'two', body: 'Body2', link: links[1].link, system_id: 2, profile: 'px4', rate_hz: 30, gcs: [g.url] },
  ]);
  const run = h.mocaplink(['run', '--config', config]);
  const [, port] = await h.waitForLog(run, /dashboard: http:\/\/127\.0\.0\.1:(\d+)\//);
  const api = h.dashboardApi(port);
  const status = async () => {
    const vehicles = (await api('GET', '/api/status')).json.vehicles;
    return [vehicles.find((v) => v.name === 'one'), vehicles.find((v) => v.name === 'two')];
  };
  await h.waitFor(() => links.every((l) => l.ready()), 10000, `mocaplink reaches both vehicles\n${run.stderr}`);
  const vehicles = [g38.scriptedAutopilot(links[0].transport, 1), g38.scriptedAutopilot(links[1].transport, 2)];
  await h.waitFor(async () => (await status()).every((v) => v.heartbeat), 10000, 'mocaplink hears both');
  const before = await status();
  assert.deepEqual(before.map((v) => v.gcs.map((e) => [e.url, e.peers])), [[[g.url, 0]], [[g.url, 0]]],
    `before a ground station spoke: ${JSON.stringify(before.map((v) => v.gcs))}`);

  // QGroundControl on vehicle 2, plus one command to vehicle 1, a broadcast and one to nobody.
  const broadcast = new common.ParamRequestList();
  broadcast.targetSystem = 0;
  broadcast.targetComponent = 0;
  const session = g38.qgcSession(g, 255, 2, {
    beats: 4, extra: [command(1, 31010, 0), broadcast, command(7, g38.CMD.ARM_DISARM, 1)],
  });
  await h.sleep(2500);
  const during = await status();
  await session;
  await h.waitFor(() => g.received.some((f) => f.sysid === 2 && f.msgid === g38.MSG.MISSION_COUNT) &&
    g.received.some((f) => f.sysid === 1 && f.msgid === g38.MSG.COMMAND_ACK), 5000,
    `the answers of both vehicles (received ${g.received.map((f) => `${f.sysid}:${f.msgid}`).join(',')})`);
  vehicles.forEach((v) => v.stop());
  await h.sleep(600);
  const stopped = await status();

  // Silence: gone after 5 s, once, and no peer left on either vehicle's view of the endpoint.
  const escaped = g.url.replace(/[.:/]/g, '\\$&');
  await h.waitForLog(run, new RegExp(`ground station 255/190 on ${escaped} gone \\(silent 5 s\\)`), 10000);
  const goneAfter = performance.now() - g.sent.at(-1).t;
  const after = await status();
  await h.stop(run);
  g.close();
  links.forEach((l) => l.close());

  // Bytes: each vehicle got exactly the frames for it.
  const sentTo = (sys) => g.sent.filter((f) => f.target && f.target[0] === sys).length;
  assert.equal(sentTo(7), 1);
  for (const v of vehicles) {
    g38.assertVehicleGotExactly(v, g, `vehicle ${v.sysid}`);
    const fromGcs = v.received.filter((f) => f.sysid === 255);
    assert.ok(fromGcs.filter((f) => f.msgid === 0).length >= 4, `vehicle ${v.sysid}: the ground station's HEARTBEATs`);
    const commands = fromGcs.filter((f) => f.msgid === 76).map((f) => h.decode(f.packet))
      .map((c) => [c.command, c.targetSystem]);
    assert.deepEqual(commands, v.sysid === 1 ? [[31010, 1]] : [[g38.CMD.ARM_DISARM, 2]], `vehicle ${v.sysid}: COMMAND_LONGs`);
  }
  // The ground station got each vehicle's frames, and nothing of mocaplink's.
  for (const v of vehicles) g38.assertGroundStationGotExactly(v, g, `from vehicle ${v.sysid}`);
  assert.deepEqual(g.received.filter((f) => f.compid !== 1 || (f.sysid !== 1 && f.sysid !== 2))
    .map((f) => `${f.sysid}/${f.compid}:${f.msgid}`), [], 'frames that are not the vehicles\'');
  const acks = g.received.filter((f) => f.msgid === g38.MSG.COMMAND_ACK).map((f) => h.decode(f.packet))
    .map((a) => [a.command, a.targetSystem, a.targetComponent]);
  assert.deepEqual(acks.sort(), [[31010, 255, 190], [g38.CMD.ARM_DISARM, 255, 190]].sort(), 'COMMAND_ACKs at the ground station');
  assert.ok(!vehicles[0].armed && vehicles[1].armed, 'only vehicle 2 was armed');

  // /api/status: the one endpoint on both vehicles, counted as one.
  for (const [i, v] of stopped.entries()) {
    const e = v.gcs;
    const what = `vehicle ${v.name}: ${JSON.stringify(e)}`;
    assert.equal(e.length, 1, what);
    assert.equal(e[0].url, g.url, what);
    assert.equal(during[i].gcs[0].peers, 1, `while it beats: ${JSON.stringify(during[i].gcs)}`);
    assert.equal(e[0].frames_from_gcs, g.sent.length, `${what}: frames_from_gcs (it sent ${g.sent.length})`);
    assert.equal(e[0].no_route, 1, `${what}: no_route (one COMMAND_LONG to system 7)`);
    // Both vehicles' frames, as sent to it; those before it spoke had no address: `dropped`.
    assert.equal(e[0].frames_to_gcs, g.received.length, `${what}: frames_to_gcs (it received ${g.received.length})`);
    assert.equal(e[0].dropped, during[i].gcs[0].dropped, `${what}: dropped while it was connected`);
    assert.equal(e[0].bad_frames, 0, what);
    assert.equal(after[i].gcs[0].peers, 0, `after the silence: ${JSON.stringify(after[i].gcs)}`);
    // What was forwarded onto this vehicle's link: the frames for it.
    const forwarded = g.sent.filter((f) => !f.target || f.target[0] === 0 || f.target[0] === vehicles[i].sysid).length;
    assert.equal(v.link_share.forwarded, forwarded, `${what}: link_share.forwarded ${JSON.stringify(v.link_share)}`);
    assert.equal(v.link_share.capacity_bytes_per_s, null, JSON.stringify(v.link_share));
  }
  assert.equal(stopped[0].gcs[0].frames_to_gcs, stopped[1].gcs[0].frames_to_gcs, 'one endpoint, one count');
  const connected = run.stderr.match(new RegExp(`ground station 255/190 on ${escaped} connected`, 'g')) || [];
  const gone = run.stderr.match(new RegExp(`ground station 255/190 on ${escaped} gone`, 'g')) || [];
  assert.equal(connected.length, 1, `"connected" logged ${connected.length} times`);
  assert.equal(gone.length, 1, `"gone" logged ${gone.length} times`);
  assert.ok(goneAfter >= 5000, `"gone" logged ${Math.round(goneAfter)} ms after the last frame`);
  console.log(`ok: ${g.sent.length} frames from the ground station, ${g.received.length} to it; ` +
    `gone logged ${(goneAfter / 1000).toFixed(1)} s after its last frame`);
}

main().catch(h.fail);
