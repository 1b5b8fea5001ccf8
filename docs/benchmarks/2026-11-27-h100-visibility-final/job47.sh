#!/usr/bin/env bash
# Issue 28: the shading of frames of one view without VIEW_SLOTS (params and frame uniform read
# from their bindings, not copied per thread into private variables; ENCORE_PROBES=-VIEW_SLOTS,
# experiment only) against with, alternating; fly-through and city at 100,000 and 1,000,000.
set -uo pipefail
carry=$(cd "$(dirname "$0")" && pwd)
W=/tmp/job47; rm -rf $W; mkdir -p $W/json
tar -C $W -xJf "$carry/encore.tar.xz"
R=$OUT/j47; mkdir -p $R
E() { bash $W/pack/run.sh encore "$@"; }
E info 2>&1 | head -1 > $R/info.txt
(nvidia-smi --query-gpu=timestamp,clocks.sm,utilization.gpu --format=csv -lms 500 > $R/smi.csv 2>&1 &)
b() { local tag=$1 n=$2 probes=$3; shift 3; echo "== $tag $n [$probes]: $*" >> $R/j47.txt
  ENCORE_PROBES=$probes E bench --scene flythrough --scene city --objects $n --width 1280 --height 720 --frames 20 --warmup 5 --json $W/json/b-$tag-$n.json -s visibility "$@" >> $R/j47.txt 2>&1; }
for r in 1 2; do
  b noslots$r 100000 -VIEW_SLOTS
  b slots$r 100000 ""
done
b noslots 1000000 -VIEW_SLOTS
b slots 1000000 ""
pkill nvidia-smi
for f in $W/json/*.json; do echo "### $(basename $f)"; cat $f; done > $R/all-json.txt
grep -E "^==|^\| (visibility|gpu-culling)|rror" $R/j47.txt
