#!/usr/bin/env bash
# Issue 28, stop 48: shading bins shared by materials of the same textures (E, working tree on
# 7db39d5) against D (7db39d5), one lease: GPU frames at 1280x720, 100,000 and 1,000,000
# objects, alternating, gpu-culling-bundles beside; CPU frame of E and gcb, three rounds.
set -uo pipefail
carry=$(cd "$(dirname "$0")" && pwd)
W=/tmp/job63; rm -rf $W; mkdir -p $W/d $W/e
tar -C $W/d -xJf "$carry/encore-d.tar.xz"
tar -C $W/e -xJf "$carry/encore-e.tar.xz"
R=$OUT/j63; mkdir -p $R
D() { bash $W/d/pack/run.sh encore "$@"; }
E() { bash $W/e/pack/run.sh encore "$@"; }
E info 2>&1 | head -1
for n in 100000 1000000; do
  args="--scene flythrough --scene city --objects $n --width 1280 --height 720 --frames 40 --warmup 5 --warmup-time 2"
  D bench $args -s visibility --json $R/D-$n-r1.json > /dev/null 2>&1
  E bench $args -s visibility --json $R/E-$n-r1.json > /dev/null 2>&1
  E bench $args -s gpu-culling-bundles --json $R/gcb-$n.json > /dev/null 2>&1
  D bench $args -s visibility --json $R/D-$n-r2.json > /dev/null 2>&1
  E bench $args -s visibility --json $R/E-$n-r2.json > /dev/null 2>&1
done
E bench --scene flythrough --scene city --objects 100000 --width 1280 --height 720 --frames 40 --warmup 5 --warmup-time 2 -s visibility --gpu-steps --json $R/Esteps-100000.json > /dev/null 2>&1
python3 - "$R" <<'PY'
import json,sys,glob,os
for f in sorted(glob.glob(sys.argv[1]+'/*.json')):
    d=json.load(open(f)); name=os.path.basename(f)[:-5]
    for r in d['results']:
        p=r['gpuPassesMs']
        short={k.replace('visibility','v').replace(' (second phase)','2').replace(': depth pyramid, second culling and raster','ph2').replace(': culling and compute raster','ph1').replace(': binning and shading','shade').replace('compute raster','cr').replace('workgroup raster','wr').replace('occlusion culling','occ').replace('depth pyramid','pyr'):v['median'] for k,v in p.items()}
        print('%-16s %-4s frame %.3f p95 %.3f '%(name, r['scene'][:4], r['gpuMs']['median'], r['gpuMs']['p95'])+' '.join('%s=%.3f'%(k,v) for k,v in sorted(short.items())))
PY
for r in 1 2 3; do
  for s in gpu-culling-bundles visibility; do
    echo "== cpu $s r$r"
    E bench --scene flythrough --scene city --objects 100000 -s $s --width 1280 --height 720 --frames 300 --warmup 5 --no-gpu-timer 2>&1 | grep -E "^\| (visibility|gpu-culling)|^### "
  done
done
