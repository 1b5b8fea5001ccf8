#!/usr/bin/env bash
# Issue 28, stop 47: --compute-raster-pixels on the kept build (58dd5b6), at 100,000 and
# 1,000,000 objects, with gpu-culling-bundles in the same lease.
set -uo pipefail
carry=$(cd "$(dirname "$0")" && pwd)
W=/tmp/job56; R=$OUT/j57; mkdir -p $R
[ -d $W/k/pack ] || { mkdir -p $W/k && tar -C $W/k -xJf "$carry/encore.tar.xz"; }
K() { bash $W/k/pack/run.sh encore "$@"; }
for obj in 100000 1000000; do
  args="--scene flythrough --scene city --objects $obj --width 1280 --height 720 --frames 40 --warmup 5 --warmup-time 2"
  K bench $args -s gpu-culling-bundles --json $R/gcb-$obj.json > /dev/null 2>&1
  for crp in 8 4 6 3; do
    K bench $args -s visibility --compute-raster-pixels $crp --json $R/crp$crp-$obj.json > /dev/null 2>&1
  done
done
python3 - "$R" <<'PY'
import json,sys,glob,os
for f in sorted(glob.glob(sys.argv[1]+'/*.json')):
    d=json.load(open(f))
    for r in d['results']:
        p=r['gpuPassesMs']
        short={k.replace('visibility ','').replace(' (second phase)','2'):v['median'] for k,v in p.items()}
        print('%-14s %-4s frame %.3f  '%(os.path.basename(f)[:-5], r['scene'][:4], r['gpuMs']['median'])+' '.join('%s=%.3f'%(k,v) for k,v in sorted(short.items())))
PY
