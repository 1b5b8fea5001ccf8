#!/usr/bin/env bash
# Renders every model of ../shared/reference under the reference's conditions, compares it with
# the Khronos Sample Renderer's picture (the reference comparison test) and rewrites
# docs/reference: the Encore | reference | difference sheets (reduced to 256 colours with
# pngquant, to keep docs/ small) and README.md with the numbers. Encore's own images, which the
# test writes beside the sheets, are left out. Usage: scripts/reference-gallery.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
out=docs/reference
command -v pngquant >/dev/null || { echo "reference-gallery.sh: needs pngquant (apt-get install pngquant)" >&2; exit 1; }
mkdir -p "$out"
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}
images=$(mktemp -d)
trap 'rm -rf "$images"' EXIT
log=$(ENCORE_REFERENCE_OUTPUT="$images" "$build/tests/gpu/encore_reference_tests" --gtest_color=no 2>&1)
for sheet in "$images"/*-compare.png; do
    [ -e "$sheet" ] || continue
    pngquant --strip --speed 1 --force --output "$out/${sheet##*/}" -- "$sheet"
done
adapter=$(printf '%s\n' "$log" | sed -n 's/^adapter: //p' | head -1)
{
    echo "# Encore against the Khronos glTF Sample Renderer"
    echo
    echo "Written by \`scripts/reference-gallery.sh\` from the reference comparison test"
    echo "(\`tests/gpu/ReferenceComparisonTest.cpp\`), $(date -u +%Y-%m-%d), adapter: $adapter."
    echo
    echo "Each model of \`../shared/reference\` rendered by Encore (\`bundles\`, 320x320, 4x MSAA)"
    echo "with the camera of its JSON file, \`studio.hdr\` turned 90 degrees about +Y (the"
    echo "Sample Renderer's default environment rotation), Khronos PBR Neutral, exposure 1 and a"
    echo "black background, then compared with the reference PNG: SSIM on luminance (Wang et al.,"
    echo "11x11 Gaussian window) and the mean absolute difference of the RGB channels (0-255)."
    echo "The same picture from the command line:"
    echo
    echo '```sh'
    echo 'encore render ../shared/models/Duck/glTF/Duck.gltf --width 320 --height 320 \'
    echo '    --environment ../shared/reference/studio.hdr --environment-rotation 90 \'
    echo '    --background "#000000" --camera-position=X,Y,Z --target X,Y,Z --yfov 45 \'
    echo '    --znear N --zfar F -o duck.png    # values from ../shared/reference/Duck.json'
    echo 'encore compare duck.png ../shared/reference/Duck.png -o duck-compare.png'
    echo '```'
    echo
    echo "| model | SSIM | mean abs error | Encore \\| reference \\| difference x4 |"
    echo "|---|---:|---:|---|"
    printf '%s\n' "$log" | awk '/^reference [A-Za-z0-9]+ +SSIM [0-9]/ && $2 != "mean" {
        printf "| %s | %s | %s | ![%s](%s-compare.png) |\n", $2, $4, $8, $2, $2 }'
    echo
    printf '%s\n' "$log" | sed -n 's/^reference mean SSIM \(.*\) over \(.*\)$/Mean SSIM \1 over \2 (those of `list.txt`;/p'
    echo "the models of \`list-extensions.txt\` Encore shades follow them, held to 0.95 each)."
    echo
    echo "The mean covers the models of \`list.txt\`; the rows after them are the material-extension"
    echo "models of \`list-extensions.txt\` whose extensions Encore shades. The numbers are the test's,"
    echo "on the full pictures; the sheets shown here are reduced to 256 colours (pngquant)."
    echo
    echo "What remains is edge antialiasing (WebGL's canvas multisampling against WebGPU's 4x"
    echo "MSAA resolved before tone mapping), texture filtering, the sRGB transfer function"
    echo "against the reference's gamma 2.2 in the darkest tones, and sampling noise of the"
    echo "prefiltered environment."
} > "$out/README.md"
echo "$out/README.md"
