#!/usr/bin/env bash
# Issue 28, stop 48: F = E with untextured materials shading in the first textured bin of their
# variant (one bin for the generated scenes' materials), against gpu-culling-bundles, one lease.
set -uo pipefail
carry=$(cd "$(dirname "$0")" && pwd)
W=/tmp/job64; rm -rf $W; mkdir -p $W/f $W/e
tar -C $W/f -xJf "$carry/encore-f.tar.xz"
tar -C $W/e -xJf "$carry/encore-e.tar.xz"
R=$OUT/j64; mkdir -p $R
F() { bash $W/f/pack/run.sh encore "$@"; }
E() { bash $W/e/pack/run.sh encore "$@"; }
F info 2>&1 | head -1
summary() {
python3 - "$R" <<'PY'
import json,sys,glob,os
for f in sorted(glob.glob(sys.argv[1]+'/*.json')):
    d=json.load(open(f)); name=os.path.basename(f)[:-5]
    for r in d['results']:
        p=r['gpuPassesMs']
        short={k.replace('visibility','v').replace(': depth pyramid, second culling and raster','ph2').replace(': culling and compute raster','ph1').replace(': binning and shading','shade'):v['median'] for k,v in p.items()}
        print('%-14s %-4s frame %.3f p95 %.3f '%(name, r['scene'][:4], r['gpuMs']['median'], r['gpuMs']['p95'])+' '.join('%s=%.3f'%(k,v) for k,v in sorted(short.items())))
PY
}
for n in 1000000 100000; do
  args="--scene flythrough --scene city --objects $n --width 1280 --height 720 --frames 40 --warmup 5 --warmup-time 2"
  F bench $args -s visibility --json $R/F-$n-r1.json > /dev/null 2>&1
  F bench $args -s gpu-culling-bundles --json $R/gcb-$n.json > /dev/null 2>&1
  E bench $args -s visibility --json $R/E-$n.json > /dev/null 2>&1
  F bench $args -s visibility --json $R/F-$n-r2.json > /dev/null 2>&1
  summary | grep -- "-$n"
done
