#!/usr/bin/env bash
# Issue 28, stop 48: the city's fixed costs. C = 291bb0c (stop 47's frame code); X = 1e8f5ff plus
# rasterMain's empty workgroups skipping their atomicAdd, and env knobs: ENCORE_EXP_COARSE (one
# timed pass per phase, as the frame runs untimed), ENCORE_EXP_SHADE_GROUPS.
set -uo pipefail
carry=$(cd "$(dirname "$0")" && pwd)
W=/tmp/job61; rm -rf $W; mkdir -p $W/x $W/c
tar -C $W/x -xJf "$carry/encore-x.tar.xz"
tar -C $W/c -xJf "$carry/encore-c.tar.xz"
R=$OUT/j61; mkdir -p $R
X() { bash $W/x/pack/run.sh encore "$@"; }
C() { bash $W/c/pack/run.sh encore "$@"; }
X info 2>&1 | head -1
args="--scene flythrough --scene city --objects 100000 --width 1280 --height 720 --frames 40 --warmup 5 --warmup-time 2"
for r in 1 2; do
  C bench $args -s visibility --json $R/a-C-100000-r$r.json > /dev/null 2>&1
  X bench $args -s visibility --json $R/b-X-100000-r$r.json > /dev/null 2>&1
  ENCORE_EXP_COARSE=1 X bench $args -s visibility --json $R/c-Xcoarse-100000-r$r.json > /dev/null 2>&1
done
ENCORE_EXP_SHADE_GROUPS=2112 X bench $args -s visibility --json $R/d-Xshade2112-100000.json > /dev/null 2>&1
X bench --scene city --objects 100000 --width 1280 --height 720 --frames 40 --warmup 5 --warmup-time 2 -s visibility --materials 1 --json $R/e-Xmat1-city.json > /dev/null 2>&1
X bench $args -s gpu-culling-bundles --json $R/f-gcb-100000.json > /dev/null 2>&1
args="--scene flythrough --scene city --objects 1000000 --width 1280 --height 720 --frames 40 --warmup 5 --warmup-time 2"
C bench $args -s visibility --json $R/g-C-1000000.json > /dev/null 2>&1
X bench $args -s visibility --json $R/h-X-1000000.json > /dev/null 2>&1
ENCORE_EXP_COARSE=1 X bench $args -s visibility --json $R/i-Xcoarse-1000000.json > /dev/null 2>&1
X bench $args -s gpu-culling-bundles --json $R/j-gcb-1000000.json > /dev/null 2>&1
python3 - "$R" <<'PY'
import json,sys,glob,os
for f in sorted(glob.glob(sys.argv[1]+'/*.json')):
    d=json.load(open(f)); name=os.path.basename(f)[:-5]
    for r in d['results']:
        p=r['gpuPassesMs']
        short={k.replace('visibility','v').replace(' (second phase)','2').replace(': depth pyramid, second culling and raster','ph2').replace(': culling and compute raster','ph1').replace(': binning and shading','shade').replace('compute raster','cr').replace('workgroup raster','wr').replace('occlusion culling','occ').replace('depth pyramid','pyr'):v['median'] for k,v in p.items()}
        print('%-20s %-4s frame %.3f '%(name, r['scene'][:4], r['gpuMs']['median'])+' '.join('%s=%.3f'%(k,v) for k,v in sorted(short.items())))
PY
