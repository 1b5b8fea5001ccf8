#!/usr/bin/env bash
# Issue 28: large triangles in the compute workgroup raster (64-bit edge functions beyond 112
# pixels) against the hardware, by --workgroup-raster-pixels (112 = the hardware takes them as
# before), alternating; a sweep for where the compute path stops paying; gpu-culling-bundles.
set -uo pipefail
carry=$(cd "$(dirname "$0")" && pwd)
W=/tmp/job38; rm -rf $W; mkdir -p $W/json
tar -C $W -xJf "$carry/encore.tar.xz"
R=$OUT/j38; mkdir -p $R
E() { bash $W/pack/run.sh encore "$@"; }
E info 2>&1 | head -1 > $R/info.txt
(nvidia-smi --query-gpu=timestamp,clocks.sm,utilization.gpu --format=csv -lms 500 > $R/smi.csv 2>&1 &)
b() { local tag=$1 n=$2; shift 2; echo "== $tag $n: $*" >> $R/j38.txt
  E bench --scene flythrough --scene city --objects $n --width 1280 --height 720 --frames 20 --warmup 5 --json $W/json/b-$tag-$n.json "$@" >> $R/j38.txt 2>&1; }
b ref 100000 -s gpu-culling-bundles
for r in 1 2; do
  b w112r$r 100000 -s visibility --workgroup-raster-pixels 112
  b w8192r$r 100000 -s visibility --workgroup-raster-pixels 8192
done
for w in 256 512 1024 2048; do b w$w 100000 -s visibility --workgroup-raster-pixels $w; done
b w112 1000000 -s visibility --workgroup-raster-pixels 112
b w8192 1000000 -s visibility --workgroup-raster-pixels 8192
b ref 1000000 -s gpu-culling-bundles
pkill nvidia-smi
for f in $W/json/*.json; do echo "### $(basename $f)"; cat $f; done > $R/all-json.txt
grep -E "^==|^\| (visibility|gpu-culling)|rror" $R/j38.txt
