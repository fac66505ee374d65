#!/usr/bin/env bash
# reports/ccsolid-tensor.sh — Joy-MacCracken with the tensor product restored
# along extraordinary edges (`ccsolid-tensor`, issue 39) beside `ccsolid`:
# every vertex one-ring with k <= 9 and the edges of valence 3..10, certified,
# with psi judged on its pieces (--psi-depth 2) as in the ccsolid tables.
# Not part of `subspectra reproduce`'s default tables (they would add about
# 40 s to the reports test): the tables are data/reproduce/ccsolid-tensor.json,
# run by
#   subspectra reproduce --certify --tables data/reproduce/ccsolid-tensor.json
# into a scratch folder (which also writes the JSR tables, left there), then
# copied to
#   DIR/ccsolid-tensor-vertices-k4-9.md, .tsv, DIR/data/...jsonl
#   DIR/ccsolid-tensor-edges-3-10.md, .tsv, DIR/data/...jsonl
# About 2 min on the shared 2-core machine.  See reports/README.md,
# "Finding 10".
#
#   reports/ccsolid-tensor.sh [--out DIR]      (default: reports)
#
# The program: $SUBSPECTRA, else build/cli/subspectra beside this script's
# folder, else subspectra on PATH.  Exit status: 0 written, 1 reproduce
# failed, 2 bad usage.
set -euo pipefail

usage() {
  sed -n '2,/^set -euo/p' "$0" | sed -e '$d' -e 's/^# \{0,1\}//'
}

out=reports
while (($#)); do
  case "$1" in
  --out) out=${2:?--out needs a folder}; shift 2 ;;
  -h | --help) usage; exit 0 ;;
  *) echo "ccsolid-tensor.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
source "$(dirname "$0")/find-program.sh" ccsolid-tensor.sh
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# from the source tree, as reproduce is run for reports/ (the reference
# files' paths are printed as found)
if ! (cd "$here" && "$exe" reproduce --certify \
  --tables data/reproduce/ccsolid-tensor.json --out "$tmp/out"); then
  echo "ccsolid-tensor.sh: reproduce failed" >&2
  exit 1
fi
mkdir -p "$out/data"
for t in ccsolid-tensor-vertices-k4-9 ccsolid-tensor-edges-3-10; do
  cp "$tmp/out/$t.md" "$tmp/out/$t.tsv" "$out/"
  cp "$tmp/out/data/$t.jsonl" "$out/data/"
done
echo "ccsolid-tensor.sh: wrote $out/ccsolid-tensor-{vertices-k4-9,edges-3-10}.md" >&2
