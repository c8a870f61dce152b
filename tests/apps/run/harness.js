// Test harness for `mocaplink run` end-to-end tests: starts real processes, listens on real
// sockets, and decodes everything with node-mavlink (an independent MAVLink implementation; see
// protocols/mavlink-wire.md §9 for what it may and may not be trusted with).
'use strict';

const assert = require('node:assert/strict');
const { spawn } = require('node:child_process');
const dgram = require('node:dgram');
const net = require('node:net');
const fs = require('node:fs');
const os = require('node:os');
const path = require('node:path');
const {
  MavLinkPacketSplitter, MavLinkPacketParser, minimal, common, standard, ardupilotmega,
} = require('node-mavlink');

const BIN = process.env.MOCAPLINK_BIN;
if (!BIN) throw new Error('MOCAPLINK_BIN is not set (CTest sets it to the built binary)');

// AUTOPILOT_VERSION is in node-mavlink's `standard` dialect, EKF_STATUS_REPORT in `ardupilotmega`.
const REGISTRY = {
  ...minimal.REGISTRY, ...standard.REGISTRY, ...common.REGISTRY, ...ardupilotmega.REGISTRY,
};

/// A fresh temporary directory, removed at exit.
function tempDir(prefix) {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), `mocaplink-${prefix}-`));
  process.on('exit', () => fs.rmSync(dir, { recursive: true, force: true }));
  return dir;
}

const started = [];

/// On failure: the error and the tail of every started process's stderr, then exit 1.
function fail(error) {
  console.error(error);
  for (const p of started) {
    console.error(`--- ${p.args.slice(0, 3).join(' ')} stderr (tail):\n${p.stderr.slice(-4000)}`);
  }
  process.exit(1);
}

/// Spawns a process and keeps its output. `proc.exited` resolves to {code, signal}.
function start(args, { env = {}, cwd } = {}) {
  const child = spawn(args[0], args.slice(1), {
    cwd,
    env: { ...process.env, MOCAPLINK_SUMMARY_S: '1', ...env },
    stdio: ['ignore', 'pipe', 'pipe'],
  });
  const proc = { child, stdout: '', stderr: '', args };
  started.push(proc);
  child.stdout.on('data', (d) => { proc.stdout += d; });
  child.stderr.on('data', (d) => { proc.stderr += d; });
  proc.exited = new Promise((resolve) => {
    child.on('exit', (code, signal) => resolve({ code, signal }));
  });
  process.on('exit', () => { if (child.exitCode === null) child.kill('SIGKILL'); });
  return proc;
}

/// `mocaplink ARGS...`.
function mocaplink(args, options) {
  return start([BIN, ...args], options);
}

/// Resolves when `predicate()` holds (polled every 10 ms); rejects after `timeoutMs`.
/// Waits until `predicate` (which may be async) returns something truthy.
async function waitFor(predicate, timeoutMs, what) {
  const deadline = Date.now() + timeoutMs;
  while (!(await predicate())) {
    if (Date.now() > deadline) throw new Error(`timed out waiting for ${what}`);
    await new Promise((r) => setTimeout(r, 10));
  }
}

const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

/// Decodes a byte stream (or datagrams) into packets with node-mavlink. Every packet that passes
/// its CRC check arrives in `onPacket(packet, receivedMs)`; CRC failures are counted by the
/// splitter (`invalid`).
class Decoder {
  constructor(onPacket) {
    this.splitter = new MavLinkPacketSplitter();
    this.parser = new MavLinkPacketParser();
    this.splitter.pipe(this.parser);
    this.parser.on('data', (packet) => onPacket(packet, performance.now()));
  }
  write(buffer) { this.splitter.write(buffer); }
  get invalid() { return this.splitter.invalidPackages; }
  get unknown() { return this.splitter.unknownPackagesCount; }
}

/// The typed message of a packet (node-mavlink class instance), or undefined for unknown ids.
function decode(packet) {
  const clazz = REGISTRY[packet.header.msgid];
  return clazz ? packet.protocol.data(packet.payload, clazz) : undefined;
}

