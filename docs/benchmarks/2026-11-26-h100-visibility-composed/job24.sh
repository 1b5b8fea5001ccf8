#!/usr/bin/env bash
# Issue 28: the frame composed in compute (no scene render pass) against the build before it
# ("base"), alternating in one lease: scenes at 100,000 and 1,000,000 objects (1280x720), the
# dense batch at four samples; gpu-culling-bundles and the default strategy once for scale.
set -uo pipefail
carry=$(cd "$(dirname "$0")" && pwd)
W=/tmp/job24; rm -rf $W; mkdir -p $W/base
tar -C $W -xJf "$carry/encore.tar.xz"
tar -C $W/base -xJf "$carry/encore-base.tar.xz"
R=$OUT/j24; mkdir -p $R
E() { bash $W/pack/run.sh encore "$@"; }
B() { bash $W/base/pack/run.sh encore "$@"; }
E info 2>&1 | head -1 > $R/info.txt
run() { local F=$1 name=$2 input=$3; shift 3; rm -rf $W/o; echo "== $name: $*" >> $R/j24.txt
  $F -v batch $input -o $W/o --quiet "$@" 2>&1 | grep -E "views in|^stages|^upload|^gpu" | sed 's/(load and encode summed.*//' >> $R/j24.txt
  rm -rf $W/o; }
E bench --scene flythrough --objects 100000 -s visibility --width 1280 --height 720 --frames 60 --warmup 10 > /dev/null 2>&1
B bench --scene flythrough --objects 100000 -s visibility --width 1280 --height 720 --frames 30 --warmup 10 > /dev/null 2>&1
for round in 1 2; do for b in B E; do
  echo "== scenes 100000 $b r$round" >> $R/j24.txt
  $b bench --scene flythrough --scene city --objects 100000 -s visibility --width 1280 --height 720 --frames 20 --warmup 5 --json $R/bench-100000-$b-r$round.json >> $R/j24.txt 2>&1
done; done
echo "== scenes 100000 gpu-culling-bundles" >> $R/j24.txt
E bench --scene flythrough --scene city --objects 100000 -s gpu-culling-bundles --width 1280 --height 720 --frames 20 --warmup 5 --json $R/bench-100000-gcb.json >> $R/j24.txt 2>&1
for b in B E; do
  echo "== scenes 1000000 $b" >> $R/j24.txt
  $b bench --scene flythrough --scene city --objects 1000000 -s visibility -s gpu-culling-bundles --width 1280 --height 720 --frames 20 --warmup 5 --json $R/bench-1000000-$b.json >> $R/j24.txt 2>&1
done
mkdir -p $W/dense
for i in $(seq 1 40); do E gen --objects 24 --meshes 4 --tessellation 256 --seed $i -o $W/dense/m$i.glb > /dev/null 2>&1 & if (( i % 8 == 0 )); then wait; fi; done; wait
for k in 1 2 3 4 5; do mkdir -p $W/dense$k; for i in $(seq 1 40); do ln -s $W/dense/m$i.glb $W/dense$k/m$i.glb; done; done
ls $W/dense[1-5]/*.glb > $W/dense200.txt
E batch $W/dense200.txt -o $W/o --quiet --strategy visibility > /dev/null 2>&1; rm -rf $W/o
B batch $W/dense200.txt -o $W/o --quiet --strategy visibility > /dev/null 2>&1; rm -rf $W/o
run E "dense200 s4 default" $W/dense200.txt --samples 4
for round in 1 2 3; do
  run B "dense200 s4 visibility base r$round" $W/dense200.txt --samples 4 --strategy visibility
  run E "dense200 s4 visibility new r$round" $W/dense200.txt --samples 4 --strategy visibility
done
head -5 $W/dense200.txt > $W/d5.txt
E batch $W/d5.txt -o $W/od --quiet --samples 4 > /dev/null 2>&1
E batch $W/d5.txt -o $W/ov --quiet --samples 4 --strategy visibility > /dev/null 2>&1
for f in $(cd $W/od && find . -name '*.png' | sort | head -60); do echo "$f $(E compare $W/od/$f $W/ov/$f 2>&1 | grep ssim)"; done > $R/ssim.txt
echo "ssim against the default: $(wc -l < $R/ssim.txt) views, lowest:" >> $R/j24.txt
sort -k3 -n $R/ssim.txt | head -2 >> $R/j24.txt
grep -E "^==|^\| (visibility|gpu-culling)|^- |^### |views in|^gpu|^ssim|png" $R/j24.txt
