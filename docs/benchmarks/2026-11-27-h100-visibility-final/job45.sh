#!/usr/bin/env bash
# Issue 28, the session's final build: encore batch, 200 dense files at four samples (three
# rounds alternating) and one, the ten light models x 100, against the default; SSIM.
set -uo pipefail
carry=$(cd "$(dirname "$0")" && pwd)
W=/tmp/job45; rm -rf $W; mkdir -p $W
tar -C $W -xJf "$carry/encore.tar.xz"
R=$OUT/j45; mkdir -p $R
E() { bash $W/pack/run.sh encore "$@"; }
E info 2>&1 | head -1 > $R/info.txt
run() { local name=$1 input=$2; shift 2; rm -rf $W/o; echo "== $name: $*" >> $R/j45.txt
  E -v batch $input -o $W/o --quiet "$@" 2>&1 | grep -E "views in|^stages|^upload|^gpu" | sed 's/(load and encode summed.*//' >> $R/j45.txt
  rm -rf $W/o; }
(nvidia-smi --query-gpu=timestamp,clocks.sm,utilization.gpu --format=csv -lms 500 > $R/smi.csv 2>&1 &)
mkdir -p $W/dense
for i in $(seq 1 40); do E gen --objects 24 --meshes 4 --tessellation 256 --seed $i -o $W/dense/m$i.glb > /dev/null 2>&1 & if (( i % 8 == 0 )); then wait; fi; done; wait
for k in 1 2 3 4 5; do mkdir -p $W/dense$k; for i in $(seq 1 40); do ln -s $W/dense/m$i.glb $W/dense$k/m$i.glb; done; done
ls $W/dense[1-5]/*.glb > $W/dense200.txt
E batch $W/dense200.txt -o $W/o --quiet --strategy visibility > /dev/null 2>&1; rm -rf $W/o
for round in 1 2 3; do
  run "dense200 s4 default r$round" $W/dense200.txt --samples 4
  run "dense200 s4 visibility r$round" $W/dense200.txt --samples 4 --strategy visibility
done
run "dense200 s1 default" $W/dense200.txt --samples 1
run "dense200 s1 visibility" $W/dense200.txt --samples 1 --strategy visibility
M=$(cd "$carry/../.gpu-carry/models" && pwd)
for i in $(seq -w 0 99); do mkdir -p $W/in/$i; for m in "$M"/*; do ln -s "$m" $W/in/$i/; done; done
for d in $W/in/*/*/; do ls "$d"*.glb "$d"*.gltf 2>/dev/null | head -1; done | head -n 1000 > $W/l1.txt
run "light s4 default" $W/l1.txt
run "light s4 visibility" $W/l1.txt --strategy visibility
head -5 $W/dense200.txt > $W/d5.txt
E batch $W/d5.txt -o $W/od --quiet --samples 4 > /dev/null 2>&1
E batch $W/d5.txt -o $W/ov --quiet --samples 4 --strategy visibility > /dev/null 2>&1
for f in $(cd $W/od && find . -name '*.png' | sort | head -60); do echo "$f $(E compare $W/od/$f $W/ov/$f 2>&1 | grep ssim)"; done > $R/ssim.txt
echo "ssim against the default: $(wc -l < $R/ssim.txt) views, lowest:" >> $R/j45.txt
sort -k3 -n $R/ssim.txt | head -2 >> $R/j45.txt
pkill nvidia-smi
grep -E "^==|views in|^gpu|^ssim|png" $R/j45.txt
