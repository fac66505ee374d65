#!/usr/bin/env bash
# reports/tuned.sh — MLCA with valence-dependent weights beside MLCA (issue 39):
# data/stencils/mlca-valence.ini tuned by `subspectra tune`, then both files
# swept with certified verdicts over every vertex link with 4..K vertices and
# the edges of valence 3..10, counted per k, with the links the tuned file
# repairs and breaks, and each failing link tuned alone.  Not part of ./run
# (about 25 min on the shared 2-core machine: 80 evaluations of 270 cases,
# 40 of each failing link).  See reports/README.md, "Finding 10".
#
#   reports/tuned.sh [--max-k K] [--db FILE] [--out DIR] [--jobs N]
#                    [--evals N] [--no-tune]
#
# Steps:
#  1. subspectra sweep --stencil data/stencils/mlca.ini --vertices 4..K
#       --edges 3..10 --certify --db FILE  (MLCA as a stencil; resumable)
#  2. each vertex link that does not pass under step 1 tuned alone
#     (tune --links ONE --evals 40; DIR/data/tuned-mlca-k4-K-alone.csv), then
#     the tuning set: the links with 9..K vertices that pass under step 1,
#     and finding 1's link; then
#       subspectra tune data/stencils/mlca-valence.ini --vertices 4..8
#         --links SET --edges 3..7 --evals N -o data/stencils/mlca-valence-tuned.ini
#     (every case MLCA passes must keep passing, finding 1 must be repaired;
#     the other failures are left out, since tune maximises the smallest
#     margin and one that no point moves would pin it).
#     --no-tune keeps the tuned file as it is.
#  3. the same sweep of the tuned file;
#  4. DIR/tuned-mlca-k4-K.md: the exhaustive rows and the summary of both
#     files (subspectra report), the links repaired and broken (the stores'
#     verdicts joined on the canonical link), tune's smallest margin.
# K is 9 or 10 (default 10).  The program: $SUBSPECTRA, else
# build/cli/subspectra beside this script's folder, else subspectra on PATH.
# Exit status: 0 written, 1 a sweep or tune ended with an error, 2 bad usage.
set -euo pipefail

usage() {
  sed -n '2,/^set -euo/p' "$0" | sed -e '$d' -e 's/^# \{0,1\}//'
}

kmax=10 db=tuned.db out=reports jobs=1 evals=80 tune=1 alone_evals=40
while (($#)); do
  case "$1" in
  --max-k) kmax=${2:?--max-k needs a value}; shift 2 ;;
  --db) db=${2:?--db needs a file}; shift 2 ;;
  --out) out=${2:?--out needs a folder}; shift 2 ;;
  --jobs) jobs=${2:?--jobs needs a number}; shift 2 ;;
  --evals) evals=${2:?--evals needs a number}; shift 2 ;;
  --no-tune) tune=0; shift ;;
  -h | --help) usage; exit 0 ;;
  *) echo "tuned.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
if [[ $kmax != 9 && $kmax != 10 ]]; then
  echo "tuned.sh: --max-k '$kmax' is not 9 or 10" >&2
  exit 2
fi
source "$(dirname "$0")/find-program.sh" tuned.sh
command -v python3 > /dev/null || { echo "tuned.sh: python3 is needed" >&2; exit 2; }
orig=$here/data/stencils/mlca.ini
family=$here/data/stencils/mlca-valence.ini
tuned=$here/data/stencils/mlca-valence-tuned.ini
finding1="8 bcdefgh,ahc,abhd,ache,adhf,aehg,afh,agfedcb"

