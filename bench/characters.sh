# The benchmark characters that bench/peer-vs-gltfpack.sh and bench/image-judge.sh give both tools, each
# as the same GLB. Sourced, from the repository's root, after $cli and $bench are set:
#   write_characters DIR     writes them into DIR and sets the array `inputs` to their paths
#   triangles LOG            the triangle count gltfpack's verbose LOG reports for its output
# Testwuson.X, FBX/animation_with_skeleton.fbx and the MD2s faerie and sydney (198 stored frames each) are
# converted once by skinned-decimate --ratio 1 --poses 8 (a fixed count, so that the inputs do not change with
# the default one: the FBX's 8-bone skin is capped to 4 against the example poses); glTF2/simple_skin is read
# as it is; DeCoro's leg, the L&S column and wuson8 (Testwuson with its skin diffused over 8 bones) come from
# omsk-bench --write.

write_characters() {
  local dir=$1 models=/usr/share/assimp/models m
  local convert=(--ratio 1 --poses 8 --no-refit --quiet --no-eval)
  "$cli" "$models/X/Testwuson.X" -o "$dir/wuson.glb" "${convert[@]}" >/dev/null 2>&1
  "$cli" "$models/FBX/animation_with_skeleton.fbx" -o "$dir/fbx.glb" "${convert[@]}" >/dev/null 2>&1
  for m in faerie sydney; do
    "$cli" "$models/MD2/$m.md2" -o "$dir/$m.glb" "${convert[@]}" >/dev/null 2>&1
  done
  for m in leg column wuson8; do "$bench" --write $m "$dir/$m.glb" >/dev/null; done
  inputs=("$dir/wuson.glb" "$dir/fbx.glb" "$models/glTF2/simple_skin/simple_skin.gltf" "$dir/leg.glb"
    "$dir/column.glb" "$dir/wuson8.glb" "$dir/faerie.glb" "$dir/sydney.glb")
}

triangles() { grep -o 'output: 1 mesh primitives ([0-9]* triangles' "$1" | grep -o '[0-9]* triangles' | cut -d' ' -f1; }
