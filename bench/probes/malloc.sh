#!/usr/bin/env bash
# Issue 48: does the loaders' CPU fall when freed memory stays in malloc's arenas? The 1,000-file
# job of the ten shared models (12 views at 512x512) at one sample and at four, default options,
# with glibc's default malloc (mmap for blocks over 128 KiB, adapting; the heap's top trimmed
# back to the kernel) and with GLIBC_TUNABLES keeping blocks up to 32 MiB in the arenas and never
# trimming, rounds alternating. Run on the device machine as
#   bash bench/probes/malloc.sh CARRY
# CARRY as for pools.sh. ROUNDS (default 3).
set -uo pipefail
P=$(cd "$(dirname "$0")" && pwd)
C=$(cd "${1:?carry folder}" && pwd)
W=/tmp/malloc; rm -rf $W; mkdir -p $W
. "$P/probe-setup.sh"
probe_unpack $W "$C"
E() { bash $W/pack/run.sh encore-new "$@"; }
echo "== machine: $(nproc) cores"; nvidia-smi -L | head -1; E info 2>&1 | head -1
probe_inputs $W "$C" 1
KEEP="glibc.malloc.mmap_threshold=33554432:glibc.malloc.trim_threshold=4294967295"
run() {  # label, tunables, options...
  local label=$1 tunables=$2; shift 2; rm -rf $W/o
  local TIMEFORMAT="process: %R s, %U s user, %S s system"
  { time GLIBC_TUNABLES=$tunables bash $W/pack/run.sh encore-new -v batch $W/all.txt -o $W/o \
      --quiet "$@" > $W/log.txt 2>&1; } 2>> $W/log.txt
  echo "== $label: $(grep -E 'views in' $W/log.txt | sed 's/.*views in/views in/')"
  grep -E "^stages" $W/log.txt | sed "s/ (load and encode summed.*//"
  tail -1 $W/log.txt
}
head -300 $W/all.txt > $W/w.txt
E batch $W/w.txt -o $W/o --quiet > /dev/null 2>&1
for s in 1 4; do
  for r in $(seq 1 ${ROUNDS:-3}); do
    run "s$s default malloc r$r" "" --samples $s
    run "s$s kept arenas r$r" "$KEEP" --samples $s
  done
done
