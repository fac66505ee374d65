#!/usr/bin/env bash
# test_reproduce.sh EXE SRCDIR — `subspectra reproduce`: usage errors (exit 2),
# a malformed reference file named by file and line (exit 2), a malformed
# tables file (data/reproduce/tables.json) named by file and entry or line
# (exit 2), then a full run
# into a temporary folder: every table (.md, .tsv, data/.jsonl) and figure is
# written, the regular cases and MLCA's edges equal values derived
# independently (B-spline spectra, tensor products of two tables), the papers'
# quoted values that match still match, and the only comparisons that differ
# from the papers are the known ones listed below.  The summary lines
# ("22 of 23 cases pass ...") are REGRESSION PINS: the program's own counts,
# kept to notice any change, not a reproduction by themselves.
set -u
exe=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
. "$(dirname "$0")/../ss_expect.sh"
ref=$src/data/reference
tables=$src/data/reproduce/tables.json

expect 0 "usage: subspectra reproduce" "$exe" reproduce --help
expect 2 "unknown option '--bogus'" "$exe" reproduce --bogus
expect 2 "unexpected argument 'x'" "$exe" reproduce --reference "$ref" x
expect 2 "no reference files" "$exe" reproduce --reference "$tmp/none" --out "$tmp/o"
: > "$tmp/file"
# (the tables are found beside --reference: DIR/../reproduce/tables.json)
expect 2 "--out $tmp/file/sub: cannot create" "$exe" reproduce --reference "$ref" --out "$tmp/file/sub"
mkdir -p "$tmp/badref"
cp "$ref"/*.tsv "$tmp/badref/"
printf 'p.txt\tsection 1\tmlca\tvertex\t4..8\t-\tlambda1\t0.5.1\tquote\tnote\n' >> "$tmp/badref/mlca-hexahedral-subdivision.tsv"
line=$(wc -l < "$tmp/badref/mlca-hexahedral-subdivision.tsv")
expect 2 "badref/mlca-hexahedral-subdivision.tsv:$line: value '0.5.1'" "$exe" reproduce --reference "$tmp/badref" --out "$tmp/o"

# the tables file: every key checked, the entry and key named
expect 2 "$tmp/none.json: No such file or directory \\(the tables to make\\)" "$exe" reproduce --reference "$ref" --tables "$tmp/none.json" --out "$tmp/o"
printf '{"tables": [\n  {"name": "t",\n' > "$tmp/t.json"
expect 2 "t.json:3: not JSON: unexpected end of data" "$exe" reproduce --reference "$ref" --tables "$tmp/t.json" --out "$tmp/o"
tab='"name": "t", "title": "T", "scheme": "loop", "case": "surface-vertex", "command": "c"'
printf '{"tables": [{%s, "source": "valences", "from": 3, "to": 4, "colour": 1}], "figures": []}' "$tab" > "$tmp/t.json"
expect 2 "t.json: table 1: colour: unknown key" "$exe" reproduce --reference "$ref" --tables "$tmp/t.json" --out "$tmp/o"
printf '{"tables": [{%s, "source": "links", "from": 4, "to": 5}], "figures": []}' "$tab" > "$tmp/t.json"
expect 2 "t.json: table 1: case: not a case kind this source yields" "$exe" reproduce --reference "$ref" --tables "$tmp/t.json" --out "$tmp/o"
printf '{"tables": [{%s, "source": "valences", "from": 5, "to": 4}], "figures": []}' "$tab" > "$tmp/t.json"
expect 2 "t.json: table 1: to: 4 not in 5..1000" "$exe" reproduce --reference "$ref" --tables "$tmp/t.json" --out "$tmp/o"
printf '{"tables": [], "figures": [{"file": "f.png", "scheme": "mlca", "case": "edge"}]}' > "$tmp/t.json"
expect 2 "t.json: figure 1: valence: missing" "$exe" reproduce --reference "$ref" --tables "$tmp/t.json" --out "$tmp/o"

printf '{"tables": [{%s, "source": "valences", "from": 3, "to": 4, "psi_depth": 9}], "figures": []}' "$tab" > "$tmp/t.json"
expect 2 "t.json: table 1: psi_depth: 9 not in 0..8" "$exe" reproduce --reference "$ref" --tables "$tmp/t.json" --out "$tmp/o"
# source list: labelled links, each checked
vtab='"name": "t", "title": "T", "scheme": "boxspline", "case": "vertex", "command": "c"'
printf '{"tables": [{%s, "source": "list"}], "figures": []}' "$vtab" > "$tmp/t.json"
expect 2 "t.json: table 1: links: missing" "$exe" reproduce --reference "$ref" --tables "$tmp/t.json" --out "$tmp/o"
printf '{"tables": [{%s, "source": "list", "links": [{"label": "5"}]}], "figures": []}' "$vtab" > "$tmp/t.json"
expect 2 "t.json: table 1: links: not an array of" "$exe" reproduce --reference "$ref" --tables "$tmp/t.json" --out "$tmp/o"
printf '{"tables": [{%s, "source": "links", "from": 4, "to": 5, "links": [{"label": "5", "link": "tetrahedron"}]}], "figures": []}' "$vtab" > "$tmp/t.json"
expect 2 "t.json: table 1: links: only for source list" "$exe" reproduce --reference "$ref" --tables "$tmp/t.json" --out "$tmp/o"
printf '{"tables": [{%s, "source": "list", "links": [{"label": "x", "link": "cube"}]}], "figures": []}' "$vtab" > "$tmp/t.json"
expect 2 "t: link x: " "$exe" reproduce --reference "$ref" --tables "$tmp/t.json" --out "$tmp/o"

# the full run (about a minute): the tables without psi_depth, whose verdicts
# on psi the `reports` test compares byte for byte; the values checked here do
# not depend on it
out=$tmp/out
python3 -c 'import json, sys
t = json.load(open(sys.argv[1]))
for x in t["tables"]:
    x.pop("psi_depth", None)
json.dump(t, open(sys.argv[2], "w"))' "$tables" "$tmp/tables-nopsi.json"
SS_EXPECT_TIMEOUT=280 expect 0 "reproduce: wrote 21 tables" "$exe" reproduce --reference "$ref" --tables "$tmp/tables-nopsi.json" --out "$out"

tables="mlca-vertices-k4-8 mlca-vertices-k9-10 tetoct-vertices-k4-7 tetoct-vertices-k8-10 tetoct-edges-3-10 tetoct-face
mlca-edges-3-8 mlca-surface-vertices-3-8 catmull-clark-surface-vertices-3-8
boxspline-vertices-5-22 boxspline-vertices-5-22-proper boxspline-vertices-table2 boxspline-edges-4-9-skew
boxspline-edges-4-9-center boxspline-avg-vertices-5-22 boxspline-avg-edges-4-9
ccsolid-vertices-k4-9 ccsolid-edges-3-10 quasi48-surface-vertices-3-16"
for t in $tables; do
  checks=$((checks + 1))
  for f in "$out/$t.md" "$out/$t.tsv" "$out/data/$t.jsonl"; do
    [ -s "$f" ] || fail "$f missing or empty"
  done
  grep -q '^\*\*Summary:\*\* ' "$out/$t.md" || fail "$t.md: no summary line"
  grep -q 'relative tolerance 1e-06' "$out/$t.md" || fail "$t.md: no tolerance"
done
for f in mlca-vertex-k4 mlca-vertex-k5 mlca-vertex-regular mlca-vertex-k7-bipyramid \
  mlca-vertex-k8-finding tetoct-vertex-k4 tetoct-edge-3 catmull-clark-3 \
  boxspline-edge-9-skew boxspline-edge-9-center-forced boxspline-vertex-k5-bipyramid; do
  checks=$((checks + 1))
  head -c 8 "$out/figures/$f.png" 2>/dev/null | grep -q PNG || fail "figure $f.png missing"
  # its caption is in the report, not in the picture
  checks=$((checks + 1))
  grep -q "^!\[$f.png\]($f.png)" "$out/figures/README.md" || fail "no caption for $f.png"
done
# the regular MLCA vertex: the tricubic lambda1..3 = 1/2 and a pass (derived, not read off)
checks=$((checks + 1))
grep -A2 '^!\[mlca-vertex-regular.png\]' "$out/figures/README.md" |
  grep -q 'λ1..3 = 0.500000 0.500000 0.500000; regularity: pass' ||
  fail "caption of the regular MLCA vertex"
# every figure shows what analyze judges (issue 33: one pipeline): its
# caption's case kind, regularity verdict and minimum scaled Jacobian (to
# the 4 digits printed) are analyze --format json's for the same case, the
# edge points (MLCA's bipyramids) and box-spline's labelling-dependent
# diagonals included; forced pictures say so instead
bad=$(python3 - "$src/data/reproduce/tables.json" "$out/figures/README.md" "$exe" <<'PY'
import json, re, subprocess, sys
figs = json.load(open(sys.argv[1]))["figures"]
text = open(sys.argv[2]).read()
for f in figs:
    m = re.search(r"^!\[" + re.escape(f["file"]) + r"\].*?\n\n(.*?)\n", text, re.M | re.S)
    if not m:
        print(f["file"], "no caption"); continue
    cap = m.group(1)
    args = ["--scheme", f["scheme"], "--diagonals", f.get("diagonals", "bfs")]
    if f["case"] == "vertex": args += ["--vertex", f["link"]]
    elif f["case"] == "face": args += ["--face"]
    else: args += ["--" + f["case"], str(f["valence"])]
    r = subprocess.run([sys.argv[3], "analyze", "--format", "json"] + args,
                       capture_output=True, text=True)
    j = json.loads(r.stdout)
    if not cap.startswith("%s, %s " % (f["scheme"], j["case"])):
        print(f["file"], "caption case", cap[:40], "analyze", j["case"])
    if f.get("force") and j["regularity"]["min_scaled_jacobian"] is None:
        if "forced: NOT a characteristic map" not in cap: print(f["file"], "forced, not said")
        continue
    want = "regularity: %s, minimum scaled Jacobian %.4f" % (
        j["regularity"]["verdict"], j["regularity"]["min_scaled_jacobian"])
    if want not in cap: print(f["file"], "caption", cap[:200], "want", want)
PY
)
checks=$((checks + 1))
[ -z "$bad" ] || fail "figures disagree with analyze: $bad"
checks=$((checks + 1))
[ "$(ls "$out"/data/*.jsonl | wc -l)" -eq 21 ] || fail "expected 21 JSON-lines files"
# the ccsolid tables put MLCA beside every case
for t in ccsolid-vertices-k4-9 ccsolid-edges-3-10; do
  checks=$((checks + 1))
  grep -q '^## Beside mlca' "$out/$t.md" && grep -q '^\*\*Side by side:\*\* ' "$out/$t.md" ||
    fail "$t.md: no side-by-side section"
done
# JSON keys that scripts rely on (DESIGN section 7)
checks=$((checks + 1))
grep -q '"scheme":"mlca","case":"vertex","link":"4 bcd,adc,abd,acb","k":4,"two_ring_size":' "$out/data/mlca-vertices-k4-8.jsonl" ||
  fail "mlca-vertices-k4-8.jsonl: keys"
grep -q '"eigen_condition":{"verdict":"pass","certified":false,"reason":"","judged_on":"spectrum","tolerance":' "$out/data/tetoct-face.jsonl" ||
  fail "tetoct-face.jsonl: eigen_condition"

# the joint spectral radius tables: derived independently, not pasted output.
# The face threshold is 1/4 exactly (C^2: below the sixfold 1/4); every row's
# verdict must agree with its bounds (pass iff upper < threshold, fail iff
# lower >= threshold), lower <= upper, and the budget is printed.
for t in tetoct-jsr boxspline-jsr; do
  checks=$((checks + 1))
  for f in "$out/$t.md" "$out/$t.tsv" "$out/data/$t.jsonl"; do
    [ -s "$f" ] || fail "$f missing or empty"
  done
  grep -q 'at most 10000 products' "$out/$t.md" || fail "$t.md: no node budget"
  awk -F'\t' '!/^#/ && $1 != "case" && $9 != "n/a" && NF == 13 {
    lo = $6 + 0; up = $7 + 0; th = $8 + 0
    want = up < th ? "pass" : (lo >= th ? "fail" : "undecided")
    if ($9 != want || lo > up) { print "bad row: " $0; bad = 1 }
    if ($1 ~ /^face/ && $8 != "0.25") { print "face threshold " $8; bad = 1 } }
    END { exit bad }' "$out/$t.tsv" || fail "$t.tsv: verdict or threshold inconsistent"
done
checks=$((checks + 1))
grep -q '^face (bfs)	jsr_verdict	pass	pass	match' "$out/tetoct-jsr.tsv" &&
  grep -q '^face (bfs)	jsr_threshold	1/4	0.25	match' "$out/tetoct-jsr.tsv" ||
  fail "tetoct-jsr.tsv: the paper's face statement not compared"

# each table's summary: cases passing both conditions, quoted values compared
# and matching, rows not quoted
# (ccsolid: edges 8..10 fail as MLCA's do, the surface factor's w = +-2 pair
# reaching 1/2, a mode test_ccsolid shows to be the tensor product's; of the
# vertices the tetrahedral link (lambda1 < 0) and two links with 9 vertices
# (folds) fail; docs/schemes.md "Catmull-Clark solids")
want_summary="boxspline-avg-edges-4-9: 6 of 6 cases pass both conditions; 0 quoted values: 0 match, 0 differ; 6 rows not quoted
boxspline-avg-vertices-5-22: 16 of 18 cases pass both conditions; 0 quoted values: 0 match, 0 differ; 18 rows not quoted
boxspline-edges-4-9-center: 4 of 6 cases pass both conditions; 29 quoted values: 15 match, 14 differ; 0 rows not quoted
boxspline-edges-4-9-skew: 6 of 6 cases pass both conditions; 52 quoted values: 43 match, 9 differ; 0 rows not quoted
boxspline-vertices-5-22: 16 of 18 cases pass both conditions; 36 quoted values: 36 match, 0 differ; 0 rows not quoted
boxspline-vertices-5-22-proper: 16 of 18 cases pass both conditions; 36 quoted values: 36 match, 0 differ; 0 rows not quoted
boxspline-vertices-table2: 17 of 22 cases pass both conditions; 159 quoted values: 153 match, 6 differ; 0 rows not quoted
catmull-clark-surface-vertices-3-8: 6 of 6 cases pass both conditions; 24 quoted values: 24 match, 0 differ; 0 rows not quoted
mlca-edges-3-8: 5 of 6 cases pass both conditions; 0 quoted values: 0 match, 0 differ; 6 rows not quoted
mlca-surface-vertices-3-8: 6 of 6 cases pass both conditions; 18 quoted values: 18 match, 0 differ; 0 rows not quoted
mlca-vertices-k4-8: 22 of 23 cases pass both conditions; 41 quoted values: 40 match, 1 differ; 3 rows not quoted
tetoct-edges-3-10: 8 of 8 cases pass both conditions; 30 quoted values: 24 match, 6 differ; 0 rows not quoted
tetoct-face: 1 of 1 cases pass both conditions; 12 quoted values: 12 match, 0 differ; 0 rows not quoted
tetoct-vertices-k4-7: 9 of 9 cases pass both conditions; 18 quoted values: 18 match, 0 differ; 0 rows not quoted
ccsolid-edges-3-10: 5 of 8 cases pass both conditions; 0 quoted values: 0 match, 0 differ; 8 rows not quoted
ccsolid-vertices-k4-9: 70 of 73 cases pass both conditions; 0 quoted values: 0 match, 0 differ; 73 rows not quoted
quasi48-surface-vertices-3-16: 20 of 20 cases pass both conditions; 0 quoted values: 0 match, 0 differ; 20 rows not quoted"
got_summary=$(cd "$out" && for f in *.tsv; do
  case $f in (*-k9-10.tsv | *-k8-10.tsv | *-jsr.tsv) continue ;; esac # checked below
  sed -n 's/^# summary: /'"${f%.tsv}"': /p' "$f"
done | LC_ALL=C sort)
checks=$((checks + 1))
want_summary=$(LC_ALL=C sort <<<"$want_summary")
[ "$got_summary" = "$want_summary" ] ||
  fail "summaries differ:$(diff <(echo "$want_summary") <(echo "$got_summary"))"

# The comparisons known to differ, each explained in reports/README.md:
#  - finding 1: the MLCA link with k = 8 whose characteristic map folds
#    (the paper reports every topology with at most 12 hexes regular);
#  - tet/oct edges of valence 3..5: the paper's form 1, lambda1, lambda1, 1/2
#    holds in that order from valence 6 on; below, 1/2 (along the edge) leads;
#  - box-spline edges: the paper's S_e has 4k + 3 points (the once-subdivided
#    star of a finite edge), our two-ring is the support neighbourhood of a
#    point on an edge; with diagonals toward the centre our smallest invariant
#    one-ring has 3n + 3 points, not the paper's 2k + 3;
#  - box-spline Tables 2 and 3: six eigenvalues printed 1 or 2 units off in
#    their sixth digit (0.312499 for 5/16, 0.249998 and 0.250002 for 1/4,
#    0.480204 and 0.480206 for the 0.480205 of other rows, 0.270178 for
#    0.2701797);
#  - Appendix B.2: the eleventh of S_e's listed eigenvalues, 1/8, is the last
#    of its 11 x 11 block, our lambda10 is 0.15 from outside it; S'_e's list
#    has (25 + sqrt 385)/160 = 0.2789 where ours has a sixth 1/4.
want_differ="boxspline-edges-4-9-center	n = 4	lambda4
boxspline-edges-4-9-center	n = 4	mult5
boxspline-edges-4-9-center	n = 4	one_ring
boxspline-edges-4-9-center	n = 4	two_ring
boxspline-edges-4-9-center	n = 5	one_ring
boxspline-edges-4-9-center	n = 5	two_ring
boxspline-edges-4-9-center	n = 6	one_ring
boxspline-edges-4-9-center	n = 6	two_ring
boxspline-edges-4-9-center	n = 7	one_ring
boxspline-edges-4-9-center	n = 7	two_ring
boxspline-edges-4-9-center	n = 8	one_ring
boxspline-edges-4-9-center	n = 8	two_ring
boxspline-edges-4-9-center	n = 9	one_ring
boxspline-edges-4-9-center	n = 9	two_ring
boxspline-edges-4-9-skew	n = 4	lambda10
boxspline-edges-4-9-skew	n = 4	two_ring
boxspline-edges-4-9-skew	n = 7	lambda3
boxspline-edges-4-9-skew	n = 9	lambda3
boxspline-vertices-table2	k = 12, 12	lambda4
boxspline-vertices-table2	k = 16, 16	lambda3
boxspline-vertices-table2	k = 20, 20(b)	lambda3
boxspline-vertices-table2	k = 6, 6	lambda1
boxspline-vertices-table2	k = 8, 8(a)	lambda4
boxspline-vertices-table2	k = 8, 8(b)	lambda4
boxspline-edges-4-9-skew	n = 5	two_ring
boxspline-edges-4-9-skew	n = 6	two_ring
boxspline-edges-4-9-skew	n = 7	two_ring
boxspline-edges-4-9-skew	n = 8	two_ring
boxspline-edges-4-9-skew	n = 9	two_ring
mlca-vertices-k4-8	k = 8	regularity
tetoct-edges-3-10	n = 3	lambda3
tetoct-edges-3-10	n = 3	mult1
tetoct-edges-3-10	n = 4	lambda3
tetoct-edges-3-10	n = 4	mult1
tetoct-edges-3-10	n = 5	lambda3
tetoct-edges-3-10	n = 5	mult1"
got_differ=$(cd "$out" && awk -F'\t' '!/^#/ && $10 == "differ" && $1 !~ /-k(9-10|8-10)$/ {print $1 "\t" $3 "\t" $5}' *.tsv | LC_ALL=C sort)
checks=$((checks + 1))
want_differ=$(LC_ALL=C sort <<<"$want_differ")
[ "$got_differ" = "$want_differ" ] ||
  fail "unexpected differences from the papers:$(diff <(echo "$want_differ") <(echo "$got_differ"))"
checks=$((checks + 1))
grep -q "| 5 | \`8 bcdefgh,ahc,abhd,ache,adhf,aehg,afh,agfedcb\` | 8 | 12 |.*| \*\*differ\*\* |" "$out/mlca-vertices-k4-8.md" ||
  fail "mlca-vertices-k4-8.md: the k = 8 finding is not marked as differ"
# The exhaustive tables beyond k = 8 (findings 5 and 6): both papers say
# every link they enumerated (k <= 12 for MLCA, k <= 10 for tet/oct) passes,
# so a row differs exactly when our verdict is not a pass.  Recounted here
# from the JSON lines, independently of the table writer: per case, the
# quoted verdicts that differ are the eigenvalue condition when it does not
# pass and the regularity when it does not pass; points on an edge (the
# bipyramid links, judged as edges) are not compared.
for t in mlca-vertices-k9-10 tetoct-vertices-k8-10; do
  checks=$((checks + 1))
  want=$(python3 -c '
import json, sys
n = 0
for line in open(sys.argv[1]):
    o = json.loads(line)
    if o["case"] == "edge-point":  # judged as an edge: not quoted as a vertex
        continue
    n += (o["eigen_condition"]["verdict"] != "pass") + (o["regularity"]["verdict"] != "pass")
print(n)' "$out/data/$t.jsonl")
  got=$(awk -F'\t' '!/^#/ && $10 == "differ"' "$out/$t.tsv" | wc -l)
  [ -n "$want" ] && [ "$got" -eq "$want" ] && [ "$got" -gt 0 ] ||
    fail "$t: $got quoted verdicts differ, the JSON lines say $want"
done
# Values derived independently of the program, from the JSON lines written
# above (a wrong local matrix or Jacobian changes them):
#  - the regular MLCA cases are the B-spline: the vertex with the octahedral
#    link and the edge of valence 4 have the tricubic spectrum 1, 1/2 (x3),
#    1/4 (x6), the surface vertex of valence 4 the bicubic 1, 1/2 (x2), 1/4
#    (x3); their characteristic maps are linear, so the minimum scaled
#    Jacobian is 1;
#  - MLCA along an edge of valence n is the tensor product of its surface rule
#    at valence n and the cubic curve (the limit paper's eq. (1), which MLCA
#    keeps): the edge's leading eigenvalues are the largest products of the
#    surface vertex's eigenvalues with 1, 1/2, 1/4, 1/8 — two tables checked
#    against each other, n = 3..8.
checks=$((checks + 1))
python3 - "$out/data" <<'PYEOF' || fail "reproduced MLCA values differ from the B-spline / tensor-product values"
import json, sys
d = sys.argv[1]
def rows(t):
    return [json.loads(l) for l in open(f"{d}/{t}.jsonl")]
def vals(o, m):
    return [e["re"] for e in o["eigenvalues"]][:m]
bad = []
def close(a, b, what, tol=1e-10):
    if len(a) != len(b) or any(abs(x - y) > tol for x, y in zip(a, b)):
        bad.append(f"{what}: {a} vs {b}")
tri = [1.0] + [0.5] * 3 + [0.25] * 6
octa = [o for o in rows("mlca-vertices-k4-8")
        if o["k"] == 6 and all(len(f) == 4 for f in o["link"].split()[1].split(","))]
if len(octa) != 1:
    bad.append(f"{len(octa)} octahedral links in mlca-vertices-k4-8")
edges = {o["valence"]: o for o in rows("mlca-edges-3-8")}
surf = {o["valence"]: o for o in rows("mlca-surface-vertices-3-8")}
for what, o, want in [("vertex, octahedral link", octa[0] if octa else None, tri),
                      ("edge 4", edges.get(4), tri),
                      ("surface vertex 4", surf.get(4), [1.0, 0.5, 0.5, 0.25, 0.25, 0.25])]:
    if o is None:
        bad.append(f"{what}: missing"); continue
    close(vals(o, len(want)), want, what)
    sj = o["regularity"]["min_scaled_jacobian"]
    if abs(sj - 1) > 1e-9:
        bad.append(f"{what}: min scaled Jacobian {sj}, not 1")
for n in range(3, 9):
    s = vals(surf[n], 16)
    prod = sorted((a * b for a in s for b in (1, 0.5, 0.25, 0.125)), reverse=True)
    close(vals(edges[n], 8), prod[:8], f"edge {n} vs surface {n} x curve")
if bad:
    print("\n".join(bad)); sys.exit(1)
PYEOF
# quasi48 (issue 19), derived without the program: the regular 4-8 vertex
# (class 4 with valence 4, class 8 with valence 8) generates cubics (the dyadic
# symbol's zeros at the other cosets are of order 4, docs/schemes.md "Quasi 4-8
# surfaces"), so its leading eigenvalues are 1, 1/2 x2, 1/4 x3, 1/8 x4; a
# class-4 vertex of valence n is a class-8 vertex of valence 2n after one
# binary step, so those rows agree (n = 3..8); quasi48 is shown beside Loop
# and Catmull-Clark at the same valences.
for vs in loop catmull-clark; do
  checks=$((checks + 1))
  grep -q "^## Beside $vs" "$out/quasi48-surface-vertices-3-16.md" ||
    fail "quasi48-surface-vertices-3-16.md: no side-by-side section for $vs"
done
checks=$((checks + 1))
python3 - "$out/data/quasi48-surface-vertices-3-16.jsonl" <<'PYEOF' || fail "reproduced quasi48 values differ from the 4-8 closed forms"
import json, sys
rows = {(o["valence"], o["class"]): o for o in map(json.loads, open(sys.argv[1]))}
bad = []
want = [1.0, 0.5, 0.5] + [0.25] * 3 + [0.125] * 4
for key in [(4, 4), (8, 8)]:
    ev = [e["re"] for e in rows[key]["eigenvalues"]][:10]
    if any(abs(a - b) > 1e-9 for a, b in zip(ev, want)) or len(ev) != 10:
        bad.append(f"regular {key}: {ev}")
for n in range(3, 9):
    a, b = rows.get((n, 4)), rows.get((2 * n, 8))
    if not a or not b or [e["re"] for e in a["eigenvalues"]] != [e["re"] for e in b["eigenvalues"]]:
        bad.append(f"class 4 valence {n} differs from class 8 valence {2 * n}")
if sorted(rows) != sorted([(n, 4) for n in range(3, 17)] + [(n, 8) for n in range(6, 17, 2)]):
    bad.append(f"cases: {sorted(rows)}")
if bad:
    print("\n".join(bad)); sys.exit(1)
PYEOF
# box-spline Table 2 (issue 38): the computed values are analyze's — row
# 10(a) recomputed by a separate `analyze` call of its link from tables.json,
# lambda1..5 equal to the TSV's computed column (printed %.9g) — and the rows
# k = 2n + 2 that are the links of edge midpoints have the spectrum of the
# edge of valence n with skew diagonals (the vertex the midpoint becomes is
# the edge point: two tables checked against each other, n = 4..9)
checks=$((checks + 1))
python3 - "$out" "$src/data/reproduce/tables.json" "$exe" <<'PYEOF' || fail "box-spline Table 2 rows are not analyze's / the edge spectra"
import json, subprocess, sys
out, spec, exe = sys.argv[1:]
t2 = next(t for t in json.load(open(spec))["tables"] if t["name"] == "boxspline-vertices-table2")
links = {x["label"]: x["link"] for x in t2["links"]}
r = subprocess.run([exe, "analyze", "--scheme", "boxspline", "--vertex", links["10(a)"],
                    "--format", "json"], capture_output=True, text=True)
ev = [e["re"] for e in json.loads(r.stdout)["eigenvalues"]]
got = {}
for line in open(f"{out}/boxspline-vertices-table2.tsv"):
    f = line.rstrip("\n").split("\t")
    if len(f) == 13 and f[2] == "k = 10, 10(a)" and f[4].startswith("lambda"):
        got[int(f[4][6:])] = f[6]
bad = []
if sorted(got) != [1, 2, 3, 4, 5]:
    bad.append(f"10(a): compared {sorted(got)}")
for i, v in got.items():
    if v != "%.9g" % ev[i]:
        bad.append(f"10(a) lambda{i}: table {v}, analyze {ev[i]!r}")
vert = {}
for line in open(f"{out}/data/boxspline-vertices-table2.jsonl"):
    o = json.loads(line)
    vert[o["link"]] = [e["re"] for e in o["eigenvalues"]][:6]
edge = {o["valence"]: [e["re"] for e in o["eigenvalues"]][:6]
        for o in map(json.loads, open(f"{out}/data/boxspline-edges-4-9-skew.jsonl"))}
for n, lab in zip(range(4, 10), ["10(a)", "12", "14(b)", "16", "18(b)", "20(b)"]):
    r = subprocess.run([exe, "analyze", "--scheme", "boxspline", "--vertex", links[lab],
                        "--format", "json"], capture_output=True, text=True)
    v = vert.get(json.loads(r.stdout)["link"])
    if v is None or any(abs(a - b) > 1e-9 for a, b in zip(v, edge[n])):
        bad.append(f"row {lab}: {v} vs edge {n}: {edge[n]}")
if bad:
    print("\n".join(bad)); sys.exit(1)
PYEOF
# the tet/oct paper's joint spectral radius statements (Appendix A): the
# face's rho^[9] = 0.238 differs from ours (0.1769, in the inf-norm with our
# complement's basis; README), the edge of valence 3 the paper left open
# passes (finding 9), valences 4..10 pass as it says; our rho^[9] lies between
# the certified lower bound and rho^[6] (rho_k >= JSR for every k, and the
# profile falls here)
checks=$((checks + 1))
want_jsr="edge 10 (bfs)	jsr_verdict	pass	pass	match
edge 3 (bfs)	jsr_verdict	undecided	pass	differ
edge 4 (bfs)	jsr_verdict	pass	pass	match
edge 5 (bfs)	jsr_verdict	pass	pass	match
edge 6 (bfs)	jsr_verdict	pass	pass	match
edge 7 (bfs)	jsr_verdict	pass	pass	match
edge 8 (bfs)	jsr_verdict	pass	pass	match
edge 9 (bfs)	jsr_verdict	pass	pass	match
face (bfs)	jsr_rho9	0.238	RHO9	differ
face (bfs)	jsr_threshold	1/4	0.25	match
face (bfs)	jsr_verdict	pass	pass	match"
rho9=$(awk -F'\t' '$2 == "jsr_rho9" {print $4}' "$out/tetoct-jsr.tsv")
got_jsr=$(awk -F'\t' 'NF == 6 && $2 ~ /^jsr_/ {print $1 "\t" $2 "\t" $3 "\t" $4 "\t" $5}' "$out/tetoct-jsr.tsv" | LC_ALL=C sort)
[ "$got_jsr" = "$(LC_ALL=C sort <<<"${want_jsr/RHO9/$rho9}")" ] ||
  fail "tetoct-jsr.tsv: the paper's statements:$(diff <(LC_ALL=C sort <<<"${want_jsr/RHO9/$rho9}") <(echo "$got_jsr"))"
checks=$((checks + 1))
python3 - "$out/data/tetoct-jsr.jsonl" "$rho9" <<'PYEOF' || fail "rho^[9] = $rho9 outside [lower, rho^[6]] of the face"
import json, sys
face = next(o for o in map(json.loads, open(sys.argv[1])) if o["case"] == "face")
r9 = float(sys.argv[2])
sys.exit(0 if face["lower"] <= r9 <= face["rho_k"][5] else 1)
PYEOF

# mutations: a quoted value changed in a copy of the reference files is
# compared, not copied — Table 2's row 7 lambda1 0.327254 -> 0.327264 differs,
# rho^[9] 0.238 -> 0.177 (ours, 0.176898, within half a unit) now matches,
# figure 15's nine MLCA topologies -> 10 differs
mkdir -p "$tmp/mutref"
cp "$ref"/*.tsv "$tmp/mutref/"
sed -i 's/^\(box-spline-solid-subdivision.txt\tTable 2, row 7\t.*\tlambda1\t\)0\.327254\t/\10.327264\t/' "$tmp/mutref/box-spline-solid-subdivision.tsv"
sed -i 's/\tjsr_rho9\t0\.238\t/\tjsr_rho9\t0.177\t/' "$tmp/mutref/tetrahedral-octahedral-subdivision.tsv"
sed -i 's/\tlinks\t9\t/\tlinks\t10\t/' "$tmp/mutref/mlca-hexahedral-subdivision.tsv"
checks=$((checks + 1))
[ "$(grep -c $'\tlambda1\t0.327264\t' "$tmp/mutref/box-spline-solid-subdivision.tsv")" = 1 ] &&
  [ "$(grep -c $'\tjsr_rho9\t0.177\t' "$tmp/mutref/tetrahedral-octahedral-subdivision.tsv")" = 1 ] &&
  [ "$(grep -c $'\tlinks\t10\t' "$tmp/mutref/mlca-hexahedral-subdivision.tsv")" = 1 ] ||
  fail "mutations not applied"
python3 -c 'import json, sys
t = json.load(open(sys.argv[1]))
t["tables"] = [x for x in t["tables"] if x["name"] in ("boxspline-vertices-table2", "mlca-vertices-k4-8")]
for x in t["tables"]:
    x.pop("psi_depth", None)
t["figures"] = []
json.dump(t, open(sys.argv[2], "w"))' "$src/data/reproduce/tables.json" "$tmp/mut.json"
SS_EXPECT_TIMEOUT=200 expect 0 "reproduce: wrote 4 tables" "$exe" reproduce --reference "$tmp/mutref" --tables "$tmp/mut.json" --out "$tmp/mut"
checks=$((checks + 1))
awk -F'\t' '$3 == "k = 7, 7" && $5 == "lambda1" && $6 == "0.327264" && $10 == "differ"' "$tmp/mut/boxspline-vertices-table2.tsv" | grep -q . &&
  awk -F'\t' '$3 == "k = 7, 7" && $5 == "lambda1" && $6 == "0.327254" && $10 == "match"' "$out/boxspline-vertices-table2.tsv" | grep -q . ||
  fail "Table 2 row 7: a wrong quoted lambda1 is not reported as a difference"
checks=$((checks + 1))
grep -q "^face (bfs)	jsr_rho9	0.177	$rho9	match" "$tmp/mut/tetoct-jsr.tsv" ||
  fail "rho^[9]: a quoted 0.177 does not match ours ($rho9)"
checks=$((checks + 1))
awk -F'\t' '$2 == "-" && $3 == "k = 4..7" && $5 == "links" && $6 == "10" && $7 == "9" && $10 == "differ"' "$tmp/mut/mlca-vertices-k4-8.tsv" | grep -q . &&
  awk -F'\t' '$3 == "k = 4..7" && $5 == "links" && $6 == "9" && $7 == "9" && $10 == "match"' "$out/mlca-vertices-k4-8.tsv" | grep -q . ||
  fail "figure 15: the count of links with k <= 7 is not compared"

# the face spectrum of the tet/oct paper, value by value
checks=$((checks + 1))
[ "$(awk -F'\t' '$1 == "tetoct-face" && $5 ~ /^lambda/ && $10 == "match"' "$out/tetoct-face.tsv" | wc -l)" -eq 9 ] ||
  fail "tetoct-face: lambda1..9 do not all match 1/2, 1/4"
expect_done reproduce
