#!/usr/bin/env bash
# test_analyze_cli.sh EXE — `subspectra analyze` and `subspectra matrix` from the
# outside: the JSON contract (DESIGN section 7), one object per input line,
# TSV, Matrix Market output that reproduces the spectrum's trace, and exit
# status 2 with a message for every kind of bad input.
set -u
exe=$1
SS_EXPECT_TIMEOUT=120
. "$(dirname "$0")/../ss_expect.sh"

expect_in 0 "eigenstructure with LAPACK" "" "$exe" analyze --help
expect_in 0 "Matrix Market" "" "$exe" matrix --help
expect_in 2 "unknown scheme 'nope'" "" "$exe" analyze --scheme nope --edge 4
expect_in 2 "give exactly one of --scheme and --stencil" "" "$exe" analyze --edge 4
expect_in 2 "exactly one of" "" "$exe" analyze --scheme mlca
# a quasi48 surface vertex whose patch outgrows the extraction's cell cap is
# a resource limit: exit 2 naming the cap, not 1 as a failed check (issue 35)
expect_in 2 "too large a case: the refined patch would exceed the cap of 6000000 cells" "" "$exe" analyze --scheme quasi48 --surface-vertex 700
expect_in 0 "patch's cap of 6e6 cells holds class 8 to N = 688" "" "$exe" analyze --help
# stencil files: the shipped MLCA stencil gives the built-in scheme's result
st="$(dirname "$0")/../../data/stencils"
a=$("$exe" analyze --stencil "$st/mlca.ini" --vertex octahedron --format json | sed 's/"scheme":"[^"]*",//')
b=$("$exe" analyze --scheme mlca --vertex octahedron --format json | sed 's/"scheme":"[^"]*",//')
checks=$((checks + 1))
[ -n "$a" ] && [ "$a" = "$b" ] || fail "mlca.ini and mlca differ: $a vs $b"
expect_in 1 "eigenvalue condition: fail" "" "$exe" analyze --stencil "$st/no-smoothing.ini" --edge 5
expect_in 2 "give exactly one of --scheme and --stencil" "" "$exe" analyze --scheme mlca --stencil "$st/mlca.ini" --edge 4
expect_in 2 "--stencil /nonexistent.ini: No such file" "" "$exe" analyze --stencil /nonexistent.ini --edge 4
# check, the CI gate: 0 for MLCA as a stencil, 1 for no smoothing, 2 for bad files
expect_in 0 "8 cases: 8 pass, 0 fail, 0 undecided, 0 errors" "" "$exe" check "$st/mlca.ini"
# all 23 links k <= 8 (the published counts 1, 1, 2, 5, 14 of triangulated
# spheres) and edges 3..7 = 28 cases.  That exactly one fails is a REGRESSION PIN
# (the program's own verdicts); the failing one, the k = 8 finding
# (reports/README.md), is derived independently in test_charmap.c (dense dgeev).
expect_in 1 "28 cases: 27 pass, 1 fail, 0 undecided, 0 errors" "" "$exe" check "$st/mlca.ini" --vertices 4..8 --edges 3..7
expect_in 1 "fail       edge 5: eigenvalue condition" "" "$exe" check "$st/no-smoothing.ini"
expect_in 0 "9 cases: 9 pass" "" "$exe" check "$st/tetoct.ini"
expect_in 1 "fail       edge 8" "" "$exe" check "$st/mlca.ini" --edges 8
sdir=$(mktemp -d)
printf '[scheme]\nname = x\nfamily = averaging\nsplit = multilinear\n[mask.hex]\nself = 1/2\nedge = 1/8\nface = 0\nopposite = 0\n' >"$sdir/sum.ini"
expect_in 2 "sum.ini:5: \[mask.hex\]: the weights sum to 7/8" "" "$exe" check "$sdir/sum.ini"
# the points and neighbours families (docs/stencils.md): ccsolid.ini and
# boxspline.ini judge every case as the built-in schemes do (two computations
# compared, verdict lines and counts); a bad points file exits 2 naming the
# file, the line and the valence
for s in ccsolid boxspline; do
  a=$("$exe" check "$st/$s.ini" --certify 2>&1 | tail -n +2)
  b=$("$exe" check --scheme $s --certify 2>&1 | tail -n +2)
  checks=$((checks + 1))
  [ -n "$a" ] && [ "$a" = "$b" ] || fail "check $s.ini and --scheme $s differ: $a vs $b"
