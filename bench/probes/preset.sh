#!/usr/bin/env bash
# One build (CARRY's encore-next.xz) on a preset's job: the first FILES of the ten shared models'
# 1,000 files (default 200), ROUNDS runs (default 3), `encore -v batch --preset PRESET`. Run on
# the device machine as
#   bash bench/probes/preset.sh CARRY PRESET [batch options...]
set -uo pipefail
P=$(cd "$(dirname "$0")" && pwd)
C=$(cd "${1:?carry folder}" && pwd); shift
PRESET=${1:?preset}; shift
W=/tmp/preset; rm -rf $W; mkdir -p $W
. "$P/probe-setup.sh"
probe_unpack $W "$C"
B() { bash $W/pack/run.sh encore-new "$@"; }
echo "== machine: $(nproc) cores"; nvidia-smi -L | head -1; B info 2>&1 | head -1
probe_inputs $W "$C" 1
head -"${FILES:-200}" $W/all.txt > $W/job.txt
for r in $(seq 1 "${ROUNDS:-3}"); do
  rm -rf $W/o
  B -v batch $W/job.txt -o $W/o --quiet --preset "$PRESET" "$@" > $W/log.txt 2>&1
  echo "== $PRESET r$r: $(grep -E 'views in' $W/log.txt | sed 's/.*views in/views in/')"
  grep -E "^stages|^error" $W/log.txt | sed "s/ (load and encode summed.*//" | head -3
done
echo "== files of one model:"; ls $W/o | head -1 | xargs -I{} sh -c "ls $W/o/{} | head -12; ls $W/o/{} | wc -l"
du -sh $W/o
