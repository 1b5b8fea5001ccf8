#!/usr/bin/env bash
# Issue 28, stop 49: J (139c989: composed straight into the target, no copy) against H
# (c26e946, its copy untimed) and gpu-culling-bundles, one lease; the CPU frame, three rounds.
set -uo pipefail
carry=$(cd "$(dirname "$0")" && pwd)
W=/tmp/job68; rm -rf $W; mkdir -p $W/h $W/j
tar -C $W/h -xJf "$carry/encore-h.tar.xz"
tar -C $W/j -xJf "$carry/encore-j.tar.xz"
R=$OUT/j68; mkdir -p $R
H() { bash $W/h/pack/run.sh encore "$@"; }
J() { bash $W/j/pack/run.sh encore "$@"; }
J info 2>&1 | head -1
summary() {
python3 - "$R" "$1" <<'PY'
import json,sys,glob,os,re
for f in sorted(glob.glob(sys.argv[1]+'/*.json')):
    d=json.load(open(f)); name=os.path.basename(f)[:-5]
    if not re.search(r'(^|-)%s(-|$)' % sys.argv[2], name): continue
    for r in d['results']:
        p=r['gpuPassesMs']
        short={k.replace('visibility','v').replace(': depth pyramid, second culling and raster','ph2').replace(': culling and compute raster','ph1').replace(': binning and shading','shade'):v['median'] for k,v in p.items()}
        span=r.get('gpuSpanMs')
        print('%-16s %-4s frame %.4f p95 %.3f span %s '%(name, r['scene'][:4], r['gpuMs']['median'], r['gpuMs']['p95'], '%.4f'%span['median'] if span else '-')+' '.join('%s=%.4f'%(k,v) for k,v in sorted(short.items())))
PY
}
for n in 1000000 100000; do
  args="--scene flythrough --scene city --objects $n --width 1280 --height 720 --frames 40 --warmup 5 --warmup-time 2"
  J bench $args -s visibility --json $R/J-$n-r1.json > /dev/null 2>&1
  J bench $args -s gpu-culling-bundles --json $R/gcb-$n.json > /dev/null 2>&1
  H bench $args -s visibility --json $R/H-$n.json > /dev/null 2>&1
  J bench $args -s visibility --json $R/J-$n-r2.json > /dev/null 2>&1
  summary $n
done
for r in 1 2 3; do
  for who in gcb J; do
    s=visibility; [ $who = gcb ] && s=gpu-culling-bundles
    echo "== cpu $who r$r"
    J bench --scene flythrough --scene city --objects 100000 -s $s --width 1280 --height 720 --frames 300 --warmup 5 --no-gpu-timer 2>&1 | grep -E "^\| (visibility|gpu-culling)"
  done
done
cd $OUT && tar -cJf j68.tar.xz j68 && rm -rf j68
