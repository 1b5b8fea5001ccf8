#!/usr/bin/env bash
# Issue 28: frames of one view shaded without view slots (their pipelines made on first use),
# the scenes against gpu-culling-bundles in the same runs (twice at 100,000 objects, once at
# 1,000,000), 1280x720; then the dense batch at four samples (the slots' pipelines, unchanged).
set -uo pipefail
carry=$(cd "$(dirname "$0")" && pwd)
W=/tmp/job48; rm -rf $W; mkdir -p $W
tar -C $W -xJf "$carry/encore.tar.xz"
R=$OUT/j48; mkdir -p $R
E() { bash $W/pack/run.sh encore "$@"; }
E info 2>&1 | head -1 > $R/info.txt
(nvidia-smi --query-gpu=timestamp,clocks.sm,utilization.gpu --format=csv -lms 500 > $R/smi.csv 2>&1 &)
for n in 100000 100000 1000000; do
  echo "== scenes $n" >> $R/j48.txt
  E bench --scene flythrough --scene city --objects $n -s visibility -s gpu-culling-bundles --width 1280 --height 720 --frames 20 --warmup 5 --json $R/bench-$n-$RANDOM.json >> $R/j48.txt 2>&1
done
pkill nvidia-smi
for f in $R/bench-*.json; do echo "### $(basename $f)"; cat $f; done > $R/all-json.txt; rm -f $R/bench-*.json
grep -E "^==|^\| (visibility|gpu-culling)|rror" $R/j48.txt
grep -E "^==|^- visibility" $R/j48.txt | grep -o "^==.*\|shading [0-9.]*"