done
printf '[scheme]\nname = x\nfamily = points\nsplit = multilinear\n[volume.edge]\ncell = 1/n\nface = 2/n + (n-1)*(n-2)*(n-3)*(n-4)/24000\nedge = (n-3)/n\n' >"$sdir/pts.ini"
expect_in 2 "pts.ini:5: \[volume.edge\]: the weights sum to 1001/1000 at n = 5, not 1" "" "$exe" check "$sdir/pts.ini"
rm -rf "$sdir"
expect_in 2 "no stencil file given" "" "$exe" check
expect_in 2 "--vertices '3..5'" "" "$exe" check "$st/mlca.ini" --vertices 3..5
expect_in 2 "--face: the stencil's split is not tetoct" "" "$exe" check "$st/mlca.ini" --face
expect_in 0 "CI gate" "" "$exe" check --help
expect_in 2 "exactly one of" "" "$exe" analyze --scheme mlca --edge 4 --face
expect_in 2 "face case exists only" "" "$exe" analyze --scheme mlca --face
expect_in 2 "does not support the vertex case" "" "$exe" analyze --scheme catmull-clark --vertex octahedron
expect_in 2 "does not support the edge case" "" "$exe" analyze --scheme loop --edge 5
expect_in 2 "valence must be an integer in 3..1000, not '2'" "" "$exe" analyze --scheme mlca --edge 2
expect_in 2 "not 'x'" "" "$exe" analyze --scheme mlca --surface-vertex x
expect_in 2 "--tol" "" "$exe" analyze --scheme mlca --edge 4 --tol 0.5
expect_in 2 "--format" "" "$exe" analyze --scheme mlca --edge 4 --format mtx
expect_in 2 "--ring" "" "$exe" matrix --scheme mlca --edge 4 --ring 3
expect_in 2 "unknown link .dodecahedron." "" "$exe" analyze --scheme mlca --vertex dodecahedron
expect_in 2 "the vertex count is 4 but there are 2" "" "$exe" analyze --scheme mlca --vertex "4 bcd,adc"
expect_in 2 "stdin:2: .*not symmetric" "octahedron
5 bcd,ade,aed,acb,abc
" "$exe" analyze --scheme tetoct --vertex - --format json
expect_in 2 "no links read" "" "$exe" analyze --scheme tetoct --vertex -
expect_in 2 "unexpected argument" "" "$exe" analyze --scheme mlca --edge 4 extra

# the JSON contract, one object per line
json=$(printf 'tetrahedron\n# a comment\n\noctahedron\nbipyramid:5\n' |
  "$exe" analyze --scheme mlca --vertex - --format json)
checks=$((checks + 1))
python3 - "$json" <<'PY' || fail "JSON contract"
import json, sys
lines = sys.argv[1].strip().split("\n")
assert len(lines) == 3, len(lines)
for s in lines:
    o = json.loads(s)
    for key in ("scheme", "case", "link", "two_ring_size", "one_ring_size",
                "eigenvalues", "eigen_condition", "regularity"):
        assert key in o, key
    # bipyramid:5 is a point on an edge of valence 5 (ss_case_edge_point)
    want = "edge-point" if o["k"] == 7 else "vertex"
    assert o["scheme"] == "mlca" and o["case"] == want, o["case"]
    assert want == "vertex" or o["valence"] == 5, o
    assert len(o["eigenvalues"]) == 16
    mods = [abs(complex(e["re"], e["im"])) for e in o["eigenvalues"]]
    assert all(a >= b - 1e-12 for a, b in zip(mods, mods[1:])), mods
    assert o["eigen_condition"]["verdict"] in ("pass", "fail", "undecided")
    assert o["regularity"]["verdict"] in ("pass", "fail", "undecided")
o = json.loads(lines[1])
assert o["two_ring_size"] == 125 and o["one_ring_size"] == 27
assert o["link"] == "6 bcde,aefc,abfd,acfe,adfb,bedc", o["link"]
assert [round(e["re"], 12) for e in o["eigenvalues"][:4]] == [1, 0.5, 0.5, 0.5]
for s in lines:  # MLCA, k <= 7: both conditions hold (with spokes: psi's
    # tubes by evidence, not proven)
    g = json.loads(s)["regularity"]
    assert g["verdict"] == "pass" and not g["certified"], g
    assert g["reason"] == "" or (g["judged_on"] == "psi" and
                                 "by evidence" in g["reason"]), g
    assert 0 < g["min_scaled_jacobian"] <= 1 and g["folded_cells"] == 0, g
