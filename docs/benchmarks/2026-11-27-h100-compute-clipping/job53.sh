#!/usr/bin/env bash
# Issue 28, stop 46: GPU frames at 1,000,000 objects again, A (this stop) and B (a70bd4e)
# alternating twice, with the SM clock logged (job52's fly-through A ran at a lowered clock:
# every pass, untouched ones included, took 2-2.5x).
set -uo pipefail
carry=$(cd "$(dirname "$0")" && pwd)
W=/tmp/job53; rm -rf $W; mkdir -p $W/a $W/b
tar -C $W/a -xJf "$carry/encore.tar.xz"
tar -C $W/b -xJf "$carry/encore-before.tar.xz"
R=$OUT/j53; mkdir -p $R
A() { bash $W/a/pack/run.sh encore "$@"; }
B() { bash $W/b/pack/run.sh encore "$@"; }
(nvidia-smi --query-gpu=timestamp,clocks.sm,utilization.gpu --format=csv,noheader -lms 250 > $R/smi.txt 2>&1 &)
A bench --scene flythrough --objects 100000 -s visibility --width 1280 --height 720 --frames 200 --warmup 5 > /dev/null 2>&1
for round in 1 2; do for who in B A; do
  echo "== gpu $who 1000000 r$round $(date +%T)" >> $R/gpu.txt
  $who bench --scene flythrough --scene city --objects 1000000 -s visibility -s gpu-culling-bundles --width 1280 --height 720 --frames 40 --warmup 5 --warmup-time 2 --json $R/bench-$who-1000000-r$round.json 2>&1 | grep -E "^\| (visibility|gpu-culling)|^### " >> $R/gpu.txt
  echo "   end $(date +%T)" >> $R/gpu.txt
done; done
pkill nvidia-smi
cat $R/gpu.txt
awk -F', ' '{print $2}' $R/smi.txt | sort | uniq -c | sort -rn | head -8
