#!/usr/bin/env bash
# bench/ros2: capture → ROS 2 subscriber latency, mocaplink against its floor, in one run (issue 46).
# The same sim:// source (N bodies at RATE_HZ) feeds, in turn, bench/ros2/ros2_floor (pre-encoded
# samples, only the stamps written per frame) and `mocaplink run` with [ros2] on loopback; each
# time the independent Cyclone DDS reader (tests/adapters/ros2/oracle, reliable) takes the first
# body's pose, the last body's pose, the middle body's odom and /tf for SECONDS. Latency: the
# reader's receive time (CLOCK_REALTIME) minus the sample's header.stamp (the capture time on the
# wall clock, as both publishers stamp it). Prints one markdown row per repetition and build, then
# the medians and mocaplink's ratio to the floor.
#
#   bench/ros2/run_ros2.sh MOCAPLINK_BIN ROS2_FLOOR_BIN ORACLE_BIN [SECONDS] [BODIES]
#
# REPEAT=K (default 2) floor/mocaplink pairs; RATE_HZ (default 240); DOMAIN (default 62). Every
# participant is confined to 127.0.0.1 (both publishers' interface "loopback", the reader's
# unicast-only configuration): nothing leaves the machine.
set -euo pipefail
bin=$1
floor=$2
oracle=$3
seconds=${4:-10}
bodies=${5:-50}
rate=${RATE_HZ:-240}
domain=${DOMAIN:-62}
work=$(mktemp -d)
trap 'rm -rf "$work"; pkill -P $$ 2>/dev/null || true' EXIT
source_url="sim://?bodies=$bodies&rate_hz=$rate"
mid=$(((bodies + 1) / 2))
subs=(--sub "pose:rt/mocap/Body1/pose" --sub "pose:rt/mocap/Body$bodies/pose"
  --sub "odom:rt/mocap/Body$mid/odom" --sub "tf:rt/tf")
cat >"$work/run.toml" <<EOF
[mocap]
source = "$source_url"
[ros2]
domain_id = $domain
interface = "loopback"
[http]
listen = "127.0.0.1:0"
EOF

# measure NAME CMD...: the reader for $seconds beside CMD; prints "samples p50_ms p99_ms cpu_pct".
measure() {
  local name=$1
  shift
  "$oracle" --domain "$domain" --count 100000000 --timeout "$((seconds + 3))" "${subs[@]}" \
    >"$work/$name.jsonl" 2>"$work/$name.oracle.err" &
  local opid=$!
  sleep 1
  MOCAPLINK_STATE_DIR="$work/state" /usr/bin/time -f '%U %S %e' -o "$work/$name.time" \
    "$@" >"$work/$name.out" 2>"$work/$name.err" &
  local tpid=$!
  sleep "$((seconds + 1))"
  pkill -TERM -P "$tpid" || true
  wait "$tpid" || true
  wait "$opid" || true  # exit 3: the reader's timeout, as intended
  node -e '
    const fs = require("fs");
    const lines = fs.readFileSync(process.argv[1], "utf8").split("\n").filter((l) => l.startsWith("{\"topic\""));
    const ms = [];
    for (const l of lines) {
      const m = JSON.parse(l);
      const h = m.header || (m.transforms && m.transforms[0] && m.transforms[0].header);
      if (!h) continue;
      const stamp = BigInt(h.stamp.sec) * 1000000000n + BigInt(h.stamp.nanosec);
      ms.push(Number(BigInt(m.receive_time_ns) - stamp) / 1e6);
    }
    ms.sort((a, b) => a - b);
    const q = (p) => (ms.length ? ms[Math.min(ms.length - 1, Math.floor(p * ms.length))] : NaN);
    const [user, sys, wall] = fs.readFileSync(process.argv[2], "utf8").trim().split(/\s+/).map(Number);
    console.log(ms.length, q(0.5).toFixed(2), q(0.99).toFixed(2), (100 * (user + sys) / wall).toFixed(1));
  ' "$work/$name.jsonl" "$work/$name.time"
}

echo "| run | samples floor / mocaplink | floor p50 / p99 | mocaplink p50 / p99 | ratio p50 / p99 | CPU floor / mocaplink |"
echo "|---|---:|---|---|---|---:|"
rows=()
for ((rep = 1; rep <= ${REPEAT:-2}; rep++)); do
  read -r fs fp50 fp99 fcpu < <(measure "floor$rep" "$floor" --source "$source_url" --domain "$domain")
  read -r ms mp50 mp99 mcpu < <(measure "run$rep" "$bin" run --config "$work/run.toml")
  rows+=("$fs $fp50 $fp99 $fcpu $ms $mp50 $mp99 $mcpu")
  echo "| $rep | $fs / $ms | $fp50 / $fp99 ms | $mp50 / $mp99 ms |" \
    "$(node -e 'console.log((process.argv[3]/process.argv[1]).toFixed(2) + " / " + (process.argv[4]/process.argv[2]).toFixed(2))' "$fp50" "$fp99" "$mp50" "$mp99") |" \
    "$fcpu / $mcpu % |"
done
node -e '
  const reps = process.argv.slice(1).map((r) => r.split(" ").map(Number));
  const med = (xs) => { const s = [...xs].sort((a, b) => a - b); const k = s.length >> 1;
    return s.length % 2 ? s[k] : (s[k - 1] + s[k]) / 2; };
  const col = (i) => med(reps.map((r) => r[i]));
  const ratio = (i, j) => med(reps.map((r) => r[i] / r[j])).toFixed(2);
  console.log(`| median | ${col(0)} / ${col(4)} | ${col(1).toFixed(2)} / ${col(2).toFixed(2)} ms | ` +
    `${col(5).toFixed(2)} / ${col(6).toFixed(2)} ms | ${ratio(5, 1)} / ${ratio(6, 2)} | ` +
    `${col(3).toFixed(1)} / ${col(7).toFixed(1)} % |`);
' "${rows[@]}"
