#!/usr/bin/env bash
# Issue 28, the session's final build: scenes (fly-through and city, 100,000 and 1,000,000
# objects, 1280x720) visibility against gpu-culling-bundles with GPU timestamps; then the CPU
# frame without the GPU timer (100 frames, alternating, three rounds).
set -uo pipefail
carry=$(cd "$(dirname "$0")" && pwd)
W=/tmp/job44; rm -rf $W; mkdir -p $W
tar -C $W -xJf "$carry/encore.tar.xz"
R=$OUT/j44; mkdir -p $R
E() { bash $W/pack/run.sh encore "$@"; }
E info 2>&1 | head -1 > $R/info.txt
(nvidia-smi --query-gpu=timestamp,clocks.sm,utilization.gpu --format=csv -lms 500 > $R/smi.csv 2>&1 &)
for n in 100000 1000000; do
  echo "== scenes $n" >> $R/j44.txt
  E bench --scene flythrough --scene city --objects $n -s visibility -s gpu-culling-bundles --width 1280 --height 720 --frames 20 --warmup 5 --json $R/bench-$n.json >> $R/j44.txt 2>&1
done
for r in 1 2 3; do for s in gpu-culling-bundles visibility; do
  echo "== cpu $s r$r" >> $R/j44.txt
  E bench --scene flythrough --scene city --objects 100000 -s $s --width 1280 --height 720 --frames 100 --warmup 5 --no-gpu-timer >> $R/j44.txt 2>&1
done; done
pkill nvidia-smi
for f in $R/bench-*.json; do echo "### $(basename $f)"; cat $f; done > $R/all-json.txt; rm -f $R/bench-*.json
grep -E "^==|^\| (visibility|gpu-culling)|rror" $R/j44.txt
