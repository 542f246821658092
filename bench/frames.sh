#!/usr/bin/env bash
# Meshes animated without a skeleton, and example poses chosen by the key-frame GA, on held-out frames:
#  1. the methods side by side (--compare): frames (per-frame quadrics of the vertices' trajectories),
#     deform (the deformation-analysis report's importance-weighted QEM), static (OpenMesh's rest-shape QEM)
#     and the skinned solver's methods (which decimate the rest shape and carry the morph offsets along),
#     on Quake's faerie.md2 and sydney.md2 (198 frames each) and a folding OBJ sequence (9 frames);
#  2. --pose-select ga against even at the same K (example poses), the held-out frames the same for both.
#
#   bench/frames.sh [RATIOS]      (default "0.5,0.25,0.1"; needs scripts/build)
set -euo pipefail
cd "$(dirname "$0")/.."
ratios=${1:-"0.5,0.25,0.1"}
cli=build/apps/skinned-decimate
models=/usr/share/assimp/models
[ -x "$cli" ] || { echo "frames: $cli is missing: run scripts/build first" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# The folding sequence: an 8 x 8 grid of squares whose far half folds up by 0, 10, ... 80 degrees.
for f in 1 2 3 4 5 6 7 8 9; do
  awk -v a="$(( (f - 1) * 10 ))" 'BEGIN {
    r = a * 3.14159265358979 / 180
    for (j = 0; j <= 8; ++j) for (i = 0; i <= 8; ++i)
      printf "v %.9f %d %.9f\n", (i <= 4 ? i : 4 + (i - 4) * cos(r)), j, (i <= 4 ? 0 : (i - 4) * sin(r))
    for (j = 0; j < 8; ++j) for (i = 0; i < 8; ++i) {
      v = j * 9 + i + 1
      printf "f %d %d %d\nf %d %d %d\n", v, v + 1, v + 10, v, v + 10, v + 9
    } }' >"$work/fold_000$f.obj"
done

echo "== 1. methods on held-out frames (mean RMS and max Hausdorff, % of the diagonal)"
for in in "$models/MD2/faerie.md2" "$models/MD2/sydney.md2" "$work/fold_0001.obj"; do
  echo "-- $(basename "$in")"
  "$cli" "$in" -o "$work/c.glb" --lods "$ratios" --compare --quiet 2>/dev/null | sed -n '/^comparison/,$p' | tail -n +2
done

echo
echo "== 2. example poses: even against the key-frame GA, same K, same held-out frames (ratio 0.25)"
printf '%-22s %4s %12s %12s %8s\n' character K "even RMS%" "ga RMS%" "ga/even"
for in in "$models/MD2/faerie.md2" "$models/MD2/sydney.md2" "$models/X/Testwuson.X" \
  "$models/FBX/animation_with_skeleton.fbx"; do
  for k in 4 8; do
    rms() {
      "$cli" "$in" -o "$work/p.glb" --ratio 0.25 --poses "$k" --pose-select "$1" --quiet 2>/dev/null |
        awk '/^  0\.2500/ {print $6}'
    }
    e=$(rms even)
    g=$(rms ga)
    awk -v c="$(basename "$in")" -v k="$k" -v e="$e" -v g="$g" \
      'BEGIN {printf "%-22s %4d %12.4f %12.4f %8.2f\n", c, k, e, g, (e > 0 ? g / e : 0)}'
  done
done
