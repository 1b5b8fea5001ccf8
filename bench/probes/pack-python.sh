#!/usr/bin/env bash
# Packs Debian's Python 3.11 with the packages encore.dask needs (distributed and what it imports,
# numpy) and the build's encore module into one xz tarball for the device machine, whose older
# glibc cannot load Dawn: Python runs there through shared/gpu/pack.sh's loader, as `encore` does.
#   bash bench/probes/pack-python.sh BUILD PACK.tar.xz OUT.tar.xz    (on the development machine)
# PACK.tar.xz: the carried encore pack, whose libraries (Dawn, glibc, ...) are not packed twice.
# On the device machine, after probe_unpack: `. bench/probes/probe-python.sh; probe_python WORK`.
set -euo pipefail
build=$(cd "${1:?build folder}" && pwd); pack=$(realpath "${2:?the encore pack .tar.xz}"); out=$(realpath "${3:?output .tar.xz}")
W=$(mktemp -d); R=$W/python; mkdir -p $R/lib/python3/dist-packages $R/bin $R/so
skip=(--exclude=__pycache__ --exclude=test --exclude=tests --exclude=idlelib --exclude=tkinter
      --exclude=turtledemo --exclude=ensurepip --exclude=lib2to3 --exclude='config-3.11*'
      --exclude=python3.11/dist-packages --exclude=pydoc_data --exclude=distutils --exclude=f2py
      --exclude='_test*' --exclude='_codecs_[a-z][a-z].*' --exclude='_codecs_iso2022*'
      --exclude='_simd.*' --exclude=numpy/core/include --exclude='*.pyi' --exclude=numpy/doc
      --exclude='_sqlite3.*' --exclude='_dbm.*' --exclude='_gdbm.*' --exclude='nis.*'
      --exclude='_tkinter.*' --exclude='_curses*' --exclude=sqlite3 --exclude=dbm --exclude=curses)
tar -C /usr/lib -cf - "${skip[@]}" python3.11 | tar -C $R/lib -xf -
packages=(distributed dask numpy tornado jinja2 markupsafe yaml _yaml toolz tlz click zict psutil
          colorama msgpack sortedcontainers cloudpickle tblib packaging locket heapdict.py
          fsspec partd importlib_metadata zipp)
D=/usr/lib/python3/dist-packages
for p in "${packages[@]}"; do [ -e $D/$p ] && tar -C $D -cf - "${skip[@]}" $p | tar -C $R/lib/python3/dist-packages -xf -; done
# Their metadata, which importlib.metadata reads for versions.
for m in $D/*.dist-info $D/*.egg-info; do
  case ${m,,} in *distributed*|*dask*|*numpy*|*tornado*|*jinja2*|*pyyaml*|*toolz*|*click*|*zict*|\
    *psutil*|*msgpack*|*sortedcontainers*|*cloudpickle*|*tblib*|*packaging*|*markupsafe*|*locket*|\
    *heapdict*|*fsspec*|*partd*) cp -r "$m" $R/lib/python3/dist-packages/ ;; esac
done
cp -r $build/python/encore $R/lib/python3/dist-packages/
strip $R/lib/python3/dist-packages/encore/*.so
cp -L /usr/bin/python3.11 $R/bin/
# Every shared library the interpreter and the extension modules load (glibc's loader comes
# from the encore pack, which these must share).
tar -tJf "$pack" | sed -n 's|^pack/lib/||p' > $W/packed
find $R -name '*.so*' -type f > $W/objects; echo $R/bin/python3.11 >> $W/objects
while read -r o; do ldd "$o" 2>/dev/null | awk '/=> \//{print $3}'; done < $W/objects | sort -u |
  while read -r lib; do grep -qxF "$(basename $lib)" $W/packed || cp -Lu "$lib" $R/so/; done
tar -C $W -cf - python | xz -T2 -6 > "$out"; rm -rf $W
ls -l "$out"
