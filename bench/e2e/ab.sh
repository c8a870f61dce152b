#!/usr/bin/env bash
# bench/e2e/ab.sh: the pose path of a change against its base, in one run (issue 50).
# Builds BASE's `mocaplink` (a git revision: a commit, a tag, HEAD~1) in a worktree of its own and
# this checkout's working tree beside it, both Release with the benches, then runs
# bench/e2e/run_e2e.sh for each, alternating A B B A … so that a machine's drift falls on both
# alike. The receivers and the floor are the working tree's for both: one ruler, two builds.
# Prints each run_e2e row prefixed with its build and round; quote the medians and the ratios to
# the floor of the same run (docs/performance.md).
#
#   bench/e2e/ab.sh BASE [N...]                   (default N: 1 50 1000)
#
# ROUNDS=K (default 2) runs of each build. SECONDS_PER_ROW (default 10) per run_e2e row.
# Everything run_e2e.sh reads (SOCKETS, REPEAT, NICE, LOAD, CPUS, RATE_HZ, ...) passes through; for
# 1000 vehicles use SOCKETS=shared, or the receivers cost more than the bridge.
# AB_DIR (default /tmp/mocaplink-ab) holds the worktrees and builds, kept between runs: a build is
# redone only when its revision (or the working tree's files) changed. AB_BUILD_ONLY=1 stops after
# building. Builds run at nice 10 so they can share the machine with other work; the runs do not.
set -euo pipefail
[ $# -ge 1 ] || { sed -n '2,17p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
base_rev=$1
shift
counts=("$@")
[ ${#counts[@]} -gt 0 ] || counts=(1 50 1000)
src=$(cd "$(dirname "$0")/../.." && pwd)
ab_dir=${AB_DIR:-/tmp/mocaplink-ab}
base_sha=$(git -C "$src" rev-parse --verify "$base_rev^{commit}")
mkdir -p "$ab_dir"

configure_and_build() {  # SOURCE BUILD TARGET...
  local source=$1 build=$2
  shift 2
  if [ ! -f "$build/CMakeCache.txt" ]; then
    nice -n 10 cmake -S "$source" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DMOCAPLINK_BENCH=ON -DBUILD_TESTING=OFF >"$build.configure.log" 2>&1 ||
      { tail -20 "$build.configure.log" >&2; exit 1; }
  fi
  nice -n 10 cmake --build "$build" --target "$@" >"$build.build.log" 2>&1 ||
    { tail -30 "$build.build.log" >&2; exit 1; }
}

# A: the base revision, in a detached worktree of its own (never this checkout's files).
base_tree=$ab_dir/tree-$base_sha
if [ ! -d "$base_tree" ]; then
  git -C "$src" worktree add --detach "$base_tree" "$base_sha" >/dev/null
fi
echo "ab: A = $base_rev ($(git -C "$src" log -1 --format='%h %<(60,trunc)%s' "$base_sha"))" >&2
configure_and_build "$base_tree" "$ab_dir/build-$base_sha" mocaplink
# B: this working tree as it is, uncommitted changes included.
echo "ab: B = working tree of $src ($(git -C "$src" log -1 --format='%h %<(60,trunc)%s')$(
  git -C "$src" diff --quiet HEAD || echo ', with uncommitted changes'))" >&2
configure_and_build "$src" "$ab_dir/build-worktree" mocaplink e2e_receivers e2e_floor
[ "${AB_BUILD_ONLY:-}" = 1 ] && exit 0

bin_a=$ab_dir/build-$base_sha/mocaplink
bin_b=$ab_dir/build-worktree/mocaplink
[ -x "$bin_a" ] || bin_a=$ab_dir/build-$base_sha/apps/mocaplink/mocaplink
[ -x "$bin_b" ] || bin_b=$ab_dir/build-worktree/apps/mocaplink/mocaplink
receivers=$(find "$ab_dir/build-worktree" -name e2e_receivers -type f -perm -u+x | head -1)
floor=$(find "$ab_dir/build-worktree" -name e2e_floor -type f -perm -u+x | head -1)

rounds=${ROUNDS:-2}
for ((round = 1; round <= rounds; round++)); do
  order=(A B)
  [ $((round % 2)) -eq 0 ] && order=(B A)
  for which in "${order[@]}"; do
    bin=$bin_a
    [ "$which" = B ] && bin=$bin_b
    "$src/bench/e2e/run_e2e.sh" "$bin" "$receivers" "$floor" "${SECONDS_PER_ROW:-10}" \
      "${counts[@]}" | sed -n '3,$p' | sed "s/^/| $which | $round /"
  done
done | { echo "| build | round | vehicles | mocap frames | lost floor / mocaplink | floor p50 / p99 | mocaplink p50 / p99 | ratio p50 / p99 | first / last vehicle p50, floor | first / last vehicle p50, mocaplink | CPU floor / mocaplink | peak RSS | superseded floor / mocaplink | CPU per datagram, ratio |"
  echo "|---|---:|---:|---:|---:|---|---|---|---|---|---:|---:|---:|---:|"
  cat; }
