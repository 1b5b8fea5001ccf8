#!/usr/bin/env bash
# Issue 28, stop 47: where the city's fixed costs go. "K" is the kept build (58dd5b6); "X" an
# experiment build of it whose ENCORE_EXP_*_GROUPS variables set the striding grids of the raster
# passes (RASTER: thread raster, WG: workgroup raster) and of each shading bin's dispatch (SHADE),
# 4096 64-thread workgroups each by default; X also adds a workgroup's culled triangles up once
# (K: each thread with culled clusters adds to one global counter). Plus K with flags.
set -uo pipefail
carry=$(cd "$(dirname "$0")" && pwd)
W=/tmp/job56; rm -rf $W; mkdir -p $W/k $W/x
tar -C $W/k -xJf "$carry/encore.tar.xz"
tar -C $W/x -xJf "$carry/encore-exp.tar.xz"
R=$OUT/j56; mkdir -p $R
K() { bash $W/k/pack/run.sh encore "$@"; }
X() { bash $W/x/pack/run.sh encore "$@"; }
K info 2>&1 | head -1 > $R/info.txt
nvidia-smi --query-gpu=name,driver_version,clocks.sm --format=csv >> $R/info.txt 2>&1
args="--scene flythrough --scene city --objects ${OBJ:-100000} -s visibility --width 1280 --height 720 --frames 40 --warmup 5 --warmup-time 2"
ENCORE_EXP_PRINT=1 X bench $args --frames 100 > /dev/null 2> $R/exp-print.txt
run() {  # name, then env assignments / flags
  local name=$1; shift
  local t0=$(date +%s)
  echo "== $name" >> $R/gpu.txt
  "$@" --json $R/$name.json 2>&1 | grep -E "^\| visibility|^### " >> $R/gpu.txt
  echo "$name $(( $(date +%s) - t0 )) s" >> $R/times.txt
}
for round in 1 2; do
  run K-r$round K bench $args
  run X-r$round X bench $args
  run X-g1056-r$round env ENCORE_EXP_RASTER_GROUPS=1056 ENCORE_EXP_WG_GROUPS=1056 ENCORE_EXP_SHADE_GROUPS=1056 bash $W/x/pack/run.sh encore bench $args
  [ $round = 2 ] && break
  run X-g528 env ENCORE_EXP_RASTER_GROUPS=528 ENCORE_EXP_WG_GROUPS=528 ENCORE_EXP_SHADE_GROUPS=528 bash $W/x/pack/run.sh encore bench $args
  run X-g2112 env ENCORE_EXP_RASTER_GROUPS=2112 ENCORE_EXP_WG_GROUPS=2112 ENCORE_EXP_SHADE_GROUPS=2112 bash $W/x/pack/run.sh encore bench $args
  run X-shade1056 env ENCORE_EXP_SHADE_GROUPS=1056 bash $W/x/pack/run.sh encore bench $args
  run X-raster1056 env ENCORE_EXP_RASTER_GROUPS=1056 ENCORE_EXP_WG_GROUPS=1056 bash $W/x/pack/run.sh encore bench $args
  run K-nocc K bench $args --no-cluster-culling
  run K-crp4 K bench $args --compute-raster-pixels 4
  run K-crp16 K bench $args --compute-raster-pixels 16
done
python3 - "$R" <<'PY' > $R/passes.txt
import json,sys,glob,os
for f in sorted(glob.glob(sys.argv[1]+'/*.json')):
    d=json.load(open(f))
    for r in d['results']:
        p=r['gpuPassesMs']
        short={k.replace('visibility ','').replace(' (second phase)','2'):v['median'] for k,v in p.items()}
        print('%-14s %-4s frame %.3f  '%(os.path.basename(f)[:-5], r['scene'][:4], r['gpuMs']['median'])+' '.join('%s=%.3f'%(k,v) for k,v in sorted(short.items())))
PY
cat $R/passes.txt $R/times.txt
