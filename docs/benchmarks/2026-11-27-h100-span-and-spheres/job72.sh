#!/usr/bin/env bash
# Issue 28, stop 49: where a one-sample visibility batch's wall time goes (verbose stage lines),
# against four samples and the default; fresh lease.
set -uo pipefail
carry=$(cd "$(dirname "$0")" && pwd)
W=/tmp/job72; rm -rf $W; mkdir -p $W/j
tar -C $W/j -xJf "$carry/encore-j.tar.xz"
J() { bash $W/j/pack/run.sh encore "$@"; }
mkdir -p $W/dense
for i in $(seq 1 40); do J gen --objects 24 --meshes 4 --tessellation 256 --seed $i -o $W/dense/m$i.glb > /dev/null 2>&1 & if (( i % 4 == 0 )); then wait; fi; done; wait
ls $W/dense | wc -l
for k in 1 2 3 4 5; do mkdir -p $W/dense$k; for i in $(seq 1 40); do ln -sf $W/dense/m$i.glb $W/dense$k/m$i.glb; done; done
ls $W/dense[1-5]/*.glb > $W/dense200.txt
run() { local name=$1; shift; rm -rf $W/o; echo "== $name"
  J -v batch $W/dense200.txt -o $W/o --quiet "$@" 2>&1 | grep -vE "^adapter|^device 0" | cut -c1-400; rm -rf $W/o; }
J batch $W/dense200.txt -o $W/o --quiet --strategy visibility > /dev/null 2>&1; rm -rf $W/o
run "s1 visibility r1" --samples 1 --strategy visibility
run "s4 visibility" --samples 4 --strategy visibility
run "s1 visibility r2" --samples 1 --strategy visibility
run "s1 default" --samples 1
