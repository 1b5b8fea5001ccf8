#!/usr/bin/env bash
# Issue 48: auto's line (--visibility-from-triangles) at one sample. The light job (the ten shared
# models, 1,000 files, 12 views at 512x512) at one sample with bundles and with auto at several
# lines, rounds alternating; then generated models of 104,000 to 1.59 M triangles (200 files
# each) at one sample and at four with bundles and visibility. Run on the device machine as
#   bash bench/probes/line-by-samples.sh CARRY
# CARRY as for pools.sh (pack.tar.xz, models/, encore-next.xz: the build under test). LINES
# (default "100000 400000 1100000"), ROUNDS (default 2), SWEEP=0 leaves the generated models out.
set -uo pipefail
P=$(cd "$(dirname "$0")" && pwd)
C=$(cd "${1:?carry folder}" && pwd)
W=/tmp/line; rm -rf $W; mkdir -p $W
. "$P/probe-setup.sh"
probe_unpack $W "$C"
E() { bash $W/pack/run.sh encore-new "$@"; }
echo "== machine: $(nproc) cores"; nvidia-smi -L | head -1; E info 2>&1 | head -1
probe_inputs $W "$C" 1
run() {  # label, list, options...
  local label=$1 list=$2; shift 2; rm -rf $W/o
  E -v batch $list -o $W/o --quiet "$@" > $W/log.txt 2>&1
  echo "== $label: $(grep -E 'views in' $W/log.txt | sed 's/.*views in/views in/')"
  grep -E "^stages|^gpu|^error" $W/log.txt | sed "s/ (load and encode summed.*//" | head -3
}
head -300 $W/all.txt > $W/w.txt
E batch $W/w.txt -o $W/o --quiet --samples 1 > /dev/null 2>&1
E batch $W/w.txt -o $W/o --quiet --samples 1 --strategy visibility > /dev/null 2>&1
for r in $(seq 1 ${ROUNDS:-2}); do
  run "light s1 bundles r$r" $W/all.txt --samples 1 --strategy bundles
  for t in ${LINES:-100000 400000 1100000}; do
    run "light s1 auto from $t r$r" $W/all.txt --samples 1 --strategy auto --visibility-from-triangles $t
  done
done
[ "${SWEEP:-1}" = 1 ] || exit 0
for t in 64 128 181 256; do
  probe_generated $W sweep$t $t 5
  for s in 1 4; do
    for st in bundles visibility; do
      run "tessellation $t s$s $st" $W/sweep$t.txt --strategy $st --samples $s
      [ $st = visibility ] && grep -ho '"triangles": *[0-9]*' $W/o/sweep$t-1/m1/metadata.json | head -1
    done
  done
done
