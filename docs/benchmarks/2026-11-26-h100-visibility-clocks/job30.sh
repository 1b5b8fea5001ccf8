#!/usr/bin/env bash
# Issue 28: the workgroup raster skipping 8x8 tiles outside the triangle ("" against
# PROBE_NO_TILE_REJECT, the previous walk), and the shading pass sampling material textures at
# a computed level (PROBE_SAMPLE_LEVEL) instead of with explicit gradients. One binary, one
# lease, alternating; per-pass timings.
set -uo pipefail
carry=$(cd "$(dirname "$0")" && pwd)
W=/tmp/job30; rm -rf $W; mkdir -p $W
tar -C $W -xJf "$carry/encore.tar.xz"
R=$OUT/j30; mkdir -p $R $W/json
E() { bash $W/pack/run.sh encore "$@"; }
E info 2>&1 | head -1 > $R/info.txt
(nvidia-smi --query-gpu=timestamp,pstate,clocks.sm,clocks.mem,power.draw,temperature.gpu,utilization.gpu,clocks_throttle_reasons.active --format=csv -lms 500 > $W/smi.csv 2>&1 &)
scenes() { local tag=$1 n=$2 probes=$3; shift 3; echo "== $n $tag [$probes] $(date +%T)" >> $R/j30.txt
  ENCORE_PROBES=$probes E bench --scene flythrough --scene city --objects $n -s visibility "$@" --width 1280 --height 720 --frames 20 --warmup 5 --json $W/json/b-$n-$tag.json >> $R/j30.txt 2>&1; }
E bench --scene flythrough --objects 100000 -s visibility --width 1280 --height 720 --frames 60 --warmup 10 > /dev/null 2>&1
for r in 1 2; do
  scenes new$r 100000 ""
  scenes old$r 100000 PROBE_NO_TILE_REJECT
  scenes level$r 100000 PROBE_SAMPLE_LEVEL
done
scenes new1 1000000 ""
scenes old1 1000000 PROBE_NO_TILE_REJECT
pkill nvidia-smi
for f in $W/json/*.json; do echo "### $(basename $f)"; cat $f; done > $R/all-json.txt
cp $W/smi.csv $R/smi.csv
grep -E "^==|^\| (visibility|gpu-culling)" $R/j30.txt
