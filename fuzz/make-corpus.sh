#!/usr/bin/env bash
# Assembles the fuzzing seed corpus in OUTPUT_DIR (under the fuzz build directory; it is never
# committed): the documents and bad inputs of the generator (CorpusGenerator.cpp), scenes of
# `encore gen` when an encore binary is given, and the small models of the shared model
# directory (.gltf and .glb files under 200 kB; .gltf files whose buffers are external files
# still exercise the JSON parser, since the targets resolve no external file).
# Usage: fuzz/make-corpus.sh OUTPUT_DIR GENERATOR MODELS_DIR [ENCORE]
set -euo pipefail
out=$1 generator=$2 models=$3 encore=${4:-}
rm -rf "$out"
mkdir -p "$out"
"$generator" "$out" >/dev/null
if [ -n "$encore" ] && [ -x "$encore" ]; then
    "$encore" gen --objects 1 --meshes 1 --materials 1 -o "$out/gen-scene-1.glb" >/dev/null
    "$encore" gen --objects 12 --meshes 3 --materials 2 -o "$out/gen-scene-12.glb" >/dev/null
fi
models_found=0
if [ -d "$models" ]; then
    while IFS= read -r -d '' file; do
        # Model name and variant make the seed's name unique: Box/glTF-Binary/Box.glb.
        name=$(realpath --relative-to="$models" "$file" | tr '/' '_')
        cp "$file" "$out/model-$name"
        models_found=$((models_found + 1))
    done < <(find -L "$models" -type f \( -name '*.gltf' -o -name '*.glb' \) -size -200k -print0)
fi
echo "fuzz corpus: $(ls "$out" | wc -l) seeds in $out ($models_found models from $models)"
