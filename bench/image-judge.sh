#!/usr/bin/env bash
# The image judge: how the original character and each LOD *look*, ours against meshoptimizer's gltfpack 1.3
# at equal triangle counts. Every file is rendered the same way by three.js in headless Chromium (the file's
# own PBR materials and textures as GLTFLoader gives them, one light rig, one environment), posed by three.js's
# own skinning and morphing at held-out frames (from our tool's --report: frames neither tool saw), seen from
# four directions framed on the original's posed bounds; each LOD's image is compared with the original's per
# pixel (bench/image-judge/metrics.mjs): PSNR on linear colour and SSIM on luma, inside the character and on
# its silhouette.
#
#   bench/image-judge.sh [--jsonl FILE] [--images DIR] [--size PX] [--frames K] [RATIOS]
#
# RATIOS defaults to "0.5 0.25 0.1". The characters are bench/peer-vs-gltfpack.sh's, built the same way;
# gltfpack runs with -si R -sv -sp -se 1 -noq and ours is asked for gltfpack's achieved count with --faces.
# --images keeps one PNG per character, ratio and frame (rows: the directions; columns: original | gltfpack |
# ours). --size: pixels per side of a view (384); --frames: held-out frames used, evenly thinned (4).
# OMSK_PEER_ONLY keeps the characters named (e.g. "faerie sydney"); OMSK_PEER_EXTRA adds arguments to ours;
# OMSK_JUDGE_FRAMES_FROM (e.g. "--poses 8") takes the held-out frames from a run of ours with those arguments
# instead of from ours itself. Needs scripts/build and scripts/setup.
set -euo pipefail
cd "$(dirname "$0")/.."
judge_args=()
while [ $# -gt 0 ]; do
  case "$1" in
    --jsonl | --images | --size | --frames)
      [ $# -ge 2 ] || { echo "image-judge: $1 needs a value" >&2; exit 2; }
      judge_args+=("$1" "$2")
      shift 2
      ;;
    -*) echo "image-judge: unknown option $1" >&2; exit 2 ;;
    *) break ;;
  esac
done
ratios=${1:-"0.5 0.25 0.1"}
cli=build/apps/skinned-decimate
bench=build/bench/omsk-bench
gltfpack=tools/node_modules/gltfpack/cli.js
models=/usr/share/assimp/models
for f in "$cli" "$bench" "$gltfpack" tools/node_modules/three tools/node_modules/playwright-core \
  tools/node_modules/esbuild "${OMSK_CHROMIUM:-/usr/bin/chromium}"; do
  [ -e "$f" ] || { echo "image-judge: $f is missing: run scripts/build and scripts/setup first" >&2; exit 1; }
done
command -v node >/dev/null || { echo "image-judge: node is missing: run scripts/setup first" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

. bench/characters.sh
write_characters "$work"

# One job line per character and ratio: name, original, ratio, gltfpack's triangles, its LOD, ours, our report.
jobs="$work/jobs.tsv"
: >"$jobs"
for in in "${inputs[@]}"; do
  name=$(basename "${in%.*}")
  if [ -n "${OMSK_PEER_ONLY:-}" ] && [[ " $OMSK_PEER_ONLY " != *" $name "* ]]; then continue; fi
  for r in $ratios; do
    gp="$work/$name-$r-gp.glb" ours="$work/$name-$r-ours.glb" report="$work/$name-$r-ours.json"
    node "$gltfpack" -i "$in" -o "$gp" -si "$r" -sv -sp -se 1 -noq -v >"$work/gp.log" 2>&1 ||
      { echo "image-judge: gltfpack failed on $in" >&2; cat "$work/gp.log" >&2; exit 1; }
    n=$(triangles "$work/gp.log" || true)
    if [ -z "$n" ] || [ "$n" -lt 1 ]; then
      printf '%s\t%s\t%s\t0\t-\t-\t-\n' "$name" "$in" "$r" >>"$jobs"
      continue
    fi
    "$cli" "$in" -o "$ours" --faces "$n" --quiet --no-eval --report "$report" ${OMSK_PEER_EXTRA:-} >"$work/ours.log" 2>&1 ||
      { echo "image-judge: skinned-decimate failed on $in:" >&2; cat "$work/ours.log" >&2; exit 1; }
    frames=""
    if [ -n "${OMSK_JUDGE_FRAMES_FROM:-}" ]; then
      # The held-out frames of another run (e.g. "--poses 8"), so that two settings are judged on the same frames.
      # They depend on the poses only, so that run makes no collapse and no fit.
      frames="$work/$name-$r-frames.json"
      "$cli" "$in" -o "$work/frames.glb" --ratio 1 --no-refit --quiet --no-eval --report "$frames" \
        $OMSK_JUDGE_FRAMES_FROM >"$work/frames.log" 2>&1 ||
        { echo "image-judge: skinned-decimate failed on $in:" >&2; cat "$work/frames.log" >&2; exit 1; }
    fi
    printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$name" "$in" "$r" "$n" "$gp" "$ours" "$report" "$frames" >>"$jobs"
  done
done
node bench/image-judge/judge.mjs "$jobs" "${judge_args[@]}"
