// The set-up list against a scripted PX4 1.14 on a real UDP socket (issue 28), with the real daemon
// (node-mavlink encodes and decodes). The vehicle answers as PX4's mavlink_parameters.cpp does:
// PARAM_REQUEST_READ by name with the int32's bytes in the float (PARAM_ENCODE_BYTEWISE, which its
// AUTOPILOT_VERSION capabilities announce), silence for a name it does not have, PARAM_SET with the
// new PARAM_VALUE. It is left at PX4's defaults for GPS flight: vision fusion off (EKF2_EV_CTRL 0),
// height from the barometer (EKF2_HGT_REF 1).
//
// Checked: the list names exactly the wrong parameters with the needed values; nothing is written
// before the operator asks; a request naming a parameter not on the list writes nothing; the named
// fixes are written (bytewise), confirmed and the list turns ready; an armed vehicle is refused.
'use strict';

const path = require('node:path');
const { MavLinkProtocolV2, common } = require('node-mavlink');
const h = require('./harness');

const { assert, ID } = h;
const { INT32, i32, f32, scriptedPx4 } = require('./scripted_px4');

async function main() {
  const dir = h.tempDir('setup');
  const link = await new h.UdpVehicle().bind();
  const config = h.writeConfig(path.join(dir, 'run.toml'), 'sim://?bodies=1&rate_hz=100', [
    { name: 'quad', body: 'Body1', link: `udp://127.0.0.1:${link.port}`, system_id: 1,
      profile: 'px4', rate_hz: 30 },
  ]);
  const run = h.mocaplink(['run', '--config', config]);
  const [, port] = await h.waitForLog(run, /dashboard: http:\/\/127\.0\.0\.1:(\d+)\//);
  const api = h.dashboardApi(port);
  const vehicle = async () => (await api('GET', '/api/vehicles/quad')).json;
  await h.waitFor(() => link.peer !== undefined, 10000, 'first datagram');
  const px4 = scriptedPx4(link, 1);
  try {
    let v;
    await h.waitFor(async () => {
      v = await vehicle();
      return v.setup.state === 'blocked' || v.setup.state === 'ready';
    }, 20000, `set-up list\n${run.stderr}`);
    assert.deepEqual(v.autopilot, { name: 'px4', version: '1.14.3', profile_in_effect: 'px4' });
    assert.equal(v.setup.state, 'blocked', JSON.stringify(v.setup));
    const item = (name) => v.setup.items.find((i) => i.parameter === name);
    const wrong = v.setup.items.filter((i) => i.status === 'wrong').map((i) => i.parameter).sort();
    // EKF2_EV_DELAY: the recommendation needs the TIMESYNC round trip; any status but wrong is fine.
    assert.deepEqual(wrong.filter((n) => n !== 'EKF2_EV_DELAY'), ['EKF2_EV_CTRL', 'EKF2_HGT_REF']);
    assert.equal(item('EKF2_EV_CTRL').current, 0);
    assert.equal(item('EKF2_EV_CTRL').severity, 'blocks');
    assert.equal(item('EKF2_EV_CTRL').fix, 15);
    assert.equal(item('EKF2_HGT_REF').severity, 'degrades');
    assert.equal(item('EKF2_HGT_REF').reboot, true);
    assert.equal(item('EKF2_GPS_CTRL').status, 'ok');
    assert.equal(item('EKF2_MAG_TYPE').status, 'ok');
    // One read per parameter (all answered; at most the 3 tries each), addressed to the autopilot.
    for (const name of px4.params.keys()) {
      const reads = px4.reads.filter((r) => r.name === name);
      assert.ok(reads.length >= 1 && reads.length <= 3, `${name}: ${reads.length} reads`);
      assert.deepEqual(reads[0].target, [1, 1]);
      assert.equal(reads[0].index, -1);
    }
    assert.equal(px4.sets.length, 0, 'nothing written before the operator asked');
    assert.match(run.stderr, /set-up blocked: EKF2_EV_CTRL is 0, needs 15/);
    await h.waitFor(async () => (await vehicle()).statustext.some((t) => /ekf2 missing data/.test(t.text)),
      5000, 'STATUSTEXT on the API');
    assert.match(run.stderr, /vehicle says \(warning\): Preflight Fail: ekf2 missing data/);
    const blocked = (await api('GET', '/api/status')).json.alerts.find((a) => a.kind === 'setup_blocked');
    assert.ok(blocked, 'setup_blocked alert');
    assert.match(blocked.message, /EKF2_EV_CTRL/);

    // A parameter not on the list: refused, nothing written.
    const unseen = await api('POST', '/api/vehicles/quad/setup', { apply: ['EKF2_EV_CTRL', 'COM_ARM_WO_GPS'] });
    assert.equal(unseen.status, 409, JSON.stringify(unseen.json));
    assert.equal(unseen.json.field, 'apply');
    const malformed = await api('POST', '/api/vehicles/quad/setup', { apply: 'EKF2_EV_CTRL' });
    assert.equal(malformed.status, 422);
    await h.sleep(1500);
    assert.equal(px4.sets.length, 0, 'a refused request writes nothing');

    // The named fixes: written bytewise to the autopilot, confirmed, the list turns ready.
    const applied = await api('POST', '/api/vehicles/quad/setup', { apply: ['EKF2_EV_CTRL', 'EKF2_HGT_REF'] });
    assert.equal(applied.status, 200, JSON.stringify(applied.json));
    const confirmed = (x, name) => x.setup.items.find((i) => i.parameter === name).apply === 'confirmed';
    await h.waitFor(async () => {
      v = await vehicle();
      return confirmed(v, 'EKF2_EV_CTRL') && confirmed(v, 'EKF2_HGT_REF');
    }, 10000, `both confirmed after apply\n${JSON.stringify(v && v.setup)}\n${run.stderr}`);
    assert.equal(v.setup.state, 'ready');
    assert.deepEqual(px4.sets.map((x) => [x.name, i32(x.raw), x.type, ...x.target]).sort(),
      [['EKF2_EV_CTRL', 15, INT32, 1, 1], ['EKF2_HGT_REF', 3, INT32, 1, 1]]);
    assert.equal(px4.params.get('EKF2_MAG_TYPE')[0], 5, 'untouched');
    assert.equal(v.setup.items.find((i) => i.parameter === 'EKF2_EV_CTRL').apply, 'confirmed');
    assert.deepEqual(v.setup.reboot_for, ['EKF2_HGT_REF']);
    assert.match(run.stderr, /EKF2_EV_CTRL set to 15 \(confirmed by the vehicle\)/);

    // Armed: refused, and so is a reboot.
    px4.armed = true;
    px4.params.set('EKF2_GPS_CTRL', [7, INT32]);  // a ground station turns GNSS fusion on...
    const announce = new common.ParamValue();    // ...and the vehicle announces it
    announce.paramId = 'EKF2_GPS_CTRL';
    announce.paramType = INT32;
    announce.paramValue = f32(7);
    link.send(new MavLinkProtocolV2(1, 1).serialize(announce, 200));
    await h.waitFor(async () => (v = await vehicle()).heartbeat.armed &&
      v.setup.items.find((i) => i.parameter === 'EKF2_GPS_CTRL').status === 'wrong', 5000, 'armed, GPS_CTRL 7');
    const armed = await api('POST', '/api/vehicles/quad/setup', { apply: ['EKF2_GPS_CTRL'] });
    assert.equal(armed.status, 409);
    assert.match(armed.json.error, /armed/);
    const reboot = await api('POST', '/api/vehicles/quad/setup', { reboot: true });
    assert.equal(reboot.status, 409);
    await h.sleep(1500);
    assert.equal(px4.sets.length, 2, 'nothing written to an armed vehicle');
    assert.equal(px4.versionRequests >= 1, true);
  } finally {
    clearInterval(px4.timer);
    await h.stop(run);
    link.close();
  }
}

/// `mocaplink vehicle setup` against a fresh scripted PX4: the same list, exit 3 while it blocks;
/// --apply writes exactly the wrong items it printed, then exit 0.
async function cli() {
  const dir = h.tempDir('setup-cli');
  const link = await new h.UdpVehicle().bind();
  const config = h.writeConfig(path.join(dir, 'run.toml'), 'sim://?bodies=1', [
    { name: 'quad', body: 'Body1', link: `udp://127.0.0.1:${link.port}`, system_id: 1, profile: 'auto' },
  ]);
  const setup = async (args) => {
    const proc = h.mocaplink(['vehicle', 'setup', '--config', config, 'quad', '--timeout', '20', ...args]);
    // Its HEARTBEAT tells the vehicle where to answer (as from a ground station).
    await h.waitFor(() => link.peer !== undefined, 10000, `a HEARTBEAT from the CLI\n${proc.stderr}`);
    return proc;
  };
  const first = await setup(['--json']);
  const px4 = scriptedPx4(link, 1);
  try {
    const { code } = await first.exited;
    assert.equal(code, 3, `exit ${code}\n${first.stdout}\n${first.stderr}`);
    const listed = JSON.parse(first.stdout);
    assert.equal(listed.setup.state, 'blocked');
    assert.equal(listed.autopilot.profile_in_effect, 'px4');  // auto on a PX4
    assert.deepEqual(listed.setup.items.filter((i) => i.status === 'wrong').map((i) => i.parameter).sort(),
      ['EKF2_EV_CTRL', 'EKF2_HGT_REF']);
    assert.equal(px4.sets.length, 0, 'nothing written without --apply');
    // No pose, no origin, no TIMESYNC from the CLI: only HEARTBEAT and the set-up's requests.
    const ids = new Set(link.packets.map((p) => p.packet.header.msgid));
    for (const id of [ID.ODOMETRY, ID.SET_GPS_GLOBAL_ORIGIN, ID.TIMESYNC]) assert.ok(!ids.has(id), `sent ${id}`);

    const second = h.mocaplink(['vehicle', 'setup', '--config', config, 'quad', '--apply', '--timeout', '20']);
    const { code: applied } = await second.exited;
    assert.equal(applied, 0, `exit ${applied}\n${second.stdout}\n${second.stderr}`);
    assert.deepEqual(px4.sets.map((x) => [x.name, i32(x.raw)]).sort(), [['EKF2_EV_CTRL', 15], ['EKF2_HGT_REF', 3]]);
    assert.match(second.stdout, /set-up blocked/);  // the list it wrote from...
    assert.match(second.stdout, /set-up ready/);    // ...and the list after
    assert.match(second.stdout, /reboot the vehicle for EKF2_HGT_REF/);
  } finally {
    clearInterval(px4.timer);
    link.close();
  }
}

main().then(cli).catch(h.fail);
