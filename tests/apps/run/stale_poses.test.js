// No stale pose from any source (issue 27): each emulator (`mocaplink serve --protocol P --from sim
// --stall 1.5:MS`) holds its frames back for MS ms, as a stalled network would, then lets them out
// in one burst with the frames after the stall, as a TCP connection delivers its backlog. The
// burst arrives fresh but was captured up to MS ms before: `mocaplink run` must judge its age from
// the capture, skip and count the frames too old to send, and mark them in the recording. The
// frames of a burst never supersede each other (core::kSameBurst), so each is judged late by its
// capture time; frames the loop was more than 10 ms (or two frame periods) late for are
// superseded (issue 30); either way they are skipped, counted and marked.
//
// The vehicle checks what reaches it: every ODOMETRY's time_usec is the pose's capture time on
// the daemon's steady clock (docs/messages.md "Time"), the same CLOCK_MONOTONIC as this process's
// process.hrtime, so its age on arrival is measured here, independently of the daemon's own
// verdict. Without the capture-time check, the burst's poses arrive up to MS ms old.
'use strict';

const fs = require('node:fs');
const path = require('node:path');
const h = require('./harness');

const { assert, ID } = h;
const RATE_HZ = 100;
const STALL_AT_S = 1.5;
const NOT_SENT = /^# (late|superseded), not sent: /;
/// Anything older on arrival was sent although too old: the limit is 250 ms, and the margin
/// covers this process being slow to read its socket on a loaded machine. A stall of 600 ms makes
/// the burst's oldest frames 600 ms old, far past it.
const MAX_AGE_MS = 350;

/// process.hrtime (CLOCK_MONOTONIC) in µs of a performance.now() time, which the vehicles stamp.
const hrtimeAtZeroUs = process.hrtime.bigint() / 1000n - BigInt(Math.round(performance.now() * 1000));
const monotonicUs = (t) => hrtimeAtZeroUs + BigInt(Math.round(t * 1000));

/// The serve arguments and the run's source URL for each protocol. `stallMs`: how long its frames
/// are held back (vicon-udp has no capture time of its own: its clock follows the frame numbers
/// only across gaps under 0.5 s, wire/arrival_clock.hpp).
const protocols = [
  { name: 'vicon', stallMs: 600, serve: async () => ({ args: ['--listen', '127.0.0.1:0'] }),
    url: (port) => `vicon://127.0.0.1:${port}` },
  { name: 'qtm', stallMs: 600, serve: async () => ({ args: ['--listen', '127.0.0.1:0'] }),
    url: (port) => `qtm://127.0.0.1:${port}` },
  // Unicast: qemu-user (the cross presets) has no IP_MULTICAST_IF for the multicast emulator.
  { name: 'natnet', stallMs: 600,
    serve: async () => ({ args: ['--listen', '127.0.0.1:0', '--set', 'transport=unicast',
      '--set', 'up=z', '--set', `data_port=${await h.freeUdpPort()}`] }),
    url: (port) => `natnet://127.0.0.1:${port}?local=127.0.0.1` },
  { name: 'vicon-udp', stallMs: 400,
    serve: async () => {
      const port = await h.freeUdpPort();
      return { args: ['--to', `127.0.0.1:${port}`], port };
    },
    url: (port) => `vicon-udp://127.0.0.1:${port}?frozen=0` },
];

async function runOnce(dir, p) {
  const served = await p.serve();
  const server = h.mocaplink(['serve', '--protocol', p.name, '--from', 'sim', '--rate',
    String(RATE_HZ), '--stall', `${STALL_AT_S}:${p.stallMs}`, ...served.args]);
  await h.waitFor(() => /serving \S+ (on|to) [^:]+:\d+/.test(server.stdout), 10000,
    `serve ${p.name} to start\n${server.stderr}`);
  const port = served.port ?? server.stdout.match(/serving \S+ on [^:]+:(\d+)/)[1];

  const vehicle = await new h.UdpVehicle().bind();
  const config = h.writeConfig(path.join(dir, `${p.name}.toml`), p.url(port), [
    { name: 'quad1', body: 'Body1', link: `udp://127.0.0.1:${vehicle.port}`, system_id: 1,
      profile: 'px4', rate_hz: 100 },
  ], 'up = "+z"\nnorth = "+x"\n');
  const record = path.join(dir, `${p.name}-rec`);
  const run = h.mocaplink(['run', '--config', config, '--record', record]);
  await h.waitFor(() => vehicle.ofId(ID.ODOMETRY).length > 0, 10000,
    `${p.name}: first ODOMETRY\n${run.stderr}`);
  // Past the stall and its burst, with a second of normal running after it.
  await h.waitForLog(run,
    /\d+ frames? (skipped as too old to send|superseded by a newer one already waiting)/, 10000);
  await h.sleep(1000);
  await h.stop(run);
  await h.stop(server);
  vehicle.close();

  const odometry = vehicle.ofId(ID.ODOMETRY).map(({ packet, t }) => ({
    ageMs: Number(monotonicUs(t) - h.decode(packet).timeUsec) / 1000,
  }));
  const oldest = Math.max(...odometry.map((o) => o.ageMs));
  assert.ok(oldest <= MAX_AGE_MS,
    `${p.name}: an ODOMETRY arrived ${oldest.toFixed(0)} ms after its capture\n${run.stderr}`);
  assert.ok(odometry.length > 100, `${p.name}: only ${odometry.length} ODOMETRY`);

  const final = run.stderr.match(
    /final: source \S+: \S+, (\d+) frames .*, (\d+) late frames skipped, (\d+) frames superseded/);
  assert.ok(final, `${p.name}: no final source line\n${run.stderr}`);
  const late = Number(final[2]);
  const superseded = Number(final[3]);
  const skipped = late + superseded;
  // At most the frames of the stall; at least one (a server may drop most of a burst for a slow
  // client, as the Vicon emulator does with its per-client queue: whole frames, counted).
  assert.ok(skipped >= 1 && skipped <= (p.stallMs / 1000) * RATE_HZ + 5,
    `${p.name}: ${late} late frames skipped, ${superseded} superseded\n${run.stderr}`);
  const csv = fs.readFileSync(path.join(record, 'mocap.csv'), 'latin1').split('\n');
  const notSent = new Set(csv.filter((l) => NOT_SENT.test(l))
    .map((l) => l.replace(NOT_SENT, '').split(',')[1]));
  assert.equal(notSent.size, skipped, `${p.name}: frames in mocap.csv marked as not sent`);
  return { name: p.name, late, superseded, oldest: oldest.toFixed(0), odometry: odometry.length };
}

async function main() {
  const dir = h.tempDir('stale');
  const results = [];
  for (const p of protocols) results.push(await runOnce(dir, p));
  console.log(`ok: ${results.map((r) => `${r.name}: ${r.late} late frames skipped, ` +
    `${r.superseded} superseded, ` +
    `oldest ODOMETRY ${r.oldest} ms, ${r.odometry} ODOMETRY`).join('; ')}`);
}

main().catch(h.fail);
