#!/usr/bin/env bash
# Issue 28, stop 49: encore batch again on a fresh lease, J (139c989) against the default,
# alternating, three rounds at four samples; one at one sample; the light models twice.
set -uo pipefail
carry=$(cd "$(dirname "$0")" && pwd)
W=/tmp/job71; rm -rf $W; mkdir -p $W/j
tar -C $W/j -xJf "$carry/encore-j.tar.xz"
J() { bash $W/j/pack/run.sh encore "$@"; }
nproc; uptime
mkdir -p $W/dense
for i in $(seq 1 40); do J gen --objects 24 --meshes 4 --tessellation 256 --seed $i -o $W/dense/m$i.glb > /dev/null 2>&1 & if (( i % 8 == 0 )); then wait; fi; done; wait
for k in 1 2 3 4 5; do mkdir -p $W/dense$k; for i in $(seq 1 40); do ln -sf $W/dense/m$i.glb $W/dense$k/m$i.glb; done; done
ls $W/dense[1-5]/*.glb > $W/dense200.txt
for i in $(seq -w 0 99); do mkdir -p $W/in/$i; for m in "$carry"/models/*.glb; do ln -sf "$m" $W/in/$i/; done; done
ls $W/in/*/*.glb > $W/light.txt
run() { local name=$1 input=$2; shift 2; rm -rf $W/o
  echo "== $name: $( J -v batch $input -o $W/o --quiet "$@" 2>&1 | grep -E "views in|stages" | sed 's/(load and encode summed.*//;s/adapter:.*HBM3, Vulkan, discrete GPU, driver NVIDIA: 580.159.04 580.159.4.0//' | tr '\n' ' ' )"; rm -rf $W/o; }
J batch $W/dense200.txt -o $W/o --quiet --strategy visibility > /dev/null 2>&1; rm -rf $W/o
for r in 1 2 3; do
  run "dense s4 visibility r$r" $W/dense200.txt --samples 4 --strategy visibility
  run "dense s4 default r$r" $W/dense200.txt --samples 4
done
run "dense s1 visibility" $W/dense200.txt --samples 1 --strategy visibility
run "dense s1 default" $W/dense200.txt --samples 1
for r in 1 2; do
  run "light visibility r$r" $W/light.txt --strategy visibility
  run "light default r$r" $W/light.txt
done
uptime
