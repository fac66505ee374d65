#!/usr/bin/env bash
# test_report_tex.sh SUBSPECTRA — `report --format tex` compiles with pdflatex
# in a one-column article and fits the page: no LaTeX error, no overfull box
# (the summary of the docs/report.md example was 117 pt too wide, its cases table a
# float 438 pt taller than a page), the cases table runs over pages as a
# longtable with its header repeated, and the labels are set.  Cases: the
# docs/report.md's MLCA sweep (long k = 9 links, a failing case's reasons) and a
# box-spline sweep (the extra column of improper diagonal pairs).  Without
# pdflatex (./run installs texlive-latex-recommended) it is SKIPPED (77).
set -u
exe=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
. "$(dirname "$0")/../ss_expect.sh"
command -v pdflatex >/dev/null || { echo "SKIP: pdflatex not installed"; exit 77; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp" || exit 1
# (a sweep exits 1 when some case fails, as these do)
"$exe" sweep --scheme mlca --vertices 4..9 --edges 3..8 --db mlca.db >/dev/null 2>&1
[ $? -le 1 ] || fail "mlca sweep"
"$exe" sweep --scheme boxspline --vertices 5..7 --edges 4..6 --db box.db >/dev/null 2>&1
[ $? -le 1 ] || fail "boxspline sweep"
"$exe" report --db mlca.db --format tex --label mlca >mlca.tex || fail "report mlca"
"$exe" report --db box.db --format tex --label box >box.tex || fail "report box"
cat >doc.tex <<'TEX'
\documentclass{article}
\usepackage{booktabs,longtable,array}
\begin{document}
See tables~\ref{tab:mlca-cases}, \ref{tab:mlca-summary}, \ref{tab:box-cases} and
\ref{tab:box-summary}.
\input{mlca.tex}
\input{box.tex}
\end{document}
TEX
# twice: longtable settles its column widths and the references on the second run
for pass in 1 2; do
  checks=$((checks + 1))
  timeout $((120 * ${SS_TIMEOUT_MULTIPLIER:-1})) pdflatex -interaction=nonstopmode \
    -halt-on-error doc.tex >/dev/null 2>&1 || fail "pdflatex pass $pass: $(grep -m3 -A2 '^!' doc.log)"
done
checks=$((checks + 1))
grep -E '^(Overfull|Underfull) \\[hv]box' doc.log | grep -v Underfull >bad.txt
[ -s bad.txt ] && fail "boxes that do not fit: $(head -3 bad.txt)"
checks=$((checks + 1))
grep -qE 'Float too large|undefined|Label\(s\) may have changed' doc.log &&
  fail "float too large, undefined reference or unsettled labels: $(grep -m3 -E 'Float too large|undefined|Label' doc.log)"
# the MLCA case table is longer than a page: the header repeats
checks=$((checks + 1))
pages=$(grep -oE 'Output written on doc.pdf \(([0-9]+) page' doc.log | grep -oE '[0-9]+ page' | grep -oE '[0-9]+')
[ "${pages:-0}" -ge 3 ] || fail "expected the case tables over several pages, got ${pages:-?}"
checks=$((checks + 1))
grep -q '\\endhead' mlca.tex && grep -q '(continued)' mlca.tex || fail "no repeated header"
checks=$((checks + 1))
[ "$(grep -c '\\label{tab:mlca-' mlca.tex)" = 2 ] && [ "$(grep -c '\\label{tab:box-' box.tex)" = 2 ] ||
  fail "labels"
expect_in 2 "--label 'a b'" "" "$exe" report --db mlca.db --format tex --label "a b"
expect_in 2 "--label is for --format tex" "" "$exe" report --db mlca.db --label x
expect_done "report_tex"
