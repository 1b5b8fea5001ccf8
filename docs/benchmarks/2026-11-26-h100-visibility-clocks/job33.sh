#!/usr/bin/env bash
# Issue 28: vertex attributes of aligned 32-bit floats loaded as whole words (PROBE_OLD_LOADS
# restores the generic path) and TEXCOORD_1's fallback not loaded twice (PROBE_OLD_UV1), one
# experiment-only binary, alternating; and the CPU frame without timestamp queries,
# visibility against gpu-culling-bundles.
set -uo pipefail
carry=$(cd "$(dirname "$0")" && pwd)
W=/tmp/job33; rm -rf $W; mkdir -p $W
tar -C $W -xJf "$carry/encore.tar.xz"
R=$OUT/j33; mkdir -p $R $W/json
E() { bash $W/pack/run.sh encore "$@"; }
E info 2>&1 | head -1 > $R/info.txt
scenes() { local tag=$1 n=$2 probes=$3; shift 3; echo "== $n $tag [$probes] $(date +%T)" >> $R/j33.txt
  ENCORE_PROBES=$probes E bench --scene flythrough --scene city --objects $n "$@" --width 1280 --height 720 --json $W/json/b-$n-$tag.json >> $R/j33.txt 2>&1; }
for r in 1 2; do
  scenes old$r 100000 PROBE_OLD_LOADS,PROBE_OLD_UV1 -s visibility --frames 20 --warmup 5
  scenes new$r 100000 "" -s visibility --frames 20 --warmup 5
done
scenes oldloads 100000 PROBE_OLD_LOADS -s visibility --frames 20 --warmup 5
scenes olduv1 100000 PROBE_OLD_UV1 -s visibility --frames 20 --warmup 5
scenes old1 1000000 PROBE_OLD_LOADS,PROBE_OLD_UV1 -s visibility --frames 20 --warmup 5
scenes new1 1000000 "" -s visibility --frames 20 --warmup 5
for r in 1 2; do
  scenes cpu$r 100000 "" -s visibility -s gpu-culling-bundles --no-gpu-timer --frames 60 --warmup 10
done
for f in $W/json/*.json; do echo "### $(basename $f)"; cat $f; done > $R/all-json.txt
grep -E "^==|^\| (visibility|gpu-culling)" $R/j33.txt
