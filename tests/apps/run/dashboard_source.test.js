// The Station card's source state in the dashboard API of the real daemon (issue 6): with the
// Vicon server not there, /api/status says not connected and why; once `mocaplink serve` listens,
// the daemon connects by itself and the error goes away.
'use strict';

const net = require('node:net');
const path = require('node:path');
const h = require('./harness');

const { assert } = h;

/** A TCP port nobody listens on (bound, then closed). */
function freePort() {
  return new Promise((resolve) => {
    const server = net.createServer();
    server.listen(0, '127.0.0.1', () => {
      const { port } = server.address();
      server.close(() => resolve(port));
    });
  });
}

async function main() {
  const dir = h.tempDir('dash-source');
  const port = await freePort();
  const vehicle = await new h.UdpVehicle().bind();
  const config = h.writeConfig(path.join(dir, 'run.toml'), `vicon://127.0.0.1:${port}`, [
    { name: 'quad', body: 'Body1', link: `udp://127.0.0.1:${vehicle.port}`, system_id: 1, profile: 'px4' },
  ]);
  const run = h.mocaplink(['run', '--config', config]);
  const [, http] = await h.waitForLog(run, /dashboard: http:\/\/127\.0\.0\.1:(\d+)\//);
  const station = async () => (await (await fetch(`http://127.0.0.1:${http}/api/status`)).json()).station;

  let s;
  const deadline = Date.now() + 10000;
  while (!(s = await station()).error && Date.now() < deadline) await h.sleep(100);
  assert.equal(s.connected, false);
  assert.match(s.error, /refused/i, JSON.stringify(s));

  const server = h.mocaplink(['serve', '--protocol', 'vicon', '--from', 'sim', '--listen', `127.0.0.1:${port}`]);
  const until = Date.now() + 15000;  // the client's reconnect back-off is at most a few seconds
  while (!(s = await station()).connected && Date.now() < until) await h.sleep(100);
  assert.equal(s.connected, true, JSON.stringify(s));
  assert.equal(s.error, '');
  await h.waitFor(() => vehicle.ofId(h.ID.ODOMETRY).length > 0, 5000, 'poses once connected');

  await h.stop(run);
  await h.stop(server);
  vehicle.close();
}

main().catch(h.fail);
