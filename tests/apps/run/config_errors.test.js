// Bad input to `mocaplink run` (the run path; libs/config's own tests cover every rule): each case
// prints exactly its messages on stderr, exits 1, and sends nothing — a UDP listener at the
// vehicle's address receives no datagram.
'use strict';

const fs = require('node:fs');
const path = require('node:path');
const h = require('./harness');

const { assert } = h;

async function main() {
  const dir = h.tempDir('config');
  const vehicle = await new h.UdpVehicle().bind();
  const link = `udp://127.0.0.1:${vehicle.port}`;
  const good = `[mocap]\nsource = "sim://"\n[[vehicle]]\nname = "q"\nbody = "Body1"\n` +
    `link = "${link}"\nsystem_id = 1\nprofile = "px4"\n`;
  const cases = [
    { name: 'typo.toml', text: `${good}rat_hz = 3\n`, expected: [
      'typo.toml:9:1: vehicle[1].rat_hz: unknown key; did you mean "rate_hz"?',
      'mocaplink run: 1 error in the configuration (typo.toml); nothing was sent'] },
    { name: 'many.toml',
      text: `[mocap]\nsource = "bogus://x"\n[[vehicle]]\nname = "q"\nbody = "Body1"\n` +
        'link = "udp://255.255.255.255:14540"\nsystem_id = 0\n',
      expected: [
        'many.toml:2:10: mocap.source: unknown source scheme "bogus" (one of: natnet, qtm, replay, sim, vicon, vicon-udp, vrpn)',
        'many.toml:3:1: vehicle[1].profile: missing required key',
        'many.toml:6:8: vehicle[1].link: broadcast and multicast addresses are not allowed: pose ' +
          'messages have no target system, so every vehicle listening would fuse them; give ' +
          'each vehicle its own unicast address',
        'many.toml:7:13: vehicle[1].system_id: must be an integer from 1 to 255, got 0',
        'mocaplink run: 4 errors in the configuration (many.toml); nothing was sent'] },
    // A source not built in: refused exactly as `check` refuses it.
    { name: 'optitrack.toml', text: good.replace('sim://', 'optitrack://10.0.0.5'), expected: [
      'optitrack.toml:2:10: mocap.source: unknown source scheme "optitrack" (one of: natnet, qtm, replay, sim, vicon, vicon-udp, vrpn)',
      'mocaplink run: 1 error in the configuration (optitrack.toml); nothing was sent'] },
    { name: 'syntax.toml', text: '[mocap\n', expected: [
      "syntax.toml:1:7: TOML syntax error: Error while parsing table header: expected ']', saw '\\n'",
      'mocaplink run: 1 error in the configuration (syntax.toml); nothing was sent'] },
    { name: 'gps.toml', text: `${good.replace('"px4"', '"px4-gps"')}signing_key = "abc"\n`,
      expected: [
        'gps.toml:8:11: vehicle[1].profile: GPS-type messages (HIL_GPS, GPS_INPUT) need the ' +
          '[origin] table (latitude_deg, longitude_deg, altitude_m)',
        'gps.toml:9:15: vehicle[1].signing_key: must be 64 hexadecimal characters (a 32-byte ' +
          'secret) or "" for unsigned, got 3 characters',
        'mocaplink run: 2 errors in the configuration (gps.toml); nothing was sent'] },
    // A valid file made invalid by the command line: the option is named.
    { name: 'good.toml', text: good, args: ['--vehicle', 'q:rate_hz=0'], expected: [
      '--vehicle 1: rate_hz: must be above 0 and at most 500, got 0',
      'mocaplink run: 1 error in the configuration (good.toml); nothing was sent'] },
    { name: 'missing.toml', text: null, expected: [
      'missing.toml: cannot read the configuration file'] },
  ];
  for (const c of cases) {
    const file = path.join(dir, c.name);
    if (c.text !== null) fs.writeFileSync(file, c.text);
    const run = h.mocaplink(['run', '--config', file, ...(c.args || [])],
      { cwd: dir, env: { MOCAPLINK_STATE_DIR: path.join(dir, 'state') } });
    const { code } = await run.exited;
    const lines = run.stderr.trimEnd().split('\n').map((l) => l.replaceAll(`${dir}/`, ''));
    assert.deepEqual(lines, c.expected, `${c.name}: stderr`);
    assert.equal(code, 1, `${c.name}: exit code`);
  }
  // Command-line problems: exit 1 as well.
  const unknown = h.mocaplink(['run', '--bogus']);
  assert.equal((await unknown.exited).code, 1);
  assert.match(unknown.stderr, /--bogus/);
  // A source URL that parses but cannot be opened (missing replay file): exit 1, nothing sent.
  const replay = h.mocaplink(['run', '--config', path.join(dir, 'good.toml'), '--source',
    `replay://${path.join(dir, 'none.csv')}`], { env: { MOCAPLINK_STATE_DIR: dir } });
  assert.equal((await replay.exited).code, 1);
  assert.match(replay.stderr, /error source replay:\/\/.*none\.csv: .*cannot open/);

  await h.sleep(200);
  assert.equal(vehicle.datagrams, 0, 'a datagram was sent despite the bad configuration');
  vehicle.close();
  console.log(`ok: ${cases.length + 2} bad inputs rejected with exit 1`);
}

main().catch(h.fail);
