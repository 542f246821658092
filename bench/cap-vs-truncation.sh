#!/usr/bin/env bash
# The weight cap alone (no decimation): skinned-decimate --ratio 1 --max-influences N (the skinned method:
# every vertex over the cap gets weights re-solved against the example poses) against plain top-N truncation
# (the heaviest N weights kept and renormalised: what --method frames does to a skin before it decimates,
# and what most tools do), judged on held-out frames by the independent glTF-spec poser (omsk-peer).
#
#   bench/cap-vs-truncation.sh [CAPS]      (default "4 2"; needs scripts/build)
#
# Characters: wuson8 (Testwuson with its skin diffused over 8 bones, omsk-bench --write wuson8) and the FBX
# character (raw deformer weights on up to 8 bones, converted by skinned-decimate --max-influences 8).
set -euo pipefail
cd "$(dirname "$0")/.."
caps=${1:-"4 2"}
cli=build/apps/skinned-decimate
bench=build/bench/omsk-bench
peer=build/bench/omsk-peer
for f in "$cli" "$bench" "$peer"; do
  [ -e "$f" ] || { echo "cap-vs-truncation: $f is missing: run scripts/build first" >&2; exit 1; }
done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$bench" --write wuson8 "$work/wuson8.glb" >/dev/null
"$cli" /usr/share/assimp/models/FBX/animation_with_skeleton.fbx -o "$work/fbx.glb" --ratio 1 --max-influences 8 --no-refit \
  --quiet --no-eval >/dev/null 2>&1
field() { grep "\"candidate\":\"$2\"" "$1" | grep -o "\"$3\":[0-9.e+-]*" | cut -d: -f2; }
printf '%-8s %4s | %12s %12s %7s | %12s %12s %7s\n' character cap "trunc RMS%" "ours RMS%" ratio "trunc Haus%" \
  "ours Haus%" ratio
for in in "$work/wuson8.glb" "$work/fbx.glb"; do
  for c in $caps; do
    "$cli" "$in" -o "$work/ours.glb" --ratio 1 --max-influences "$c" --quiet --no-eval >/dev/null 2>&1
    "$cli" "$in" -o "$work/trunc.glb" --ratio 1 --max-influences "$c" --method frames --no-refit --quiet --no-eval \
      >/dev/null 2>&1
    "$peer" "$in" "$work/trunc.glb" "$work/ours.glb" >"$work/peer.jsonl"
    tr=$(field "$work/peer.jsonl" "$work/trunc.glb" heldout_rms)
    or=$(field "$work/peer.jsonl" "$work/ours.glb" heldout_rms)
    th=$(field "$work/peer.jsonl" "$work/trunc.glb" heldout_hausdorff)
    oh=$(field "$work/peer.jsonl" "$work/ours.glb" heldout_hausdorff)
    awk -v n="$(basename "${in%.*}")" -v c="$c" -v tr="$tr" -v or="$or" -v th="$th" -v oh="$oh" \
      'BEGIN {printf "%-8s %4d | %12.6f %12.6f %7.2f | %12.6f %12.6f %7.2f\n", n, c, tr, or, (tr > 0 ? or / tr : 0),
              th, oh, (th > 0 ? oh / th : 0)}'
  done
done
