#!/usr/bin/env bash
# Fuzzes the import path with libFuzzer for N minutes (default 30), then (bench/fuzz-triage.sh) runs every input that crashed
# or hung the in-process importer through skinned-decimate, which must refuse each with exit 1 and one
# line (its isolated reader turns a reader crash into an error).
#
#   bench/fuzz.sh [--pipeline] [MINUTES]   results in bench/results/fuzz/ (or fuzz-pipeline/ with --pipeline)
#
# --pipeline fuzzes fuzz/fuzz_pipeline instead: import, one decimation level and export of small inputs,
# so that a strange number that the reader lets through is followed into the solves and the writer.
# Builds with Clang into build-fuzz/ (ASan + UBSan + libFuzzer); needs the normal build for the CLI.
set -euo pipefail
cd "$(dirname "$0")/.."
target=fuzz_import
out=bench/results/fuzz
if [ "${1:-}" = "--pipeline" ]; then
  target=fuzz_pipeline
  out=bench/results/fuzz-pipeline
  shift
fi
minutes=${1:-30}
[ "$minutes" -ge 1 ] 2>/dev/null || { echo "usage: bench/fuzz.sh [--pipeline] [MINUTES >= 1]" >&2; exit 2; }
command -v clang++ >/dev/null || { echo "fuzz.sh: installing clang"; apt-get install -y -qq clang >/dev/null; }
scripts/setup
CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DOMSK_BUILD_FUZZ=ON \
  -DOMSK_BUILD_TESTS=OFF -DOMSK_BUILD_APPS=OFF -DOMSK_BUILD_BENCH=OFF >/dev/null
cmake --build build-fuzz -j2 --target "$target"
scripts/build >/dev/null

# Seed corpus: the Debian test models of the formats users bring, first byte = format (see fuzz_import.cc).
corpus=build-fuzz/corpus
rm -rf "$corpus" "$out/artifacts"
mkdir -p "$corpus" "$out/artifacts"
M=/usr/share/assimp/models
i=0
add() {  # add FILE FORMAT-INDEX
  { printf "\\x$(printf %02x "$2")"; cat "$1"; } >"$corpus/seed$i"
  i=$((i + 1))
}
for f in $M/X/*.x $M/X/*.X; do add "$f" 0; done
add $M/MD5/SimpleCube.md5mesh 1
for f in $M/FBX/animation_with_skeleton.fbx $M/FBX/huesitos.fbx $M/FBX/box.fbx $M/FBX/spider.fbx; do add "$f" 2; done
add $M/glTF2/simple_skin/simple_skin.gltf 3
add $M/glTF2/glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf 3
for f in $M/glTF2/BoxTextured-glTF-Binary/BoxTextured.glb $M/glTF2/BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb; do add "$f" 4; done
for f in $M/OBJ/box.obj $M/OBJ/spider.obj; do [ -f "$f" ] && add "$f" 5; done
add $M/Collada/duck.dae 6
add $M/PLY/cube.ply 7
for f in $M/SMD/*.smd; do add "$f" 8; done
for f in $M/B3D/*.b3d; do add "$f" 9; done
echo "fuzz.sh: $i seeds; fuzzing for $minutes minutes"

# -fork keeps going after a crash (the known assimp crashers would otherwise stop the run at once).
# Leak checks are off: the leaks it finds are assimp's and zlib's on failed reads, and each one would end
# a fork job; the ASan run of the test suite checks our own code for leaks.
log=$out/libfuzzer.log
build-fuzz/"$target" "$corpus" -fork=1 -ignore_crashes=1 -ignore_ooms=1 -ignore_timeouts=1 \
  -max_total_time=$((minutes * 60)) -timeout=30 -rss_limit_mb=4096 -max_len=1048576 -detect_leaks=0 \
  -artifact_prefix="$out/artifacts/" >"$log" 2>&1 || true

# Every finding through the CLI, and where each happens.
FUZZ_TARGET=$target bench/fuzz-triage.sh "$out" "$minutes"
