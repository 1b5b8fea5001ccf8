#!/usr/bin/env bash
# Issue 48's multi-GPU rows: the 1,000-file job of the ten shared models per GPU (12 views at
# 512x512, `encore -v batch`, default options) on one GPU, on every GPU of the machine
# (`--devices all`) and as one process per GPU, rounds alternating; then whether the files of the
# first 1,000 are the same from one GPU and from all. Run on the device machine as
#   bash bench/probes/multi-gpu.sh CARRY [batch options...]
# CARRY as for ab.sh (pack.tar.xz, models/, encore-next.xz: the build under test).
set -uo pipefail
P=$(cd "$(dirname "$0")" && pwd)
C=$(cd "${1:?carry folder}" && pwd); shift
W=/tmp/multi; rm -rf $W; mkdir -p $W
. "$P/probe-setup.sh"
probe_unpack $W "$C"
E() { bash $W/pack/run.sh encore-new "$@"; }
GPUS=$(nvidia-smi -L | wc -l)
ROUNDS=${ROUNDS:-3}
echo "== machine: $(nproc) cores, $GPUS GPUs"; nvidia-smi -L; E info 2>&1 | head -$((GPUS + 1))
probe_inputs $W "$C" $GPUS
head -1000 $W/all.txt > $W/one.txt
for g in $(seq 0 $((GPUS - 1))); do sed -n "$((g * 1000 + 1)),$((g * 1000 + 1000))p" $W/all.txt > $W/part$g.txt; done
head -300 $W/all.txt > $W/w.txt; E batch $W/w.txt -o $W/o --quiet "$@" > /dev/null 2>&1; rm -rf $W/o

run() {  # label, list, options...
  local label=$1 list=$2; shift 2; rm -rf $W/o
  local TIMEFORMAT="process: %R s, %U s user, %S s system"
  { time E -v batch $list -o $W/o --quiet "$@" > $W/log.txt 2>&1; } 2>> $W/log.txt
  echo "== $label: $(grep -E 'views in' $W/log.txt | sed 's/.*views in/views in/')"
  grep -E "^device [0-9]+ \(|^stages" $W/log.txt | sed "s/ (load and encode summed.*//; s/(NVIDIA.*)://" | head -$((GPUS + 1))
  tail -1 $W/log.txt
}
processes() {  # label, options...
  local label=$1; shift; rm -rf $W/proc-*; local start=$(date +%s%N)
  for g in $(seq 0 $((GPUS - 1))); do
    E batch $W/part$g.txt -o $W/proc-out$g --quiet --device $g --jobs $(( $(nproc) / GPUS )) "$@" > $W/proc-log$g.txt 2>&1 &
  done; wait
  local ms=$(( ($(date +%s%N) - start) / 1000000 ))
  echo "== $label: $((GPUS * 12000)) views in $ms ms: $(( GPUS * 12000 * 1000 / ms )) views/s (start to end)"
  grep -h "views in" $W/proc-log*.txt
}
for r in $(seq 1 $ROUNDS); do
  run "one GPU r$r" $W/one.txt --device 0 "$@"; [ $r = 1 ] && mv $W/o $W/keep-one
  run "$GPUS GPUs (--devices all) r$r" $W/all.txt --devices all "$@"; [ $r = 1 ] && mv $W/o $W/keep-all
  processes "$GPUS processes r$r" "$@"
done
echo "== md5 lists of the first 1,000 files' outputs, one GPU and all (metadata.json left out)"
(cd $W/keep-one && find . -type f ! -name metadata.json | sort | xargs md5sum) > $W/one.md5
(cd $W/keep-all && find . -type f ! -name metadata.json | sort | xargs md5sum) > $W/all-every.md5
# The files of the first 1,000 models: the lines of the all-GPU list whose paths one GPU wrote.
awk 'NR == FNR { want[$2] = 1; next } ($2 in want)' $W/one.md5 $W/all-every.md5 > $W/all.md5
wc -l < $W/one.md5; wc -l < $W/all.md5
cmp -s $W/one.md5 $W/all.md5 && echo "identical" || { echo "DIFFERENT"; diff $W/one.md5 $W/all.md5 | head -5; }
