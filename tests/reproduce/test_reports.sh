#!/usr/bin/env bash
# test_reports.sh EXE SRCDIR — the committed reports/ are what
# `subspectra reproduce --certify` writes, byte for byte (issue 34, 6): a
# slip that moves a certified bound in its last digits (a margin dropped from
# a JSR upper bound, say) changes reports/data/*-jsr.jsonl and fails here,
# even where no verdict moves.  Compared: every file the run writes (the
# tables' .md and .tsv, data/*.jsonl, figures/*.png and figures/README.md),
# and every such file of reports/ must be written by the run.  Not compared
# (not written by reproduce): reports/README.md, the exhaustive tables
# (reports/exhaustive-*, reports/data/exhaustive-*, made by
# reports/exhaustive.sh), the k = 11 sweep (reports/vertices-k11-certified.md,
# made by `subspectra sweep`), reports/tuned-* (reports/tuned.sh),
# reports/ccsolid-tensor-* (reports/ccsolid-tensor.sh), and the sources beside
# them (*.c, *.h, meson.build).
# About 3 minutes on an idle machine (psi and its spokes on the MLCA and ccsolid
# vertex tables).
set -u
exe=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
out=$tmp/out
# from the source tree with the defaults, as reports/ was made (the reference
# files' paths are printed as found)
if ! (cd "$src" && "$exe" reproduce --certify --out "$out") 2>"$tmp/err"; then
  echo "FAIL: reproduce --certify: $(tail -3 "$tmp/err")"
  exit 1
fi
bad=0
n=0
# every file written equals its committed counterpart
while IFS= read -r f; do
  n=$((n + 1))
  if [ ! -f "$src/reports/$f" ]; then
    echo "FAIL: reports/$f is not committed (reproduce writes it)"
    bad=1
  elif ! cmp -s "$out/$f" "$src/reports/$f"; then
    echo "FAIL: reports/$f differs from what reproduce --certify writes:"
    diff "$src/reports/$f" "$out/$f" | head -6
    bad=1
  fi
done < <(cd "$out" && find . -type f | sed 's|^\./||' | LC_ALL=C sort)
# every committed file of the kinds reproduce writes is written
while IFS= read -r f; do
  [ -f "$out/$f" ] || { echo "FAIL: reports/$f is no longer written by reproduce"; bad=1; }
done < <(cd "$src/reports" && find . -type f \( -name '*.md' -o -name '*.tsv' \
  -o -name '*.jsonl' -o -name '*.png' \) ! -name 'exhaustive-*' ! -path ./README.md \
  ! -name 'vertices-k11-certified.md' ! -name 'tuned-*' ! -name 'ccsolid-tensor-*' |
  sed 's|^\./||' | LC_ALL=C sort)
[ "$n" -ge 50 ] || { echo "FAIL: only $n files written"; bad=1; }
[ "$bad" -eq 0 ] && echo "ok: $n files written by reproduce --certify, each equal to reports/"
exit "$bad"
