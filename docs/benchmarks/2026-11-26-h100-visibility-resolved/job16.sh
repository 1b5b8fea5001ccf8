#!/usr/bin/env bash
# Issue 28: the per-pixel composite and staged geometry. Dense batch (200 files) default against
# visibility at 4 and 1 samples, two rounds alternating; light models at 4 samples.
set -uo pipefail
carry=$(cd "$(dirname "$0")" && pwd)
W=/tmp/job16; rm -rf $W; mkdir -p $W
tar -C $W -xJf "$carry/encore.tar.xz"
R=$OUT/j16; mkdir -p $R
save() { (cd $OUT && tar -cf results.tar j16); }
E() { bash $W/pack/run.sh encore "$@"; }
E info 2>&1 | head -1 > $R/info.txt
run() { local name=$1 input=$2; shift 2; rm -rf $W/o; echo "== $name: $*" >> $R/j16.txt
  E -v batch $input -o $W/o --quiet "$@" 2>&1 | grep -E "views in|^stages|^upload|^gpu|before" | sed 's/(load and encode summed.*//' >> $R/j16.txt
  rm -rf $W/o; save; }
mkdir -p $W/dense
for i in $(seq 1 40); do E gen --objects 24 --meshes 4 --tessellation 256 --seed $i -o $W/dense/m$i.glb > /dev/null 2>&1 & if (( i % 8 == 0 )); then wait; fi; done; wait
for k in 1 2 3 4 5; do mkdir -p $W/dense$k; for i in $(seq 1 40); do ln -s $W/dense/m$i.glb $W/dense$k/m$i.glb; done; done
ls $W/dense[1-5]/*.glb > $W/dense200.txt
E batch $W/dense200.txt -o $W/o --quiet --strategy visibility > /dev/null 2>&1; rm -rf $W/o
for s in 4 1; do for round in 1 2 3; do
  run "dense200 s$s default r$round" $W/dense200.txt --samples $s
  run "dense200 s$s visibility r$round" $W/dense200.txt --samples $s --strategy visibility
done; done
M=$(cd "$carry/../.gpu-carry/models" && pwd)
for i in $(seq -w 0 99); do mkdir -p $W/in/$i; for m in "$M"/*; do ln -s "$m" $W/in/$i/; done; done
for d in $W/in/*/*/; do ls "$d"*.glb "$d"*.gltf 2>/dev/null | head -1; done | head -n 1000 > $W/l1.txt
run "light s4 default" $W/l1.txt
run "light s4 visibility" $W/l1.txt --strategy visibility
cat $R/j16.txt
