#!/usr/bin/env bash
# Issue 51's target: a 1,000-file collection with 10% hostile files (ten of each kind
# hostile_files.py writes, plus a FIFO, a link out of the folder and a truncated GLB made here)
# among 900 files of the ten shared models, one batch with default options against the 900
# alone: every good model's files the same, every hostile file failed or drawn with its image
# failed, the time and peak memory. Run on the device machine as
#   bash bench/probes/hostile-collection.sh CARRY
# CARRY as for pools.sh, with hostile/ (hostile_files.py's output).
set -uo pipefail
P=$(cd "$(dirname "$0")" && pwd)
C=$(cd "${1:?carry folder}" && pwd)
W=/tmp/hostile; rm -rf $W; mkdir -p $W
. "$P/probe-setup.sh"
probe_unpack $W "$C"
E() { bash $W/pack/run.sh encore-new "$@"; }
echo "== machine: $(nproc) cores"; nvidia-smi -L | head -1; E info 2>&1 | head -1
probe_inputs $W "$C" 1
head -900 $W/all.txt > $W/clean.txt
for i in $(seq -w 0 9); do
  H=$W/in/h$i; cp -r "$C/hostile" $H
  ln -s $H/secret.bin $H/link/link.bin
  mkfifo $H/fifo/pipe.bin
  mkdir -p $H/truncated; head -c 2000 "$C/models/Duck.glb" > $H/truncated/model.glb
  ls $H/*/model.gltf $H/truncated/model.glb >> $W/hostile.txt
done
cat $W/clean.txt $W/hostile.txt | sort > $W/mixed.txt
echo "files: $(wc -l < $W/clean.txt) good, $(wc -l < $W/hostile.txt) hostile"
peak() {  # Runs its arguments, then prints the peak resident memory of the process tree.
  if [ -x /usr/bin/time ]; then /usr/bin/time -f "peak resident memory %M kB" "$@"; else "$@"; fi
}
for run in clean mixed; do
  rm -rf $W/out-$run; start=$(date +%s%N)
  peak timeout -k 10 900 bash $W/pack/run.sh encore-new -v batch $W/$run.txt -o $W/out-$run --quiet \
    > $W/log-$run.txt 2>&1
  echo "== $run: exit $? after $(( ($(date +%s%N) - start) / 1000000 )) ms"
  grep -E "views in|^stages|peak resident|^warning" $W/log-$run.txt | sed "s/ (load and.*//"
done
echo "== failures of the mixed run, by kind (file's folder) and stage"
python3 - "$W/out-mixed/failures.jsonl" <<'PY' 2>/dev/null || sed 's/"error".*"file"/"file"/' $W/out-mixed/failures.jsonl | head -20
import collections, json, sys
rows = [json.loads(line) for line in open(sys.argv[1])]
kinds = collections.Counter((r["file"].split("/")[-2], r["stage"]) for r in rows)
for (kind, stage), count in sorted(kinds.items()):
    example = next(r["error"] for r in rows if r["file"].split("/")[-2] == kind)
    print(f"{count:4d} {kind:14s} {stage:8s} {example[-150:]}")
PY
echo "== the hostile models that rendered: their failed images"
for f in $W/out-mixed/h*/*/model/metadata.json; do
  echo "$(basename $(dirname $(dirname $f))): $(tr -d '\n' < $f | grep -o '"imagesFailed": *\[[^]]*\]' | cut -c1-160)"
done | sort | uniq -c | head -4
echo "== the good models' files (metadata.json left out: times), clean against mixed"
for run in clean mixed; do
  (cd $W/out-$run && find . -type f ! -name metadata.json ! -name failures.jsonl ! -path './h*' \
    | sort | xargs md5sum) > $W/$run.md5
done
wc -l < $W/clean.md5 $W/mixed.md5; cmp -s $W/clean.md5 $W/mixed.md5 && echo "identical" || echo "DIFFERENT"
diff $W/clean.md5 $W/mixed.md5 | head -6
