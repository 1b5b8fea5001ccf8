#!/usr/bin/env bash
# Issue 28, stop 49: G (4c0eca7: one-bin scenes unbinned, the visibility clear in the first
# pass, the frame's span) against F (7298c07, stop 48's measured build) and
# gpu-culling-bundles, one lease. gpuMs = sum of passes; span = first pass to the frame's end.
set -uo pipefail
carry=$(cd "$(dirname "$0")" && pwd)
W=/tmp/job65; rm -rf $W; mkdir -p $W/f $W/g
tar -C $W/f -xJf "$carry/encore-f.tar.xz"
tar -C $W/g -xJf "$carry/encore-g.tar.xz"
R=$OUT/j65; mkdir -p $R
F() { bash $W/f/pack/run.sh encore "$@"; }
G() { bash $W/g/pack/run.sh encore "$@"; }
G info 2>&1 | head -1
summary() {
python3 - "$R" "$1" <<'PY'
import json,sys,glob,os
for f in sorted(glob.glob(sys.argv[1]+'/*-%s*.json' % sys.argv[2])):
    d=json.load(open(f)); name=os.path.basename(f)[:-5]
    for r in d['results']:
        p=r['gpuPassesMs']
        short={k.replace('visibility','v').replace(': depth pyramid, second culling and raster','ph2').replace(': culling and compute raster','ph1').replace(': binning and shading','shade'):v['median'] for k,v in p.items()}
        span=r.get('gpuSpanMs')
        print('%-16s %-4s frame %.4f p95 %.3f span %s '%(name, r['scene'][:4], r['gpuMs']['median'], r['gpuMs']['p95'], '%.4f'%span['median'] if span else '-')+' '.join('%s=%.4f'%(k,v) for k,v in sorted(short.items())))
PY
}
for n in 1000000 100000; do
  args="--scene flythrough --scene city --objects $n --width 1280 --height 720 --frames 40 --warmup 5 --warmup-time 2"
  G bench $args -s visibility --json $R/G-$n-r1.json > /dev/null 2>&1
  G bench $args -s gpu-culling-bundles --json $R/gcb-$n.json > /dev/null 2>&1
  F bench $args -s visibility --json $R/F-$n.json > /dev/null 2>&1
  G bench $args -s visibility --json $R/G-$n-r2.json > /dev/null 2>&1
  summary $n
done
cd $OUT && tar -cJf j65.tar.xz j65 && rm -rf j65