sweep() { # sweep FILE: certified, every link 4..K and edges 3..10
  echo "tuned.sh: sweep --stencil $1 --vertices 4..$kmax --edges 3..10 --certify (store $db)" >&2
  local rc=0
  "$exe" sweep --stencil "$1" --vertices "4..$kmax" --edges 3..10 --certify \
    --jobs "$jobs" --db "$db" --quiet || rc=$?
  if ((rc != 0 && rc != 1)); then
    echo "tuned.sh: the sweep of $1 ended with status $rc; rerun to resume" >&2
    exit 1
  fi
}
name_of() { sed -n 's/^name *= *\([^ ;]*\).*/\1/p' "$1" | head -1; }
# the store identity of stencil file $1 (its bytes' hash), from a one-case
# sweep into a scratch store: a store may hold older tuned files too
ident() {
  local tmp
  tmp=$(mktemp -d)
  echo "$finding1" | "$exe" sweep --stencil "$1" --links - --certify --db "$tmp/i.db" --quiet > /dev/null 2>&1 || true
  "$exe" report --db "$tmp/i.db" --table cases --format csv |
    python3 -c 'import csv, sys; print(next(csv.DictReader(sys.stdin))["identity"])'
  rm -rf "$tmp"
}

sweep "$orig"
[[ -f $db ]] || { echo "tuned.sh: no store $db" >&2; exit 2; }
set_file=$(mktemp)
trap 'rm -f "$set_file"' EXIT
alone=$out/data/tuned-mlca-k4-$kmax-alone.csv
if ((tune)); then
  # 2a. every vertex link MLCA does not pass, tuned alone
  mkdir -p "$out/data"
  "$exe" report --db "$db" --table cases --format csv \
    --where "kind = 'vertex' AND k BETWEEN 4 AND $kmax AND verdict != 'pass' AND identity = '$(ident "$orig")'" |
    python3 -c 'import csv, sys
for r in sorted(csv.DictReader(sys.stdin), key=lambda r: (int(r["k"]), r["link"])): print(r["link"])' > "$set_file"
  echo "tuned.sh: tune $family on each of the $(wc -l < "$set_file") links MLCA does not pass, alone ($alone_evals evaluations)" >&2
  one=$(mktemp) scratch=$(mktemp)
  echo "link,margin,point" > "$alone.tmp"
  while read -r l; do
    echo "$l" > "$one"
    line=$("$exe" tune "$family" --links "$one" --evals "$alone_evals" -o "$scratch" 2>&1 |
      sed -n 's/^search: .*best smallest margin \([^ ]*\) at \(.*\)$/\1,\2/p') || true
    echo "\"$l\",${line:-,}" >> "$alone.tmp"
  done < "$set_file"
  rm -f "$one" "$scratch"
  mv "$alone.tmp" "$alone"
  # 2b. the tuning set
  "$exe" report --db "$db" --table cases --format csv \
    --where "kind = 'vertex' AND k BETWEEN 9 AND $kmax AND verdict = 'pass' AND scheme = '$(name_of "$orig")'" |
    python3 -c 'import csv, sys
for r in sorted(csv.DictReader(sys.stdin), key=lambda r: (int(r["k"]), r["link"])): print(r["link"])' > "$set_file"
  echo "$finding1" >> "$set_file"
  echo "tuned.sh: tune $family on $(wc -l < "$set_file") links with 9..$kmax vertices (and finding 1), --vertices 4..8, --edges 3..7" >&2
  rc=0
  "$exe" tune "$family" --vertices 4..8 --links "$set_file" --edges 3..7 --evals "$evals" \
    --jobs "$jobs" -o "$tuned" || rc=$?
  ((rc == 0 || rc == 1)) || { echo "tuned.sh: tune ended with status $rc" >&2; exit 1; }
fi
[[ -f $tuned && -f $alone ]] || { echo "tuned.sh: no $tuned or $alone (run without --no-tune)" >&2; exit 2; }
sweep "$tuned"

