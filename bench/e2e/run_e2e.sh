#!/usr/bin/env bash
# bench/e2e: sim:// (240 Hz) → mocaplink run → N UDP receivers on loopback, for N in $VEHICLES,
# and the floor (bench/e2e/e2e_floor: the same source and loop hand-off, one pre-encoded datagram
# per vehicle, no logic) in the same run, right before mocaplink for each N.
# Prints one markdown table row per N: mocap frames, ODOMETRY lost, latency p50/p99 of the floor
# and of mocaplink (frame's host capture time → datagram received, CLOCK_MONOTONIC), mocaplink's
# ratio to the floor, the p50 of the first and of the last vehicle alone (what comes before any
# vehicle's send, and what each vehicle adds), the CPU of both (user+sys as % of one core) and
# mocaplink's peak RSS, the frames the floor and mocaplink superseded (issue 30: the loop was
# behind and a newer frame was waiting; both apply core::LateFrames alike, so both lose alike), and
# mocaplink's CPU time per datagram received as a multiple of the floor's (both over the same wall
# time: CPU % / datagrams received).
# Usage: bench/e2e/run_e2e.sh MOCAPLINK_BIN RECEIVERS_BIN FLOOR_BIN [SECONDS] [N...]
# NICE=-10 runs every process at that priority (a shared, busy machine; needs root).
# LOAD=compile keeps one compiler busy for the whole run (the other core loaded by a build);
# LOAD_JOBS=2 keeps two busy (both cores of this 2-core machine).
# REPEAT=K measures floor and mocaplink K times per N, back to back, and prints the medians (the
# ratios: the median of each repetition's ratio). POLL_MS sets the receivers' polling (default 2).
# SOCKETS=shared makes 250 vehicles share each receiving socket (e2e_receivers --sockets shared),
# so that the receivers cost the machine little even for 1000 vehicles.
# FLOOR_LISTEN=1 runs the floor with --listen (its sockets also wait for the vehicles' datagrams, as
# mocaplink's links do). FLOOR_SHARED_SOCKET=1 runs it with --shared-socket (one unconnected socket
# per send thread, each thread's datagrams in one sendmmsg; both may be set).
# CPUS=LIST runs the floor and mocaplink under `taskset -c LIST` (CPUS=1: one core, a stand-in for
# sizing a smaller machine; the receivers are not pinned). RATE_HZ sets the mocap rate and every
# vehicle's rate_hz (default 240; still one ODOMETRY per frame).
# ROS2=DOMAIN adds [ros2] (interface loopback, that domain) to mocaplink's configuration, not the
# floor's: every body on ROS 2 topics beside the vehicles (issue 46). A subscriber is the caller's
# to start (tests/adapters/ros2/oracle), or the writers have no reader to send to.
set -euo pipefail
bin=$1
receivers=$2
floor=$3
seconds=${4:-30}
shift 4 || true
counts=("$@")
[ $# -eq 0 ] && counts=(1 5 50 500 1000)
work=$(mktemp -d)
loaders=()
cleanup() {
  [ "${#loaders[@]}" -eq 0 ] || kill "${loaders[@]}" 2>/dev/null
  rm -rf "$work"
}
trap cleanup EXIT
if [ "${LOAD:-}" = compile ]; then
  src=$(dirname "$0")/e2e_receivers.cpp
  for ((job = 0; job < ${LOAD_JOBS:-1}; job++)); do
    (while true; do c++ -O2 -std=c++20 -c "$src" -o "$work/load$job.o"; done) >/dev/null 2>&1 &
    loaders+=($!)
  done
fi
prio=()
[ -n "${NICE:-}" ] && prio=(nice -n "$NICE")
pin=()
[ -n "${CPUS:-}" ] && pin=(taskset -c "$CPUS")
floor_args=()
[ "${FLOOR_LISTEN:-}" = 1 ] && floor_args+=(--listen)
[ "${FLOOR_SHARED_SOCKET:-}" = 1 ] && floor_args+=(--shared-socket)

# measure N BIN ARGS...: runs BIN ARGS... against N fresh receivers for $seconds; prints
# "frames received p50_us p99_us cpu_pct rss_mib first_p50_us last_p50_us superseded".
measure() {
  local n=$1
  shift
  # The previous receivers' "ready" must not be read as these ones': under load the redirection
  # below can run after the wait loop's first grep, which then found the old file, and the bridge
  # read a c.toml the new receivers were still writing ("mocap.source: missing required key").
  rm -f "$work/recv.out"
  "${prio[@]}" "$receivers" --vehicles "$n" --config "$work/c.toml" --poll-ms "${POLL_MS:-2}" \
    --sockets "${SOCKETS:-each}" --mocap-hz "${RATE_HZ:-240}" --rate-hz "${RATE_HZ:-240}" \
    > "$work/recv.out" &
  local rpid=$!
  while ! grep -q ready "$work/recv.out" 2>/dev/null; do sleep 0.1; done
  if [ -n "${ROS2:-}" ] && [ "$1" != "$floor" ]; then
    printf '[ros2]\ninterface = "loopback"\ndomain_id = %s\n' "$ROS2" >> "$work/c.toml"
  fi
  MOCAPLINK_STATE_DIR="$work/state" MOCAPLINK_SUMMARY_S=3600 /usr/bin/time -f '%U %S %e %M' \
    -o "$work/time.out" "${prio[@]}" "${pin[@]}" "$@" --config "$work/c.toml" 2> "$work/run.err" &
  local tpid=$!
  sleep "$seconds"
  pkill -TERM -P "$tpid" || true  # the child of /usr/bin/time (or nice's exec)
  wait "$tpid" || true
  if ! grep -q -e 'final: source' -e '^floor:' "$work/run.err"; then  # it never ran: say why
    kill "$rpid"
    echo "run_e2e: $1 did not run:" >&2
    { grep -v '^warning' "$work/run.err" || true; } | tail -5 >&2
    exit 1
  fi
  wait "$rpid"
  local user sys wall rss_kb frames overflows late superseded
  read -r user sys wall rss_kb < "$work/time.out"
  frames=$(sed -n -e 's/.*final: source [^ ]*: [a-z ]*, \([0-9]*\) frames.*/\1/p' \
    -e 's/^floor: \([0-9]*\) frames.*/\1/p' "$work/run.err")
  overflows=$(sed -n -e 's/.*final: source .* \([0-9]*\) queue overflows.*/\1/p' \
    -e 's/^floor: [0-9]* frames, \([0-9]*\) queue overflows.*/\1/p' "$work/run.err")
  late=$(sed -n -e 's/.*final: source .* \([0-9]*\) late frames skipped.*/\1/p' \
    -e 's/^floor: .* \([0-9]*\) late frames skipped.*/\1/p' "$work/run.err")
  superseded=$(sed -n -e 's/.*final: source .* \([0-9]*\) frames superseded.*/\1/p' \
    -e 's/^floor: .* \([0-9]*\) frames superseded.*/\1/p' "$work/run.err")
  node -e '
    const r = JSON.parse(require("fs").readFileSync(process.argv[1], "utf8").split("\n")[1]);
    const [frames, user, sys, wall, rss] = process.argv.slice(2).map(Number);
    console.log(frames, r.odometry, r.latency_us.p50, r.latency_us.p99,
      (100 * (user + sys) / wall).toFixed(1), (rss / 1024).toFixed(1),
      r.first_vehicle_p50_us, r.last_vehicle_p50_us, process.argv[7]);
  ' "$work/recv.out" "$((frames + ${overflows:-0} + ${late:-0} + ${superseded:-0}))" "$user" "$sys" \
    "$wall" "$rss_kb" "${superseded:-0}"
}

echo "| vehicles | mocap frames | lost floor / mocaplink | floor p50 / p99 | mocaplink p50 / p99 | ratio p50 / p99 | first / last vehicle p50, floor | first / last vehicle p50, mocaplink | CPU floor / mocaplink | peak RSS | superseded floor / mocaplink | CPU per datagram, ratio |"
echo "|---:|---:|---:|---|---|---|---|---|---:|---:|---:|---:|"
for n in "${counts[@]}"; do
  rows=()
  for ((rep = 0; rep < ${REPEAT:-1}; rep++)); do
    read -r ff fr fp50 fp99 fcpu _ ffirst flast fsup < <(measure "$n" "$floor" "${floor_args[@]}")
    read -r mf mr mp50 mp99 cpu rss mfirst mlast msup < <(measure "$n" "$bin" run)
    rows+=("$ff $fr $fp50 $fp99 $fcpu $mf $mr $mp50 $mp99 $cpu $rss $ffirst $flast $mfirst $mlast $msup $fsup")
  done
  # One row per N: each column the median over the repetitions, the ratios the median of each
  # repetition's own ratio (floor and mocaplink measured back to back).
  node -e '
    const n = Number(process.argv[1]);
    const reps = process.argv.slice(2).map((r) => r.split(" ").map(Number));
    const median = (xs) => { const s = [...xs].sort((a, b) => a - b); const k = s.length >> 1;
      return s.length % 2 ? s[k] : (s[k - 1] + s[k]) / 2; };
    const col = (i) => median(reps.map((r) => r[i]));
    const lost = (r, f, g) => 100 * (1 - r[g] / (n * r[f]));
    const ms = (us) => (us / 1000).toFixed(2);
    const ratio = (i, j) => median(reps.map((r) => (r[j] > 0 ? r[i] / r[j] : NaN))).toFixed(2);
    console.log(`| ${n} | ${col(5)} | ${median(reps.map((r) => lost(r, 0, 1))).toFixed(3)} % / ` +
      `${median(reps.map((r) => lost(r, 5, 6))).toFixed(3)} % | ${ms(col(2))} / ${ms(col(3))} ms | ` +
      `${ms(col(7))} / ${ms(col(8))} ms | ${ratio(7, 2)} / ${ratio(8, 3)} | ` +
      `${ms(col(11))} / ${ms(col(12))} ms | ${ms(col(13))} / ${ms(col(14))} ms | ` +
      `${col(4).toFixed(1)} / ${col(9).toFixed(1)} % | ${col(10).toFixed(1)} MiB | ` +
      `${col(16)} / ${col(15)} | ` +
      `${median(reps.map((r) => (r[9] / r[6]) / (r[4] / r[1]))).toFixed(2)} |`);
  ' "$n" "${rows[@]}"
done
