#!/usr/bin/env bash
# Installs Encore's build and test dependencies on Debian 12 (bookworm), all from Debian's
# own packages. Dawn exists only in sid, so sid is added at pin priority 100 (nothing is
# taken from it unless asked with -t sid); Mesa's lavapipe comes from bookworm-backports
# because bookworm's is too old for Dawn and sid's would remove gdb and perf.
# The new sources are copied from the machine's own debian.sources so that no registry
# address is written here. Does nothing when every package is already installed.
set -euo pipefail

# libspng-dev and libjpeg62-turbo-dev decode PNG and JPEG textures (stb_image is slower),
# libwebp-dev WebP ones (EXT_texture_webp);
# libdeflate-dev compresses the PNGs Encore writes (faster than zlib, and smaller files);
# libopenexr-dev writes EXR depth and HDR passes, libarchive-dev WebDataset .tar shards.
# libembree-dev builds the ray tracer's bounding volume hierarchies (rtcBuildBVH).
# clang and libclang-rt-14-dev (libFuzzer, sanitizer runtimes) build the fuzz targets.
# libglfw3-dev opens `encore view`'s window; xvfb and xauth (xvfb-run) give its tests a display.
# pybind11-dev, python3-dev, python3-numpy and python3-pytest build and test the Python module;
# python3-distributed (Dask's distributed scheduler, with python3-dask) runs encore.dask;
# python3-pip and python3-venv install it with pip (pyproject.toml) into a venv, as
# python/tests/install-test.sh does.
# ninja-build and ccache keep the build short (docs/ci.md); clang-format-16 checks the style
# (.clang-format's InsertBraces needs 16); pngquant reduces docs/reference's sheets
# (scripts/reference-gallery.sh).
bookworm_packages=(g++ make ninja-build ccache pkg-config libglm-dev libstb-dev libcli11-dev libgtest-dev
                   nlohmann-json3-dev libdraco-dev libmeshoptimizer-dev zlib1g-dev
                   libspng-dev libjpeg62-turbo-dev libwebp-dev libdeflate-dev
                   libopenexr-dev libarchive-dev libembree-dev
                   librsvg2-bin pngquant clang libclang-rt-14-dev clang-format-16 libglfw3-dev xvfb xauth
                   pybind11-dev python3-dev python3-numpy python3-pytest python3-dask
                   python3-distributed python3-pip python3-venv)
# Dawn's CMake package declares C++ module file sets, which need CMake >= 3.28.
# python3-scikit-build-core (0.11; bookworm has none) builds the wheel of pyproject.toml.
backports_packages=(mesa-vulkan-drivers cmake python3-scikit-build-core)
sid_packages=(libwebgpu-dawn-dev)

all=("${bookworm_packages[@]}" "${backports_packages[@]}" "${sid_packages[@]}")
missing=()
for p in "${all[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
# bookworm's Mesa and CMake are present on many images but too old: require the backports.
require_version() {
    local version
    version=$(dpkg-query -W -f='${Version}' "$1" 2>/dev/null || true)
    if [ -n "$version" ] && dpkg --compare-versions "$version" lt "$2"; then
        missing+=("$1")
    fi
}
require_version mesa-vulkan-drivers 25
require_version cmake 3.28
[ ${#missing[@]} -eq 0 ] && exit 0
echo "install-deps: installing ${missing[*]}"

SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO=sudo
export DEBIAN_FRONTEND=noninteractive

src=/etc/apt/sources.list.d/debian.sources
# The first stanza of debian.sources is the main archive; reuse its URIs and keyring.
stanza() {
    awk -v suite="$1" 'BEGIN{RS=""; FS="\n"} NR==1 {
        for (i = 1; i <= NF; i++) {
            if ($i ~ /^Suites:/) print "Suites: " suite; else if ($i !~ /^#/) print $i
        }
        exit }' "$src"
}
if [ ! -f /etc/apt/sources.list.d/encore-sid.sources ]; then
    stanza sid | $SUDO tee /etc/apt/sources.list.d/encore-sid.sources >/dev/null
    stanza bookworm-backports | $SUDO tee /etc/apt/sources.list.d/encore-backports.sources >/dev/null
    printf 'Package: *\nPin: release n=sid\nPin-Priority: 100\n' |
        $SUDO tee /etc/apt/preferences.d/encore-sid >/dev/null
fi
apt_opts=(-o Acquire::Check-Valid-Until=false -o Acquire::Retries=3)
$SUDO apt-get "${apt_opts[@]}" update -q
$SUDO apt-get "${apt_opts[@]}" install -y -q --no-install-recommends "${bookworm_packages[@]}"
$SUDO apt-get "${apt_opts[@]}" install -y -q --no-install-recommends -t bookworm-backports \
    "${backports_packages[@]}"
$SUDO apt-get "${apt_opts[@]}" install -y -q --no-install-recommends -t sid "${sid_packages[@]}"
