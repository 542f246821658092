#!/usr/bin/env bash
# Triage of bench/fuzz.sh's findings (re-runnable on its results without fuzzing again):
#  1. every artifact through skinned-decimate, which must exit 0, or 1-2 with one line (its isolated
#     reader turns a reader crash, OOM or hang into an error);
#  2. where each one happens, replayed in-process: the innermost frame of the first stack trace that is
#     in this repository ("ours"), in libassimp or in zlib; our code called back from inside assimp (its
#     logger) counts as assimp's. A libFuzzer RSS-limit OOM has no allocation stack (it shows libFuzzer's
#     own heap), so those are listed as "rss-limit"; an input that no longer fails is "no-crash-on-replay".
#
#   bench/fuzz-triage.sh [RESULTS-DIR [MINUTES]]     default bench/results/fuzz; writes summary.txt, owners.txt
#   (FUZZ_TARGET=fuzz_pipeline replays with the pipeline target, as bench/fuzz.sh --pipeline does)
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-bench/results/fuzz}
minutes=${2:-?}
log=$out/libfuzzer.log
ext=(.x .md5mesh .fbx .gltf .glb .obj .dae .ply .smd .b3d)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
clean=0 bad=0
owners=$out/owners.txt
: >"$owners"
for a in "$out"/artifacts/*; do
  [ -f "$a" ] || continue
  b=$(od -An -tu1 -N1 "$a" | tr -d ' ')
  f="$tmp/input${ext[$((b % 10))]}"
  tail -c +2 "$a" >"$f"
  set +e
  timeout 120 build/apps/skinned-decimate "$f" -o "$tmp/out.glb" --quiet --time-limit 30 >/dev/null 2>"$tmp/err"
  code=$?
  set -e
  msg=$(grep -v ': warning: ' "$tmp/err" || true)
  lines=$(grep -c . <<<"$msg" || true)
  if [ "$code" -le 2 ] && { [ "$code" -eq 0 ] || [ "$lines" -eq 1 ]; }; then
    clean=$((clean + 1))
  else
    bad=$((bad + 1))
    echo "NOT CLEAN: $a exit $code: $msg"
  fi

  trace=$(build-fuzz/"${FUZZ_TARGET:-fuzz_import}" -runs=1 -timeout=10 -rss_limit_mb=4096 -malloc_limit_mb=4096 -detect_leaks=0 "$a" 2>&1 || true)
  # The first stack trace only; its frames in the code that matters: ours, assimp's, zlib's.
  frames=$(awk '/^ +#0 0x/ { n++ } n == 1 && /^ +#[0-9]+ 0x/' <<<"$trace" |
    grep -E "$PWD/(OpenMeshSkinned|fuzz)/|libassimp|Assimp::|libz\.so" || true)
  frame=${frames%%$'\n'*}
  if grep -q 'libFuzzer: out-of-memory (used:' <<<"$trace"; then
    owner=rss-limit
  else
    case "$frame" in
      *"$PWD/OpenMeshSkinned/"* | *"$PWD/fuzz/"*)
        # Our code called back from inside assimp (its logger): the loop or fault is the reader's.
        if [[ "${frames#*$'\n'}" == *libassimp* ]]; then owner=libassimp-via-callback; else owner=ours; fi ;;
      *assimp* | *Assimp::*) owner=libassimp ;;
      *libz.so* | *inflate* | *deflate*) owner=zlib ;;
      "") owner=no-crash-on-replay ;;
      *) owner=other ;;  # not reached: frames holds only the three kinds
    esac
  fi
  echo "$(basename "$a") $owner $(printf '%s' "$frame" | sed -E 's/^ +#[0-9]+ 0x[0-9a-f]+ (in )?//' | cut -c1-160)" >>"$owners"
done
{
  echo "libFuzzer, $minutes minutes:"
  grep -E '^#[0-9]+.*(DONE|cov:)' "$log" | tail -1
  echo "artifacts (crash/leak/timeout/oom inputs): $(ls "$out"/artifacts | wc -l)"
  ls "$out"/artifacts | sed 's/-.*//' | sort | uniq -c
  echo "where they happen (innermost frame in our code, assimp or zlib; owners.txt):"
  awk '{print $2}' "$owners" | sort | uniq -c
  echo "through skinned-decimate: $clean clean (exit 0, or 1-2 with one line), $bad not clean"
} | tee "$out/summary.txt"
[ "$bad" -eq 0 ] && ! grep -q ' ours ' "$owners"
