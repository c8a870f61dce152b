// A VRPN server that stalls right after an incomplete round (issue 27): a tracker server written
// here from vrpn.md (cookie, descriptions, Pos_Quat, one write per update) reports Body1 at 50 Hz
// and Body2 at 25 Hz, ends on an update with Body1 alone (incomplete against the one before) and
// then sends nothing, connection open. What reaches the vehicle must be young: no ODOMETRY may
// arrive more than 250 ms (core::kMaxFrameWait) after the server's last report. The round is
// either sent at once or, if the client let it wait, skipped and counted by `run`; it must never
// go out as a fresh pose half a second later (it did: the client closed it at lost_ms = 500).
'use strict';

const net = require('node:net');
const path = require('node:path');
const h = require('./harness');

const { assert, ID } = h;
const PERIOD_MS = 20;
const UPDATES = 75;  // odd: the last update holds Body1 alone
const MAX_AGE_MS = 250;

function be32(n) { const b = Buffer.alloc(4); b.writeInt32BE(n); return b; }

/// One message (vrpn.md §3): header with the unpadded length, payload padded to 8.
function message(sender, type, payload) {
  const now = Date.now();
  const header = Buffer.concat([be32(24 + payload.length), be32(Math.floor(now / 1000)),
    be32((now % 1000) * 1000), be32(sender), be32(type), be32(0)]);
  const pad = Buffer.alloc((8 - (payload.length % 8)) % 8);
  return Buffer.concat([header, payload, pad]);
}

function describe(kind, id, name) {
  const bytes = Buffer.concat([Buffer.from(name), Buffer.alloc(1)]);
  return message(id, kind, Buffer.concat([be32(bytes.length), bytes]));
}

function posQuat(sender, x) {
  const p = Buffer.alloc(64);
  p.writeDoubleBE(x, 8);
  p.writeDoubleBE(1.0, 24);  // z up 1 m
  p.writeDoubleBE(1.0, 56);  // w = 1
  return message(sender, 0, p);
}

async function main() {
  const dir = h.tempDir('vrpn-stall');
  let lastReportAt = null;
  const sockets = [];
  const server = net.createServer((socket) => {
    sockets.push(socket);
    socket.setNoDelay(true);
    socket.write(Buffer.from('vrpn: ver. 07.38  0\0\0\0\0\0', 'latin1'));
    socket.once('data', () => {  // the client's cookie: now the descriptions, then updates
      socket.write(Buffer.concat([describe(-1, 0, 'VRPN Control'), describe(-1, 1, 'Body1'),
        describe(-1, 2, 'Body2'), describe(-2, 0, 'vrpn_Tracker Pos_Quat')]));
      let n = 0;
      const timer = setInterval(() => {
        n += 1;
        const parts = [posQuat(1, 0.001 * n)];
        if (n % 2 === 0) parts.push(posQuat(2, 2.0));
        socket.write(Buffer.concat(parts));
        lastReportAt = performance.now();
        if (n === UPDATES) clearInterval(timer);  // the stall: nothing more, socket open
      }, PERIOD_MS);
      socket.on('close', () => clearInterval(timer));
      socket.on('error', () => clearInterval(timer));
    });
  });
  await new Promise((r) => server.listen(0, '127.0.0.1', r));
  const url = `vrpn://127.0.0.1:${server.address().port}`;

  const vehicle = await new h.UdpVehicle().bind();
  const config = h.writeConfig(path.join(dir, 'run.toml'), url, [{
    name: 'quad1', body: 'Body1', link: `udp://127.0.0.1:${vehicle.port}`, system_id: 1,
    profile: 'px4', rate_hz: 100,
  }], 'up = "+z"\nnorth = "+x"\n[origin]\nlatitude_deg = 47.397742\n' +
    'longitude_deg = 8.545594\naltitude_m = 488.0\n');
  const run = h.mocaplink(['run', '--config', config]);
  await h.waitFor(() => vehicle.ofId(ID.ODOMETRY).length > 0, 10000,
    `first ODOMETRY\n${run.stderr}`);
  await h.waitFor(() => lastReportAt !== null && performance.now() > lastReportAt + 1500,
    20000, `the stall\n${run.stderr}`);
  await h.stop(run);
  sockets.forEach((s) => s.destroy());
  server.close();
  vehicle.close();

  const odometry = vehicle.ofId(ID.ODOMETRY);
  assert.ok(odometry.length > 20, `only ${odometry.length} ODOMETRY`);
  const after = odometry.filter(({ t }) => t > lastReportAt);
  for (const { t } of after) {
    assert.ok(t - lastReportAt <= MAX_AGE_MS,
      `ODOMETRY ${(t - lastReportAt).toFixed(0)} ms after the server's last report\n${run.stderr}`);
  }
  const final = run.stderr.match(/final: source .*?(\d+) late frames skipped/);
  assert.ok(final, `no final summary\n${run.stderr}`);
  // The last update (Body1 alone) is not lost either: sent young, or skipped and counted.
  assert.ok(after.length > 0 || Number(final[1]) > 0,
    `the last update was neither sent nor counted as skipped\n${run.stderr}`);
  console.log(`ok: ${odometry.length} ODOMETRY, ${after.length} after the last report ` +
    `(latest ${after.length ? (after[after.length - 1].t - lastReportAt).toFixed(1) : '-'} ms ` +
    `after it), ${final[1]} late frames skipped`);
}

main().catch(h.fail);
