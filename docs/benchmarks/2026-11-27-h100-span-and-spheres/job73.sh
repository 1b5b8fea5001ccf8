#!/usr/bin/env bash
# Issue 28, stop 49: is the visibility batch's loading serialised by the kernel's memory map
# lock (large allocations freed and mapped again by 16 loader threads)? The same runs with
# glibc's malloc keeping large blocks on its heaps (GLIBC_TUNABLES), alternating.
set -uo pipefail
carry=$(cd "$(dirname "$0")" && pwd)
W=/tmp/job73; rm -rf $W; mkdir -p $W/j
tar -C $W/j -xJf "$carry/encore-j.tar.xz"
J() { bash $W/j/pack/run.sh encore "$@"; }
mkdir -p $W/dense
for i in $(seq 1 40); do J gen --objects 24 --meshes 4 --tessellation 256 --seed $i -o $W/dense/m$i.glb > /dev/null 2>&1 & if (( i % 4 == 0 )); then wait; fi; done; wait
ls $W/dense | wc -l
for k in 1 2 3 4 5; do mkdir -p $W/dense$k; for i in $(seq 1 40); do [ -f $W/dense/m$i.glb ] && ln -sf $W/dense/m$i.glb $W/dense$k/m$i.glb; done; done
ls $W/dense[1-5]/*.glb > $W/dense200.txt
T="glibc.malloc.mmap_threshold=268435456:glibc.malloc.trim_threshold=2147483648"
run() { local name=$1 tun=$2; shift 2; rm -rf $W/o
  echo "== $name: $( env ${tun:+GLIBC_TUNABLES=$tun} bash $W/j/pack/run.sh encore -v batch $W/dense200.txt -o $W/o --quiet "$@" 2>&1 | grep -E "views in|^stages" | sed 's/(load and encode summed.*//' | tr '\n' ' ' | cut -c1-330)"; rm -rf $W/o; }
J batch $W/dense200.txt -o $W/o --quiet --strategy visibility > /dev/null 2>&1; rm -rf $W/o
for r in 1 2; do
  run "s1 visibility r$r" "" --samples 1 --strategy visibility
  run "s1 visibility tunables r$r" "$T" --samples 1 --strategy visibility
done
run "s4 visibility" "" --samples 4 --strategy visibility
run "s4 visibility tunables" "$T" --samples 4 --strategy visibility
run "s4 default" "" --samples 4
run "s4 default tunables" "$T" --samples 4
