#!/usr/bin/env bash
# Issue 28: where the visibility strategy's time goes, each step timed in a pass of its own
# (culling, compute raster, workgroup raster, hardware raster, depth pyramid, occlusion culling,
# binning, shading, composition), scenes at 100,000 and 1,000,000 objects, 1280x720; the dense
# batch's start (16 files against 200).
set -uo pipefail
carry=$(cd "$(dirname "$0")" && pwd)
W=/tmp/job25; rm -rf $W; mkdir -p $W
tar -C $W -xJf "$carry/encore.tar.xz"
R=$OUT/j25; mkdir -p $R
E() { bash $W/pack/run.sh encore "$@"; }
E info 2>&1 | head -1 > $R/info.txt
run() { local name=$1 input=$2; shift 2; rm -rf $W/o; echo "== $name: $*" >> $R/j25.txt
  local t0=$(date +%s.%N)
  E -v batch $input -o $W/o --quiet "$@" 2>&1 | grep -E "views in|^stages|^upload|^gpu" | sed 's/(load and encode summed.*//' >> $R/j25.txt
  echo "wall $(awk "BEGIN{print $(date +%s.%N) - $t0}") s (the process, start to exit)" >> $R/j25.txt
  rm -rf $W/o; }
E bench --scene flythrough --objects 100000 -s visibility --width 1280 --height 720 --frames 60 --warmup 10 > /dev/null 2>&1
for round in 1 2; do
  echo "== scenes 100000 r$round" >> $R/j25.txt
  E bench --scene flythrough --scene city --objects 100000 -s visibility -s gpu-culling-bundles --width 1280 --height 720 --frames 20 --warmup 5 --json $R/bench-100000-r$round.json >> $R/j25.txt 2>&1
done
echo "== scenes 1000000" >> $R/j25.txt
E bench --scene flythrough --scene city --objects 1000000 -s visibility --width 1280 --height 720 --frames 20 --warmup 5 --json $R/bench-1000000.json >> $R/j25.txt 2>&1
mkdir -p $W/dense
for i in $(seq 1 40); do E gen --objects 24 --meshes 4 --tessellation 256 --seed $i -o $W/dense/m$i.glb > /dev/null 2>&1 & if (( i % 8 == 0 )); then wait; fi; done; wait
for k in 1 2 3 4 5; do mkdir -p $W/dense$k; for i in $(seq 1 40); do ln -s $W/dense/m$i.glb $W/dense$k/m$i.glb; done; done
ls $W/dense[1-5]/*.glb > $W/dense200.txt
head -16 $W/dense200.txt > $W/dense16.txt
E batch $W/dense200.txt -o $W/o --quiet --strategy visibility > /dev/null 2>&1; rm -rf $W/o
for round in 1 2; do
  run "dense16 s4 visibility r$round" $W/dense16.txt --samples 4 --strategy visibility
  run "dense200 s4 visibility r$round" $W/dense200.txt --samples 4 --strategy visibility
done
run "dense16 s4 default" $W/dense16.txt --samples 4
grep -E "^==|^\| (visibility|gpu-culling)|^- |^### |views in|^stages|^upload|^gpu|^wall" $R/j25.txt