assert abs(json.loads(lines[1])["regularity"]["min_scaled_jacobian"] - 1) < 1e-9
PY

# regularity: the MLCA finding fails with its reason and exit status 1; an
# eigenvalue-condition failure leaves the map undecided
k8="8 bcdefgh,ahc,abhd,ache,adhf,aehg,afh,agfedcb"
# (judged on the ring: level r has 8^r times level 0's cells; the fold
# persists, i.e. its share of the cells does not halve from level to level)
k8json=$("$exe" analyze --scheme mlca --vertex "$k8" --format json)
checks=$((checks + 1))
python3 - "$k8json" <<'PY' || fail "k = 8 finding: $k8json"
import json, sys
g = json.loads(sys.argv[1])["regularity"]
lv = g["ring_levels"]
assert g["verdict"] == "fail" and "persists" in g["reason"] and not g["certified"], g
assert len(lv) == 3 and g["ring_level"] == 2, g
assert all(l["cells"] == lv[0]["cells"] * 8 ** l["level"] for l in lv), lv
bad = [(l["folded"] + l["inverted"]) / l["cells"] for l in lv]
assert all(b > 0 for b in bad) and bad[2] >= 0.5 * bad[1], bad
assert g["min_scaled_jacobian"] < 0 and g["folded_cells"] == lv[2]["folded"], g
assert g["inverted_cells"] == lv[2]["inverted"] > 0, g
PY
# and a symmetry sigma of the link (order 2) with psi o sigma = psi: not
# injective, and not regular either (det Dpsi vanishes on sigma's fixed rays)
expect_in 1 "regularity: fail: psi o sigma = psi for link automorphism .* of order 2 .* the ring alone: fail: ring level 2: .* the fold persists" "" "$exe" analyze --scheme mlca --vertex "$k8"
expect_in 1 "injectivity: fail: psi o sigma = psi" "" "$exe" analyze --scheme mlca --vertex "$k8"
# psi judged on its pieces: the same failure witnessed on psi itself (two
# points with det Dpsi of opposite signs), judged on psi; --psi-depth 0 leaves
# psi out (the net's JSON: judged on the control net for a regular vertex)
checks=$((checks + 1))
python3 - "$k8json" <<'PY' || fail "k = 8 on psi: $k8json"
import json, sys
g = json.loads(sys.argv[1])["regularity"]
w = g["witness"]
assert g["judged_on"] == "psi" and g["psi"]["verdict"] == "fail", g
assert len(w) == 2 and w[0]["det"][0] * w[1]["det"][1] < 0, w
assert 0 < g["covered"] < 1 and g["net_verdict"]["verdict"] == "fail", g
PY
expect_in 0 '"judged_on":"control-net"' "" "$exe" analyze --scheme mlca --vertex octahedron --psi-depth 0 --format json
expect_in 0 "psi on its polynomial pieces .*: pass; 8 pieces" "" "$exe" analyze --scheme mlca --vertex octahedron
expect_in 2 "psi-depth: .* 0..8, not '9'" "" "$exe" analyze --scheme mlca --vertex octahedron --psi-depth 9
# --psi-tubes: the spokes' tubes proven (the icosahedron: a certified pass on psi,
# every one of its 120 tube boxes proven); only with --certify and a psi depth
expect_in 0 '"tubes":{"proven":120,"boxes":120' "" "$exe" analyze --scheme mlca --vertex icosahedron --certify --psi-depth 2 --psi-tubes --format json
expect_in 0 "regularity: pass, certified: det Dpsi of one sign on all 440 pieces and in the tubes of all 120 boxes" "" "$exe" analyze --scheme mlca --vertex icosahedron --certify --psi-depth 2 --psi-tubes
expect_in 2 "--psi-tubes needs --certify" "" "$exe" analyze --scheme mlca --vertex icosahedron --psi-tubes
expect_in 2 "--psi-tubes needs --certify" "" "$exe" analyze --scheme mlca --vertex icosahedron --certify --psi-depth 0 --psi-tubes
expect_in 1 "regularity: undecided: no characteristic map" "" "$exe" analyze --scheme mlca --edge 8

