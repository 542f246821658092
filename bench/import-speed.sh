#!/usr/bin/env bash
# glTF import speed (issue 33): the 238,848-triangle human (omsk-bench --write human) read by the CLI, as the
# report's import_seconds: isolated (the default: read in a child process and shipped back) and --no-isolate.
# With a reference build, both run in the same script, alternating, and the ratios are ours / reference; each
# figure is the minimum over the runs (the least disturbed one: other work may share the cores).
#   bench/import-speed.sh [REFERENCE_BUILD_DIR] [RUNS]   (default: no reference, 5 runs; needs scripts/build)
set -euo pipefail
cd "$(dirname "$0")/.."
ref=${1:-}
runs=${2:-5}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
build/bench/omsk-bench --write human "$work/human.glb"
import_seconds() { /usr/bin/python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["import_seconds"])' "$1"; }
# One run of $1 on the human: "isolated_import no_isolate_import".
one() {
  "$1" "$work/human.glb" -o "$work/o.glb" --ratio 1 --no-eval --quiet --report "$work/a.json" >/dev/null
  "$1" "$work/human.glb" -o "$work/o.glb" --ratio 1 --no-eval --quiet --no-isolate --report "$work/b.json" >/dev/null
  echo "$(import_seconds "$work/a.json") $(import_seconds "$work/b.json")"
}
binaries=(build/apps/skinned-decimate)
[ -n "$ref" ] && binaries=("$ref/apps/skinned-decimate" build/apps/skinned-decimate)
for r in $(seq "$runs"); do
  for b in "${binaries[@]}"; do echo "$b $(one "$b")"; done
done > "$work/all"
awk -v ref="${ref:+$ref/apps/skinned-decimate}" '
  { for (c = 2; c <= 3; ++c) if (!(($1, c) in m) || $c < m[$1, c]) m[$1, c] = $c; seen[$1] = 1 }
  END {
    printf "%-44s %12s %16s\n", "binary (min of '"$runs"' runs)", "import s", "--no-isolate s"
    for (b in seen) printf "%-44s %12.3f %16.3f\n", b, m[b, 2], m[b, 3]
    if (ref != "") { o = "build/apps/skinned-decimate"
      printf "%-44s %12.2f %16.2f\n", "ours / reference", m[o, 2] / m[ref, 2], m[o, 3] / m[ref, 3] }
  }' "$work/all"
