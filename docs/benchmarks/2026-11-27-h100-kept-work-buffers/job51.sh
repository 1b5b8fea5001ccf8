#!/usr/bin/env bash
# Issue 28, stop 45, third lease: this stop's build (cace4fc) on light models (ten shared
# sample models x 100 = 1,000 files, 12 views of 512x512, four samples), default against
# visibility, two rounds alternating; SSIM of 60 dense views against the default.
set -uo pipefail
carry=$(cd "$(dirname "$0")" && pwd)
W=/tmp/job51; rm -rf $W; mkdir -p $W/a
tar -C $W/a -xJf "$carry/encore.tar.xz"
R=$OUT/j51; mkdir -p $R
A() { bash $W/a/pack/run.sh encore "$@"; }
A info 2>&1 | head -1 > $R/info.txt
(nvidia-smi --query-gpu=timestamp,clocks.sm,utilization.gpu --format=csv -lms 500 > $R/smi.csv 2>&1 &)
run() { local name=$1 input=$2; shift 2; rm -rf $W/o; echo "== $name: $*" >> $R/batch.txt
  A -v batch $input -o $W/o --quiet "$@" 2>&1 | grep -E "views in|^stages|^upload|^gpu" | sed 's/(load and encode summed.*//' >> $R/batch.txt
  rm -rf $W/o; }
for i in $(seq -w 0 99); do mkdir -p $W/in/$i; for m in "$carry"/models/*.glb; do ln -s "$m" $W/in/$i/; done; done
ls $W/in/*/*.glb > $W/light.txt
A batch $W/light.txt -o $W/o --quiet --strategy visibility > /dev/null 2>&1; rm -rf $W/o
for round in 1 2; do
  run "light s4 default r$round" $W/light.txt
  run "light s4 visibility r$round" $W/light.txt --strategy visibility
done
mkdir -p $W/dense
for i in 1 2 3 4 5; do A gen --objects 24 --meshes 4 --tessellation 256 --seed $i -o $W/dense/m$i.glb > /dev/null 2>&1 & done; wait
ls $W/dense/*.glb > $W/d5.txt
A batch $W/d5.txt -o $W/od --quiet --samples 4 > /dev/null 2>&1
A batch $W/d5.txt -o $W/ov --quiet --samples 4 --strategy visibility > /dev/null 2>&1
for f in $(cd $W/od && find . -name '*.png' | sort | head -60); do echo "$f $(A compare $W/od/$f $W/ov/$f 2>&1 | grep ssim)"; done > $R/ssim.txt
echo "ssim against the default: $(wc -l < $R/ssim.txt) views, lowest:" >> $R/batch.txt
sort -k3 -n $R/ssim.txt | head -2 >> $R/batch.txt
pkill nvidia-smi
grep -E "^==|views in|^upload|^gpu|ssim|png" $R/batch.txt
