#!/usr/bin/env bash
# Issue 28, stop 47: the build of this stop ("C": tiles binned in one dispatch, one thread per
# triangle up to 6 pixels, frames composed in compute at one sample shaded into place) against
# the kept build of the last stop ("K", 58dd5b6).
# 1. GPU frames, 1280x720, 100,000 and 1,000,000 objects, two rounds alternating, and
#    gpu-culling-bundles.
# 2. CPU frame without the GPU timer: gpu-culling-bundles, K, C, five rounds alternating,
#    fly-through and city at 100,000 objects, 300 frames.
# 3. encore batch: 200 dense files at four samples and at one; seven light models x 100.
set -uo pipefail
carry=$(cd "$(dirname "$0")" && pwd)
W=/tmp/job59; rm -rf $W; mkdir -p $W/k $W/c
tar -C $W/k -xJf "$carry/encore.tar.xz"
tar -C $W/c -xJf "$carry/encore-c.tar.xz"
R=$OUT/j59; mkdir -p $R
K() { bash $W/k/pack/run.sh encore "$@"; }
C() { bash $W/c/pack/run.sh encore "$@"; }
C info 2>&1 | head -1 > $R/info.txt
C bench --scene flythrough --objects 100000 -s visibility --width 1280 --height 720 --frames 200 --warmup 5 > /dev/null 2>&1
for n in 100000 1000000; do
  args="--scene flythrough --scene city --objects $n --width 1280 --height 720 --frames 40 --warmup 5 --warmup-time 2"
  for r in 1 2; do
    K bench $args -s visibility --json $R/K-$n-r$r.json > /dev/null 2>&1
    C bench $args -s visibility --json $R/C-$n-r$r.json > /dev/null 2>&1
  done
  C bench $args -s gpu-culling-bundles --json $R/gcb-$n.json > /dev/null 2>&1
done
python3 - "$R" <<'PY' > $R/passes.txt
import json,sys,glob,os
for f in sorted(glob.glob(sys.argv[1]+'/*.json')):
    d=json.load(open(f))
    for r in d['results']:
        p=r['gpuPassesMs']
        short={k.replace('visibility ','').replace(' (second phase)','2'):v['median'] for k,v in p.items()}
        print('%-12s %-4s frame %.3f '%(os.path.basename(f)[:-5], r['scene'][:4], r['gpuMs']['median'])+' '.join('%s=%.3f'%(k,v) for k,v in sorted(short.items())))
PY
cat $R/passes.txt
for r in 1 2 3 4 5; do
  for who in gcb K C; do
    case $who in gcb) X=C; s=gpu-culling-bundles;; K) X=K; s=visibility;; C) X=C; s=visibility;; esac
    echo "== cpu $who r$r" >> $R/cpu.txt
    $X bench --scene flythrough --scene city --objects 100000 -s $s --width 1280 --height 720 --frames 300 --warmup 5 --no-gpu-timer 2>&1 | grep -E "^\| (visibility|gpu-culling)|^### " >> $R/cpu.txt
  done
done
mkdir -p $W/dense
for i in $(seq 1 40); do C gen --objects 24 --meshes 4 --tessellation 256 --seed $i -o $W/dense/m$i.glb > /dev/null 2>&1 & if (( i % 8 == 0 )); then wait; fi; done; wait
for k in 1 2 3 4 5; do mkdir -p $W/dense$k; for i in $(seq 1 40); do ln -s $W/dense/m$i.glb $W/dense$k/m$i.glb; done; done
ls $W/dense[1-5]/*.glb > $W/dense200.txt
for i in $(seq -w 0 99); do mkdir -p $W/in/$i; for m in "$carry"/models/*.glb; do ln -s "$m" $W/in/$i/; done; done
ls $W/in/*/*.glb > $W/light.txt
run() { local name=$1 X=$2 input=$3; shift 3; rm -rf $W/o; echo "== $name: $*" >> $R/batch.txt
  $X -v batch $input -o $W/o --quiet "$@" 2>&1 | grep -E "views in" | sed 's/(load and encode summed.*//' >> $R/batch.txt; rm -rf $W/o; }
C batch $W/dense200.txt -o $W/o --quiet --strategy visibility > /dev/null 2>&1; rm -rf $W/o
for r in 1 2; do
  run "dense s4 K r$r" K $W/dense200.txt --samples 4 --strategy visibility
  run "dense s4 C r$r" C $W/dense200.txt --samples 4 --strategy visibility
  run "dense s1 K r$r" K $W/dense200.txt --samples 1 --strategy visibility
  run "dense s1 C r$r" C $W/dense200.txt --samples 1 --strategy visibility
  run "light K r$r" K $W/light.txt --strategy visibility
  run "light C r$r" C $W/light.txt --strategy visibility
  run "light default r$r" C $W/light.txt
done
run "dense s4 default" C $W/dense200.txt --samples 4
cat $R/batch.txt
cat $R/cpu.txt | grep -E "^==|^\|" | head -80
