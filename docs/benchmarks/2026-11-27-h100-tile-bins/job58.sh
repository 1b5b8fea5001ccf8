#!/usr/bin/env bash
# Issue 28, stop 47: tile binning ("A": each 8x8 tile listed once per bin it holds, in one
# dispatch; the shading walks the tiles) against the kept build ("K", 58dd5b6: pixels counted,
# prefix-summed and scattered into per-bin lists, three dispatches). GPU frames at 1280x720,
# 100,000 and 1,000,000 objects, two rounds alternating; A at --compute-raster-pixels 6;
# gpu-culling-bundles; encore batch on 200 dense files at four samples.
set -uo pipefail
carry=$(cd "$(dirname "$0")" && pwd)
W=/tmp/job58; rm -rf $W; mkdir -p $W/k $W/a
tar -C $W/k -xJf "$carry/encore.tar.xz"
tar -C $W/a -xJf "$carry/encore-a.tar.xz"
R=$OUT/j58; mkdir -p $R
K() { bash $W/k/pack/run.sh encore "$@"; }
A() { bash $W/a/pack/run.sh encore "$@"; }
A info 2>&1 | head -1 > $R/info.txt
for n in 100000 1000000; do
  args="--scene flythrough --scene city --objects $n --width 1280 --height 720 --frames 40 --warmup 5 --warmup-time 2"
  for r in 1 2; do
    K bench $args -s visibility --json $R/K-$n-r$r.json > /dev/null 2>&1
    A bench $args -s visibility --json $R/A-$n-r$r.json > /dev/null 2>&1
  done
  A bench $args -s visibility --compute-raster-pixels 6 --json $R/A6-$n.json > /dev/null 2>&1
  A bench $args -s gpu-culling-bundles --json $R/gcb-$n.json > /dev/null 2>&1
done
python3 - "$R" <<'PY' > $R/passes.txt
import json,sys,glob,os
for f in sorted(glob.glob(sys.argv[1]+'/*.json')):
    d=json.load(open(f))
    for r in d['results']:
        p=r['gpuPassesMs']
        short={k.replace('visibility ','').replace(' (second phase)','2'):v['median'] for k,v in p.items()}
        print('%-14s %-4s frame %.3f cpu %.3f '%(os.path.basename(f)[:-5], r['scene'][:4], r['gpuMs']['median'], r['cpuMs']['median'])+' '.join('%s=%.3f'%(k,v) for k,v in sorted(short.items())))
PY
cat $R/passes.txt
mkdir -p $W/dense
for i in $(seq 1 40); do A gen --objects 24 --meshes 4 --tessellation 256 --seed $i -o $W/dense/m$i.glb > /dev/null 2>&1 & if (( i % 8 == 0 )); then wait; fi; done; wait
for k in 1 2 3 4 5; do mkdir -p $W/dense$k; for i in $(seq 1 40); do ln -s $W/dense/m$i.glb $W/dense$k/m$i.glb; done; done
ls $W/dense[1-5]/*.glb > $W/dense200.txt
run() { local name=$1 X=$2; shift 2; rm -rf $W/o; echo "== $name: $*" >> $R/batch.txt
  $X -v batch $W/dense200.txt -o $W/o --quiet --samples 4 "$@" 2>&1 | grep -E "views in" | sed 's/(load and encode summed.*//' >> $R/batch.txt; rm -rf $W/o; }
A batch $W/dense200.txt -o $W/o --quiet --strategy visibility > /dev/null 2>&1; rm -rf $W/o
for r in 1 2; do run "K r$r" K --strategy visibility; run "A r$r" A --strategy visibility; done
run "default" A
cat $R/batch.txt
