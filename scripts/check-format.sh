#!/usr/bin/env bash
# Checks (or, with --fix, applies) the repository's .clang-format on C++ sources: those changed
# since BASE (a revision; default: every tracked .h and .cpp). The whole tree takes about two
# seconds, so CI checks all of it. clang-format 16 or later: the style uses InsertBraces.
set -euo pipefail
cd "$(dirname "$0")/.."
fix=0
base=""
for argument in "$@"; do
    case $argument in
        --fix) fix=1 ;;
        *) base=$argument ;;
    esac
done
format=$(command -v clang-format-16 || command -v clang-format || true)
if [ -z "$format" ] || [ "$("$format" --version | grep -oE '[0-9]+' | head -1)" -lt 16 ]; then
    echo "check-format: needs clang-format 16 or later (Debian: clang-format-16)" >&2
    exit 2
fi
if [ -n "$base" ]; then
    mapfile -t files < <(git diff --name-only --diff-filter=ACMR "$base" -- '*.h' '*.cpp')
else
    mapfile -t files < <(git ls-files '*.h' '*.cpp')
fi
[ ${#files[@]} -gt 0 ] || exit 0
if [ $fix = 1 ]; then
    "$format" -i --style=file "${files[@]}"
elif ! "$format" --dry-run -Werror --style=file "${files[@]}"; then
    echo "check-format: the files above differ from .clang-format; run scripts/check-format.sh --fix" >&2
    exit 1
fi
