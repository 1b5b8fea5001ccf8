#!/usr/bin/env bash
# Issue 48: the GPU time per model of each of the ten shared models with bundles and with
# visibility (compute raster), at 4x and at one sample: 100 copies of one model per run
# (12 views at 512x512, `encore -v batch`), the `gpu` line's ms per model. Where `--strategy auto`
# should draw light models with visibility. Run on the device machine as
#   bash bench/probes/per-model-gpu.sh CARRY
# CARRY as for pools.sh. Also times the decode of every image of the models (decode_probe, when
# CARRY holds one: a build of bench/probes/decode_probe.cpp).
set -uo pipefail
P=$(cd "$(dirname "$0")" && pwd)
C=$(cd "${1:?carry folder}" && pwd)
W=/tmp/per-model; rm -rf $W; mkdir -p $W
. "$P/probe-setup.sh"
probe_unpack $W "$C"
E() { bash $W/pack/run.sh encore-new "$@"; }
echo "== machine: $(nproc) cores"; nvidia-smi -L | head -1; E info 2>&1 | head -1
probe_inputs $W "$C" 1
for m in $(sed 's|.*/||' $W/all.txt | sort -u); do grep "/$m\$" $W/all.txt > $W/$m.txt; done
E batch $W/Duck.glb.txt -o $W/o --quiet > /dev/null 2>&1
if [ "${DECODE_ONLY:-0}" = 1 ]; then set -- ; fi
for s in $([ "${DECODE_ONLY:-0}" = 1 ] || echo 4 1); do
  for list in $W/*.gl*.txt; do
    m=$(basename $list .txt)
    for strategy in bundles visibility; do
      rm -rf $W/o
      E -v batch $list -o $W/o --quiet --samples $s --strategy $strategy > $W/log.txt 2>&1
      echo "s$s $m $strategy: $(grep -E 'views in' $W/log.txt | sed 's/.*views in/views in/') |" \
        "$(grep -E '^gpu' $W/log.txt | sed 's/.*together/together/')"
    done
  done
done
if [ -x "$C/decode_probe" ]; then
  mkdir -p $W/img
  python3 - "$C/models" "$W/img" <<'PY'
import json, struct, glob, os, sys
for f in sorted(glob.glob(sys.argv[1] + '/*.glb')):
    b = open(f, 'rb').read(); n = struct.unpack('<I', b[12:16])[0]
    j = json.loads(b[20:20 + n]); base = 20 + n + 8
    for i, im in enumerate(j.get('images', [])):
        v = j['bufferViews'][im['bufferView']]; o = base + v.get('byteOffset', 0)
        d = b[o:o + v['byteLength']]
        ext = 'jpg' if d[:2] == bytes([0xff, 0xd8]) else 'png'
        open(f"{sys.argv[2]}/{os.path.basename(f)[:-4]}-{i}.{ext}", 'wb').write(d)
PY
  cp "$C"/models/Avocado/*.png $W/img/
  cp "$C/decode_probe" $W/pack/bin/
  for t in 1 16; do bash $W/pack/run.sh decode_probe $t 4 $W/img/*; done
fi
