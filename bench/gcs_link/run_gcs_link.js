#!/usr/bin/env node
// bench/gcs_link: a ground station on the vehicle's serial link, through mocaplink — poses first
// (issue 38). Measures what a ground station's traffic does to the poses, and what of it gets
// through, over an emulated UART.
//
// Set-up, per run: gcs_uart_relay (uart_relay.cpp) joins two ptys as a serial cable at BAUD
// (baud/10 bytes/s each way, full duplex, a 4 KiB driver buffer); `mocaplink run` opens one end
// (`link = "serial:///dev/pts/N?baud=BAUD"`, profile ardupilot, source
// sim://?bodies=1&rate_hz=100, rate_hz 15 at 57600 and 50 at 921600 unless --rate says otherwise)
// and the scripted vehicle (vehicle.js: ArduPilot-like, ~1000 parameters, 50 logs) the other.
// Conditions, in this order in every repetition:
//   baseline  no `gcs` key: today's pose stream alone;
//   idle      `gcs = ["udpin://127.0.0.1:PORT"]`, no ground station connected;
//   download  a ground station (gcs.js, as QGroundControl: HEARTBEAT 1 Hz as a GCS, system 255)
//             downloading all parameters (re-requesting missing ones by index) and the log list,
//             over and over;
//   upload    a ground station uploading a 200-item mission over and over (MISSION_COUNT,
//             MISSION_REQUEST_INT / MISSION_ITEM_INT, MISSION_ACK) — the heavy direction toward
//             the vehicle;
//   direct-download, direct-upload   the reference for the ground station's traffic: the same
//             ground station with the link to itself (direct.js forwards UDP to the pty as is; no
//             mocaplink, no poses), as if it had the radio alone.
// Each run warms up (--warmup, 5 s: the vehicle's set-up reads, the ground station's connection)
// and then measures for --seconds (20):
//   * pose latency, per ODOMETRY the vehicle receives: from when mocaplink wrote it (the relay
//     read its last byte from the pty; exact while the relay's queue is not full, see "full ms")
//     to when the vehicle had it complete ("write→vehicle"), and from its time_usec, the
//     estimated capture time on mocaplink's steady clock, to the same moment ("capture→vehicle":
//     includes anything mocaplink held it for) — CLOCK_MONOTONIC throughout; p50 and p99;
//   * the pose rate the vehicle receives;
//   * ground-station traffic each way: frames/s and bytes/s the ground station sent and the
//     vehicle received from system 255, and the vehicle's frames/s and bytes/s the ground station
//     received; the difference toward the vehicle is what was lost (dropped by mocaplink: poses
//     first; ± the few frames in flight at the window's edges), and what mocaplink itself
//     reports dropped in the window, from /api/status's vehicle at the end minus at the start:
//     toward the vehicle the counters named *forward*drop* (`link_share.forwarded_dropped`),
//     toward the ground station those named drop under `gcs` (`gcs[i].dropped`: also what had
//     no ground station to go to); every counter under `gcs` or `link_share`/forward* is in the JSON;
//   * completed parameter downloads, log listings and mission uploads, with their median time;
//   * the emulated line's use toward the vehicle and how long the relay's queue was full;
//   * the CPU each process used over the window (% of one core; mocaplink's in the table).
// Medians over --runs (3) repetitions; a markdown table on stdout, everything as JSON (--json FILE,
// default stdout's tail).
// Conditions that need `gcs` are skipped (and said so) when `mocaplink check` refuses the key.
// The direct conditions give the ground station's own figures a reference: what fraction of its
// traffic it keeps when it shares the link with the poses.
//
// Usage: node bench/gcs_link/run_gcs_link.js --mocaplink BIN --relay BIN [--seconds 20]
//   [--runs 3] [--warmup 5] [--bauds 57600,921600] [--rate 57600:15,921600:50]
//   [--conditions baseline,idle,download,upload,direct-download,direct-upload] [--json FILE]
//   [--raw 1]   (--raw 1: every pose's times in the JSON, to see when a p99 happened)
// Build: cmake --build --preset ci --target mocaplink gcs_uart_relay (build/ci/mocaplink,
// build/ci/bench/gcs_uart_relay). Takes ~(seconds + 8) × conditions × runs × bauds seconds.
'use strict';

const { spawn, fork, spawnSync } = require('node:child_process');
const fs = require('node:fs');
const net = require('node:net');
const os = require('node:os');
const path = require('node:path');
const readline = require('node:readline');

