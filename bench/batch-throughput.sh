#!/usr/bin/env bash
# Batch throughput: `skinned-decimate batch` over the suite's characters with --jobs 1 and --jobs 2, in one run
# (every asset re-made: --force), and a resumed run that finds them all up to date.
#   bench/batch-throughput.sh [BUILD_DIR]   (default build)
set -euo pipefail
cd "$(dirname "$0")/.."
exe="${1:-build}/apps/skinned-decimate"
m=/usr/share/assimp/models
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/lib"
for f in X/Testwuson.X FBX/huesitos.fbx FBX/animation_with_skeleton.fbx glTF2/simple_skin/simple_skin.gltf \
  MD2/faerie.md2 MD2/sydney.md2; do
  ln -s "$m/$f" "$work/lib/$(basename "$f")"
done
cp "$m/MD2/"*.bmp "$work/lib/"  # the MD2 skins beside their models
n=$(ls "$work/lib" | grep -vc '\.bmp$')
# Each asset's own work runs on every core by default; with --threads 1 the jobs share them out instead.
for run in "1" "2" "2 --threads 1" "1"; do
  set -- $run
  t0=$(date +%s.%N)
  "$exe" batch "$work/lib" -o "$work/out" --jobs "$@" --force --lods 0.5,0.25,0.1 --quiet \
    > "$work/log" || true
  t1=$(date +%s.%N)
  echo "--jobs $*: $n assets in $(echo "$t1 - $t0" | bc) s ($(tail -1 "$work/log"))"
done
t0=$(date +%s.%N)
"$exe" batch "$work/lib" -o "$work/out" --jobs 1 --lods 0.5,0.25,0.1 --quiet > "$work/log" || true
t1=$(date +%s.%N)
echo "resumed (all up to date): $(echo "$t1 - $t0" | bc) s ($(tail -1 "$work/log"))"
