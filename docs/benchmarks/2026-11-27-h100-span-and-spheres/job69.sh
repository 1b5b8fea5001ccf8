#!/usr/bin/env bash
# Issue 28, stop 49: encore batch, J (139c989) with --strategy visibility against the default
# strategy and H (c26e946): 200 dense files (40 generated, 24 objects x 4 meshes at tessellation
# 256: 1.59 M triangles per view, 12 views each, 512x512) at four samples and at one; the seven
# light sample models x 100. Runs on the warm machine of job68 (its unpacked builds).
set -uo pipefail
carry=$(cd "$(dirname "$0")" && pwd)
W=/tmp/job68
[ -d $W/j ] || { mkdir -p $W/j $W/h; tar -C $W/j -xJf "$carry/encore-j.tar.xz"; tar -C $W/h -xJf "$carry/encore-h.tar.xz"; }
R=$OUT/j69; mkdir -p $R
J() { bash $W/j/pack/run.sh encore "$@"; }
H() { bash $W/h/pack/run.sh encore "$@"; }
mkdir -p $W/dense
for i in $(seq 1 40); do J gen --objects 24 --meshes 4 --tessellation 256 --seed $i -o $W/dense/m$i.glb > /dev/null 2>&1 & if (( i % 8 == 0 )); then wait; fi; done; wait
for k in 1 2 3 4 5; do mkdir -p $W/dense$k; for i in $(seq 1 40); do ln -sf $W/dense/m$i.glb $W/dense$k/m$i.glb; done; done
ls $W/dense[1-5]/*.glb > $W/dense200.txt
for i in $(seq -w 0 99); do mkdir -p $W/in/$i; for m in "$carry"/models/*.glb; do ln -sf "$m" $W/in/$i/; done; done
ls $W/in/*/*.glb > $W/light.txt
wc -l $W/dense200.txt $W/light.txt
run() { local name=$1 X=$2 input=$3; shift 3; rm -rf $W/o
  echo "== $name: $(  $X -v batch $input -o $W/o --quiet "$@" 2>&1 | grep -E "views in" | sed 's/(load and encode summed.*//' )"; rm -rf $W/o; }
J batch $W/dense200.txt -o $W/o --quiet --strategy visibility > /dev/null 2>&1; rm -rf $W/o
run "dense s4 J r1" J $W/dense200.txt --samples 4 --strategy visibility
run "dense s4 H" H $W/dense200.txt --samples 4 --strategy visibility
run "dense s4 default" J $W/dense200.txt --samples 4
run "dense s4 J r2" J $W/dense200.txt --samples 4 --strategy visibility
run "dense s1 J" J $W/dense200.txt --samples 1 --strategy visibility
run "dense s1 default" J $W/dense200.txt --samples 1
run "light J r1" J $W/light.txt --strategy visibility
run "light default" J $W/light.txt
run "light J r2" J $W/light.txt --strategy visibility
J render $W/dense/m1.glb -s visibility --samples 4 --width 512 --height 512 -o $W/v.png > /dev/null 2>&1
J render $W/dense/m1.glb --samples 4 --width 512 --height 512 -o $W/d.png > /dev/null 2>&1
echo "== dense m1 s4 visibility vs default: $(J compare $W/v.png $W/d.png 2>&1 | tr '\n' ' ')"