// --- Options. ------------------------------------------------------------------------------------
function parseArgs(argv) {
  const o = { seconds: 20, runs: 3, warmup: 5, bauds: [57600, 921600],
              rate: { 57600: 15, 921600: 50 }, conditions: ['baseline', 'idle', 'download', 'upload', 'direct-download',
                           'direct-upload'],
              json: null, mocaplink: null, relay: null, raw: false };
  for (let i = 0; i < argv.length; i += 2) {
    const [key, value] = [argv[i], argv[i + 1]];
    if (value === undefined) throw new Error(`${key} needs a value`);
    if (key === '--mocaplink') o.mocaplink = path.resolve(value);
    else if (key === '--relay') o.relay = path.resolve(value);
    else if (key === '--seconds') o.seconds = Number(value);
    else if (key === '--runs') o.runs = Number(value);
    else if (key === '--warmup') o.warmup = Number(value);
    else if (key === '--bauds') o.bauds = value.split(',').map(Number);
    else if (key === '--rate') {
      for (const pair of value.split(',')) {
        const [baud, hz] = pair.split(':').map(Number);
        o.rate[baud] = hz;
      }
    } else if (key === '--conditions') o.conditions = value.split(',');
    else if (key === '--json') o.json = value;
    else if (key === '--raw') o.raw = value === '1';
    else throw new Error(`unknown option ${key}`);
  }
  if (!o.mocaplink || !o.relay) throw new Error('--mocaplink BIN and --relay BIN are required');
  for (const b of o.bauds) if (!o.rate[b]) throw new Error(`no --rate for ${b} baud`);
  return o;
}

// --- Small helpers. ------------------------------------------------------------------------------
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
const nowNs = () => process.hrtime.bigint();

async function waitFor(predicate, timeoutMs, what) {
  const deadline = Date.now() + timeoutMs;
  while (!predicate()) {
    if (Date.now() > deadline) throw new Error(`timed out waiting for ${what}`);
    await sleep(20);
  }
}

function quantile(values, q) {
  if (values.length === 0) return null;
  const sorted = [...values].sort((a, b) => a - b);
  return sorted[Math.min(sorted.length - 1, Math.floor(q * sorted.length))];
}
const median = (values) => {
  const v = values.filter((x) => x !== null && x !== undefined && !Number.isNaN(x));
  if (v.length === 0) return null;
  const s = [...v].sort((a, b) => a - b);
  return s.length % 2 ? s[(s.length - 1) / 2] : (s[s.length / 2 - 1] + s[s.length / 2]) / 2;
};

/// CPU time (user + system) a process has used, in seconds; null once it is gone.
function cpuSeconds(pid) {
  try {
    const stat = fs.readFileSync(`/proc/${pid}/stat`, 'utf8');
    const fields = stat.slice(stat.lastIndexOf(')') + 2).split(' ');
    return (Number(fields[11]) + Number(fields[12])) / 100;  // utime, stime in USER_HZ (100)
  } catch {
    return null;
  }
}

async function freePort(kind) {
  if (kind === 'tcp') {
    const server = net.createServer();
    await new Promise((r) => server.listen(0, '127.0.0.1', r));
    const { port } = server.address();
    await new Promise((r) => server.close(r));
    return port;
  }
  const dgram = require('node:dgram');
  const s = dgram.createSocket('udp4');
  await new Promise((r) => s.bind(0, '127.0.0.1', r));
  const { port } = s.address();
  await new Promise((r) => s.close(r));
  return port;
}

function writeConfig(file, { tty, baud, rateHz, gcsPort, httpPort }) {
  const gcs = gcsPort ? `gcs = ["udpin://127.0.0.1:${gcsPort}"]\n` : '';
  fs.writeFileSync(file, `[mocap]\nsource = "sim://?bodies=1&rate_hz=100"\n\n` +
    `[http]\nlisten = "127.0.0.1:${httpPort}"\n\n[[vehicle]]\nname = "quad"\nbody = "Body1"\n` +
    `link = "serial://${tty}?baud=${baud}"\nprofile = "ardupilot"\nsystem_id = 1\n` +
    `rate_hz = ${rateHz}\n${gcs}`);
}

