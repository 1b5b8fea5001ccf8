#!/usr/bin/env bash
# Issue 28, stop 45, second lease: the CPU frame of this stop's build (A: cace4fc, counts read
# from the counters) against gpu-culling-bundles, five rounds alternating, 300 frames without
# the GPU timer; beside them an experiment-only build (P) that leaves out parts of the frame
# (ENCORE_CPU_PROBE: nohw, the two hardware raster passes; nopyr, the pyramid's dispatches;
# noshdisp, the shading dispatches; nocompose, the composition's dispatch), to say where the
# visibility strategy's CPU frame goes on this host. Then GPU frames of A for the plot.
set -uo pipefail
carry=$(cd "$(dirname "$0")" && pwd)
W=/tmp/job50; rm -rf $W; mkdir -p $W/a $W/p
tar -C $W/a -xJf "$carry/encore.tar.xz"
tar -C $W/p -xJf "$carry/encore-probe.tar.xz"
R=$OUT/j50; mkdir -p $R
A() { bash $W/a/pack/run.sh encore "$@"; }
P() { bash $W/p/pack/run.sh encore "$@"; }
A info 2>&1 | head -1 > $R/info.txt
(nvidia-smi --query-gpu=timestamp,clocks.sm,utilization.gpu --format=csv -lms 500 > $R/smi.csv 2>&1 &)
A bench --scene flythrough --objects 100000 -s visibility --width 1280 --height 720 --frames 200 --warmup 5 > /dev/null 2>&1
cpu() { local label=$1 X=$2 s=$3 probe=$4
  echo "== cpu $label r$r" >> $R/cpu.txt
  ENCORE_CPU_PROBE=$probe $X bench --scene flythrough --scene city --objects 100000 -s $s --width 1280 --height 720 --frames 300 --warmup 5 --no-gpu-timer 2>&1 | grep -E "^\| (visibility|gpu-culling)|^### " >> $R/cpu.txt; }
for r in 1 2 3 4 5; do
  cpu gcb A gpu-culling-bundles none
  cpu vis A visibility none
  cpu probe-none P visibility none
  cpu probe-nohw P visibility nohw
  cpu probe-nopyr P visibility nopyr
  cpu probe-noshdisp P visibility noshdisp
  cpu probe-nocompose P visibility nocompose
done
for n in 100000 1000000; do
  echo "== gpu A $n" >> $R/gpu.txt
  A bench --scene flythrough --scene city --objects $n -s visibility -s gpu-culling-bundles --width 1280 --height 720 --frames 20 --warmup 5 --json $R/bench-A-$n.json 2>&1 | grep -E "^\| (visibility|gpu-culling)|^### " >> $R/gpu.txt
done
pkill nvidia-smi
grep -E "^==|^\| (visibility|gpu-culling)" $R/cpu.txt | awk '/^==/{l=$0; next} {split($0,f,"|"); printf "%s %s\n", l, f[3]}' | head -80
cat $R/gpu.txt
