// Vehicles added and removed at run time through the dashboard API of the real daemon (issue 6):
// `mocaplink run` with the sim source, a UDP "vehicle" per link decoding with node-mavlink, plain
// HTTP requests. An added vehicle gets its own system id's stream at its own rate on its own link;
// refusals name the field and change nothing; a removed vehicle gets nothing more; the same name
// added again continues its .tlog.
'use strict';

const fs = require('node:fs');
const path = require('node:path');
const h = require('./harness');

const { assert, ID } = h;

/** Pose messages of `vehicle` per second over the next `ms`, and their system ids. */
async function measure(vehicle, msgid, ms) {
  const from = performance.now();
  await h.sleep(ms);
  const got = vehicle.ofId(msgid).filter((p) => p.t >= from);
  return { hz: got.length / (ms / 1000), sysids: new Set(got.map((p) => p.packet.header.sysid)) };
}

/** Records of a .tlog: [{ us, msgid, sysid }]. */
function tlogRecords(file) {
  const bytes = fs.readFileSync(file);
  const out = [];
  for (let at = 0; at < bytes.length;) {
    assert.equal(bytes[at + 8], 0xfd, `${file}: record at ${at} is not MAVLink 2`);
    const len = bytes[at + 9];
    out.push({ us: Number(bytes.readBigUInt64BE(at)), sysid: bytes[at + 13], msgid: bytes.readUIntLE(at + 15, 3) });
    at += 8 + 12 + len;
  }
  return out;
}