/// Does this mocaplink know the `gcs` key? (`check` of a config that has one.)
function gcsSupported(bin, dir) {
  const file = path.join(dir, 'probe.toml');
  writeConfig(file, { tty: '/dev/pts/0', baud: 57600, rateHz: 15, gcsPort: 14550, httpPort: 8080 });
  const r = spawnSync(bin, ['check', file], { encoding: 'utf8' });
  return { ok: r.status === 0, output: `${r.stdout}${r.stderr}`.trim() };
}

/// Numeric leaves of `value` whose path names `gcs`, as {path: number}.
function gcsCounters(value, at = '', inside = false, out = {}) {
  if (value === null || value === undefined) return out;
  if (typeof value === 'number') {
    if (inside) out[at] = value;
  } else if (typeof value === 'object') {
    for (const [k, v] of Object.entries(value)) {
      gcsCounters(v, at ? `${at}.${k}` : k, inside || /gcs|ground|forward|share/i.test(k), out);
    }
  }
  return out;
}

// Every process started, ended with the bench (also when it is interrupted).
const children = new Set();
function track(child) {
  children.add(child);
  child.on('exit', () => children.delete(child));
  return child;
}
for (const signal of ['SIGINT', 'SIGTERM']) {
  process.on(signal, () => {
    for (const child of children) child.kill('SIGKILL');
    process.exit(1);
  });
}

// --- One child process talking over IPC. -----------------------------------------------------------
function forkChild(script, args) {
  const child = track(fork(path.join(__dirname, script), args,
    { stdio: ['ignore', 'inherit', 'pipe', 'ipc'] }));
  const proc = { child, messages: [], stderr: '' };
  child.stderr.on('data', (d) => { proc.stderr += d; });
  child.on('message', (m) => proc.messages.push(m));
  proc.ask = async (cmd, reply, timeoutMs = 10000) => {
    const from = proc.messages.length;
    child.send({ cmd });
    await waitFor(() => proc.messages.slice(from).some((m) => m.cmd === reply), timeoutMs,
      `${script} ${reply}\n${proc.stderr}`);
    return proc.messages.slice(from).find((m) => m.cmd === reply);
  };
  proc.exited = new Promise((r) => child.on('exit', r));
  return proc;
}

