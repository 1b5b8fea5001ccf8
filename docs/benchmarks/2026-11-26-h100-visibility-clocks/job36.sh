#!/usr/bin/env bash
# Issue 28: the thread raster's limit again after the batched units, word loads and 32x32
# blocks (bb1c7c4): --compute-raster-pixels 4, 8, 12, 16 at 100,000 objects, 8 and 16 at
# 1,000,000; per-pass timings.
set -uo pipefail
carry=$(cd "$(dirname "$0")" && pwd)
W=/tmp/job36; rm -rf $W; mkdir -p $W
tar -C $W -xJf "$carry/encore.tar.xz"
R=$OUT/j36; mkdir -p $R $W/json
E() { bash $W/pack/run.sh encore "$@"; }
E info 2>&1 | head -1 > $R/info.txt
scenes() { local n=$1 px=$2 tag=$3; echo "== $n px$px $tag" >> $R/j36.txt
  E bench --scene flythrough --scene city --objects $n -s visibility --compute-raster-pixels $px --width 1280 --height 720 --frames 20 --warmup 5 --json $W/json/b-$n-px$px-$tag.json >> $R/j36.txt 2>&1; }
i=0; for px in 8 4 12 16 8; do i=$((i+1)); scenes 100000 $px r$i; done
scenes 1000000 8 r; scenes 1000000 16 r
for f in $W/json/*.json; do echo "### $(basename $f)"; cat $f; done > $R/all-json.txt
grep -E "^==|^\| (visibility|gpu-culling)" $R/j36.txt
