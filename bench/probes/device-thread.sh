#!/usr/bin/env bash
# Issue 48: what is left of a model's device-thread time with four GPUs busy once the pools
# are in (pools.sh): who changes the memory map (strace -k of mprotect/munmap/mmap: the first
# frame outside libc, and the Dawn frame under it), whether the output disk matters (/dev/shm),
# and whether texture bytes do (--max-texture-size 1024). Run on the device machine as
#   bash bench/probes/device-thread.sh CARRY      (CARRY as pools.sh takes it)
set -uo pipefail
P=$(cd "$(dirname "$0")" && pwd)
C=$(cd "${1:?carry folder}" && pwd)
W=/tmp/lane; rm -rf $W; mkdir -p $W
. "$P/probe-setup.sh"
probe_unpack $W "$C"
NEW() { bash $W/pack/run.sh encore-new "$@"; }
L="$W/pack/lib/ld-linux-x86-64.so.2 --library-path $W/pack/lib"
GPUS=$(nvidia-smi -L | wc -l)
probe_inputs $W "$C" $GPUS
head -$((50 * GPUS)) $W/all.txt > $W/all50.txt
run() {  # label, output folder, options...
  local label=$1 out=$2; shift 2; rm -rf $out
  NEW -v batch $W/all.txt -o $out --quiet --devices all "$@" > $W/log.txt 2>&1
  echo "== $label: $(grep -E 'views in' $W/log.txt | sed 's/.*views in/views in/')"
  grep -E "^stages|^upload|^materials" $W/log.txt | sed "s/ (load and encode summed.*//"
  rm -rf $out
}
NEW batch $W/all50.txt -o $W/o --quiet --devices all > /dev/null 2>&1; rm -rf $W/o
run "$GPUS GPUs, output on disk" $W/o
run "$GPUS GPUs, output on /dev/shm" /dev/shm/lane-out
run "$GPUS GPUs, --max-texture-size 1024" $W/o --max-texture-size 1024
run "$GPUS GPUs, --png-compression fast" $W/o --png-compression fast

echo "== strace -f -k: who calls mprotect, munmap and mmap ($((50 * GPUS)) files, $GPUS GPUs)"
rm -rf $W/o
$L $W/pack/bin/strace -f -k -e trace=mprotect,munmap,mmap -o $W/k.txt \
  bash $W/pack/run.sh encore-new batch $W/all50.txt -o $W/o --quiet --devices all > /dev/null 2>&1
for call in mprotect munmap mmap; do
  echo "-- $call: $(grep -cE "^[0-9]+ $call\(" $W/k.txt) calls; first frame outside libc, then the next frame"
  awk -v call="$call" '
    function name(line, frame) { frame = line; sub(/^ > /, "", frame); sub(/\+0x.*/, "", frame)
                                 sub(/.*\//, "", frame); return frame }
    function flush() { if (want) n[first " <- " (dawn == "" ? "?" : dawn)]++; want = 0 }
    $0 ~ "^[0-9]+ " call "\\(" { flush(); want = 1; first = ""; dawn = ""; next }
    want && /^ > / {
      frame = name($0)
      if (first == "" && frame !~ /^libc\.so/) first = frame
      if (dawn == "" && frame ~ /^(libwebgpu_dawn|encore)/) dawn = frame
      next }
    { flush() }
    END { flush(); for (k in n) print n[k], k }' $W/k.txt | sort -nr | head -8
done
