// Rates that read true whoever asks and when (issue 29): the first GET /api/status of a run —
// a single curl, a monitoring script — shows the pose rate that flows (the daemon measured it
// between two requests and showed 0.0 Hz), and the final log line gives the whole run's average
// and says so (it gave the rate since the last periodic summary).
'use strict';

const h = require('./harness');

const { assert, ID } = h;

/// Whether `hz` (printed to 0.1) is `count` over `seconds` (printed to 0.1 s).
function averageOf(hz, count, seconds) {
  const [r, n, s] = [Number(hz), Number(count), Number(seconds)];
  return r >= n / (s + 0.05) - 0.05 && r <= n / (s - 0.05) + 0.05;
}

async function main() {
  const quad = await new h.UdpVehicle().bind();
  // No periodic summary during the run: the final one is the only one.
  const run = h.mocaplink(['run', '--http', '127.0.0.1:0', '--source', 'sim://?bodies=1',
    '--vehicle', `quad:body=Body1,link=udp://127.0.0.1:${quad.port},system_id=1,profile=px4,rate_hz=50`],
  { env: { MOCAPLINK_SUMMARY_S: '600' } });
  const [, port] = await h.waitForLog(run, /dashboard: http:\/\/127\.0\.0\.1:(\d+)\//);
  // Half a second of poses, then the run's first status request.
  await h.waitFor(() => quad.ofId(ID.ODOMETRY).length >= 25, 10000, '25 ODOMETRY');
  const status = await (await fetch(`http://127.0.0.1:${port}/api/status`)).json();
  const { send_rate_hz: first } = status.vehicles[0];
  assert.ok(Math.abs(first - 50) <= 5, `first send_rate_hz ${first}, expected ~50`);
  assert.ok(status.station.frame_rate_hz > 150, `first frame_rate_hz ${status.station.frame_rate_hz}`);

  await h.sleep(1500);
  await h.stop(run);
  const received = quad.ofId(ID.ODOMETRY).length;
  const [, hz, seconds, total] = run.stderr.match(
    /final: vehicle quad: ([\d.]+) Hz poses on average over the run's ([\d.]+) s \((\d+) total\)/);
  // The run's average: every pose sent over the run's length (start-up included), not the rate of
  // its last moments; the vehicle got them all (loopback).
  assert.ok(averageOf(hz, total, seconds), run.stderr);
  assert.ok(Number(hz) > 35 && Number(hz) <= 51, `average ${hz} Hz`);
  assert.ok(Math.abs(Number(total) - received) <= 2, `${total} sent, ${received} received`);
  const [, frames, frameHz, runSeconds] = run.stderr.match(
    /final: source \S+: connected, (\d+) frames \(([\d.]+) Hz on average over the run's ([\d.]+) s\)/);
  assert.ok(averageOf(frameHz, frames, runSeconds), run.stderr);
  assert.equal(runSeconds, seconds);
  console.log(`ok: first status ${first} Hz poses, ${status.station.frame_rate_hz} Hz frames; ` +
    `final ${hz} Hz poses over ${seconds} s (${total}), ${frameHz} Hz frames`);
  quad.close();
}

main().then(() => process.exit(0), h.fail);
