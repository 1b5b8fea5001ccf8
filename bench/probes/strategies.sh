#!/usr/bin/env bash
# Issue 48 step 4: the default strategy (bundles) against visibility per model on one GPU, GPU
# time per model from the batch's stage timestamps; light models (the ten shared models, 1,000
# files) at four samples and one, dense models (encore gen, 1.59 M triangles per view, 1,000
# files) at four samples; rounds alternate. STRATEGIES names those compared (default: bundles
# visibility; auto for the batch's per-model choice), SWEEP=1 adds generated models of 100,000 to
# 800,000 triangles (200 files each, one round), LIGHT_S1=0 and BENCH=0 leave out the light
# models at one sample and the single-model GPU times, DENSE=0 the dense models; THRESHOLDS="N .."
# adds auto with --visibility-from-triangles N on the light models; SAMPLES=1 draws the light
# rounds at one sample. Run on the device machine as
#   bash bench/probes/strategies.sh CARRY
# CARRY as for pools.sh (pack.tar.xz, models/, encore-next.xz: the build under test).
set -uo pipefail
P=$(cd "$(dirname "$0")" && pwd)
C=$(cd "${1:?carry folder}" && pwd)
W=/tmp/strategies; rm -rf $W; mkdir -p $W
. "$P/probe-setup.sh"
probe_unpack $W "$C"
E() { bash $W/pack/run.sh encore-new "$@"; }
ROUNDS=${ROUNDS:-3}
echo "== machine: $(nproc) cores"; nvidia-smi -L | head -1; E info 2>&1 | head -2
probe_inputs $W "$C" 1
probe_generated $W dense 256 25  # 1,000 dense files.

run() {  # label, list, options...
  local label=$1 list=$2; shift 2; rm -rf $W/o
  E -v batch $list -o $W/o --quiet "$@" > $W/log.txt 2>&1
  echo "== $label: $(grep -E 'views in' $W/log.txt | sed 's/.*views in/views in/')"
  grep -E "^stages|^gpu|^error" $W/log.txt | sed "s/ (load and encode summed.*//" | head -4
}
head -300 $W/all.txt > $W/w.txt
E batch $W/w.txt -o $W/o --quiet > /dev/null 2>&1
E batch $W/w.txt -o $W/o2 --quiet --strategy visibility > /dev/null 2>&1; rm -rf $W/o $W/o2
strategies=${STRATEGIES:-bundles visibility}
for r in $(seq 1 $ROUNDS); do
  for s in $strategies; do
    run "light s${SAMPLES:-4} $s r$r" $W/all.txt --strategy $s --samples ${SAMPLES:-4}
    [ $r = 1 ] && { rm -rf $W/keep-$s; mv $W/o $W/keep-$s; }
  done
done
if [ -d $W/keep-auto ] && [ -d $W/keep-bundles ]; then
  echo "== md5 lists of the light models' files, bundles against auto (metadata.json left out)"
  for s in bundles auto; do
    (cd $W/keep-$s && find . -type f ! -name metadata.json | sort | xargs md5sum) > $W/$s.md5
  done
  wc -l < $W/bundles.md5; cmp -s $W/bundles.md5 $W/auto.md5 && echo "identical"
  grep -ho '"strategy": *"[a-z+-]*"' -r $W/keep-auto --include=metadata.json | sort | uniq -c
  # The models auto drew with bundles: the same files as the bundles run's.
  grep -l '"strategy": *"bundles"' -r $W/keep-auto --include=metadata.json | xargs -n1 dirname |
    sed "s|$W/keep-auto/|./|" | sort > $W/auto-bundles.txt
  for s in bundles auto; do grep -F -f <(sed 's|$|/|' $W/auto-bundles.txt) $W/$s.md5 > $W/$s-b.md5; done
  echo "models auto drew with bundles: $(wc -l < $W/auto-bundles.txt), files $(wc -l < $W/auto-b.md5);" \
    "$(cmp -s $W/bundles-b.md5 $W/auto-b.md5 && echo identical || echo DIFFERENT) to the bundles run's" 
fi
for r in $(seq 1 $ROUNDS); do  # Auto's threshold on the light models (THRESHOLDS="N ...").
  for t in ${THRESHOLDS:-}; do
    run "light s4 auto from $t triangles r$r" $W/all.txt --visibility-from-triangles $t
  done
done
if [ "${LIGHT_S1:-1}" = 1 ]; then
  for s in $strategies; do run "light s1 $s" $W/all.txt --strategy $s --samples 1; done
fi
for r in $(seq 1 $ROUNDS); do
  [ "${DENSE:-1}" = 1 ] || break
  for s in $strategies; do run "dense s4 $s r$r" $W/dense.txt --strategy $s; done
done
if [ "${SWEEP:-0}" = 1 ]; then
  for t in 64 96 128 181; do
    probe_generated $W sweep$t $t 5
    for s in bundles visibility; do
      run "tessellation $t s4 $s" $W/sweep$t.txt --strategy $s
      [ $s = visibility ] && grep -ho '"triangles": *[0-9]*' $W/o/sweep$t-1/m1/metadata.json
    done
  done
fi
[ "${BENCH:-1}" = 1 ] || exit 0
echo "== bench, one light model at a time, 512x512, four samples (GPU ms per frame)"
for m in 2CylinderEngine Duck BrainStem; do
  E bench --model "$C/models/$m.glb" -s bundles -s visibility --samples 4 --frames 30 --warmup 5 \
    2>&1 | grep -E "^\| (bundles|visibility)" | sed "s/^/$m /"
done
