#!/usr/bin/env bash
# Issue 28: the thread raster's triangle threads read their unit's item and first triangle from
# workgroup memory (as the unit's thread loaded them) against the build before (d227213),
# alternating in one lease; fly-through and city at 100,000 and 1,000,000 objects.
set -uo pipefail
carry=$(cd "$(dirname "$0")" && pwd)
W=/tmp/job43; rm -rf $W; mkdir -p $W/json $W/a $W/b
tar -C $W/a -xJf "$carry/encore-before.tar.xz"
tar -C $W/b -xJf "$carry/encore.tar.xz"
R=$OUT/j43; mkdir -p $R
(nvidia-smi --query-gpu=timestamp,clocks.sm,utilization.gpu --format=csv -lms 500 > $R/smi.csv 2>&1 &)
b() { local tag=$1 dir=$2 n=$3; echo "== $tag $n" >> $R/j43.txt
  bash $W/$dir/pack/run.sh encore bench --scene flythrough --scene city --objects $n --width 1280 --height 720 --frames 20 --warmup 5 --json $W/json/b-$tag-$n.json -s visibility >> $R/j43.txt 2>&1; }
for r in 1 2; do b before$r a 100000; b shared$r b 100000; done
b before a 1000000; b shared b 1000000
pkill nvidia-smi
for f in $W/json/*.json; do echo "### $(basename $f)"; cat $f; done > $R/all-json.txt
grep -E "^==|^\| (visibility|gpu-culling)|rror" $R/j43.txt
grep -E "^==|^- visibility" $R/j43.txt | grep -o "^==.*\|compute raster [0-9.]*\|compute raster (second phase) [0-9.]*"
