#!/usr/bin/env bash
# check_format.sh CLANG_FORMAT SRCDIR — every C source and header is formatted
# as .clang-format says (the style rule "clang-format; warnings are errors").
set -u
cf=$1
src=$2
if [ -z "$cf" ]; then
  echo "format: SKIPPED — clang-format not found (./run installs it)"
  exit 77
fi
cd "$src" || exit 1
files=$(find src enumerate analysis reports cli tests examples -name '*.[ch]' | sort)
n=$(wc -w <<<"$files")
bad=0
# one clang-format for all files (one per file took 30 s on a loaded machine);
# only when it objects, once more per file to name the culprits
if "$cf" --dry-run --Werror $files >/dev/null 2>&1 && [ "$n" -gt 0 ]; then
  echo "format: $n files, 0 not formatted"
  exit 0
fi
n=0
for f in $files; do
  n=$((n + 1))
  if ! "$cf" --dry-run --Werror "$f" >/dev/null 2>&1; then
    bad=$((bad + 1))
    echo "not clang-formatted: $f (run: clang-format -i $f)" >&2
  fi
done
echo "format: $n files, $bad not formatted"
[ "$bad" -eq 0 ] && [ "$n" -gt 0 ]
