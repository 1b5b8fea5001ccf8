#!/usr/bin/env bash
# Issue 28, stop 49: the CPU frame again (no GPU timer), J (139c989) against
# gpu-culling-bundles, five rounds alternating, fly-through and city at 100,000 objects.
set -uo pipefail
carry=$(cd "$(dirname "$0")" && pwd)
W=/tmp/job74; rm -rf $W; mkdir -p $W/j
tar -C $W/j -xJf "$carry/encore-j.tar.xz"
J() { bash $W/j/pack/run.sh encore "$@"; }
J bench --scene flythrough --objects 100000 -s visibility --width 1280 --height 720 --frames 100 --warmup 5 --no-gpu-timer > /dev/null 2>&1
for r in 1 2 3 4 5; do
  for s in gpu-culling-bundles visibility; do
    echo "== cpu $s r$r"
    J bench --scene flythrough --scene city --objects 100000 -s $s --width 1280 --height 720 --frames 300 --warmup 5 --no-gpu-timer 2>&1 | grep -E "^\| (visibility|gpu-culling)" | cut -d'|' -f2-4
  done
done
