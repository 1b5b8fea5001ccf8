#!/usr/bin/env bash
# Issue 28: (1) the compute raster's split by triangle size at 100,000 objects (per-pass
# timings): --compute-raster-pixels 4, 8, 16, 32; (2) the batch's start with the visibility
# pipelines compiled side by side ("new") against one after another ("base"), 16 and 200 dense
# files, alternating.
set -uo pipefail
carry=$(cd "$(dirname "$0")" && pwd)
W=/tmp/job26; rm -rf $W; mkdir -p $W/base
tar -C $W -xJf "$carry/encore.tar.xz"
tar -C $W/base -xJf "$carry/encore-base.tar.xz"
R=$OUT/j26; mkdir -p $R
E() { bash $W/pack/run.sh encore "$@"; }
B() { bash $W/base/pack/run.sh encore "$@"; }
E info 2>&1 | head -1 > $R/info.txt
run() { local F=$1 name=$2 input=$3; shift 3; rm -rf $W/o; echo "== $name: $*" >> $R/j26.txt
  local t0=$(date +%s.%N)
  $F -v batch $input -o $W/o --quiet "$@" 2>&1 | grep -E "views in|^stages|^upload" | sed 's/(load and encode summed.*//' >> $R/j26.txt
  echo "wall $(awk "BEGIN{print $(date +%s.%N) - $t0}") s (the process, start to exit)" >> $R/j26.txt
  rm -rf $W/o; }
E bench --scene flythrough --objects 100000 -s visibility --width 1280 --height 720 --frames 60 --warmup 10 > /dev/null 2>&1
for px in 4 8 16 32; do
  echo "== scenes 100000 compute-raster-pixels $px" >> $R/j26.txt
  E bench --scene flythrough --scene city --objects 100000 -s visibility --compute-raster-pixels $px --width 1280 --height 720 --frames 20 --warmup 5 --json $R/bench-px$px.json >> $R/j26.txt 2>&1
done
mkdir -p $W/dense
for i in $(seq 1 40); do E gen --objects 24 --meshes 4 --tessellation 256 --seed $i -o $W/dense/m$i.glb > /dev/null 2>&1 & if (( i % 8 == 0 )); then wait; fi; done; wait
for k in 1 2 3 4 5; do mkdir -p $W/dense$k; for i in $(seq 1 40); do ln -s $W/dense/m$i.glb $W/dense$k/m$i.glb; done; done
ls $W/dense[1-5]/*.glb > $W/dense200.txt
head -16 $W/dense200.txt > $W/dense16.txt
E batch $W/dense200.txt -o $W/o --quiet --strategy visibility > /dev/null 2>&1; rm -rf $W/o
B batch $W/dense200.txt -o $W/o --quiet --strategy visibility > /dev/null 2>&1; rm -rf $W/o
for round in 1 2 3; do
  run B "dense16 s4 visibility base r$round" $W/dense16.txt --samples 4 --strategy visibility
  run E "dense16 s4 visibility new r$round" $W/dense16.txt --samples 4 --strategy visibility
done
for round in 1 2 3; do
  run B "dense200 s4 visibility base r$round" $W/dense200.txt --samples 4 --strategy visibility
  run E "dense200 s4 visibility new r$round" $W/dense200.txt --samples 4 --strategy visibility
done
run E "dense200 s4 default" $W/dense200.txt --samples 4
run E "dense16 s4 default" $W/dense16.txt --samples 4
grep -E "^==|^\| (visibility|gpu-culling)|^- |^### |views in|^wall" $R/j26.txt
