# Sourced by the probe scripts beside it, on the device machine.

# probe_unpack WORK CARRY: CARRY's pack.tar.xz into WORK/pack (shared/gpu/pack.sh's folder), and
# CARRY's encore-next.xz, when there is one, over WORK/pack/bin/encore-new.
probe_unpack() {
  tar -C "$1" -xJf "$2/pack.tar.xz"
  if [ -f "$2/encore-next.xz" ]; then xz -dc "$2/encore-next.xz" > "$1/pack/bin/encore-new"; fi
}

# probe_inputs WORK CARRY GPUS: the ten models of CARRY/models 100 times per GPU through
# symbolic links (1,000 files per GPU), listed in WORK/all.txt.
probe_inputs() {
  local i m
  for i in $(seq -w 0 $((100 * $3 - 1))); do
    mkdir -p "$1/in/$i"
    for m in "$2"/models/*.glb; do ln -sf "$m" "$1/in/$i/"; done
    ln -sfn "$2/models/Avocado" "$1/in/$i/Avocado"
  done
  ls "$1"/in/*/*.glb "$1"/in/*/Avocado/Avocado.gltf | sort > "$1/all.txt"
}

# probe_generated WORK NAME TESSELLATION COPIES: 40 models of `encore gen --objects 24 --meshes 4
# --tessellation TESSELLATION` (seeds 1-40, made through the caller's E) in WORK/NAME, linked into
# COPIES folders WORK/NAME-1 ...; the 40 x COPIES links listed in WORK/NAME.txt.
probe_generated() {
  local i k
  mkdir -p "$1/$2"
  for i in $(seq 1 40); do
    E gen --objects 24 --meshes 4 --tessellation "$3" --seed $i -o "$1/$2/m$i.glb" > /dev/null 2>&1 &
    if (( i % 8 == 0 )); then wait; fi
  done; wait
  for k in $(seq 1 "$4"); do
    mkdir -p "$1/$2-$k"; for i in $(seq 1 40); do ln -sf "$1/$2/m$i.glb" "$1/$2-$k/"; done
  done
  ls "$1/$2"-*/m*.glb > "$1/$2.txt"
}

# probe_python WORK CARRY: CARRY's python.tar.xz (bench/probes/pack-python.sh) into WORK/python
# and a function PY that runs its Python through the encore pack's loader (probe_unpack first).
# Worker processes that multiprocessing spawns start through WORK/python/bin/python-packed, the
# same command as a script: set it with multiprocessing.set_executable (ENCORE_PYTHON names it).
probe_python() {
  tar -C "$1" -xJf "$2/python.tar.xz"
  local w; w=$(cd "$1" && pwd)
  bash "$w/pack/run.sh" encore-new info > /dev/null 2>&1 || true  # unpacks the GL dispatch libraries
  cat > "$w/python/bin/python-packed" <<SCRIPT
#!/usr/bin/env bash
export PYTHONHOME=$w/python PYTHONPATH=$w/python/lib/python3/dist-packages
export VK_DRIVER_FILES=\${VK_DRIVER_FILES:-/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json}
export XDG_RUNTIME_DIR=\${XDG_RUNTIME_DIR:-/tmp} ENCORE_PYTHON=$w/python/bin/python-packed
exec $w/pack/lib/ld-linux-x86-64.so.2 --library-path $w/pack/lib:$w/python/so:/usr/local/nvidia/lib64 \\
  $w/python/bin/python3.11 "\$@"
SCRIPT
  chmod +x "$w/python/bin/python-packed"
  PROBE_PYTHON=$w/python/bin/python-packed
  PY() { "$PROBE_PYTHON" "$@"; }
}
