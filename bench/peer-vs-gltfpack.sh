#!/usr/bin/env bash
# The peer benchmark: skinned-decimate against meshoptimizer's gltfpack 1.3 (npm, pinned in tools/) at equal
# triangle counts, judged on held-out frames neither tool saw, every file posed by the glTF spec itself
# (build/bench/omsk-peer). gltfpack simplifies first; ours is asked for gltfpack's achieved count with --faces.
#
#   bench/peer-vs-gltfpack.sh [RATIOS]      (default "0.5 0.25 0.1"; needs scripts/build and scripts/setup)
#
# Characters (each given to both tools as the same GLB): Testwuson.X and FBX/animation_with_skeleton.fbx
# (converted once by skinned-decimate --ratio 1), glTF2/simple_skin, DeCoro's leg and the L&S column
# (omsk-bench --write), and wuson8: Testwuson with its skin diffused over 8 bones (three rounds of
# Laplacian smoothing of the weight field, 8 heaviest kept, renormalised: OpenMeshSkinned::diffuse_skin_weights).
# The last column is the texture-space deviation in the rest pose (omsk-peer's uv_rms, % of the texture's width),
# and its 95th percentile, gltfpack's / ours, where both outputs keep UVs. OMSK_PEER_EXTRA adds arguments to ours
# (e.g. OMSK_PEER_EXTRA=--no-refit); OMSK_PEER_ONLY keeps the characters named (e.g. "faerie sydney"). gltfpack runs twice: -se 1 (no error limit: it reaches the ratio) and with its default error limit
# (it may stop early; ours is then asked for the same, larger, count: light simplification).
# faerie and sydney: Quake MD2 characters animated without a skeleton (198 stored frames each, read by
# skinned-decimate into one morph-target clip and written with --ratio 1); ours decimates them with its
# default method for such meshes, frames. Its final fit fits each of their stored frames on its own (every
# stored frame is data the LOD keeps as a morph target); the held-out times fall between stored frames, so for
# these two the bench measures blends of fitted frames, not poses the tool never saw (bench/README.md).
set -euo pipefail
cd "$(dirname "$0")/.."
ratios=${1:-"0.5 0.25 0.1"}
cli=build/apps/skinned-decimate
bench=build/bench/omsk-bench
peer=build/bench/omsk-peer
gltfpack=tools/node_modules/gltfpack/cli.js
models=/usr/share/assimp/models
for f in "$cli" "$bench" "$peer" "$gltfpack"; do
  [ -e "$f" ] || { echo "peer-vs-gltfpack: $f is missing: run scripts/build and scripts/setup first" >&2; exit 1; }
done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

. bench/characters.sh
write_characters "$work"
field() { grep "\"candidate\":\"$2\"" "$1" | grep -o "\"$3\":[0-9.e+-]*" | cut -d: -f2; }

printf '%-14s %-9s %6s %9s | %10s %10s %7s | %10s %10s %7s | %21s\n' character gltfpack ratio triangles \
  "gp RMS%" "ours RMS%" "ratio" "gp Haus%" "ours Haus%" "ratio" "UV RMS/p95 gp | ours"
for in in "${inputs[@]}"; do
  name=$(basename "${in%.*}")
  if [ -n "${OMSK_PEER_ONLY:-}" ] && [[ " $OMSK_PEER_ONLY " != *" $name "* ]]; then continue; fi
  for r in $ratios; do
    for mode in "-se 1" "default"; do
      extra=()
      [ "$mode" = "-se 1" ] && extra=(-se 1)
      node "$gltfpack" -i "$in" -o "$work/gp.glb" -si "$r" -sv -sp "${extra[@]}" -noq -v >"$work/gp.log" 2>&1 ||
        { echo "peer-vs-gltfpack: gltfpack failed on $in" >&2; cat "$work/gp.log" >&2; exit 1; }
      n=$(triangles "$work/gp.log" || true)
      if [ -z "$n" ] || [ "$n" -lt 1 ]; then
        printf '%-14s %-9s %6s   gltfpack kept no triangle\n' "$name" "$mode" "$r"
        continue
      fi
      "$cli" "$in" -o "$work/ours.glb" --faces "$n" --quiet --no-eval ${OMSK_PEER_EXTRA:-} >"$work/ours.log" 2>&1 ||
        { echo "peer-vs-gltfpack: skinned-decimate failed on $in:" >&2; cat "$work/ours.log" >&2; exit 1; }
      "$peer" "$in" "$work/gp.glb" "$work/ours.glb" >"$work/peer.jsonl"
      gr=$(field "$work/peer.jsonl" "$work/gp.glb" heldout_rms)
      or=$(field "$work/peer.jsonl" "$work/ours.glb" heldout_rms)
      gh=$(field "$work/peer.jsonl" "$work/gp.glb" heldout_hausdorff)
      oh=$(field "$work/peer.jsonl" "$work/ours.glb" heldout_hausdorff)
      ot=$(field "$work/peer.jsonl" "$work/ours.glb" triangles)
      # Texture-space deviation (rest pose, % of the texture's width) where both outputs keep UVs: gltfpack drops
      # them when no material uses a texture.
      gu=$(field "$work/peer.jsonl" "$work/gp.glb" uv_rms || true)
      ou=$(field "$work/peer.jsonl" "$work/ours.glb" uv_rms || true)
      gp95=$(field "$work/peer.jsonl" "$work/gp.glb" uv_p95 || true)
      op95=$(field "$work/peer.jsonl" "$work/ours.glb" uv_p95 || true)
      awk -v c="$name" -v m="$mode" -v r="$r" -v n="$n" -v ot="$ot" -v gr="$gr" -v or="$or" -v gh="$gh" -v oh="$oh" \
        -v gu="${gu:--}" -v ou="${ou:--}" -v gp95="${gp95:--}" -v op95="${op95:--}" \
        'BEGIN {uv = (gu == "-" || ou == "-") ? "-" : sprintf("%.1f/%.1f | %.1f/%.1f", gu, gp95, ou, op95);
                printf "%-14s %-9s %6s %4s/%-4s | %10.4f %10.4f %7.2f | %10.4f %10.4f %7.2f | %21s\n", c, m, r, n, ot, gr,
                or, (gr > 0 ? or / gr : 0), gh, oh, (gh > 0 ? oh / gh : 0), uv}'
    done
  done
done
