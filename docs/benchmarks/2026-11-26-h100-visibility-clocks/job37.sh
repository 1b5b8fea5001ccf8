#!/usr/bin/env bash
# Issue 28: the shading pipelines compiled without MATERIAL_EXTENSIONS (NOEXT, an
# experiment-only build binding each material's base-slot group) against with them, for
# scenes whose materials use no extension; alternating, per-pass timings.
set -uo pipefail
carry=$(cd "$(dirname "$0")" && pwd)
W=/tmp/job37; rm -rf $W; mkdir -p $W
tar -C $W -xJf "$carry/encore.tar.xz"
R=$OUT/j37; mkdir -p $R $W/json
E() { bash $W/pack/run.sh encore "$@"; }
E info 2>&1 | head -1 > $R/info.txt
scenes() { local tag=$1 probes=$2; echo "== $tag [$probes]" >> $R/j37.txt
  ENCORE_PROBES=$probes E bench --scene flythrough --scene city --objects 100000 -s visibility --width 1280 --height 720 --frames 20 --warmup 5 --json $W/json/b-$tag.json >> $R/j37.txt 2>&1; }
scenes ext1 ""; scenes noext1 NOEXT; scenes ext2 ""; scenes noext2 NOEXT
for f in $W/json/*.json; do echo "### $(basename $f)"; cat $f; done > $R/all-json.txt
grep -E "^==|^\| (visibility|gpu-culling)|rror" $R/j37.txt
