#!/usr/bin/env bash
# One build on the gobjaverse preset, a run each: the preset, then with EXR depth as PNG, the nerf
# layout and one sample (which parts cost), on 100 of the 1,000 files. Run on the device machine
# from the repository root with .gpu-carry as for ab.sh:  bash bench/probes/gobjaverse-parts.sh
set -uo pipefail
P=bench/probes; C=$(cd .gpu-carry && pwd); W=/tmp/gp; rm -rf $W; mkdir -p $W
. $P/probe-setup.sh; probe_unpack $W "$C"
B() { bash $W/pack/run.sh encore-new "$@"; }
probe_inputs $W "$C" 1; head -100 $W/all.txt > $W/job.txt
one() { local label=$1; shift; rm -rf $W/o
  B -v batch $W/job.txt -o $W/o --quiet --preset gobjaverse "$@" > $W/$label.log 2>&1
  echo "== $label: $(grep -E 'views in' $W/$label.log | sed 's/.*views in/views in/')"
  grep -vE "^\s*$" $W/$label.log | grep -E "^(stages|gpu|image|device|read|ring|pool|encode|render)" | cut -c1-400 | head -8; }
one preset
one depth-png --depth-format png
one layout-nerf --layout nerf
one samples1 --samples 1
cp $W/*.log $OUT/ 2>/dev/null
