#!/usr/bin/env bash
# Issue 48's Dask row: the 1,000-file job of the ten shared models per GPU (12 views at 512x512,
# default options) on one GPU, on every GPU (`encore batch --devices all`) and through
# encore.dask.render_collection on encore.dask.gpu_cluster() (DASK_RUNS: chunk size:tasks per
# GPU pairs, by default "8:2 32:2"), rounds alternating; then whether the first Dask run's files
# are those of `--devices all`.
# Run on the device machine from the repository root:  bash bench/probes/dask-gpus.sh CARRY
# CARRY: pack.tar.xz (its bin/encore-new the build under test), python.tar.xz (pack-python.sh
# from the same build) and models/.
set -uo pipefail
P=$(cd "$(dirname "$0")" && pwd)
C=$(cd "${1:?carry folder}" && pwd); shift
W=/tmp/dask; rm -rf $W; mkdir -p $W
. "$P/probe-setup.sh"
probe_unpack $W "$C"; probe_python $W "$C"
E() { bash $W/pack/run.sh encore-new "$@"; }
GPUS=$(nvidia-smi -L | wc -l); ROUNDS=${ROUNDS:-3}
echo "== machine: $(nproc) cores, $GPUS GPUs"; nvidia-smi -L; E info 2>&1 | head -$((GPUS + 1))
probe_inputs $W "$C" $GPUS
head -1000 $W/all.txt > $W/one.txt
head -300 $W/all.txt > $W/w.txt; E batch $W/w.txt -o $W/o --quiet > /dev/null 2>&1; rm -rf $W/o

batch() {  # label, list, options...
  local label=$1 list=$2; shift 2; rm -rf $W/o
  E -v batch $list -o $W/o --quiet "$@" > $W/log.txt 2>&1
  echo "== $label: $(grep -E 'views in' $W/log.txt | sed 's/.*views in/views in/')"
}
dask() {  # label, chunk size, tasks per GPU
  rm -rf $W/o
  (cd $W && PY "$P/dask_gpus.py" $W/all.txt $W/o "$2" "$3" > $W/dask.log 2> $W/dask-err.log)
  echo "== $1: $(grep -E '^dask:' $W/dask.log)"; grep -E '^(stages|adapters)' $W/dask.log
  grep -iE "error|traceback" $W/dask-err.log | head -5
}
for r in $(seq 1 $ROUNDS); do
  batch "one GPU r$r" $W/one.txt --device 0
  batch "$GPUS GPUs (--devices all) r$r" $W/all.txt --devices all; [ $r = 1 ] && mv $W/o $W/keep-all
  for run in ${DASK_RUNS:-8:2 32:2}; do  # chunk size:tasks per GPU
    dask "dask, chunks of ${run%:*}, ${run#*:} tasks per GPU r$r" ${run%:*} ${run#*:}
    [ $r = 1 ] && [ ! -d $W/keep-dask ] && mv $W/o $W/keep-dask
  done
done
echo "== md5 lists: --devices all and Dask (metadata.json and failures.jsonl left out)"
for d in all dask; do
  (cd $W/keep-$d && find . -type f ! -name metadata.json ! -name failures.jsonl | sort | xargs md5sum) > $W/$d.md5
done
wc -l < $W/all.md5; wc -l < $W/dask.md5
cmp -s $W/all.md5 $W/dask.md5 && echo "identical" || { echo "DIFFERENT"; diff $W/all.md5 $W/dask.md5 | head -5; }
cp $W/dask-err.log $OUT/ 2>/dev/null || true
