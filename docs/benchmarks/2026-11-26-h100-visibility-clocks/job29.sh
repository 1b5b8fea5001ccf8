#!/usr/bin/env bash
# Issue 28, where the time of the visibility passes goes: shader probes (ENCORE_PROBES, an
# experiment-only build) that drop parts of a pass, per-pass timings in one lease, with the GPU's
# clocks logged alongside.
set -uo pipefail
carry=$(cd "$(dirname "$0")" && pwd)
W=/tmp/job29; rm -rf $W; mkdir -p $W
tar -C $W -xJf "$carry/encore.tar.xz"
R=$OUT/j29; mkdir -p $R
E() { bash $W/pack/run.sh encore "$@"; }
E info 2>&1 | head -1 > $R/info.txt
(nvidia-smi --query-gpu=timestamp,pstate,clocks.sm,clocks.mem,power.draw,temperature.gpu,utilization.gpu,clocks_throttle_reasons.active --format=csv -lms 250 > $R/smi.csv 2>&1 &) 
scenes() { local tag=$1 n=$2 probes=$3; shift 3; echo "== $n $tag [$probes] $(date +%T)" >> $R/j29.txt
  ENCORE_PROBES=$probes E bench --scene flythrough --objects $n -s visibility "$@" --width 1280 --height 720 --frames 30 --warmup 10 --json $R/b-$n-$tag.json >> $R/j29.txt 2>&1; }
E bench --scene flythrough --objects 100000 -s visibility --width 1280 --height 720 --frames 60 --warmup 10 > /dev/null 2>&1
scenes base1 100000 ""
scenes shadeid 100000 PROBE_SHADE_ID
scenes shadegeo 100000 PROBE_SHADE_GEOMETRY
scenes noatomic 100000 PROBE_NO_ATOMIC
scenes setup 100000 PROBE_SETUP_ONLY
scenes base2 100000 ""
scenes mat1 100000 "" --materials 1
scenes notex 100000 "" --no-textures
scenes base1 1000000 ""
scenes noatomic 1000000 PROBE_NO_ATOMIC
scenes setup 1000000 PROBE_SETUP_ONLY
scenes shadeid 1000000 PROBE_SHADE_ID
scenes base2 1000000 ""
pkill nvidia-smi
grep -E "^==|^\| (visibility|gpu-culling)" $R/j29.txt
