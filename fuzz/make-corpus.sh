#!/usr/bin/env bash
# Assembles the fuzzing seed corpus in OUTPUT_DIR (under the fuzz build directory, or under the
# sanitizer build's for the frame fuzzer; it is never committed): the documents and bad inputs
# of the generator (CorpusGenerator.cpp), scenes of `encore gen` when an encore binary is
# given, and the small models of the shared model directory (.gltf and .glb files under 200 kB;
# .gltf files whose buffers are external files still exercise the JSON parser, since the targets
# resolve no external file), plus, when python3 is there, a self-contained copy of each .gltf
# whose buffers and images are external files (embedded as data: uris, kept when under 200 kB):
# the only form of the Draco, meshopt and quantized variants that the targets can load, and
# what encore_fuzz_numbers and the frame fuzzer mutate.
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
embedded=0
if [ -d "$models" ] && command -v python3 >/dev/null; then
    embedded=$(python3 - "$models" "$out" <<'PY'
import base64, json, os, sys
models, out = sys.argv[1], sys.argv[2]
count = 0
for root, _, files in os.walk(models, followlinks=True):
    for name in sorted(files):
        if not name.endswith(".gltf"):
            continue
        path = os.path.join(root, name)
        try:
            with open(path, "rb") as file:
                document = json.load(file)
            external = False
            for key, mime in (("buffers", "application/octet-stream"), ("images", None)):
                for item in document.get(key, []):
                    uri = item.get("uri")
                    if not isinstance(uri, str) or uri.startswith("data:"):
                        continue
                    target = os.path.join(root, uri)
                    if os.path.getsize(target) > 200_000:
                        raise OSError("too large")
                    with open(target, "rb") as file:
                        data = base64.b64encode(file.read()).decode()
                    kind = mime or ("image/png" if uri.lower().endswith(".png") else "image/jpeg")
                    item["uri"] = f"data:{kind};base64,{data}"
                    external = True
        except (OSError, ValueError, AttributeError):
            continue
        text = json.dumps(document, separators=(",", ":"))
        if not external or len(text) >= 200_000:
            continue
        seed = os.path.relpath(path, models).replace("/", "_")[: -len(".gltf")]
        with open(os.path.join(out, f"model-{seed}-embedded.gltf"), "w") as file:
            file.write(text)
        count += 1
print(count)
PY
)
fi
echo "fuzz corpus: $(ls "$out" | wc -l) seeds in $out ($models_found models from $models, $embedded embedded copies)"
