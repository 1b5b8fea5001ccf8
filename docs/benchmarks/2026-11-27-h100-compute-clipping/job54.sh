#!/usr/bin/env bash
# Issue 28, stop 46: shading bins per group of materials that share textures ("A", c3adf78)
# against the build before it ("B", e42f913: triangles clipped in compute, bins per material).
# 1. CPU frame without the GPU timer: gpu-culling-bundles, B, A, five rounds alternating,
#    fly-through and city at 100,000 objects, 300 frames.
# 2. GPU frames with timestamps, B and A, 100,000 and 1,000,000 objects, 1280x720.
# 3. encore batch: 200 dense files at four samples (default, B, A) and the ten light models x 100
#    (default, A; seven of the ten, within the carry limit), two rounds; SSIM of A against the
#    default, 60 dense and 60 light views.
set -uo pipefail
carry=$(cd "$(dirname "$0")" && pwd)
W=/tmp/job54; rm -rf $W; mkdir -p $W/a $W/b
tar -C $W/a -xJf "$carry/encore.tar.xz"
tar -C $W/b -xJf "$carry/encore-before.tar.xz"
R=$OUT/j54; mkdir -p $R
A() { bash $W/a/pack/run.sh encore "$@"; }
B() { bash $W/b/pack/run.sh encore "$@"; }
A info 2>&1 | head -1 > $R/info.txt
(nvidia-smi --query-gpu=timestamp,clocks.sm --format=csv,noheader -lms 250 > $R/smi.txt 2>&1 &)
A bench --scene flythrough --objects 100000 -s visibility --width 1280 --height 720 --frames 200 --warmup 5 > /dev/null 2>&1
for r in 1 2 3 4 5; do
  for who in gcb vb va; do
    case $who in gcb) X=A; s=gpu-culling-bundles;; vb) X=B; s=visibility;; va) X=A; s=visibility;; esac
    echo "== cpu $who r$r" >> $R/cpu.txt
    $X bench --scene flythrough --scene city --objects 100000 -s $s --width 1280 --height 720 --frames 300 --warmup 5 --no-gpu-timer 2>&1 | grep -E "^\| (visibility|gpu-culling)|^### " >> $R/cpu.txt
  done
done
for n in 100000 1000000; do for who in B A; do
  echo "== gpu $who $n" >> $R/gpu.txt
  $who bench --scene flythrough --scene city --objects $n -s visibility -s gpu-culling-bundles --width 1280 --height 720 --frames 40 --warmup 5 --warmup-time 2 --json $R/bench-$who-$n.json 2>&1 | grep -E "^\| (visibility|gpu-culling)|^### " >> $R/gpu.txt
done; done
run() { local name=$1 X=$2 input=$3; shift 3; rm -rf $W/o; echo "== $name: $*" >> $R/batch.txt
  $X -v batch $input -o $W/o --quiet "$@" 2>&1 | grep -E "views in|^upload" | sed 's/(load and encode summed.*//' >> $R/batch.txt
  rm -rf $W/o; }
mkdir -p $W/dense
for i in $(seq 1 40); do A gen --objects 24 --meshes 4 --tessellation 256 --seed $i -o $W/dense/m$i.glb > /dev/null 2>&1 & if (( i % 8 == 0 )); then wait; fi; done; wait
for k in 1 2 3 4 5; do mkdir -p $W/dense$k; for i in $(seq 1 40); do ln -s $W/dense/m$i.glb $W/dense$k/m$i.glb; done; done
ls $W/dense[1-5]/*.glb > $W/dense200.txt
for i in $(seq -w 0 99); do mkdir -p $W/in/$i; for m in "$carry"/models/*.glb; do ln -s "$m" $W/in/$i/; done; done
ls $W/in/*/*.glb > $W/light.txt
A batch $W/dense200.txt -o $W/o --quiet --strategy visibility > /dev/null 2>&1; rm -rf $W/o
for round in 1 2; do
  run "dense200 s4 default r$round" A $W/dense200.txt --samples 4
  run "dense200 s4 visibility-B r$round" B $W/dense200.txt --samples 4 --strategy visibility
  run "dense200 s4 visibility-A r$round" A $W/dense200.txt --samples 4 --strategy visibility
  run "light s4 default r$round" A $W/light.txt
  run "light s4 visibility-A r$round" A $W/light.txt --strategy visibility
done
ls $W/dense/m[1-5].glb > $W/d5.txt
ls "$carry"/models/*.glb > $W/l10.txt
for set in d5 l10; do
  A batch $W/$set.txt -o $W/od-$set --quiet --samples 4 > /dev/null 2>&1
  A batch $W/$set.txt -o $W/ov-$set --quiet --samples 4 --strategy visibility > /dev/null 2>&1
  for f in $(cd $W/od-$set && find . -name '*.png' | sort | head -60); do echo "$f $(A compare $W/od-$set/$f $W/ov-$set/$f 2>&1 | grep ssim)"; done > $R/ssim-$set.txt
  echo "ssim $set against the default: $(wc -l < $R/ssim-$set.txt) views, lowest:" >> $R/batch.txt
  sort -k3 -n $R/ssim-$set.txt | head -2 >> $R/batch.txt
done
pkill nvidia-smi
grep -E "^==|^\| (visibility|gpu-culling)" $R/cpu.txt | head -80
grep -E "^==|^###|^\| (visibility|gpu-culling)" $R/gpu.txt
grep -E "^==|views in|ssim|png" $R/batch.txt
