// mocaplink.exe under Wine, end to end (issue 14): sim → `mocaplink.exe run` → a UDP vehicle on
// loopback (decoded by node-mavlink), the dashboard answering over HTTP, then Ctrl-C stopping it
// cleanly. The configuration sits in a directory with spaces in its name, `check` reports a Linux
// serial device with file:line and the Windows form, and the signing state is written on the
// clean stop to %LOCALAPPDATA%\mocaplink — Wine's own %LOCALAPPDATA% (it sets the variable from
// its user profile, under the Wine prefix, whatever the Unix environment says) — and the log to
// %LOCALAPPDATA%\mocaplink\logs\mocaplink.log.
//
// Wine turns a SIGINT to the process into the console's CTRL_C_EVENT, which the C runtime raises
// as SIGINT — the same path a Ctrl-C in a Windows console takes.
'use strict';

const fs = require('node:fs');
const os = require('node:os');
const path = require('node:path');
const h = require('../run/harness');

const { assert } = h;

/// The Wine (Windows) name of a Unix path: Wine's Z: drive is the Unix root.
const windowsPath = (unixPath) => `Z:${unixPath.replace(/\//g, '\\')}`;

async function main() {
  const dir = path.join(h.tempDir('wine'), 'lab files');
  fs.mkdirSync(dir, { recursive: true });
  const prefix = process.env.WINEPREFIX || path.join(os.homedir(), '.wine');
  const appData = path.join(prefix, 'drive_c', 'users', os.userInfo().username, 'AppData', 'Local',
    'mocaplink');
  const state = path.join(appData, 'quad1.signing');
  const log = path.join(appData, 'logs', 'mocaplink.log');
  fs.rmSync(state, { force: true });
  fs.rmSync(log, { force: true });
  const vehicle = await new h.UdpVehicle().bind();
  const config = h.writeConfig(path.join(dir, 'lab config.toml'), 'sim://?bodies=1&rate_hz=100', [
    { name: 'quad1', body: 'Body1', link: `udp://127.0.0.1:${vehicle.port}`, profile: 'classic',
      system_id: 1, rate_hz: 50, signing_key: 'ab'.repeat(32) },
  ], '[origin]\nlatitude_deg = 47.397742\nlongitude_deg = 8.545594\naltitude_m = 488.0\n');

  // `check` reports a Linux serial device with the file, line and the Windows form.
  const bad = path.join(dir, 'bad config.toml');
  fs.writeFileSync(bad, fs.readFileSync(config, 'utf8')
    .replace(`udp://127.0.0.1:${vehicle.port}`, 'serial:///dev/ttyUSB0?baud=57600'));
  const check = h.mocaplink(['check', windowsPath(bad)], { env: { WINEDEBUG: '-all' } });
  const checked = await check.exited;
  assert.notEqual(checked.code, 0, 'check accepted a Linux device path on Windows');
  assert.match(check.stdout + check.stderr, /bad config\.toml:\d+:\d+: .*serial device must be a COM port name, as in serial:\/\/COM3\?baud=921600, got "\/dev\/ttyUSB0"/);

  const proc = h.mocaplink(['run', '--config', windowsPath(config)], {
    env: { MOCAPLINK_STATE_DIR: '', WINEDEBUG: '-all' },
  });
  const [, port] = await h.waitForLog(proc, /dashboard: http:\/\/127\.0\.0\.1:(\d+)\//, 60000);

  // Poses arrive, signed, and decode with an independent MAVLink implementation.
  await h.waitFor(() => vehicle.ofId(h.ID.ATT_POS_MOCAP).length >= 50, 30000,
    `50 ATT_POS_MOCAP (got ${vehicle.packets.length} packets)`);
  assert.equal(vehicle.decoder.invalid, 0, 'frames with a bad CRC');
  assert.ok(vehicle.ofId(h.ID.ATT_POS_MOCAP).every((p) => p.packet.signature !== null),
    'unsigned ATT_POS_MOCAP on a signed link');

  // The dashboard answers over HTTP.
  const api = h.dashboardApi(Number(port));
  const status = await api('GET', '/api/status');
  assert.equal(status.status, 200);
  assert.equal(status.json.vehicles.length, 1);
  assert.equal(status.json.vehicles[0].name, 'quad1');

  // Ctrl-C: a clean stop, exit 0, and the signing timestamp saved under %LOCALAPPDATA%.
  proc.child.kill('SIGINT');
  const { code, signal } = await proc.exited;
  assert.equal(signal, null, `killed by ${signal}\n${proc.stderr}`);
  assert.equal(code, 0, `exit ${code}\n${proc.stderr}`);
  assert.match(proc.stderr, /stopping: SIGINT/);
  assert.match(fs.readFileSync(state, 'utf8'), /^mocaplink-signing-timestamp 1 [1-9]\d*\n$/);
  // The log is also in %LOCALAPPDATA%\mocaplink\logs (a closed console window keeps nothing),
  // where the first lines say it is, and it holds the whole run down to the clean stop.
  assert.match(proc.stderr, /log file: .*\\mocaplink\\logs\\mocaplink\.log/);
  const logged = fs.readFileSync(log, 'utf8');
  assert.match(logged, /info mocaplink [\d.]+: source sim:/);
  assert.match(logged, /stopping: SIGINT/);
  vehicle.close();
  console.log(`ok: ${vehicle.packets.length} packets decoded, dashboard on ${port}, ` +
    `clean stop on Ctrl-C, signing state in ${state}, log in ${log}`);
}

main().catch(h.fail);
