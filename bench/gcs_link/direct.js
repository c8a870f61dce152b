// bench/gcs_link: the reference for the ground station's traffic — the ground station with the
// serial link to itself, as if QGroundControl had the radio (no mocaplink, no poses). Forwards
// unchanged bytes between the pty (argv[2]) and the last UDP peer of 127.0.0.1:PORT (argv[3]),
// the way the `direct-*` conditions of run_gcs_link.js use it.
'use strict';

const dgram = require('node:dgram');
const fs = require('node:fs');
const tty = require('node:tty');

const [ttyPath, portText] = process.argv.slice(2);
const input = new tty.ReadStream(fs.openSync(ttyPath, fs.constants.O_RDONLY | fs.constants.O_NOCTTY));
const output = new tty.WriteStream(fs.openSync(ttyPath, fs.constants.O_WRONLY | fs.constants.O_NOCTTY));
input.setRawMode(true);
const socket = dgram.createSocket('udp4');
let peer = null;
socket.on('message', (datagram, from) => {
  peer = from;
  output.write(datagram);
});
input.on('data', (chunk) => {
  if (peer) socket.send(chunk, peer.port, peer.address);
});
socket.bind(Number(portText), '127.0.0.1', () => process.send({ cmd: 'ready' }));
process.on('message', (message) => {
  if (message.cmd === 'exit') process.exit(0);
});