// --- One run. -------------------------------------------------------------------------------------
async function measure(o, baud, condition, dir) {
  const relay = track(spawn(o.relay, [String(baud)], { stdio: ['ignore', 'pipe', 'inherit'] }));
  const relayOut = { a: null, b: null, odometry: new Map(), stats: [] };
  readline.createInterface({ input: relay.stdout }).on('line', (line) => {
    const f = line.split(' ');
    if (f[0] === 'A') relayOut.a = f[1];
    else if (f[0] === 'B') relayOut.b = f[1];
    else if (f[0] === 'O') {
      relayOut.odometry.set(f[1], { readNs: BigInt(f[2]), doneNs: BigInt(f[3]), ahead: Number(f[4]) });
    } else if (f[0] === 'S') relayOut.stats.push(f.slice(1).map(BigInt));
  });
  const started = [];
  let run = null;
  try {
    await waitFor(() => relayOut.a && relayOut.b, 5000, 'gcs_uart_relay');
    const vehicle = forkChild('vehicle.js', [relayOut.b, String(baud)]);
    started.push(vehicle);
    await waitFor(() => vehicle.messages.some((m) => m.cmd === 'ready'), 5000, 'vehicle');

    const gcsPort = condition === 'baseline' ? null : await freePort('udp');
    const direct = condition.startsWith('direct-');
    const task = condition.replace('direct-', '');
    let runLog = '';
    let runExit = null;
    let httpPort = null;
    if (direct) {
      const forwarder = forkChild('direct.js', [relayOut.a, String(gcsPort)]);
      started.push(forwarder);
      await waitFor(() => forwarder.messages.some((m) => m.cmd === 'ready'), 5000, 'direct.js');
    } else {
      httpPort = await freePort('tcp');
      const config = path.join(dir, `${baud}-${condition}.toml`);
      writeConfig(config, { tty: relayOut.a, baud, rateHz: o.rate[baud], gcsPort, httpPort });
      run = track(spawn(o.mocaplink, ['run', '--config', config], {
        env: { ...process.env, MOCAPLINK_STATE_DIR: path.join(dir, `state-${baud}-${condition}`) },
        stdio: ['ignore', 'ignore', 'pipe'] }));
      run.stderr.on('data', (d) => { runLog += d; });
      runExit = new Promise((r) => run.on('exit', (code, signal) => r({ code, signal })));
      await waitFor(() => relayOut.odometry.size > 0, 15000, `poses on the link\n${runLog}`);
    }

    let gcs = null;
    if (task === 'download' || task === 'upload') {
      gcs = forkChild('gcs.js', [String(gcsPort), task]);
      started.push(gcs);
      await waitFor(() => gcs.messages.some((m) => m.cmd === 'ready'), 15000,
        `the ground station to hear the vehicle through mocaplink\n${runLog}`);
    }
    await sleep(o.warmup * 1000);

    await vehicle.ask('mark', 'marked');
    if (gcs) await gcs.ask('mark', 'marked');
    const markNs = nowNs();
    const pids = { mocaplink: run ? run.pid : null, relay: relay.pid,
                   vehicle: vehicle.child.pid, gcs: gcs ? gcs.child.pid : null };
    const cpuAtMark = Object.fromEntries(Object.entries(pids).map(([k, pid]) => [k, pid && cpuSeconds(pid)]));
    const loadAtMark = os.loadavg()[0];
    const statusAtMark = run ? await getStatus(httpPort) : null;
    await sleep(o.seconds * 1000);
    const endNs = nowNs();
    // CPU over the window, % of one core.
    const cpu = Object.fromEntries(Object.entries(pids).map(([k, pid]) => {
      const [a, b] = [cpuAtMark[k], pid && cpuSeconds(pid)];
      return [k, a === null || b === null || !pid ? null : (100 * (b - a)) / (Number(endNs - markNs) / 1e9)];
    }));
    const v = await vehicle.ask('report', 'report');
    const g = gcs ? await gcs.ask('report', 'report') : null;
    let status = null;
    let exit = null;
    if (run) {
      status = await getStatus(httpPort);
      run.kill('SIGTERM');
      exit = await runExit;
      run = null;
    }
    await sleep(300);  // the relay's last O lines
    const r = summarize(o, baud, condition,
      { v, g, status, statusAtMark, relayOut, markNs, endNs, exit, runLog });
    return { ...r, cpu_percent: cpu, load_at_start: loadAtMark };
  } finally {
    if (run) run.kill('SIGKILL');
    for (const p of started) {
      p.child.kill('SIGTERM');
      await p.exited;
    }
    relay.kill('SIGTERM');
  }
}

async function getStatus(httpPort) {
  try {
    const response = await fetch(`http://127.0.0.1:${httpPort}/api/status`);
    return await response.json();
  } catch (error) {
    return { error: String(error) };
  }
}

