#!/usr/bin/env bash
# Issue 48: a model's staging started while the previous one uploads (DeviceLane::stageAhead)
# against the build before it (staging threads alone), alternating in one lease. Run on the
# device machine as
#   bash bench/probes/stage-ahead.sh CARRY
# CARRY as pools.sh takes it, with encore-next.xz (stage ahead) and encore-prev.xz (before).
set -uo pipefail
P=$(cd "$(dirname "$0")" && pwd)
C=$(cd "${1:?carry folder}" && pwd)
W=/tmp/ahead; rm -rf $W; mkdir -p $W
. "$P/probe-setup.sh"
probe_unpack $W "$C"
xz -dc "$C/encore-prev.xz" > $W/pack/bin/encore-prev; chmod +x $W/pack/bin/encore-prev
GPUS=$(nvidia-smi -L | wc -l)
probe_inputs $W "$C" $GPUS
head -1000 $W/all.txt > $W/one.txt; head -300 $W/all.txt > $W/warm.txt
run() {  # label, binary, list, options...
  local label=$1 bin=$2 list=$3; shift 3; rm -rf $W/o
  bash $W/pack/run.sh $bin -v batch $list -o $W/o --quiet "$@" > $W/log.txt 2>&1
  echo "== $label: $(grep -E 'views in' $W/log.txt | sed 's/.*views in/views in/')"
  grep -E "^stages|^upload|^materials" $W/log.txt | sed "s/ (load and encode summed.*//"
  rm -rf $W/o
}
for bin in encore-prev encore-new; do
  bash $W/pack/run.sh $bin batch $W/warm.txt -o $W/o --quiet --devices all > /dev/null 2>&1; rm -rf $W/o
done
for r in 1 2; do
  run "before, $GPUS GPUs, r$r" encore-prev $W/all.txt --devices all
  run "stage ahead, $GPUS GPUs, r$r" encore-new $W/all.txt --devices all
done
run "before, one GPU" encore-prev $W/one.txt --device 0
run "stage ahead, one GPU" encore-new $W/one.txt --device 0
