#!/usr/bin/env bash
# Times skinned-decimate end to end against meshoptimizer's gltfpack 1.3 (npm, pinned in tools/) on the
# same large skinned GLB in the same run: wall seconds and peak memory (GNU time), the median of N runs.
# gltfpack simplifies first; ours is asked for gltfpack's achieved triangle count with --faces.
#
#   bench/cli-vs-gltfpack.sh [RATIO] [RUNS]      (defaults 0.01 and 3; needs scripts/build and scripts/setup)
#   OMSK_CHARACTER=human4 bench/cli-vs-gltfpack.sh 0.01 1       (the human subdivided once more: 955,392)
#
# The input is the human workload of omsk-bench (Testwuson Loop-subdivided three times, 238,848
# triangles, its three clips), written by `omsk-bench --write human FILE`, or the character
# OMSK_CHARACTER names (`omsk-bench --help` lists them).
set -euo pipefail
cd "$(dirname "$0")/.."
ratio=${1:-0.01}
runs=${2:-3}
cli=build/apps/skinned-decimate
bench=build/bench/omsk-bench
gltfpack=tools/node_modules/gltfpack/cli.js
for f in "$cli" "$bench" "$gltfpack"; do
  [ -e "$f" ] || { echo "cli-vs-gltfpack: $f is missing: run scripts/build and scripts/setup first" >&2; exit 1; }
done
[ -x /usr/bin/time ] || { echo "cli-vs-gltfpack: GNU time (/usr/bin/time) is missing: apt-get install time" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
character=${OMSK_CHARACTER:-human}
"$bench" --write "$character" "$work/human.glb"

# Runs a command RUNS times; prints "median_seconds peak_kb" (peak: the largest over the runs).
measure() {
  local times=() peak=0
  for _ in $(seq "$runs"); do
    /usr/bin/time -f "%e %M" -o "$work/time" "$@" >"$work/out" 2>&1 || { cat "$work/out" >&2; exit 1; }
    read -r s kb <"$work/time"
    times+=("$s")
    [ "$kb" -gt "$peak" ] && peak=$kb
  done
  printf '%s\n' "${times[@]}" | sort -g | awk -v p="$peak" '{a[NR]=$1} END {print a[int((NR+1)/2)], p}'
}

pack=(node "$gltfpack" -i "$work/human.glb" -o "$work/gltfpack.glb" -si "$ratio" -sv -sp -se 1 -noq)
read -r pack_s pack_kb < <(measure "${pack[@]}")
"${pack[@]}" -v >"$work/pack.log" 2>&1
faces=$(grep -o 'output: 1 mesh primitives ([0-9]* triangles' "$work/pack.log" | grep -o '[0-9]* triangles' | cut -d' ' -f1)
[ -n "$faces" ] || { echo "cli-vs-gltfpack: could not read gltfpack's triangle count" >&2; cat "$work/pack.log" >&2; exit 1; }

echo "input: omsk-bench $character ($(grep -o 'input: 1 mesh primitives ([0-9]* triangles' "$work/pack.log" | grep -o '[0-9]* triangles')), gltfpack -si $ratio reached $faces triangles; median of $runs runs"
printf '%-44s %9s %9s %10s %10s\n' "command" "seconds" "peak MB" "time x" "memory x"
row() {
  local name=$1 s=$2 kb=$3
  awk -v n="$name" -v s="$s" -v kb="$kb" -v ps="$pack_s" -v pk="$pack_kb" \
    'BEGIN {printf "%-44s %9.2f %9.0f %10.2f %10.2f\n", n, s, kb / 1024, s / ps, kb / pk}'
}
row "gltfpack 1.3 -si $ratio -sv -sp -se 1 -noq" "$pack_s" "$pack_kb"
for variant in "" "--no-eval" "--no-eval --normal-weight 0" "--no-eval --threads 1"; do
  # shellcheck disable=SC2086
  read -r s kb < <(measure "$cli" "$work/human.glb" -o "$work/ours.glb" --faces "$faces" --quiet $variant)
  row "skinned-decimate --faces $faces $variant" "$s" "$kb"
done
