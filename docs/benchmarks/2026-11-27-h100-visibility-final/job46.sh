#!/usr/bin/env bash
# Issue 28: the striding grids' size (ENCORE_GRID, an experiment-only override of the 4,096
# workgroups of persistentWorkgroups: raster passes, workgroup raster, shading), alternating;
# fly-through and city at 100,000 and 1,000,000 objects.
set -uo pipefail
carry=$(cd "$(dirname "$0")" && pwd)
W=/tmp/job46; rm -rf $W; mkdir -p $W/json
tar -C $W -xJf "$carry/encore.tar.xz"
R=$OUT/j46; mkdir -p $R
E() { bash $W/pack/run.sh encore "$@"; }
(nvidia-smi --query-gpu=timestamp,clocks.sm,utilization.gpu --format=csv -lms 500 > $R/smi.csv 2>&1 &)
b() { local grid=$1 n=$2 tag=$3; echo "== grid $grid $n $tag" >> $R/j46.txt
  ENCORE_GRID=$grid E bench --scene flythrough --scene city --objects $n --width 1280 --height 720 --frames 20 --warmup 5 --json $W/json/b-$grid-$n-$tag.json -s visibility >> $R/j46.txt 2>&1; }
for r in 1 2; do for g in 4096 8192 16384; do b $g 100000 r$r; done; done
for g in 4096 16384; do b $g 1000000 r1; done
pkill nvidia-smi
for f in $W/json/*.json; do echo "### $(basename $f)"; cat $f; done > $R/all-json.txt
grep -E "^==|^\| (visibility|gpu-culling)|rror" $R/j46.txt