function summarize(o, baud, condition,
  { v, g, status, statusAtMark, relayOut, markNs, endNs, exit, runLog }) {
  const seconds = Number(endNs - markNs) / 1e9;
  const writeMs = [];
  const captureMs = [];
  const lineMs = [];
  const ahead = [];
  const raw = [];
  let unmatched = 0;
  for (const [timeUsec, recvText] of v.odometry) {
    const recvNs = BigInt(recvText);
    const r = relayOut.odometry.get(timeUsec);
    captureMs.push(Number(recvNs - BigInt(timeUsec) * 1000n) / 1e6);
    if (!r) {
      unmatched += 1;
      continue;
    }
    writeMs.push(Number(recvNs - r.readNs) / 1e6);
    lineMs.push(Number(r.doneNs - r.readNs) / 1e6);
    ahead.push(r.ahead);
    if (o.raw) {
      raw.push([Number(BigInt(timeUsec) * 1000n - markNs) / 1e6, Number(r.readNs - markNs) / 1e6,
                Number(recvNs - markNs) / 1e6, r.ahead]);
    }
  }
  // The relay's cumulative counters over the window: the first line after the mark, the last
  // before the end.
  const inWindow = relayOut.stats.filter((s) => s[0] >= markNs && s[0] <= endNs);
  let line = null;
  if (inWindow.length >= 2) {
    const [a, b] = [inWindow[0], inWindow[inWindow.length - 1]];
    const span = Number(b[0] - a[0]) / 1e9;
    line = {
      to_vehicle_bytes_per_s: Number(b[2] - a[2]) / span,
      to_vehicle_use: Number(b[2] - a[2]) / span / (baud / 10),
      from_vehicle_bytes_per_s: Number(b[4] - a[4]) / span,
      to_vehicle_full_ms: Number(b[5] - a[5]) / 1e6,
      from_vehicle_full_ms: Number(b[6] - a[6]) / 1e6,
      to_vehicle_queue_max: Number(b[7]),
    };
  }
  // mocaplink's own counters over the window: at the end minus at the mark.
  const vehicleOf = (st) => (st && Array.isArray(st.vehicles) ? st.vehicles[0] : null);
  const atEnd = gcsCounters(vehicleOf(status));
  const atMark = gcsCounters(vehicleOf(statusAtMark));
  const counters = Object.fromEntries(Object.entries(atEnd).map(([k, x]) => [k, x - (atMark[k] ?? 0)]));
  // Dropped toward the vehicle (the forwarded queue, poses first) and toward the ground station.
  const sum = (re) => {
    const keys = Object.keys(counters).filter((k) => re.test(k));
    return keys.length ? keys.reduce((total, k) => total + counters[k], 0) : null;
  };
  const perS = (x) => (x === undefined || x === null ? null : x / seconds);
  const ms = (list) => (list.length ? median(list) / 1000 : null);
  return {
    baud, condition, seconds, rate_hz: o.rate[baud],
    pose: {
      received: v.odometry.length, rate_hz: v.odometry.length / seconds,
      write_to_vehicle_ms: { p50: quantile(writeMs, 0.5), p99: quantile(writeMs, 0.99),
                             max: quantile(writeMs, 1) },
      capture_to_vehicle_ms: { p50: quantile(captureMs, 0.5), p99: quantile(captureMs, 0.99) },
      on_line_ms: { p50: quantile(lineMs, 0.5), p99: quantile(lineMs, 0.99) },
      // Bytes still queued on the line when the pose was written: what delayed it.
      bytes_ahead: { p50: quantile(ahead, 0.5), p99: quantile(ahead, 0.99), max: quantile(ahead, 1) },
      not_seen_by_relay: unmatched,
    },
    to_vehicle: {
      gcs_sent_frames_per_s: g ? perS(g.sent.frames) : null,
      gcs_sent_bytes_per_s: g ? perS(g.sent.bytes) : null,
      delivered_frames_per_s: perS(v.from_gcs.frames),
      delivered_bytes_per_s: perS(v.from_gcs.bytes),
      lost_frames: g ? g.sent.frames - v.from_gcs.frames : null,
      delivered_by_message: v.from_gcs.by_message,
      mocaplink_frames_per_s: perS(v.from_others.frames),
      mocaplink_by_message: v.from_others.by_message,
    },
    to_gcs: {
      vehicle_sent_frames_per_s: perS(v.sent.frames),
      vehicle_sent_bytes_per_s: perS(v.sent.bytes),
      delivered_frames_per_s: g ? perS(g.from_vehicle.frames) : null,
      delivered_bytes_per_s: g ? perS(g.from_vehicle.bytes) : null,
      other_systems_frames: g ? g.from_others.frames : null,
    },
    mocaplink_reports: { dropped_to_vehicle: sum(/forward\w*drop/i),
                         dropped_to_gcs: sum(/^gcs\.\d+\.\w*drop/i),
                         gcs_counters_in_window: counters, gcs_counters_at_end: atEnd, exit },
    raw_poses_ms: o.raw ? raw : undefined,  // [capture, written, received] after the mark, bytes ahead
    tasks: g ? {
      param_downloads: g.done.param_downloads.length, param_download_s: ms(g.done.param_downloads),
      log_listings: g.done.log_listings.length, log_listing_s: ms(g.done.log_listings),
      mission_uploads: g.done.mission_uploads.length, mission_upload_s: ms(g.done.mission_uploads),
      param_rerequests: g.done.param_rerequests, list_rerequests: g.done.list_rerequests,
      mission_count_resent: g.done.mission_count_resent,
      vehicle_item_rerequests: v.events.mission_items_rerequested,
    } : null,
    crc_failures: { vehicle: v.crc_failures, gcs: g ? g.crc_failures : null },
    line,
    mocaplink_warnings: runLog.split('\n').filter((l) => / warning /.test(l)).slice(0, 5),
    mocaplink_final: runLog.split('\n').filter((l) => / final: /.test(l)),
  };
}