/// A UDP "vehicle": binds 127.0.0.1:0, records every packet with its receive time (ms,
/// performance.now()), and remembers where the bridge sends from (for replies).
class UdpVehicle {
  constructor() {
    this.packets = [];
    this.datagrams = 0;
    // The largest receive buffer the kernel grants without privileges (net.core.rmem_max): a
    // busy machine can hold node's loop back for a while, and a full buffer drops datagrams that
    // the bridge did send (seen in /proc/net/snmp RcvbufErrors), which a test would blame on it.
    this.socket = dgram.createSocket({ type: 'udp4', recvBufferSize: 8 << 20 });
    this.decoder = new Decoder((packet, t) => this.packets.push({ packet, t }));
    this.socket.on('message', (msg, rinfo) => {
      this.datagrams += 1;
      this.peer = rinfo;
      this.decoder.write(msg);
    });
  }
  async bind() {
    await new Promise((r) => this.socket.bind(0, '127.0.0.1', r));
    this.port = this.socket.address().port;
    return this;
  }
  send(buffer) {
    if (!this.peer) throw new Error('no datagram received yet: reply address unknown');
    this.socket.send(buffer, this.peer.port, this.peer.address);
  }
  close() { this.socket.close(); }
  ofId(msgid) { return this.packets.filter((p) => p.packet.header.msgid === msgid); }
}

/// Message ids (MAVLink common.xml).
const ID = {
  HEARTBEAT: 0, LOCAL_POSITION_NED: 32, SET_GPS_GLOBAL_ORIGIN: 48, GPS_GLOBAL_ORIGIN: 49,
  COMMAND_LONG: 76, VISION_POSITION_ESTIMATE: 102, VISION_SPEED_ESTIMATE: 103, TIMESYNC: 111,
  HIL_GPS: 113, ATT_POS_MOCAP: 138, GPS_INPUT: 232, ODOMETRY: 331,
};

/// A UDP port free on 127.0.0.1 right now (bound, then closed; the caller's process binds it next).
async function freeUdpPort() {
  const s = dgram.createSocket('udp4');
  await new Promise((resolve) => s.bind(0, '127.0.0.1', resolve));
  const { port } = s.address();
  await new Promise((resolve) => s.close(resolve));
  return port;
}

/// A TCP port free on 127.0.0.1 right now (listened on, then closed).
async function freeTcpPort() {
  const server = net.createServer();
  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  const { port } = server.address();
  await new Promise((resolve) => server.close(resolve));
  return port;
}

/// Waits for `proc` to print a line matching `re` on stderr; returns the match.
async function waitForLog(proc, re, timeoutMs = 10000) {
  let m = null;
  await waitFor(() => (m = proc.stderr.match(re)) !== null, timeoutMs, `log ${re}\n${proc.stderr}`);
  return m;
}

/// Writes a run configuration: `source` and vehicles given as objects of [[vehicle]] keys
/// (strings quoted, numbers as is).
function writeConfig(file, source, vehicles, extra = '') {
  const value = (v) => (typeof v === 'number' ? String(v) : JSON.stringify(v));
  const blocks = vehicles.map((v) => `[[vehicle]]\n${Object.entries(v)
    .map(([k, x]) => `${k} = ${value(x)}`).join('\n')}\n`);
  // [http] on port 0: parallel tests must not compete for the dashboard's default port 8080.
  fs.writeFileSync(file, `[mocap]\nsource = ${JSON.stringify(source)}\n${extra}\n` +
    `[http]\nlisten = "127.0.0.1:0"\n${blocks.join('')}`);
  return file;
}

/// A client of the dashboard API on `port`: api(method, route, body?) → { status, json, headers }.
function dashboardApi(port) {
  return async (method, route, body) => {
    const response = await fetch(`http://127.0.0.1:${port}${route}`, {
      method,
      headers: body === undefined ? {} : { 'Content-Type': 'application/json' },
      body: body === undefined ? undefined : JSON.stringify(body),
    });
    const text = await response.text();
    return { status: response.status, json: text ? JSON.parse(text) : undefined, headers: response.headers };
  };
}

/// Sends SIGTERM and waits for the exit; asserts a clean exit (0).
async function stop(proc) {
  proc.child.kill('SIGTERM');
  const { code, signal } = await proc.exited;
  assert.equal(signal, null, `killed by ${signal}\n${proc.stderr}`);
  assert.equal(code, 0, `exit ${code}\n${proc.stderr}`);
}

module.exports = {
  assert, BIN, dashboardApi, Decoder, fail, freeTcpPort, freeUdpPort, ID, UdpVehicle, decode, mocaplink, sleep, start, stop, tempDir, writeConfig, waitFor,
  waitForLog,
};
