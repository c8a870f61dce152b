// A bridge that falls behind its source sends the newest pose, not a queue of old ones, says so,
// and still records every frame (issues 15 and 30; core/late_frames.hpp). The event loop is made to
// stall for real: the recording's mocap.csv is a FIFO that this test does not read at first, so
// once the pipe is full the loop blocks in its write while the source thread keeps queueing
// frames. Then the test reads the FIFO, the loop goes on, and of the backlog only the newest frame
// may be sent: every older one is superseded (a newer frame with all its bodies was waiting) or,
// if it was the newest of its batch and older than 250 ms, skipped as late. Checked: the warning,
// the counts in the final summary, the first frame sent after the stall being the newest that was
// waiting, and every frame handed over either sent through the core (counted by the Station) or
// skipped — and recorded either way, a skipped one as comments. Replaying that recording at speed
// 1 then sends as many poses as the live run did (less any frame the replay itself skipped, which
// it reports: on a loaded machine its loop can fall a frame behind too).
'use strict';

const childProcess = require('node:child_process');
const fs = require('node:fs');
const path = require('node:path');
const h = require('./harness');

const { assert, ID, sleep } = h;
const LATE = '# late, not sent: ';  // '#' and run_recorder.hpp kLateComment
const SUPERSEDED = '# superseded, not sent: ';  // '#' and kSupersededComment
const FINAL = /final: source \S+: connected, (\d+) frames .*, (\d+) queue overflows, (\d+) late frames skipped, (\d+) frames superseded/;

// ODOMETRY received by `vehicle` once no more datagrams arrive.
async function settledOdometry(vehicle) {
  let before;
  do {
    before = vehicle.datagrams;
    await sleep(200);
  } while (vehicle.datagrams !== before);
  return vehicle.ofId(ID.ODOMETRY).length;
}