id_orig=$(ident "$orig") id_tuned=$(ident "$tuned")
where="identity IN ('$id_orig', '$id_tuned')"
md=$out/tuned-mlca-k4-$kmax.md
{
  echo "# MLCA with valence-dependent weights beside MLCA: links with 4..$kmax vertices"
  echo
  echo "Written by \`reports/tuned.sh --max-k $kmax\` (not part of \`./run\`):"
  echo "\`data/stencils/mlca-valence.ini\` (hex masks self 1/8 + 7t/8, the other"
  echo "roles (1 - t)/8, with t = t_n free at n = 6, 10, 12, 14, 16 fine hexes;"
  echo "n = 8, every regular point, is MLCA) tuned by \`subspectra tune\` on every"
  echo "case MLCA passes with 4..$kmax vertices, finding 1's link and edges 3..7,"
  echo "then both files swept with certified verdicts (\`subspectra sweep"
  echo "--stencil F --vertices 4..$kmax --edges 3..10 --certify\`).  The findings:"
  echo "reports/README.md, \"Finding 10\"."
  echo
  echo "Tuned weights (\`data/stencils/mlca-valence-tuned.ini\`; the smallest margin"
  echo "is tune's, over its cases: min(spectral gap, minimum scaled Jacobian)):"
  echo
  grep -E '^t[0-9]+ = ' "$tuned" | sed 's/^/    /'
  echo
  echo "## Vertex links"
  echo
  echo "\`$id_orig\` is \`data/stencils/mlca.ini\` (MLCA), \`$id_tuned\` the tuned file."
  echo
  "$exe" report --db "$db" --where "$where" --table exhaustive
  echo
  echo "## Summary per case kind and k (worst minimum scaled Jacobian, |lambda1|)"
  echo
  "$exe" report --db "$db" --where "$where" --table summary
  echo
  echo "## The links MLCA does not pass, each tuned alone"
  echo
  echo "\`subspectra tune mlca-valence.ini --links ONE --evals $alone_evals\` on each"
  echo "link alone: the best smallest margin found (positive: that link can pass"
  echo "with some t_n; negative: no point of the search made it pass, which is"
  echo "evidence, not proof)."
  echo
  python3 -c 'import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
pos = sum(1 for r in rows if r["margin"] and float(r["margin"]) > 0)
print("%d of %d pass alone." % (pos, len(rows)))
print()
print("| k | link | margin | at |")
print("|--:|---|--:|---|")
for r in sorted(rows, key=lambda r: -float(r["margin"] or "-99")):
    print("| %s | `%s` | %s | %s |" % (r["link"].split()[0], r["link"], r["margin"] or "error", r["point"]))' "$alone"
  echo
  echo "## Links whose verdict changes"
  echo
  "$exe" report --db "$db" --table cases --format csv --where "$where AND kind = 'vertex'" |
    python3 -c '
import csv, sys
orig, tuned = sys.argv[1], sys.argv[2]
def cls(r):  # the first condition that does not pass, as the tables count
    for c in ("eigen_condition", "regularity", "injectivity"):
        if r[c] != "pass":
            return "%s %s" % (r[c], c.replace("eigen_condition", "eigenvalue condition"))
    return "pass"
v = {}
for r in csv.DictReader(sys.stdin):
    v.setdefault(r["link"], {})[r["scheme"]] = (cls(r), r["k"])
rep = sorted((int(x[orig][1]), l, x[orig][0]) for l, x in v.items()
             if orig in x and tuned in x and x[orig][0] != "pass" and x[tuned][0] == "pass")
brk = sorted((int(x[orig][1]), l, x[tuned][0]) for l, x in v.items()
             if orig in x and tuned in x and x[orig][0] == "pass" and x[tuned][0] != "pass")
other = sorted((int(x[orig][1]), l, x[orig][0], x[tuned][0]) for l, x in v.items()
               if orig in x and tuned in x and "pass" not in (x[orig][0], x[tuned][0])
               and x[orig][0] != x[tuned][0])
print("Repaired (do not pass under MLCA, pass tuned): %d" % len(rep))
print()
for k, l, o in rep: print("- k = %d, MLCA: %s: `%s`" % (k, o, l))
print()
print("Broken (pass under MLCA, not tuned): %d" % len(brk))
print()
for k, l, t in brk: print("- k = %d, tuned: %s: `%s`" % (k, t, l))
print()
print("Not passing under either, class changed: %d" % len(other))
print()
for k, l, o, t in other: print("- k = %d, MLCA: %s; tuned: %s: `%s`" % (k, o, t, l))
' "$(name_of "$orig")" "$(name_of "$tuned")"
} > "$md.tmp"
mv "$md.tmp" "$md"
echo "tuned.sh: wrote $md" >&2
