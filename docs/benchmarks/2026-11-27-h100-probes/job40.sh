#!/usr/bin/env bash
# Issue 28 probes (experiment build, ENCORE_PROBES): where the first phase's raster time goes.
# Without occlusion culling (the probes change what the pyramid holds). NOATOMIC: samples tested but no atomic written; NOCOVER: workgroup blocks set up, not covered.
set -uo pipefail
carry=$(cd "$(dirname "$0")" && pwd)
W=/tmp/job40; rm -rf $W; mkdir -p $W/json
tar -C $W -xJf "$carry/encore.tar.xz"
R=$OUT/j40; mkdir -p $R
E() { bash $W/pack/run.sh encore "$@"; }
E info 2>&1 | head -1 > $R/info.txt
(nvidia-smi --query-gpu=timestamp,clocks.sm,utilization.gpu --format=csv -lms 500 > $R/smi.csv 2>&1 &)
b() { local tag=$1 probes=$2; echo "== $tag [$probes]" >> $R/j40.txt
  ENCORE_PROBES=$probes E bench --scene flythrough --scene city --objects 100000 --width 1280 --height 720 --frames 20 --warmup 5 --json $W/json/b-$tag.json -s visibility --no-occlusion >> $R/j40.txt 2>&1; }
for r in 1 2; do b base$r ""; b noatomic$r NOATOMIC; b nocover$r NOCOVER; done
pkill nvidia-smi
for f in $W/json/*.json; do echo "### $(basename $f)"; cat $f; done > $R/all-json.txt
grep -E "^==|^- visibility" $R/j40.txt | sed 's/visibility //g'
