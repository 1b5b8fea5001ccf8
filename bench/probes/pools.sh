#!/usr/bin/env bash
# Issue 48: the lane's resource pool and the kept allocator memory, against the build before
# them, in one lease. Run on the device machine as
#   bash bench/probes/pools.sh CARRY
# CARRY holds pack.tar.xz (shared/gpu/pack.sh's folder pack/ with the earlier encore, strace and
# encore-new, the build under test, stripped; the same libraries), models/, and optionally
# encore-next.xz, a later build under test.
set -uo pipefail
P=$(cd "$(dirname "$0")" && pwd)
C=$(cd "${1:?carry folder}" && pwd)
W=/tmp/pools; rm -rf $W; mkdir -p $W
. "$P/probe-setup.sh"
probe_unpack $W "$C"
OLD() { bash $W/pack/run.sh encore "$@"; }
NEW() { bash $W/pack/run.sh encore-new "$@"; }
NEW_GLIBC() { ENCORE_KEEP_FREED_MEMORY=0 bash $W/pack/run.sh encore-new "$@"; }
L="$W/pack/lib/ld-linux-x86-64.so.2 --library-path $W/pack/lib"
GPUS=$(nvidia-smi -L | wc -l)
OLD_ROUNDS=${OLD_ROUNDS:-2}  # Rounds of the earlier build beside the three of the new one.
echo "== machine: $(nproc) cores, $GPUS GPUs"; nvidia-smi -L | head -1
probe_inputs $W "$C" $GPUS
head -1000 $W/all.txt > $W/one.txt; head -2000 $W/all.txt > $W/two.txt
for g in $(seq 0 $((GPUS - 1))); do sed -n "$((g * 1000 + 1)),$((g * 1000 + 1000))p" $W/all.txt > $W/part$g.txt; done

run() {  # label, binary, list, options...
  local label=$1 bin=$2 list=$3; shift 3; rm -rf $W/o
  $bin -v batch $list -o $W/o --quiet "$@" > $W/log.txt 2>&1
  echo "== $label: $(grep -E 'views in' $W/log.txt | sed 's/.*views in/views in/')"
  grep -E "^stages|^upload|^materials|created:" $W/log.txt | sed "s/ (load and encode summed.*//" | head -8
}
keep() { rm -rf $W/keep-$1; mv $W/o $W/keep-$1; }

head -300 $W/one.txt > $W/w.txt
OLD batch $W/w.txt -o $W/o --quiet > /dev/null 2>&1
NEW batch $W/w.txt -o $W/o2 --quiet > /dev/null 2>&1; rm -rf $W/o $W/o2
for r in 1 2 3; do
  run "new, one GPU, r$r" NEW $W/one.txt --device 0; [ $r = 1 ] && keep new1
  if [ $r -le $OLD_ROUNDS ]; then run "old, one GPU, r$r" OLD $W/one.txt --device 0; [ $r = 1 ] && keep old1; fi
  run "new, $GPUS GPUs, r$r" NEW $W/all.txt --devices all
  if [ $r -le $OLD_ROUNDS ]; then run "old, $GPUS GPUs, r$r" OLD $W/all.txt --devices all; fi
done
run "new, two GPUs (0,1)" NEW $W/two.txt --devices 0,1
run "new, $GPUS GPUs, allocator as glibc leaves it" NEW_GLIBC $W/all.txt --devices all

echo "== new, $GPUS processes, one GPU and $(( $(nproc) / GPUS )) jobs each"
rm -rf $W/process-*; start=$(date +%s%N)
for g in $(seq 0 $((GPUS - 1))); do
  NEW batch $W/part$g.txt -o $W/process-out$g --quiet --device $g --jobs $(( $(nproc) / GPUS )) \
    > $W/process-log$g.txt 2>&1 &
done; wait
ms=$(( ($(date +%s%N) - start) / 1000000 ))
echo "$((GPUS * 12000)) views in $ms ms: $(( GPUS * 12000 * 1000 / ms )) views/s (process start to end)"
grep -h "views in" $W/process-log*.txt; rm -rf $W/process-out*

echo "== md5 lists, one GPU, first 1000 files (metadata.json left out: it records times)"
(cd $W/keep-old1 && find . -type f ! -name metadata.json | sort | xargs md5sum) > $W/old.md5
(cd $W/keep-new1 && find . -type f ! -name metadata.json | sort | xargs md5sum) > $W/new.md5
wc -l < $W/old.md5; md5sum $W/old.md5 $W/new.md5 | sed "s|$W/||"; cmp -s $W/old.md5 $W/new.md5 && echo "identical"
python3 - $W/keep-new1 <<'PY'
import json, pathlib, sys
rows = sorted(pathlib.Path(sys.argv[1]).rglob("metadata.json"))
created = [json.loads(p.read_text())["gpu"] for p in rows]
late = created[100:]
print(f"metadata.json gpu: {len(rows)} models; objectsCreated>0 in {sum(c['objectsCreated'] > 0 for c in created)}, "
      f"of the last {len(late)}: {sum(c['objectsCreated'] > 0 or c['bytesMapped'] > 0 for c in late)} created or mapped")
PY

echo "== strace -f -T, 100 files per GPU, new"
head -$((100 * GPUS)) $W/all.txt > $W/all100.txt; rm -rf $W/o
$L $W/pack/bin/strace -f -T -e trace=ioctl,mmap,munmap,madvise,mprotect -o $W/trace.txt \
  bash $W/pack/run.sh encore-new batch $W/all100.txt -o $W/o --quiet --devices all > /dev/null 2>&1
awk -f "$P/strace-by-request.awk" $W/trace.txt | sort -k2 -nr | head -14

echo "== page faults (/proc/vmstat pgfault) of a $GPUS-GPU run, new then old"
for bin in NEW OLD; do
  rm -rf $W/o; before=$(awk '/^pgfault /{print $2}' /proc/vmstat)
  $bin batch $W/all.txt -o $W/o --quiet --devices all > /dev/null 2>&1
  echo "$bin: $(( $(awk '/^pgfault /{print $2}' /proc/vmstat) - before )) faults for $((GPUS * 1000)) models"
done