# --certify: proven verdicts.  The regular vertex: the exact roots 1 and 1/2
# (x3, minimal polynomial 2x - 1) and every verdict proven; finding 1: the
# failure proven; Loop's irrational weights: nothing proven, undecided
cj=$("$exe" analyze --scheme mlca --vertex octahedron --certify --format json)
checks=$((checks + 1))
python3 - "$cj" <<'PY' || fail "analyze --certify: $cj"
import json, sys
o = json.loads(sys.argv[1])
c, g = o["eigen_condition"], o["regularity"]
assert c["verdict"] == "pass" and c["certified"] is True, c
assert g["verdict"] == "pass" and g["certified"] is True, g
r = c["exact_roots"]
assert r[0]["minimal_polynomial"] == "x - 1" and r[0]["multiplicity"] == 1, r[0]
assert r[1]["re"] == 0.5 and r[1]["radius"] == 0 and r[1]["multiplicity"] == 3, r[1]
assert r[1]["minimal_polynomial"] == "2*x - 1", r[1]
PY
expect_in 1 "regularity: fail, certified: psi o sigma = psi" "" "$exe" analyze --scheme mlca --vertex "$k8" --certify
expect_in 0 "regularity: pass, certified" "" "$exe" analyze --scheme loop --surface-vertex 5 --certify
# the text says what the JSON's "certified" says (issue 40: injectivity was a
# plain "pass" where the JSON said certified: false): each decided verdict of
# --certify's text is ", certified" or ", not certified" as the JSON is true
# or false, on a case with both (tetoct's octahedron: injectivity on the net)
for a in "tetoct --vertex octahedron" "mlca --edge 5"; do
  # shellcheck disable=SC2086
  txt=$("$exe" analyze --scheme $a --certify)
  # shellcheck disable=SC2086
  js=$("$exe" analyze --scheme $a --certify --format json)
  checks=$((checks + 1))
  python3 - "$txt" "$js" <<'PY' || fail "analyze --scheme $a --certify: text and JSON disagree on certified"
import json, re, sys
txt, j = sys.argv[1], json.loads(sys.argv[2])
seen = 0
for key, label in (("regularity", "regularity"), ("injectivity", "injectivity")):
    v = j[key]
    if v["verdict"] == "undecided":
        continue
    m = re.search(r"^%s: %s(, (not )?certified)?" % (label, v["verdict"]), txt, re.M)
    want = ", certified" if v["certified"] else ", not certified"
    assert m and m.group(1) == want, (key, v, m and m.group(0))
    seen += not v["certified"]
assert "not certified" not in txt or seen
PY
done
expect_in 0 "^injectivity: pass, not certified" "" "$exe" analyze --scheme tetoct --vertex octahedron --certify
expect_in 2 "--certify is an option of analyze" "" "$exe" matrix --scheme mlca --edge 4 --certify
expect_in 2 "--depth" "" "$exe" analyze --scheme mlca --edge 4 --depth 13

