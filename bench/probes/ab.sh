#!/usr/bin/env bash
# Two builds side by side on the 1,000-file job of the ten shared models per GPU (12 views at
# 512x512, 4x, `encore -v batch`), rounds alternating, then the md5 lists of their first round's
# files (metadata.json left out: it records times). Run on the device machine as
#   bash bench/probes/ab.sh CARRY [batch options...]
# CARRY as for pools.sh, with encore-prev.xz (A, the build before) and encore-next.xz (B).
set -uo pipefail
P=$(cd "$(dirname "$0")" && pwd)
C=$(cd "${1:?carry folder}" && pwd); shift
W=/tmp/ab; rm -rf $W; mkdir -p $W
. "$P/probe-setup.sh"
probe_unpack $W "$C"
xz -dc "$C/encore-prev.xz" > $W/pack/bin/encore-prev
A() { bash $W/pack/run.sh encore-prev "$@"; }
B() { bash $W/pack/run.sh encore-new "$@"; }
ROUNDS=${ROUNDS:-3}
GPUS=$(nvidia-smi -L | wc -l)
echo "== machine: $(nproc) cores, $GPUS GPUs"; nvidia-smi -L | head -1; B info 2>&1 | head -1
probe_inputs $W "$C" 1
head -300 $W/all.txt > $W/w.txt
A batch $W/w.txt -o $W/o --quiet "$@" > /dev/null 2>&1
B batch $W/w.txt -o $W/o2 --quiet "$@" > /dev/null 2>&1; rm -rf $W/o $W/o2
run() {  # label, binary, options...
  local label=$1 bin=$2; shift 2; rm -rf $W/o
  local TIMEFORMAT="process: %R s, %U s user, %S s system"
  { time $bin -v batch $W/all.txt -o $W/o --quiet "$@" > $W/log.txt 2>&1; } 2>> $W/log.txt
  echo "== $label: $(grep -E 'views in' $W/log.txt | sed 's/.*views in/views in/')"
  grep -E "^stages|^gpu|^image blocks|^error|^warning" $W/log.txt |
    sed "s/ (load and encode summed.*//" | head -5
  tail -1 $W/log.txt
}
for r in $(seq 1 $ROUNDS); do
  run "A (before) r$r" A "$@"; [ $r = 1 ] && mv $W/o $W/keep-a
  run "B (after) r$r" B "$@"; [ $r = 1 ] && mv $W/o $W/keep-b
done
echo "== md5 lists of the first rounds (metadata.json left out)"
for s in a b; do (cd $W/keep-$s && find . -type f ! -name metadata.json | sort | xargs md5sum) > $W/$s.md5; done
wc -l < $W/a.md5; cmp -s $W/a.md5 $W/b.md5 && echo "identical" || echo "DIFFERENT"
