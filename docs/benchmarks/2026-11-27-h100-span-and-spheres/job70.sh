#!/usr/bin/env bash
# Issue 28, stop 49: job69's batch runs again on the same warm machine (its files), one sample
# first: J against H and the default, alternating.
set -uo pipefail
W=/tmp/job68
J() { bash $W/j/pack/run.sh encore "$@"; }
H() { bash $W/h/pack/run.sh encore "$@"; }
run() { local name=$1 X=$2 input=$3; shift 3; rm -rf $W/o
  echo "== $name: $(  $X -v batch $input -o $W/o --quiet "$@" 2>&1 | grep -E "views in|GPU" | sed 's/(load and encode summed.*//' | tr '\n' ' ' )"; rm -rf $W/o; }
for r in 1 2; do
  run "dense s1 J r$r" J $W/dense200.txt --samples 1 --strategy visibility
  run "dense s1 H r$r" H $W/dense200.txt --samples 1 --strategy visibility
done
run "dense s1 default" J $W/dense200.txt --samples 1
run "dense s4 H" H $W/dense200.txt --samples 4 --strategy visibility
run "dense s4 J" J $W/dense200.txt --samples 4 --strategy visibility
