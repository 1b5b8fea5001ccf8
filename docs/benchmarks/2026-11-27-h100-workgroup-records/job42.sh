#!/usr/bin/env bash
# Issue 28: the build before triangle records (f88f03a) against the records build (and its
# NORECORD probe), alternating in one lease; fly-through and city at 100,000 objects.
set -uo pipefail
carry=$(cd "$(dirname "$0")" && pwd)
W=/tmp/job42; rm -rf $W; mkdir -p $W/json $W/a $W/b
tar -C $W/a -xJf "$carry/encore-f88f03a.tar.xz"
tar -C $W/b -xJf "$carry/encore.tar.xz"
R=$OUT/j42; mkdir -p $R
(nvidia-smi --query-gpu=timestamp,clocks.sm,utilization.gpu --format=csv -lms 500 > $R/smi.csv 2>&1 &)
b() { local tag=$1 dir=$2 probes=$3; echo "== $tag [$probes]" >> $R/j42.txt
  ENCORE_PROBES=$probes bash $W/$dir/pack/run.sh encore bench --scene flythrough --scene city --objects 100000 --width 1280 --height 720 --frames 20 --warmup 5 --json $W/json/b-$tag.json -s visibility >> $R/j42.txt 2>&1; }
for r in 1 2; do b before$r a ""; b records$r b ""; b norecord$r b NORECORD; done
pkill nvidia-smi
for f in $W/json/*.json; do echo "### $(basename $f)"; cat $f; done > $R/all-json.txt
grep -E "^==|^\| (visibility|gpu-culling)|rror" $R/j42.txt
grep -E "^==|^- visibility" $R/j42.txt | grep -o "^==.*\|workgroup raster [0-9.]*"
