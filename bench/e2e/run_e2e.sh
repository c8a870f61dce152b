#!/usr/bin/env bash
# bench/e2e: sim:// (240 Hz) → mocaplink run → N UDP receivers on loopback, for N in $VEHICLES.
# Prints one markdown table row per N: frames lost, latency p50/p99/max (frame generated →
# ODOMETRY datagram received, CLOCK_MONOTONIC), CPU (user+sys as % of one core) and peak RSS of
# mocaplink. Usage: bench/e2e/run_e2e.sh MOCAPLINK_BIN RECEIVERS_BIN [SECONDS] [N...]
# NICE=-10 runs both processes at that priority (a shared, busy machine; needs root).
set -euo pipefail
bin=$1
receivers=$2
seconds=${3:-30}
shift 3 || true
counts=("${@:-1 5 50 500}")
[ $# -eq 0 ] && counts=(1 5 50 500)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "| vehicles | mocap frames | ODOMETRY received | lost | latency p50 / p99 / max | CPU (one core) | peak RSS |"
echo "|---:|---:|---:|---:|---|---:|---:|"
for n in "${counts[@]}"; do
  prio=()
  [ -n "${NICE:-}" ] && prio=(nice -n "$NICE")
  "${prio[@]}" "$receivers" --vehicles "$n" --config "$work/c.toml" > "$work/recv.out" &
  rpid=$!
  while ! grep -q ready "$work/recv.out" 2>/dev/null; do sleep 0.1; done
  MOCAPLINK_STATE_DIR="$work/state" MOCAPLINK_SUMMARY_S=3600 /usr/bin/time -f '%U %S %e %M' \
    -o "$work/time.out" "${prio[@]}" "$bin" run --config "$work/c.toml" 2> "$work/run.err" &
  tpid=$!
  sleep "$seconds"
  pkill -TERM -P "$tpid" || true  # the child of /usr/bin/time (mocaplink, or nice's exec)
  wait "$tpid" || true
  wait "$rpid"
  read -r user sys wall rss_kb < "$work/time.out"
  frames=$(sed -n 's/.*final: source [^ ]*: [a-z ]*, \([0-9]*\) frames.*/\1/p' "$work/run.err")
  overflows=$(sed -n 's/.*final: source .* \([0-9]*\) queue overflows.*/\1/p' "$work/run.err")
  node -e '
    const r = JSON.parse(require("fs").readFileSync(process.argv[1], "utf8").split("\n")[1]);
    const [n, frames, overflows, user, sys, wall, rss] = process.argv.slice(2).map(Number);
    const expected = n * (frames + overflows);
    const lost = 100 * (1 - r.odometry / expected);
    const ms = (us) => (us / 1000).toFixed(2);
    console.log(`| ${n} | ${frames + overflows} | ${r.odometry} | ${lost.toFixed(3)} % | ` +
      `${ms(r.latency_us.p50)} / ${ms(r.latency_us.p99)} / ${ms(r.latency_us.max)} ms | ` +
      `${(100 * (user + sys) / wall).toFixed(1)} % | ${(rss / 1024).toFixed(1)} MiB |`);
  ' "$work/recv.out" "$n" "$frames" "$overflows" "$user" "$sys" "$wall" "$rss_kb"
done