# draw: pictures, and its errors
tmp=$(mktemp -d)
expect_in 0 "wrote $tmp/t.png \\(regularity pass\\)" "" "$exe" draw --scheme mlca --vertex tetrahedron -o "$tmp/t.png" --size 400x300 --view 10,20
expect_in 0 "wrote $tmp/t.svg" "" "$exe" draw --scheme catmull-clark --surface-vertex 5 -o "$tmp/t.svg"
expect_in 0 "wrote $tmp/t.vtk" "" "$exe" draw --scheme tetoct --face -o "$tmp/t.vtk"
expect_in 1 "regularity fail" "" "$exe" draw --scheme mlca --vertex "$k8" -o "$tmp/k8.png"
expect_in 1 "^subspectra draw: nothing to draw: no characteristic map: the eigenvalue condition fails" "" "$exe" draw --scheme mlca --edge 8 -o "$tmp/e8.png"
expect_in 2 "-o FILE is required" "" "$exe" draw --scheme mlca --edge 4
# box-spline solids: the figure-23 edge pair; "center" has no characteristic
# map at valence 9 (lambda3 = lambda4), --force draws the would-be map
expect_in 0 "regularity pass" "" "$exe" draw --scheme boxspline --edge 9 --diagonals skew -o "$tmp/s9.png"
expect_in 1 "^subspectra draw: nothing to draw: no characteristic map" "" "$exe" draw --scheme boxspline --edge 9 --diagonals center -o "$tmp/c9.png"
expect_in 1 "forced map, eigenvalue condition fails; its cells: fail" "" "$exe" draw --scheme boxspline --edge 9 --diagonals center --force -o "$tmp/c9.png"
[ -s "$tmp/c9.png" ] || fail "draw --force wrote no picture"
expect_in 2 "--force is an option of draw only" "" "$exe" analyze --scheme boxspline --edge 9 --force
# The counts of improper pairs below are REGRESSION PINS (the program's own
# output); the diagonals themselves are tested in tests/scheme/test_boxspline.c.
expect_in 0 "major diagonals: skew; 9 of 9 face-adjacent pairs improper" "" "$exe" analyze --scheme boxspline --edge 9 --diagonals skew --eigenvalues 4
# a rule that reads no diagonals refuses a choice (it would only relabel the star)
expect_in 2 "scheme tetoct does not read major diagonals: diagonals .skew. do not apply" "" "$exe" analyze --scheme tetoct --edge 5 --diagonals skew
expect_in 2 "scheme tetoct does not read major diagonals: diagonals .proper. do not apply" "" "$exe" analyze --scheme tetoct --vertex octahedron --diagonals proper
expect_in 1 "major diagonals: center; 0 of 9 face-adjacent pairs improper" "" "$exe" analyze --scheme boxspline --edge 9 --diagonals center --eigenvalues 4
expect_in 1 "major diagonals: proper; 2 of 9 face-adjacent pairs improper" "" "$exe" analyze --scheme boxspline --vertex bipyramid:3 --diagonals proper
expect_in 2 "defined around an edge" "" "$exe" analyze --scheme boxspline --vertex bipyramid:3 --diagonals skew
expect_in 0 "scheme boxspline-avg, edge case, valence 5" "" "$exe" analyze --scheme boxspline-avg --edge 5
avgout=$("$exe" analyze --scheme boxspline-avg --edge 5 --format json)
checks=$((checks + 1))
grep -q '"diagonals"' <<<"$avgout" && fail "boxspline-avg reports diagonals it does not read"
expect_in 2 "^subspectra draw: [^ ]*x.gif: unknown picture format" "" "$exe" draw --scheme mlca --edge 4 -o "$tmp/x.gif"
expect_in 2 "cannot" "" "$exe" draw --scheme mlca --edge 4 -o /nonexistent/dir/x.png
expect_in 2 "--size" "" "$exe" draw --scheme mlca --edge 4 -o "$tmp/x.png" --size 10x10
expect_in 2 "--view" "" "$exe" draw --scheme mlca --edge 4 -o "$tmp/x.png" --view 10
# PDF (text as text: a font with a ToUnicode map), a picture without caption
expect_in 0 "wrote $tmp/c.pdf \\(regularity pass\\)" "" "$exe" draw --scheme mlca --edge 5 -o "$tmp/c.pdf" --no-caption
checks=$((checks + 1))
head -c 5 "$tmp/c.pdf" | grep -q '%PDF-' && grep -aq '/ToUnicode' "$tmp/c.pdf" || fail "draw -o x.pdf"
expect_in 2 "--no-caption is an option of draw only" "" "$exe" analyze --scheme mlca --edge 5 --no-caption
# matrix and draw take exactly one link on standard input
expect_in 2 "no links read" "" "$exe" draw --scheme mlca --vertex - -o "$tmp/x.png"
expect_in 2 "stdin:3: a second link" "octahedron
# a comment
tetrahedron
" "$exe" draw --scheme mlca --vertex - -o "$tmp/x.png"
checks=$((checks + 1))
[ -e "$tmp/x.png" ] && fail "draw wrote a picture for a stream of two links"
checks=$((checks + 1))
[ "$(printf '# one\n\n  octahedron  \n' | "$exe" matrix --scheme mlca --vertex -)" = \
  "$("$exe" matrix --scheme mlca --vertex octahedron)" ] ||
  fail "matrix --vertex - differs from the same link given by name"
checks=$((checks + 1))
[ -s "$tmp/t.png" ] && [ -s "$tmp/t.svg" ] && grep -q "^CELL_TYPES" "$tmp/t.vtk" || fail "draw outputs"
rm -rf "$tmp"

