#!/usr/bin/env bash
# Issue 28, stop 46: why the material table (c3adf78, reverted) slowed the shading. "K" is the
# kept build (fb429e9); "X" an experiment build of c3adf78 whose ENCORE_EXP_* variables pick a
# variant: none (the table, materials sharing textures grouped, untextured ones joining them, one
# bin shaded without binning), BINNED (the same, binned), NO_JOIN (untextured materials in a
# group of their own: two bins, binned), PER_MATERIAL (a bin per material as K, materials still
# read from the table: the copy alone). GPU passes at 1280x720, 100,000 objects.
set -uo pipefail
carry=$(cd "$(dirname "$0")" && pwd)
W=/tmp/job55; rm -rf $W; mkdir -p $W/k $W/x
tar -C $W/k -xJf "$carry/encore.tar.xz"
tar -C $W/x -xJf "$carry/encore-exp.tar.xz"
R=$OUT/j55; mkdir -p $R
K() { bash $W/k/pack/run.sh encore "$@"; }
X() { bash $W/x/pack/run.sh encore "$@"; }
K info 2>&1 | head -1 > $R/info.txt
args="--scene flythrough --scene city --objects 100000 -s visibility --width 1280 --height 720 --frames 40 --warmup 5 --warmup-time 2"
K bench --scene flythrough --objects 100000 -s visibility --width 1280 --height 720 --frames 100 --warmup 5 > /dev/null 2>&1
for round in 1 2; do
  echo "== K r$round" >> $R/gpu.txt; K bench $args --json $R/K-r$round.json 2>&1 | grep -E "^\| visibility|^### " >> $R/gpu.txt
  echo "== X r$round" >> $R/gpu.txt; X bench $args --json $R/X-r$round.json 2>&1 | grep -E "^\| visibility|^### " >> $R/gpu.txt
  for v in BINNED NO_JOIN PER_MATERIAL; do
    echo "== X-$v r$round" >> $R/gpu.txt
    env ENCORE_EXP_$v=1 bash $W/x/pack/run.sh encore bench $args --json $R/X-$v-r$round.json 2>&1 | grep -E "^\| visibility|^### " >> $R/gpu.txt
  done
done
python3 - "$R" <<'PY' > $R/passes.txt
import json,sys,glob,os
for f in sorted(glob.glob(sys.argv[1]+'/*.json')):
    d=json.load(open(f))
    for r in d['results']:
        p=r['gpuPassesMs']
        print(os.path.basename(f), r['scene'][:4], 'frame %.3f'%r['gpuMs']['median'], 'shading %.3f'%p.get('visibility shading',{}).get('median',0), 'binning %.3f'%p.get('visibility binning',{}).get('median',0))
PY
cat $R/passes.txt