async function main() {
  const dir = h.tempDir('late');
  const record = path.join(dir, 'rec');
  fs.mkdirSync(record);
  const fifo = path.join(record, 'mocap.csv');
  childProcess.execFileSync('mkfifo', [fifo]);
  // Open for reading first (non-blocking), so that the daemon's open for writing does not wait.
  const reader = fs.openSync(fifo, fs.constants.O_RDONLY | fs.constants.O_NONBLOCK);

  const vehicle = await new h.UdpVehicle().bind();
  vehicle.socket.setRecvBufferSize(4 << 20);  // the burst after the stall must all arrive
  const quad = (port) => [{ name: 'quad', body: 'Body1', link: `udp://127.0.0.1:${port}`,
    profile: 'px4', system_id: 1, rate_hz: 240 }];
  const config = h.writeConfig(path.join(dir, 'late.toml'), 'sim://?bodies=3&rate_hz=240',
    quad(vehicle.port));
  const run = h.mocaplink(['run', '--config', config, '--record', record],
    { env: { MOCAPLINK_STATE_DIR: path.join(dir, 'state') } });
  await h.waitFor(() => vehicle.packets.length > 10, 10000, `traffic\n${run.stderr}`);

  // Nobody reads: the pipe fills (64 KiB, a few hundred frames) and the loop blocks in a write.
  // Wait until no pose has come for a second, i.e. the loop has been stalled that long.
  let seen = -1;
  let quietSince = Date.now();
  await h.waitFor(() => {
    if (vehicle.packets.length !== seen) {
      seen = vehicle.packets.length;
      quietSince = Date.now();
    }
    return Date.now() - quietSince > 1000;
  }, 20000, `the loop to stall on the full pipe\n${run.stderr}`);

  // Read from now on, and keep reading until the daemon has closed its end.
  let csv = '';
  let closed = false;
  const buffer = Buffer.alloc(1 << 16);
  const drain = async () => {
    while (!closed) {
      let n = 0;
      try {
        n = fs.readSync(reader, buffer, 0, buffer.length, null);
      } catch (error) {
        if (error.code !== 'EAGAIN') throw error;
        await sleep(5);
        continue;
      }
      if (n === 0) {
        if (run.child.exitCode !== null || run.child.signalCode !== null) closed = true;
        else await sleep(5);
        continue;
      }
      csv += buffer.toString('latin1', 0, n);
      await sleep(0);  // let the rest of the test run between chunks
    }
  };
  const logBefore = run.stderr.length;  // the warning must come from this stall
  const reading = drain();
  await h.waitFor(() => /warning \d+ frames? superseded by a newer one already waiting, not sent/
    .test(run.stderr.slice(logBefore)), 10000, `the warning\n${run.stderr}`);
  const posesAfter = vehicle.packets.length;
  await h.waitFor(() => vehicle.packets.length > posesAfter + 50, 10000,
    `poses again after the stall\n${run.stderr}`);
  await h.stop(run);
  await reading;
  fs.closeSync(reader);
  const liveOdometry = await settledOdometry(vehicle);
  vehicle.close();

  const final = run.stderr.match(FINAL);
  assert.ok(final, `no final source line\n${run.stderr}`);
  const [tracked, overflows, late, superseded] = final.slice(1).map(Number);
  // The backlog of over a second (a few hundred frames) was superseded, not sent in order.
  assert.ok(superseded > 100, `${superseded} superseded after a stall of over a second\n${run.stderr}`);
  const recording = run.stderr.match(/recording: (\d+) frames in/);
  assert.ok(recording, run.stderr);
  // Every frame the loop took from the queue was recorded; it was then either tracked or skipped,
  // and a skipped one is in the file as comments.
  assert.equal(Number(recording[1]), tracked + late + superseded, run.stderr);
  assert.match(run.stderr, new RegExp(
    `recording: \\d+ frames in .* \\(${late + superseded} not sent, written as comments\\)`));
  const lines = csv.split('\n').slice(2).filter((l) => l !== '');
  const frameOf = (row) => Number(row.split(',')[1]);
  const commented = (prefix) => new Set(lines.filter((l) => l.startsWith(prefix))
    .map((l) => frameOf(l.slice(prefix.length))));
  const sent = new Set(lines.filter((l) => !l.startsWith('#')).map(frameOf));
  const lateFrames = commented(LATE);
  const supersededFrames = commented(SUPERSEDED);
  assert.equal(sent.size, tracked, 'frames in mocap.csv as rows');
  assert.equal(lateFrames.size, late, 'late frames in mocap.csv as comments');
  assert.equal(supersededFrames.size, superseded, 'superseded frames in mocap.csv as comments');
  assert.equal([...lateFrames, ...supersededFrames].filter((f) => sent.has(f)).length, 0,
    'a frame both sent and not');
  // Newest first: every superseded frame has a newer frame behind it (the one that superseded
  // it), and after the longest run of skipped frames (the backlog) the next frame in the file was
  // sent: the loop went straight from the stall to the newest pose that was waiting.
  const order = [...new Set(lines.map((l) => frameOf(l.startsWith('#') ? l.replace(/^# [a-z]+, not sent: /, '') : l)))];
  let longest = { start: 0, length: 0 };
  for (let i = 0, run0 = 0; i < order.length; i += 1) {
    if (sent.has(order[i])) {
      run0 = i + 1;
    } else if (i + 1 - run0 > longest.length) {
      longest = { start: run0, length: i + 1 - run0 };
    }
  }
  const afterBacklog = order[longest.start + longest.length];
  assert.ok(longest.length > 100, `the backlog: ${longest.length} frames skipped in a row`);
  assert.ok(sent.has(afterBacklog), `frame ${afterBacklog}, right after the backlog, was not sent`);
  for (const f of supersededFrames) {
    assert.ok(order.indexOf(f) < order.length - 1, `superseded frame ${f} is the last one`);
  }

  // The replay sends what the live run sent: the skipped frames are comments, so it skips them.
  const file = path.join(dir, 'live.csv');
  fs.writeFileSync(file, csv, 'latin1');
  const target = await new h.UdpVehicle().bind();
  target.socket.setRecvBufferSize(4 << 20);
  const replayConfig = h.writeConfig(path.join(dir, 'replay.toml'), `replay://${file}?speed=1`,
    quad(target.port));
  const replay = h.mocaplink(['run', '--config', replayConfig],
    { env: { MOCAPLINK_STATE_DIR: path.join(dir, 'replay-state') } });
  const { code } = await replay.exited;  // it stops by itself at the end of the recording
  assert.equal(code, 0, replay.stderr);
  assert.match(replay.stderr, new RegExp(`${tracked} frames replayed`));
  const replayFinal = replay.stderr.match(
    /final: source .* (\d+) late frames skipped, (\d+) frames superseded/);
  assert.ok(replayFinal, replay.stderr);
  const replaySkipped = Number(replayFinal[1]) + Number(replayFinal[2]);
  const replayOdometry = await settledOdometry(target);
  target.close();
  // One ODOMETRY per frame sent (rate_hz = the mocap rate): equal when the replay kept up.
  assert.equal(replayOdometry + replaySkipped, liveOdometry,
    `ODOMETRY: replay ${replayOdometry} (${replaySkipped} frames skipped), live ${liveOdometry}`);
  console.log(`ok: ${superseded} frames superseded and ${late} late, ${tracked} tracked ` +
    `(${overflows} overflows); ${liveOdometry} ODOMETRY live, ${replayOdometry} replayed ` +
    `(${replaySkipped} skipped by the replay)`);
}

main().catch(h.fail);