# edge cases carry their valence; tsv has a header and one row per case
expect_in 0 '"case":"edge","valence":5' "" "$exe" analyze --scheme tetoct --edge 5 --format json
expect_in 0 "^scheme	case	link_or_valence" "" "$exe" analyze --scheme loop --surface-vertex 7 --format tsv
expect_in 0 "eigenvalue condition: pass" "" "$exe" analyze --scheme catmull-clark --surface-vertex 5

# Matrix Market: header, labels, and the trace equals the sum of the eigenvalues
mtx=$("$exe" matrix --scheme catmull-clark --surface-vertex 5)
checks=$((checks + 1))
python3 - "$mtx" "$("$exe" analyze --scheme catmull-clark --surface-vertex 5 --format json --eigenvalues 1000)" <<'PY' || fail "Matrix Market export"
import json, sys
lines = sys.argv[1].split("\n")
assert lines[0] == "%%MatrixMarket matrix coordinate real general", lines[0]
body = [l for l in lines if l and not l.startswith("%")]
n, m, nnz = map(int, body[0].split())
assert n == m == 31 and nnz == len(body) - 1, (n, m, nnz)
labels = [l for l in lines if l.startswith("% ") and l[2:].split(" ")[0].isdigit()]
assert len(labels) == 31 and labels[0] == "% 1 ()", labels[:2]
rows = {}
trace = 0.0
for l in body[1:]:
    i, j, v = l.split()
    rows[int(i)] = rows.get(int(i), 0.0) + float(v)
    if i == j:
        trace += float(v)
assert all(abs(s - 1) < 1e-12 for s in rows.values()) and len(rows) == 31
ev = json.loads(sys.argv[2])["eigenvalues"]
assert len(ev) == 31
assert abs(sum(e["re"] for e in ev) - trace) < 1e-9, (trace, sum(e["re"] for e in ev))
PY
expect_in 0 "^9 9 " "" "$exe" matrix --scheme mlca --surface-vertex 4 --ring 1

# Eigenvectors (issue 21): SciPy reads the Matrix Market arrays; with S they
# satisfy S R = R diag(lambda), L^T S = diag(lambda) L^T and L^T R = I (the
# lambda0 and the tied lambda1 = lambda2 groups); analyze's JSON carries the
# same vectors and the limit masks; MLCA's edge 4 is the tensor product of
# cubic B-splines, whose limit-position mask at a vertex is 1/6 (1, 4, 1):
# here the centre's weight is (4/6)^3 = 8/27 (derived, not read off a run).
edir=$(mktemp -d)
"$exe" matrix --scheme catmull-clark --surface-vertex 5 -o "$edir/S.mtx"
"$exe" matrix --scheme catmull-clark --surface-vertex 5 --eigenvectors 3 -o "$edir/R.mtx"
"$exe" matrix --scheme catmull-clark --surface-vertex 5 --eigenvectors 3 --left -o "$edir/L.mtx"
"$exe" analyze --scheme catmull-clark --surface-vertex 5 --eigenvectors 3 --format json >"$edir/a.json"
"$exe" analyze --scheme mlca --edge 4 --eigenvectors 4 --format json >"$edir/e4.json"
"$exe" analyze --scheme mlca --edge 4 --eigenvectors 1 --format json >"$edir/e1.json"
checks=$((checks + 1))
/usr/bin/python3 - "$edir" <<'PY' || fail "eigenvector export (SciPy)"
import json, sys
import numpy as np
from scipy.io import mmread
d = sys.argv[1]
S = mmread(d + "/S.mtx").toarray()
R = np.asarray(mmread(d + "/R.mtx"))
L = np.asarray(mmread(d + "/L.mtx"))
a = json.load(open(d + "/a.json"))["eigenvectors"]
lam = np.array([e["re"] for e in a["eigenvalues"]])
assert R.shape == L.shape == (31, 3), (R.shape, L.shape)
assert np.abs(S @ R - R * lam).max() < 1e-13, np.abs(S @ R - R * lam).max()
assert np.abs(L.T @ S - lam[:, None] * L.T).max() < 1e-13
assert np.abs(L.T @ R - np.eye(3)).max() < 1e-12, L.T @ R
assert np.array_equal(R, np.array(a["right"]).T) and np.array_equal(L, np.array(a["left"]).T)
m = a["limit_masks"]
assert np.array_equal(np.array(m["position"]), L[:, 0]) and abs(sum(m["position"]) - 1) < 1e-14
assert np.array_equal(np.array(m["tangent"]), L[:, 1:].T) and len(a["points"]) == 31
e4 = json.load(open(d + "/e4.json"))["eigenvectors"]
assert e4["points"][0] == "()" and abs(e4["limit_masks"]["position"][0] - 8 / 27) < 1e-14, e4["limit_masks"]
e1 = json.load(open(d + "/e1.json"))["eigenvectors"]
assert e1["k"] == 1 and e1["limit_masks"] is None, e1["limit_masks"]
assert e1["limit_masks_reason"] == "the masks need --eigenvectors 4 or more", e1
PY
rm -rf "$edir"
expect_in 2 "analyze writes them with --format json" "" "$exe" analyze --scheme loop --surface-vertex 5 --eigenvectors 2
expect_in 2 "--eigenvectors: expected a positive integer" "" "$exe" matrix --scheme loop --surface-vertex 5 --eigenvectors 0
expect_in 2 "--eigenvectors 11: the matrix has only 10 rows" "" "$exe" matrix --scheme loop --surface-vertex 3 --eigenvectors 11
expect_in 2 "--left needs --eigenvectors K" "" "$exe" matrix --scheme loop --surface-vertex 3 --left
expect_in 2 "--left is an option of matrix" "" "$exe" analyze --scheme loop --surface-vertex 3 --left
expect_in 2 "--eigenvectors is an option of analyze and matrix" "" "$exe" draw --scheme loop --surface-vertex 3 --eigenvectors 2 -o "$tmp/x.png"