// --- Medians and the table. ------------------------------------------------------------------------
const METRICS = {
  pose_hz: (r) => r.pose.rate_hz,
  write_p50: (r) => r.pose.write_to_vehicle_ms.p50,
  write_p99: (r) => r.pose.write_to_vehicle_ms.p99,
  ahead_p99: (r) => r.pose.bytes_ahead.p99,
  capture_p50: (r) => r.pose.capture_to_vehicle_ms.p50,
  capture_p99: (r) => r.pose.capture_to_vehicle_ms.p99,
  to_vehicle_sent_fps: (r) => r.to_vehicle.gcs_sent_frames_per_s,
  to_vehicle_fps: (r) => r.to_vehicle.delivered_frames_per_s,
  to_vehicle_bps: (r) => r.to_vehicle.delivered_bytes_per_s,
  to_vehicle_lost: (r) => r.to_vehicle.lost_frames,
  to_gcs_fps: (r) => r.to_gcs.delivered_frames_per_s,
  to_gcs_bps: (r) => r.to_gcs.delivered_bytes_per_s,
  dropped_to_vehicle: (r) => r.mocaplink_reports.dropped_to_vehicle,
  dropped_to_gcs: (r) => r.mocaplink_reports.dropped_to_gcs,
  param_download_s: (r) => (r.tasks ? r.tasks.param_download_s : null),
  param_downloads: (r) => (r.tasks ? r.tasks.param_downloads : null),
  mission_upload_s: (r) => (r.tasks ? r.tasks.mission_upload_s : null),
  mission_uploads: (r) => (r.tasks ? r.tasks.mission_uploads : null),
  line_use: (r) => (r.line ? r.line.to_vehicle_use : null),
  full_ms: (r) => (r.line ? r.line.to_vehicle_full_ms + r.line.from_vehicle_full_ms : null),
  mocaplink_cpu: (r) => (r.cpu_percent ? r.cpu_percent.mocaplink : null),
};

function medians(results) {
  const groups = new Map();
  for (const r of results) {
    const key = `${r.baud} ${r.condition}`;
    if (!groups.has(key)) groups.set(key, []);
    groups.get(key).push(r);
  }
  const out = [];
  for (const runs of groups.values()) {
    const m = { baud: runs[0].baud, condition: runs[0].condition, runs: runs.length };
    for (const [name, get] of Object.entries(METRICS)) m[name] = median(runs.map(get));
    out.push(m);
  }
  // Ratios to the same repetition's baseline, then their median.
  for (const m of out) {
    const ratios = { write_p50: [], write_p99: [], pose_hz: [] };
    for (const r of results.filter((x) => x.baud === m.baud && x.condition === m.condition)) {
      const base = results.find((x) => x.baud === r.baud && x.condition === 'baseline' &&
                                       x.repetition === r.repetition);
      if (!base) continue;
      for (const k of Object.keys(ratios)) {
        const [a, b] = [METRICS[k](r), METRICS[k](base)];
        if (a !== null && b) ratios[k].push(a / b);
      }
    }
    m.ratio_write_p50 = median(ratios.write_p50);
    m.ratio_write_p99 = median(ratios.write_p99);
    m.ratio_pose_hz = median(ratios.pose_hz);
    // The ground station's figures against the same repetition's direct-<task> (link to itself).
    const vsDirect = { to_vehicle_fps: [], to_gcs_fps: [], param_download_s: [], mission_upload_s: [] };
    for (const r of results.filter((x) => x.baud === m.baud && x.condition === m.condition)) {
      const ref = results.find((x) => x.baud === r.baud && x.condition === `direct-${r.condition}` &&
                                      x.repetition === r.repetition);
      if (!ref) continue;
      for (const k of Object.keys(vsDirect)) {
        const [a, b] = [METRICS[k](r), METRICS[k](ref)];
        if (a !== null && b) vsDirect[k].push(a / b);
      }
    }
    m.vs_direct = Object.fromEntries(Object.entries(vsDirect).map(([k, v]) => [k, median(v)]));
  }
  return out;
}

