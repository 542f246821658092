#!/usr/bin/env bash
# Wall time of this build against a reference build in the same run, for changes that must not make the tool
# slower (a refactoring, a reader change): each command runs on both builds, alternating, and each figure is
# the minimum over the runs (the least disturbed one: other work may share the cores).
#
#   bench/time-vs-reference.sh REFERENCE_BUILD_DIR [RUNS]    (default 3 runs; needs scripts/build)
#
# REFERENCE_BUILD_DIR holds apps/skinned-decimate and bench/omsk-bench, e.g. a build of an older commit
# (git worktree add /tmp/ref COMMIT && (cd /tmp/ref && scripts/build)). Commands: the CLI on the
# 238,848-triangle human (omsk-bench --write human) at 1 %, with its held-out report and with --no-eval;
# omsk-bench's column workload; its human workload's skinned modules under LazyDecimaterT on one thread.
set -euo pipefail
cd "$(dirname "$0")/.."
ref=${1:?usage: bench/time-vs-reference.sh REFERENCE_BUILD_DIR [RUNS]}
runs=${2:-3}
for b in "$ref" build; do
  for f in apps/skinned-decimate bench/omsk-bench; do
    [ -x "$b/$f" ] || { echo "time-vs-reference: $b/$f is missing" >&2; exit 1; }
  done
done
[ -x /usr/bin/time ] || { echo "time-vs-reference: GNU time (/usr/bin/time) is missing: apt-get install time" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
build/bench/omsk-bench --write human "$work/human.glb" >/dev/null

names=("cli human 1%" "cli human 1% --no-eval" "omsk-bench column" "omsk-bench human lazy 1 thread")
# Command number $2 of build $1.
command_of() {
  case $2 in
    0) echo "$1/apps/skinned-decimate $work/human.glb -o $work/o.glb --ratio 0.01 --quiet" ;;
    1) echo "$1/apps/skinned-decimate $work/human.glb -o $work/o.glb --ratio 0.01 --quiet --no-eval" ;;
    2) echo "$1/bench/omsk-bench --workload column" ;;
    3) echo "$1/bench/omsk-bench --workload human --lazy-only --threads 1 --no-heldout" ;;
  esac
}
for _ in $(seq "$runs"); do
  for c in "${!names[@]}"; do
    for b in ref ours; do
      dir=build
      [ $b = ref ] && dir=$ref
      # shellcheck disable=SC2046
      /usr/bin/time -f "%e" -o "$work/t" $(command_of "$dir" "$c") >"$work/out" 2>&1 || {
        cat "$work/out" >&2
        exit 1
      }
      echo "$c $b $(cat "$work/t")"
    done
  done
done >"$work/all"
printf '%-34s %12s %12s %8s\n' "command (min of $runs runs)" "reference s" "ours s" "ratio"
for c in "${!names[@]}"; do
  awk -v c="$c" -v n="${names[$c]}" '$1 == c { if (!($2 in m) || $3 < m[$2]) m[$2] = $3 }
    END { printf "%-34s %12.2f %12.2f %8.2f\n", n, m["ref"], m["ours"], m["ours"] / m["ref"] }' "$work/all"
done