# a tolerance below the eigenvalues' rounding error is raised to it and says so
# (at 1e-15 the computed lambda0 = 1 - 1.1e-15 "was not 1"); JSON carries both
expect_in 0 "eigenvalue condition: pass \(equal within relative tolerance [0-9.]*e-1[0-4]: the requested 1.0e-15 is below the eigenvalues. rounding error bound\)" "" "$exe" analyze --scheme mlca --vertex octahedron --tol 1e-15
out=$("$exe" analyze --scheme mlca --vertex octahedron --tol 1e-15 --format json)
checks=$((checks + 1))
python3 -c '
import json, sys
c = json.loads(sys.argv[1])["eigen_condition"]
assert c["verdict"] == "pass" and c["tolerance_requested"] == 1e-15, c
assert c["tolerance"] == c["rounding_bound"] and 1e-15 < c["tolerance"] < 1e-9, c
' "$out" || fail "octahedron at --tol 1e-15: $out"
# Cost guard (issue 16): a case is estimated before anything is built.  Beyond
# the memory budget it is refused at once with exit 2 and the estimate
# (--edge 1000, the documented maximum, needs 30005 rows of S and ~16.8 GB).
t0=$(date +%s%N)
expect_in 2 "--edge 1000 needs about 30005 rows of S and ~16\.8 GB of memory \(more than the budget of 8\.0 GB\): set --max-memory to override" "" "$exe" analyze --scheme mlca --edge 1000 --max-memory 8G
t1=$(date +%s%N)
checks=$((checks + 1))
[ $(( (t1 - t0) / 1000000 )) -lt $((2000 * ${SS_TIMEOUT_MULTIPLIER:-1})) ] || fail "--edge 1000 took $(( (t1 - t0) / 1000000 )) ms to refuse"
expect_in 2 "needs about 30005 rows of S" "" "$exe" matrix --scheme mlca --edge 1000 --max-memory 8G
expect_in 2 "needs about 30005 rows of S" "" "$exe" draw --scheme mlca --edge 1000 --max-memory 8G -o /dev/null.png
# a link is estimated before its canonical form (O(k^2)), as the vertex case
expect_in 2 "a link with k = 1000 vertices\) needs about 29945 rows" "" "$exe" analyze --scheme mlca --vertex bipyramid:998 --max-memory 1G
expect_in 2 "--max-memory: expected a size" "" "$exe" analyze --scheme mlca --edge 4 --max-memory 8X
expect_in 2 "--max-memory: expected a size" "" "$exe" analyze --scheme mlca --edge 4 --max-memory -1G
expect_in 0 "--max-memory SIZE" "" "$exe" analyze --help
# check and sweep: the case is skipped with its estimate, the others run, exit 2
expect_in 2 "error      edge 3: needs about 95 rows of S.*budget of 17\.0 MB" "" "$exe" check "$st/mlca.ini" --edges 3..3 --max-memory 17M
expect_in 0 "--max-memory SIZE" "" "$exe" check --help
sdb=$(mktemp -d)
expect_in 2 "sweep: edge 3: needs about 95 rows of S" "" "$exe" sweep --scheme mlca --edges 3..3 --db "$sdb/s.db" --jobs 1 --max-memory 17M
expect_in 0 "--max-memory SIZE" "" "$exe" sweep --help
rm -rf "$sdb"
# progress on stderr with --progress; standard output unchanged
pout=$("$exe" analyze --scheme mlca --edge 12 --format json --progress 2>"${TMPDIR:-/tmp}/ss_progress.$$")
pst=$?
perr=$(cat "${TMPDIR:-/tmp}/ss_progress.$$")
rm -f "${TMPDIR:-/tmp}/ss_progress.$$"
qout=$("$exe" analyze --scheme mlca --edge 12 --format json 2>/dev/null)
checks=$((checks + 1))
[ "$pst" -eq 1 ] && [ -n "$pout" ] && [ "$pout" = "$qout" ] || fail "--progress changed standard output or status ($pst)"
checks=$((checks + 1))
grep -q "refining the star to level" <<<"$perr" && grep -q "reading S, rows 365" <<<"$perr" &&
  grep -Eq "eigen-solve, block ([0-9]+)/\1" <<<"$perr" || fail "--progress lines: $perr"