function table(rows) {
  const f = (x, digits = 1) => (x === null || x === undefined ? '–' : x.toFixed(digits));
  const pct = (x) => (x === null || x === undefined ? '–' : `${(100 * x).toFixed(0)} %`);
  const poses = [
    '| baud | condition | poses Hz | write→vehicle p50 / p99 ms | × baseline p50 / p99 | ' +
      'capture→vehicle p50 / p99 ms | bytes ahead p99 | line use → vehicle | relay queue full ms | ' +
      'mocaplink CPU |',
    '|---|---|---:|---|---|---|---:|---:|---:|---:|',
  ];
  const traffic = [
    '| baud | condition | GCS→vehicle frames/s sent / delivered | B/s delivered | lost | ' +
      'mocaplink dropped →vehicle / →GCS | vehicle→GCS frames/s | B/s | × direct (→vehicle / →GCS) | ' +
      'parameters s (n) | mission s (n) |',
    '|---|---|---|---:|---:|---:|---:|---:|---|---|---|',
  ];
  for (const m of rows) {
    if (!m.condition.startsWith('direct-')) {
      poses.push(`| ${m.baud} | ${m.condition} | ${f(m.pose_hz)} | ${f(m.write_p50)} / ${f(m.write_p99)} | ` +
        `${f(m.ratio_write_p50, 2)} / ${f(m.ratio_write_p99, 2)} | ${f(m.capture_p50)} / ${f(m.capture_p99)} | ` +
        `${f(m.ahead_p99, 0)} | ${pct(m.line_use)} | ${f(m.full_ms, 0)} | ${f(m.mocaplink_cpu)} % |`);
    }
    if (m.condition !== 'baseline' && m.condition !== 'idle') {
      const d = m.vs_direct || {};
      traffic.push(`| ${m.baud} | ${m.condition} | ${f(m.to_vehicle_sent_fps)} / ${f(m.to_vehicle_fps)} | ` +
        `${f(m.to_vehicle_bps, 0)} | ${f(m.to_vehicle_lost, 0)} | ` +
        `${f(m.dropped_to_vehicle, 0)} / ${f(m.dropped_to_gcs, 0)} | ` +
        `${f(m.to_gcs_fps)} | ${f(m.to_gcs_bps, 0)} | ${f(d.to_vehicle_fps, 2)} / ${f(d.to_gcs_fps, 2)} | ` +
        `${f(m.param_download_s)} (${f(m.param_downloads, 0)}) | ` +
        `${f(m.mission_upload_s, 2)} (${f(m.mission_uploads, 0)}) |`);
    }
  }
  return `${poses.join('\n')}\n\n${traffic.join('\n')}`;
}

async function main() {
  const o = parseArgs(process.argv.slice(2));
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'gcs-link-'));
  process.on('exit', () => fs.rmSync(dir, { recursive: true, force: true }));
  const probe = gcsSupported(o.mocaplink, dir);
  let conditions = o.conditions;
  if (!probe.ok) {
    conditions = conditions.filter((c) => c === 'baseline' || c.startsWith('direct-'));
    console.error(`note: this mocaplink refuses the gcs key; only the baseline runs.\n${probe.output}`);
  }
  const results = [];
  for (const baud of o.bauds) {
    for (let repetition = 1; repetition <= o.runs; repetition += 1) {
      for (const condition of conditions) {
        const r = await measure(o, baud, condition, dir);
        r.repetition = repetition;
        results.push(r);
        console.error(`${baud} ${condition} #${repetition}: poses ${r.pose.rate_hz.toFixed(1)} Hz, ` +
          `write→vehicle p50 ${r.pose.write_to_vehicle_ms.p50?.toFixed(2) ?? '–'} p99 ` +
          `${r.pose.write_to_vehicle_ms.p99?.toFixed(2) ?? '–'} ms, GCS→vehicle ` +
          `${r.to_vehicle.delivered_frames_per_s.toFixed(1)} frames/s, vehicle→GCS ` +
          `${r.to_gcs.delivered_frames_per_s?.toFixed(1) ?? '–'} frames/s`);
      }
    }
  }
  const rows = medians(results);
  const commit = spawnSync('git', ['-C', __dirname, 'rev-parse', '--short', 'HEAD'], { encoding: 'utf8' });
  const report = {
    date: new Date().toISOString(), bench_commit: commit.stdout.trim(), mocaplink: o.mocaplink,
    gcs_supported: probe.ok, loadavg: os.loadavg(), cpus: os.cpus().length,
    options: { seconds: o.seconds, runs: o.runs, warmup: o.warmup, bauds: o.bauds, rate: o.rate },
    medians: rows, runs: results,
  };
  console.log(table(rows));
  if (o.json) fs.writeFileSync(o.json, `${JSON.stringify(report, null, 1)}\n`);
  else console.log(JSON.stringify(report));
}

main().catch((error) => {
  console.error(error);
  process.exit(1);
});
