// Stream links through real OS plumbing: a vehicle on a serial port (a pty pair made by the
// pty_relay helper, whose master side is relayed to UDP here) and a vehicle behind a TCP server
// that drops the connection once: the bridge reconnects and the stream resumes. Both decoded as
// byte streams by node-mavlink.
'use strict';

const net = require('node:net');
const path = require('node:path');
const dgram = require('node:dgram');
const h = require('./harness');

const { assert, ID } = h;
const RELAY = process.env.PTY_RELAY_BIN;

async function main() {
  const dir = h.tempDir('stream');
  // Serial side: UDP socket ← pty_relay ← /dev/pts/N ← mocaplink.
  const serialPackets = [];
  const serialDecoder = new h.Decoder((packet) => serialPackets.push(packet));
  const relaySocket = dgram.createSocket('udp4');
  relaySocket.on('message', (msg) => serialDecoder.write(msg));
  await new Promise((r) => relaySocket.bind(0, '127.0.0.1', r));
  const relay = h.start([RELAY, String(relaySocket.address().port)]);
  await h.waitFor(() => relay.stdout.includes('\n'), 5000, 'pty_relay');
  const tty = relay.stdout.trim();

  // TCP side: a server that accepts, and closes the first connection after 40 packets.
  const tcpPackets = [[], []];
  const decoders = [];
  let connections = 0;
  const server = net.createServer((socket) => {
    const index = connections;
    connections += 1;
    const decoder = new h.Decoder((packet) => {
      if (index < 2) tcpPackets[index].push(packet);
      if (index === 0 && tcpPackets[0].length === 40) socket.destroy();
    });
    decoders.push(decoder);
    socket.on('data', (d) => decoder.write(d));
    socket.on('error', () => {});
  });
  await new Promise((r) => server.listen(0, '127.0.0.1', r));

  const config = h.writeConfig(path.join(dir, 'stream.toml'), 'sim://?bodies=2', [
    { name: 'ser', body: 'Body1', link: `serial://${tty}?baud=115200`, profile: 'px4',
      system_id: 7, rate_hz: 30 },
    { name: 'tcp', body: 'Body2', link: `tcp://127.0.0.1:${server.address().port}`,
      profile: 'ardupilot', system_id: 8, rate_hz: 30 },
  ]);
  const run = h.mocaplink(['run', '--config', config],
    { env: { MOCAPLINK_STATE_DIR: path.join(dir, 'state') } });
  await h.waitFor(() => tcpPackets[1].length >= 40 && serialPackets.length >= 60, 15000,
    `traffic on both links\n${run.stderr}`);
  // The summary (every 1 s here) warns in the period frames were dropped while the link was
  // down, and is info again in the next periods, with the run's total still shown.
  const tcpSummaries = () => run.stderr.split('\n').filter((l) => / vehicle tcp: .* Hz poses over the last/.test(l));
  const dropped = (line) => Number(/ (\d+) dropped,/.exec(line)[1]);
  await h.waitFor(() => {
    const lines = tcpSummaries();
    const w = lines.findIndex((l) => / warning /.test(l));
    return w >= 0 ? lines.slice(w + 1).some((l) => / info /.test(l)) : lines.length >= 4;
  }, 10000, `summaries of vehicle tcp\n${run.stderr}`);
  const summaries = tcpSummaries();
  const warned = summaries.findIndex((l) => / warning /.test(l));
  if (warned >= 0) {
    assert.ok(dropped(summaries[warned]) > 0, summaries[warned]);
    const later = summaries.slice(warned + 1).find((l) => / info /.test(l));
    assert.ok(dropped(later) >= dropped(summaries[warned]), later);
  }
  await h.stop(run);
  relay.child.kill('SIGTERM');
  server.close();
  relaySocket.close();

  const odometry = serialPackets.filter((p) => p.header.msgid === ID.ODOMETRY);
  assert.ok(odometry.length >= 30, `serial: ${odometry.length} ODOMETRY`);
  assert.ok(serialPackets.every((p) => p.header.sysid === 7), 'serial: foreign sysid');
  assert.equal(serialDecoder.invalid, 0, 'serial: CRC failures (bytes altered by the tty?)');
  assert.ok(connections >= 2, 'TCP: the bridge did not reconnect');
  for (const packets of tcpPackets) {
    assert.ok(packets.some((p) => p.header.msgid === ID.ODOMETRY), 'TCP: no ODOMETRY');
    assert.ok(packets.every((p) => p.header.sysid === 8), 'TCP: foreign sysid');
  }
  decoders.forEach((d) => assert.equal(d.invalid, 0, 'TCP: CRC failures'));
  assert.match(run.stderr, /vehicle tcp: link down/);
  console.log(`ok: serial ${serialPackets.length} packets via ${tty}; TCP ${connections} ` +
    `connections, ${tcpPackets[1].length} packets after the reconnect; summary ` +
    (warned >= 0 ? `warned of ${dropped(summaries[warned])} dropped, then info` : 'never warned (nothing dropped)'));
}

main().catch(h.fail);
