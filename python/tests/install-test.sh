#!/usr/bin/env bash
# The install test of the Python package (CTest python_install_test, `make test`): pip installs
# the clone (pyproject.toml, scikit-build-core) into a temporary virtual environment that sees
# Debian's packages, offline (--no-build-isolation --no-index), then, from a folder outside the
# clone and without PYTHONPATH, imports encore, checks that it is the venv's copy and renders a
# tetrahedron the test writes as glTF; every view must have covered pixels (alpha > 0).
#
#   python/tests/install-test.sh [SOURCE_DIR [WHEEL_BUILD_DIR [PYTHON]]]
#
# SOURCE_DIR: the clone (default: this script's); WHEEL_BUILD_DIR: scikit-build-core's build
# folder, kept between runs so that a second run only rebuilds what changed (default
# SOURCE_DIR/build-wheel, pyproject.toml's); PYTHON: the interpreter of the venv
# (default /usr/bin/python3, whose numpy and scikit-build-core Debian installs).
set -euo pipefail

source_dir=$(cd "${1:-$(dirname "$0")/../..}" && pwd)
build_dir=${2:-$source_dir/build-wheel}
python=${3:-/usr/bin/python3}

# ccache serves the objects of `make build` (same compiler name, flags and depth in the clone:
# Makefile, docs/ci.md). scikit-build-core would otherwise compile with sysconfig's CXX
# (x86_64-linux-gnu-g++), a name that ccache keeps apart from CMake's c++.
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$source_dir}
export CCACHE_NOHASHDIR=${CCACHE_NOHASHDIR:-true}
export CXX=${CXX:-c++}
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}
unset PYTHONPATH PYTHONHOME

work=$(mktemp -d "${TMPDIR:-/tmp}/encore-install-test.XXXXXX")
trap 'rm -rf "$work"' EXIT

# One build at a time in the build folder (`make install` and `make test` may share it).
mkdir -p "$build_dir"
exec 9>"$build_dir/.pip.lock"
flock 9

start=$SECONDS
# Debian's pip (python3-pip) from the system site packages installs into the venv: --without-pip
# saves ensurepip's 6 s.
"$python" -m venv --system-site-packages --without-pip "$work/venv"
"$work/venv/bin/python" -m pip install --no-build-isolation --no-index --disable-pip-version-check \
    --root-user-action=ignore --config-settings="build-dir=$build_dir" "$source_dir"
echo "install-test: pip install took $((SECONDS - start)) s"

mkdir "$work/elsewhere"
cd "$work/elsewhere"
"$work/venv/bin/python" - "$work/venv" "$source_dir" "$build_dir" <<'PY'
import base64, json, os, struct, sys

venv, source_dir, build_dir = (os.path.realpath(p) for p in sys.argv[1:])
import encore
import encore._encore

def inside(path, folder):
    return os.path.commonpath([os.path.realpath(path), folder]) == folder

for module in (encore, encore._encore):
    assert inside(module.__file__, venv), f"{module.__name__} from {module.__file__}, not {venv}"
for entry in filter(None, sys.path):
    assert not inside(entry, source_dir) and not inside(entry, build_dir), f"sys.path has {entry}"
import importlib.util
assert inside(importlib.util.find_spec("encore.dask").origin, venv)

# A tetrahedron (positions and indices in one data: URI buffer), red and double-sided.
positions = [(0, 1, 0), (-1, -1, 1), (1, -1, 1), (0, -1, -1)]
indices = [0, 1, 2, 0, 2, 3, 0, 3, 1, 1, 3, 2]
data = b"".join(struct.pack("<3f", *p) for p in positions) + struct.pack(f"<{len(indices)}H", *indices)
gltf = {
    "asset": {"version": "2.0"},
    "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
    "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.1, 0.1, 1]},
                   "doubleSided": True}],
    "buffers": [{"byteLength": len(data),
                 "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                    {"buffer": 0, "byteOffset": 48, "byteLength": 2 * len(indices)}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                   "min": [-1, -1, -1], "max": [1, 1, 1]},
                  {"bufferView": 1, "componentType": 5123, "count": len(indices), "type": "SCALAR"}],
}
with open("tetrahedron.gltf", "w") as f:
    json.dump(gltf, f)

renderer = encore.Renderer()
images, intrinsics, cameras = renderer.render_views(renderer.load("tetrahedron.gltf"), views=3,
                                                    size=32)
assert images.shape == (3, 32, 32, 4) and images.dtype.name == "uint8", images.shape
covered = [int((view[..., 3] > 0).sum()) for view in images]
assert all(covered), f"empty views: covered pixels {covered}"
print(f"install-test: encore {encore.__file__} on {renderer.adapter}; covered pixels {covered}")
PY
echo "install-test: passed in $((SECONDS - start)) s"
