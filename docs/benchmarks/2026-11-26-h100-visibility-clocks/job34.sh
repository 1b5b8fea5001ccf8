#!/usr/bin/env bash
# Issue 28: the workgroup raster's triangles split into blocks of 32x32 pixels listed apart
# (default) against one block per triangle (PROBE_BLOCK128, as before) and blocks of 16 and 64
# (PROBE_BLOCK16, PROBE_BLOCK64); one experiment-only binary, alternating, per-pass timings.
set -uo pipefail
carry=$(cd "$(dirname "$0")" && pwd)
W=/tmp/job34; rm -rf $W; mkdir -p $W
tar -C $W -xJf "$carry/encore.tar.xz"
R=$OUT/j34; mkdir -p $R $W/json
E() { bash $W/pack/run.sh encore "$@"; }
E info 2>&1 | head -1 > $R/info.txt
scenes() { local tag=$1 n=$2 probes=$3; shift 3; echo "== $n $tag [$probes] $(date +%T)" >> $R/j34.txt
  ENCORE_PROBES=$probes E bench --scene flythrough --scene city --objects $n -s visibility "$@" --width 1280 --height 720 --frames 20 --warmup 5 --json $W/json/b-$n-$tag.json >> $R/j34.txt 2>&1; }
for r in 1 2; do
  scenes one$r 100000 PROBE_BLOCK128
  scenes b32-$r 100000 ""
done
scenes b16 100000 PROBE_BLOCK16
scenes b64 100000 PROBE_BLOCK64
scenes one1 1000000 PROBE_BLOCK128
scenes b32-1 1000000 ""
for f in $W/json/*.json; do echo "### $(basename $f)"; cat $f; done > $R/all-json.txt
grep -E "^==|^\| (visibility|gpu-culling)" $R/j34.txt