checks=$((checks + 1))
[ -z "$("$exe" analyze --scheme mlca --edge 12 2>&1 >/dev/null)" ] || fail "progress without --progress and without a terminal"
# Out of memory is exit 2, never 1 (the code for a failed check): under an
# address-space limit the budget refuses what the estimate says cannot fit,
# and a real allocation failure (budget overridden) says "out of memory".
# (Not under AddressSanitizer, which needs terabytes of address space.)
if ! ldd "$exe" 2>/dev/null | grep -q libasan; then
  expect_in 2 "needs about .* rows of S .*budget of 768\.0 MB" "" bash -c "ulimit -v 1000000; exec \"\$0\" analyze --scheme mlca --edge 1000" "$exe"
  expect_in 2 "needs about 2999945 rows of S .*budget of 3\.1 GB" "" bash -c "ulimit -v 4000000; exec \"\$0\" analyze --scheme mlca --vertex bipyramid:99998" "$exe"
  expect_in 2 "out of memory \(canonical form\)" "" bash -c "ulimit -v 1000000; exec \"\$0\" analyze --scheme mlca --vertex bipyramid:20000 --max-memory 10T" "$exe"
  expect_in 2 "out of memory \(local matrix\)" "" bash -c "ulimit -v 200000; exec \"\$0\" analyze --scheme mlca --surface-vertex 1000 --max-memory 100G" "$exe"
  expect_in 2 "out of memory" "" bash -c "ulimit -v 200000; exec \"\$0\" matrix --scheme mlca --surface-vertex 1000 --max-memory 100G" "$exe"
fi

# Catmull-Clark solids through the same machinery (the tests in
# tests/scheme/test_ccsolid.c check the matrices themselves)
expect_in 0 "two-ring 125 points, one-ring 27" "" "$exe" analyze --scheme ccsolid --vertex octahedron
expect_in 0 '"two_ring_size":155' "" "$exe" analyze --scheme ccsolid --edge 5 --format json
expect_in 0 "MatrixMarket" "" "$exe" matrix --scheme ccsolid --edge 3 --format mtx
expect_in 0 "6 cases: 6 pass" "" "$exe" check --scheme ccsolid --vertices 5..6 --edges 3..5
expect_in 1 "fail       vertex 4 bcd,adc,abd,acb: eigenvalue condition" "" "$exe" check --scheme ccsolid --vertices 4..4 --edges 4..4
expect_in 2 "a stencil file and --scheme" "" "$exe" check --scheme ccsolid "$st/mlca.ini"
expect_in 2 "--face: the scheme's split is not tetoct" "" "$exe" check --scheme ccsolid --face
ctmp=$(mktemp -d)
expect_in 0 "wrote $ctmp/c.png \\(regularity pass\\)" "" "$exe" draw --scheme ccsolid --edge 5 -o "$ctmp/c.png" --size 300x200
expect_in 0 "4 cases of ccsolid" "" "$exe" sweep --scheme ccsolid --vertices 5..6 --edges 4..4 --db "$ctmp/s.db"
rm -rf "$ctmp"

expect_done "analyze_cli"
