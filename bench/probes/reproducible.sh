#!/usr/bin/env bash
# Issue 48: whether `--strategy visibility` (and auto) write the same bytes every time, before
# (A, encore-prev.xz) and after (B, encore-next.xz) ids count units by the scene's unit table;
# then their speed side by side. The 1,000-file job of the ten shared models (100 copies of each:
# a model's copies must match within a run too), 12 views at 512x512, 4x. Run on the device
# machine as
#   bash bench/probes/reproducible.sh CARRY
# CARRY as for ab.sh. ROUNDS (default 3) speed rounds, DENSE=0 leaves out the dense models.
set -uo pipefail
P=$(cd "$(dirname "$0")" && pwd)
C=$(cd "${1:?carry folder}" && pwd)
W=/tmp/repro; rm -rf $W; mkdir -p $W
. "$P/probe-setup.sh"
probe_unpack $W "$C"
xz -dc "$C/encore-prev.xz" > $W/pack/bin/encore-prev
A() { bash $W/pack/run.sh encore-prev "$@"; }
B() { bash $W/pack/run.sh encore-new "$@"; }
E() { B "$@"; }  # probe_generated's.
echo "== machine: $(nproc) cores"; nvidia-smi -L | head -1; B info 2>&1 | head -1
probe_inputs $W "$C" 1
head -300 $W/all.txt > $W/w.txt
A batch $W/w.txt -o $W/o --quiet --strategy visibility > /dev/null 2>&1
B batch $W/w.txt -o $W/o2 --quiet --strategy visibility > /dev/null 2>&1; rm -rf $W/o $W/o2
run() {  # label, binary, list, options...
  local label=$1 bin=$2 list=$3; shift 3; rm -rf $W/o
  $bin -v batch $list -o $W/o --quiet "$@" > $W/log.txt 2>&1
  echo "== $label: $(grep -E 'views in' $W/log.txt | sed 's/.*views in/views in/')"
  grep -E "^gpu|^error|^warning" $W/log.txt | head -3
}
md5list() {  # folder -> "copy model/file md5" lines, metadata.json left out
  (cd $1 && find . -type f ! -name metadata.json | sort | xargs md5sum) |
    awk '{ split($2, p, "/"); f = p[3]; for (i = 4; i <= length(p); i++) f = f "/" p[i];
           print p[2], f, $1 }'
}
for s in visibility auto; do
  for b in A B; do
    for r in 1 2; do
      run "$b $s r$r" $b $W/all.txt --strategy $s; md5list $W/o > $W/$b-$s-$r.md5
    done
    echo "-- $b $s: files $(wc -l < $W/$b-$s-1.md5); run 1 against run 2:" \
      "$(cmp -s $W/$b-$s-1.md5 $W/$b-$s-2.md5 && echo identical ||
         echo "$(diff <(awk '{print $2, $3}' $W/$b-$s-1.md5) <(awk '{print $2, $3}' $W/$b-$s-2.md5) |
                 grep -c '^<') lines differ")"
    echo "   files with more than one md5 among a model's 100 copies (both runs):"
    cat $W/$b-$s-1.md5 $W/$b-$s-2.md5 | awk '{ k = $2; if (!(k SUBSEP $3 in seen)) { seen[k SUBSEP $3] = 1; n[k]++ } }
      END { for (k in n) if (n[k] > 1) { split(k, p, "/"); m[p[1]]++; t++ }
            for (x in m) printf "   %s: %d files\n", x, m[x]; printf "   in all: %d\n", t + 0 }'
  done
done
echo "== bundles-drawn files: A against B"
for b in A B; do run "$b bundles" $b $W/all.txt --strategy bundles; md5list $W/o > $W/$b-bundles.md5; done
cmp -s $W/A-bundles.md5 $W/B-bundles.md5 && echo identical || echo DIFFERENT
for r in $(seq 1 ${ROUNDS:-3}); do
  for b in A B; do run "speed light s4 auto $b r$r" $b $W/all.txt --strategy auto; done
done
[ "${DENSE:-1}" = 1 ] || exit 0
probe_generated $W dense 256 25  # 1,000 dense files.
for r in $(seq 1 ${ROUNDS:-3}); do
  for b in A B; do run "speed dense s4 visibility $b r$r" $b $W/dense.txt --strategy visibility; done
done