async function main() {
  const dir = h.tempDir('dash-vehicles');
  const quad = await new h.UdpVehicle().bind();
  const rover = await new h.UdpVehicle().bind();
  const config = h.writeConfig(path.join(dir, 'run.toml'), 'sim://?rate_hz=200', [
    { name: 'quad', body: 'Body1', link: `udp://127.0.0.1:${quad.port}`, system_id: 1, profile: 'px4' },
  ]);
  const record = path.join(dir, 'rec');
  const run = h.mocaplink(['run', '--config', config, '--record', record]);
  const [, port] = await h.waitForLog(run, /dashboard: http:\/\/127\.0\.0\.1:(\d+)\//);
  const api = h.dashboardApi(port);
  const names = async () => (await api('GET', '/api/vehicles')).json.map((v) => v.name);
  const roverSpec = {
    name: 'rover', body: 'Body2', link: `udp://127.0.0.1:${rover.port}`, system_id: 2, profile: 'px4', rate_hz: 20,
  };

  // Add: 201 with the vehicle; its link gets sysid 2 at 20 Hz, the quad's link is unchanged.
  const added = await api('POST', '/api/vehicles', roverSpec);
  assert.equal(added.status, 201, JSON.stringify(added.json));
  assert.equal(added.headers.get('location'), '/api/vehicles/rover');
  assert.equal(added.json.name, 'rover');
  assert.equal(added.json.link, `udp://127.0.0.1:${rover.port}`);
  assert.equal(added.json.system_id, 2);
  assert.equal(added.json.rate_hz, 20);
  await h.waitForLog(run, /dashboard: vehicle rover added/);
  await h.sleep(500);
  const roverRate = await measure(rover, ID.ODOMETRY, 2000);
  // ±25 %: tells 20 Hz from the quad's 50 and from 10 on a loaded 2-core machine.
  assert.ok(roverRate.hz > 15 && roverRate.hz < 25, `rover ODOMETRY ${roverRate.hz} Hz, asked 20`);
  assert.deepEqual([...roverRate.sysids], [2]);
  assert.ok(rover.ofId(ID.HEARTBEAT).length > 0, 'no HEARTBEAT to the added vehicle');
  const quadRate = await measure(quad, ID.ODOMETRY, 2000);
  assert.ok(quadRate.hz > 40 && quadRate.hz < 60, `quad ODOMETRY ${quadRate.hz} Hz`);
  assert.deepEqual([...quadRate.sysids], [1]);
  // Body2's pose, not Body1's: the sim's Body2 and Body1 are never at the same place.
  const last = (v) => h.decode(v.ofId(ID.ODOMETRY).at(-1).packet);
  const [r, q] = [last(rover), last(quad)];
  assert.ok(Math.hypot(r.x - q.x, r.y - q.y) > 0.1, `rover at the quad's position ${r.x},${r.y}`);
  assert.deepEqual(await names(), ['quad', 'rover']);

  // Refusals: the field at fault, nothing added.
  const refused = async (body, status, field) => {
    const answer = await api('POST', '/api/vehicles', body);
    assert.equal(answer.status, status, JSON.stringify(answer.json));
    assert.equal(answer.json.field, field, JSON.stringify(answer.json));
    return answer.json.error;
  };
  await refused(roverSpec, 409, 'name');
  const clash = await refused({ ...roverSpec, name: 'rover2', link: `udp://127.0.0.1:${quad.port}`, system_id: 1 },
    422, 'system_id');
  assert.match(clash, /system_id 1 is already used on udp:\/\/127\.0\.0\.1:\d+ by vehicle "quad"/);
  const gps = await refused({ ...roverSpec, name: 'rover2', profile: 'px4-gps' }, 422, 'profile');
  assert.match(gps, /origin/);
  await refused({ ...roverSpec, name: 'rover2', link: 'udp://127.0.0.1' }, 422, 'link');
  assert.deepEqual(await names(), ['quad', 'rover']);

  // PATCH works on an added vehicle like on a configured one.
  assert.equal((await api('PATCH', '/api/vehicles/rover', { rate_hz: 10 })).status, 200);
  await h.sleep(300);
  const slower = await measure(rover, ID.ODOMETRY, 2000);
  assert.ok(slower.hz > 7.5 && slower.hz < 12.5, `rover ODOMETRY ${slower.hz} Hz, patched to 10`);

  // Remove: 204, then nothing at all reaches its link; the quad goes on.
  const removed = await api('DELETE', '/api/vehicles/rover');
  assert.equal(removed.status, 204);
  const removedAt = Date.now();
  await h.sleep(300);
  const silentFrom = rover.packets.length;
  await h.sleep(1500);
  assert.equal(rover.packets.length, silentFrom, 'the removed vehicle still gets frames');
  assert.equal((await api('GET', '/api/vehicles/rover')).status, 404);
  assert.equal((await api('DELETE', '/api/vehicles/rover')).status, 404);
  assert.deepEqual(await names(), ['quad']);
  assert.ok((await measure(quad, ID.ODOMETRY, 1000)).hz > 30, 'the quad stopped with the rover');

  // The same name again: a fresh start on the same link; its .tlog continues.
  const readdedAt = Date.now();
  assert.equal((await api('POST', '/api/vehicles', roverSpec)).status, 201);
  await h.sleep(300);
  const again = await measure(rover, ID.ODOMETRY, 2000);
  assert.ok(again.hz > 15 && again.hz < 25, `re-added rover ODOMETRY ${again.hz} Hz`);

  await h.stop(run);
  assert.match(run.stderr, /dashboard: vehicle rover removed/);
  const records = tlogRecords(path.join(record, 'rover.tlog'));
  const before = records.filter((x) => x.us < (removedAt + 100) * 1000);
  const during = records.filter((x) => x.us > (removedAt + 300) * 1000 && x.us < (readdedAt - 100) * 1000);
  const after = records.filter((x) => x.us > readdedAt * 1000);
  assert.ok(before.length > 40, `rover.tlog lost the first session (${before.length} records)`);
  assert.equal(during.length, 0, 'rover.tlog has records from while it was removed');
  assert.ok(after.some((x) => x.msgid === ID.ODOMETRY && x.sysid === 2), 'rover.tlog lacks the second session');
  quad.close();
  rover.close();
}

main().catch(h.fail);
