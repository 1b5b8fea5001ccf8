#!/usr/bin/env bash
# Issue 48, step 1: where several GPUs of one machine serialise. Run on the device machine as
#   bash bench/probes/serialising-point.sh CARRY
# CARRY (an ignored folder named in the device tool's carry) holds:
#   pack.tar.xz  encore, perf and strace packed by shared/gpu/pack.sh (folder pack/)
#   models/      the ten shared models (.glb, and Avocado's glTF folder)
#   fresh_pages  bench/probes/fresh_pages.c built static
set -uo pipefail
P=$(cd "$(dirname "$0")" && pwd)
C=$(cd "${1:?carry folder}" && pwd)
W=/tmp/probe; rm -rf $W; mkdir -p $W
. "$P/probe-setup.sh"
probe_unpack $W "$C"
E() { bash $W/pack/run.sh encore "$@"; }
L="$W/pack/lib/ld-linux-x86-64.so.2 --library-path $W/pack/lib"
PERF="$L $W/pack/bin/perf"
STRACE="$L $W/pack/bin/strace"
GPUS=$(nvidia-smi -L | wc -l)
echo "== machine: $(nproc) cores, $GPUS GPUs, kernel $(uname -r)"
nvidia-smi -L
cat /proc/cmdline | tr ' ' '\n' | grep -E 'page_reporting|balloon|zero' || true
echo "page_reporting_order: $(cat /sys/module/page_reporting/parameters/page_reporting_order 2>/dev/null)"
grep -E 'MemTotal|MemFree' /proc/meminfo
E info 2>&1 | head -8

probe_inputs $W "$C" $GPUS
head -1000 $W/all.txt > $W/one.txt
head -300 $W/all.txt > $W/one300.txt
head -$((300 * GPUS)) $W/all.txt > $W/all300.txt
wc -l $W/all.txt $W/one.txt

echo "== fresh pages: map, write, unmap 64 MiB (the VM's first-touch cost), all processes"
for n in 1 2 4 8 16; do $C/fresh_pages $n 64 $((32 / n)) fresh; done
$C/fresh_pages 1 64 32 reuse
$C/fresh_pages 16 64 8 reuse

echo "== driver calls, one process per GPU"
for n in 1 $GPUS; do timeout 60 python3 $P/driver_calls.py $n 16 2>&1 | grep -v Warning; done

vm() { grep -E '^(pgfault|pgalloc_normal|pgfree|pgmajfault|thp_fault_alloc|nr_free_pages) ' /proc/vmstat | tr '\n' ' '; }
batch() {  # name, list, options...
  local name=$1 list=$2; shift 2; rm -rf $W/o
  local before; before=$(vm)
  local start=$(date +%s%N)
  E -v batch $list -o $W/o --quiet "$@" > $W/log.txt 2>&1
  local rc=$?
  echo "== $name (rc $rc, $(( ($(date +%s%N) - start) / 1000000 )) ms)"
  grep -E "views in|stages|^upload|^materials|^device [0-9]" $W/log.txt | sed "s/ (load and encode summed.*//" | cut -c1-300
  echo "vmstat before: $before"; echo "vmstat after:  $(vm)"
  rm -rf $W/o
}
E batch $W/one300.txt -o $W/o --quiet --device 0 > /dev/null 2>&1; rm -rf $W/o   # warm-up
batch "one GPU r1" $W/one.txt --device 0
batch "all GPUs r1" $W/all.txt --devices all
batch "one GPU r2" $W/one.txt --device 0
batch "all GPUs r2" $W/all.txt --devices all

echo "== perf stat, software events, one GPU then all"
for run in "one --device 0" "all --devices all"; do
  set -- $run; rm -rf $W/o
  $PERF stat -e page-faults,minor-faults,major-faults,context-switches,cpu-migrations,task-clock \
    -o $W/stat-$1.txt bash $W/pack/run.sh encore batch $W/$1.txt -o $W/o --quiet $2 $3 > /dev/null 2>&1
  echo "-- $1"; grep -vE '^#|^$' $W/stat-$1.txt
done

echo "== strace -f -c -w: wall-clock time in system calls, 300 files per GPU"
for run in "one300 --device 0" "all300 --devices all"; do
  set -- $run; rm -rf $W/o
  $STRACE -f -c -w -o $W/strace-$1.txt bash $W/pack/run.sh encore batch $W/$1.txt -o $W/o --quiet $2 $3 > /dev/null 2>&1
  echo "-- $1"; head -30 $W/strace-$1.txt
done
cp $W/strace-*.txt $OUT/ 2>/dev/null

echo "== strace -f -T: each ioctl and mapping call by request, 100 files per GPU"
head -100 $W/all.txt > $W/one100.txt; head -$((100 * GPUS)) $W/all.txt > $W/all100.txt
for run in "one100 --device 0" "all100 --devices all"; do
  set -- $run; rm -rf $W/o
  $STRACE -f -T -e trace=ioctl,mmap,munmap,madvise,mprotect -o $W/trace-$1.txt \
    bash $W/pack/run.sh encore batch $W/$1.txt -o $W/o --quiet $2 $3 > /dev/null 2>&1
  echo "-- $1: calls, total s, mean us by request (top 25 by total time)"
  awk -f "$P/strace-by-request.awk" $W/trace-$1.txt | sort -k2 -nr | head -25
done

echo "== perf record -a -g (cpu-clock) over the all-GPU run: kernel and user symbols"
rm -rf $W/o
$PERF record -F 199 -a -g -o $W/perf.data bash $W/pack/run.sh encore batch $W/all.txt -o $W/o --quiet --devices all > /dev/null 2>&1
$PERF report -i $W/perf.data --stdio --no-children --sort sym --percent-limit 0.7 -g none 2>/dev/null | grep -v '^#' | grep -v '^$' | head -45 > $OUT/perf-all-sym.txt
$PERF report -i $W/perf.data --stdio --no-children --sort comm,dso --percent-limit 1 -g none 2>/dev/null | grep -v '^#' | grep -v '^$' | head -30 > $OUT/perf-all-dso.txt
cat $OUT/perf-all-dso.txt $OUT/perf-all-sym.txt

echo "== the same with page reporting off (the VM keeps what it freed): a diagnosis only"
p=/sys/module/page_reporting/parameters/page_reporting_order
old=$(cat $p 2>/dev/null)
if [ -n "$old" ] && echo 63 > $p 2>/dev/null; then
  $C/fresh_pages 16 64 2 fresh
  batch "one GPU, no page reporting" $W/one.txt --device 0
  batch "all GPUs, no page reporting" $W/all.txt --devices all
  echo $old > $p
else
  echo "page_reporting_order not writable"
fi
