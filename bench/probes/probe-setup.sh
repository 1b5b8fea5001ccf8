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
