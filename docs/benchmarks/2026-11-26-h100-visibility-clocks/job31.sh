#!/usr/bin/env bash
# Issue 28 after the bench's timed warm-up (3bbd0c0: at least 0.5 s, the GPU's clocks raised):
# scenes at 100,000 and 1,000,000 objects, 1280x720, visibility against gpu-culling-bundles; and
# the thread raster in batches of units (PROBE_BATCHED, an experiment-only build) against the
# current one. SM clocks logged alongside.
set -uo pipefail
carry=$(cd "$(dirname "$0")" && pwd)
W=/tmp/job31; rm -rf $W; mkdir -p $W
tar -C $W -xJf "$carry/encore.tar.xz"
R=$OUT/j31; mkdir -p $R $W/json
E() { bash $W/pack/run.sh encore "$@"; }
E info 2>&1 | head -1 > $R/info.txt
(nvidia-smi --query-gpu=timestamp,pstate,clocks.sm,clocks.mem,power.draw,temperature.gpu,utilization.gpu,clocks_throttle_reasons.active --format=csv -lms 200 > $W/smi.csv 2>&1 &)
scenes() { local tag=$1 n=$2 probes=$3; shift 3; echo "== $n $tag [$probes] $(date +%T)" >> $R/j31.txt
  ENCORE_PROBES=$probes E bench --scene flythrough --scene city --objects $n "$@" --width 1280 --height 720 --frames 20 --warmup 5 --json $W/json/b-$n-$tag.json >> $R/j31.txt 2>&1
  echo "-- done $(date +%T)" >> $R/j31.txt; }
scenes both1 100000 "" -s visibility -s gpu-culling-bundles
scenes batched1 100000 PROBE_BATCHED -s visibility
scenes both2 100000 "" -s visibility -s gpu-culling-bundles
scenes both1 1000000 "" -s visibility -s gpu-culling-bundles
scenes batched1 1000000 PROBE_BATCHED -s visibility
scenes vis2 1000000 "" -s visibility
pkill nvidia-smi
for f in $W/json/*.json; do echo "### $(basename $f)"; cat $f; done > $R/all-json.txt
cp $W/smi.csv $R/smi.csv
grep -E "^==|^--|^\| (visibility|gpu-culling)" $R/j31.txt
