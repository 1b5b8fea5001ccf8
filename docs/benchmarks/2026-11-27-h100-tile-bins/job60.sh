#!/usr/bin/env bash
# Issue 28, stop 47: job59's gpu-culling-bundles runs and batch again (its summary files did not
# come back), on the same warm machine with job59's unpacked builds and dense files.
set -uo pipefail
W=/tmp/job59; R=$OUT/j60; mkdir -p $R
K() { bash $W/k/pack/run.sh encore "$@"; }
C() { bash $W/c/pack/run.sh encore "$@"; }
for n in 100000 1000000; do
  C bench --scene flythrough --scene city --objects $n --width 1280 --height 720 --frames 40 --warmup 5 --warmup-time 2 -s gpu-culling-bundles --json $R/gcb-$n.json 2>&1 | grep -E "^\| gpu-culling"
done
run() { local name=$1 X=$2 input=$3; shift 3; rm -rf $W/o; echo "== $name: $(  $X -v batch $input -o $W/o --quiet "$@" 2>&1 | grep -E "views in" | sed 's/.*views in/views in/;s/(load and encode summed.*//' )"; rm -rf $W/o; }
for r in 1 2 3; do
  run "dense s4 K r$r" K $W/dense200.txt --samples 4 --strategy visibility
  run "dense s4 C r$r" C $W/dense200.txt --samples 4 --strategy visibility
  run "dense s1 K r$r" K $W/dense200.txt --samples 1 --strategy visibility
  run "dense s1 C r$r" C $W/dense200.txt --samples 1 --strategy visibility
done
run "light K" K $W/light.txt --strategy visibility
run "light C" C $W/light.txt --strategy visibility
