// A dashboard PATCH goes through the configuration's rules like a file (issue 11): the real
// daemon, the sim source, one ArduPilot vehicle on a UDP link. A PATCH to 60 Hz is applied and
// gets the ArduPilot > 50 Hz warning a [[vehicle]] table with rate_hz = 60 gets (in the daemon's
// log); refusals carry the configuration's messages; a later add is checked against the patched
// state (the daemon's configuration is current, not the file's).
'use strict';

const path = require('node:path');
const h = require('./harness');

const { assert } = h;

const kArduWarning = "ArduPilot's external-navigation input is meant for at most 50 Hz";

async function main() {
  const dir = h.tempDir('dash-patch');
  const ardu = await new h.UdpVehicle().bind();
  const config = h.writeConfig(path.join(dir, 'run.toml'), 'sim://?rate_hz=200', [
    { name: 'ardu', body: 'Body1', link: `udp://127.0.0.1:${ardu.port}`, system_id: 1, profile: 'ardupilot',
      rate_hz: 30 },
  ]);
  const run = h.mocaplink(['run', '--config', config]);
  const [, port] = await h.waitForLog(run, /dashboard: http:\/\/127\.0\.0\.1:(\d+)\//);
  assert.ok(!run.stderr.includes(kArduWarning), `a warning at 30 Hz:\n${run.stderr}`);
  const api = h.dashboardApi(port);

  // Above 50 Hz: applied, with the file's warning in the log (the API answer is the vehicle).
  const fast = await api('PATCH', '/api/vehicles/ardu', { rate_hz: 60 });
  assert.equal(fast.status, 200, JSON.stringify(fast.json));
  assert.equal(fast.json.rate_hz, 60);
  await h.waitForLog(run, new RegExp(`warning.*dashboard: PATCH /api/vehicles/ardu: rate_hz: ${kArduWarning}`));
  await h.waitForLog(run, /dashboard: vehicle ardu: rate_hz=60/);

  // Refusals: the configuration's messages and keys; nothing changes.
  const refused = async (body, field, re) => {
    const answer = await api('PATCH', '/api/vehicles/ardu', body);
    assert.equal(answer.status, 422, JSON.stringify(answer.json));
    assert.equal(answer.json.field, field, JSON.stringify(answer.json));
    assert.match(answer.json.error, re);
  };
  await refused({ rate_hz: 0, paused: true }, 'rate_hz', /^rate_hz: must be above 0 and at most 500, got 0$/);
  await refused({ messages: ['odometry', 'teleport'] }, 'messages', /^messages: unknown message "teleport"/);
  await refused({ messages: ['hil_gps'] }, 'messages', /^messages: GPS-type messages .* need the \[origin\] table/);
  const now = (await api('GET', '/api/vehicles/ardu')).json;
  assert.equal(now.rate_hz, 60);
  assert.equal(now.paused, false);

  // A later add is checked against the state now: the patched vehicle is there, on its link.
  const clash = await api('POST', '/api/vehicles',
    { name: 'ardu2', body: 'Body2', link: `udp://127.0.0.1:${ardu.port}`, system_id: 1, profile: 'ardupilot' });
  assert.equal(clash.status, 422, JSON.stringify(clash.json));
  assert.equal(clash.json.field, 'system_id');
  assert.match(clash.json.error, /system_id 1 is already used on udp:\/\/127\.0\.0\.1:\d+ by vehicle "ardu"/);
  // The warning belongs to the PATCH that set 60 Hz: an add does not repeat it, a later PATCH
  // within range gives none.
  const warnings = () => run.stderr.split(kArduWarning).length - 1;
  assert.equal(warnings(), 1, run.stderr);
  const other = await new h.UdpVehicle().bind();
  assert.equal((await api('POST', '/api/vehicles',
    { name: 'ardu2', body: 'Body2', link: `udp://127.0.0.1:${other.port}`, system_id: 2, profile: 'ardupilot',
      rate_hz: 70 })).status, 201);
  await h.waitForLog(run, /dashboard: POST \/api\/vehicles: rate_hz: ArduPilot's external-navigation/);
  assert.equal((await api('PATCH', '/api/vehicles/ardu', { rate_hz: 40 })).status, 200);
  await h.waitForLog(run, /dashboard: vehicle ardu: rate_hz=40/);
  assert.equal(warnings(), 2, run.stderr);

  await h.stop(run);
  ardu.close();
  other.close();
}

main().catch(h.fail);
