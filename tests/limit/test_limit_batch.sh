#!/usr/bin/env bash
# test_limit_batch.sh EXE — `subspectra limit` batches and VTU (issue 36):
# a point that cannot be evaluated does not discard the others (every point
# written, with its status; the others the same numbers as a run of them
# alone; null in JSON, nan in text; exit 1), and VTU merges the samples that
# neighbouring cells share (point counts against counts made from the mesh's
# own vertices, edges and faces; hexahedra against the legacy VTK's; the
# Jacobian tensor against the JSON).
set -u
exe=$1
SS_EXPECT_TIMEOUT=120
. "$(dirname "$0")/../ss_expect.sh"
. "$(dirname "$0")/limit_grid.sh"
mesh="$(dirname "$0")/../../data/meshes/hexstar-icosahedron.mesh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# --- a batch of --at points: two good ones, an unknown cell (refused), the
# icosahedron vertex with --derivatives (its Jacobian is unbounded there:
# the point without it)
g1="3 0.25 0.5 0.125"
g2="7 0.6 0.1 0.9"
bad="21 0.5 0.5 0.5"
ev="1 0 0 0"
for f in text json; do
  "$exe" limit --scheme mlca "$mesh" -d --at "$g1" --at "$bad" --at "$ev" --at "$g2" --format $f > "$tmp/batch.$f" 2> "$tmp/batch.$f.err"
  rc=$?
  checks=$((checks + 1)); [ $rc -eq 1 ] || fail "$f batch: exit $rc, not 1"
  checks=$((checks + 1)); grep -q "cell 21 does not exist" "$tmp/batch.$f.err" && grep -q "2 of 4 points" "$tmp/batch.$f.err" || fail "$f batch: stderr $(cat "$tmp/batch.$f.err")"
  expect 0 "" "$exe" limit --scheme mlca "$mesh" -d --at "$g1" --at "$g2" --format $f -o "$tmp/alone.$f"
  expect 0 "" "$exe" limit --scheme mlca "$mesh" --at "$ev" --format $f -o "$tmp/vertex.$f"
done
# text: 1 + 3 + 3 + 9 columns and the status; the good lines equal the run
# of them alone, the vertex's point equals the run without -d
checks=$((checks + 1))
r=$(awk 'NR == FNR {alone[FNR] = $0; next} FILENAME ~ /vertex/ {vx = $5 " " $6 " " $7; next}
  { line[FNR] = $0; st[FNR] = $NF; if (NF != 17) bad = bad " NF" FNR; $NF = ""; sub(/ $/, ""); row[FNR] = $0 }
  END {
    if (row[1] != alone[1] || row[4] != alone[2]) bad = bad " good-differ"
    if (st[1] != "ok" || st[2] != "refused" || st[3] != "no_derivatives" || st[4] != "ok") bad = bad " statuses"
    split(line[2], a, " "); if (a[1] != 21) bad = bad " cell"
    for (i = 5; i <= 16; i++) if (a[i] != "nan") bad = bad " refused-value"
    split(line[3], b, " "); if (b[5] " " b[6] " " b[7] != vx) bad = bad " vertex-point"
    for (i = 8; i <= 16; i++) if (b[i] != "nan") bad = bad " vertex-jacobian"
    print bad == "" ? "ok" : bad }' "$tmp/alone.text" "$tmp/vertex.text" "$tmp/batch.text")
[ "$r" = "ok" ] || fail "text batch:$r"
# JSON: valid (no NaN, no Infinity), status and reason per point, null where
# there is no value, the good points' numbers those of the run alone; a run
# with every point ok has no status (the output of before)
checks=$((checks + 1))
if ! python3 - "$tmp/batch.json" "$tmp/alone.json" "$tmp/vertex.json" <<'PY'; then
import json, sys
def load(p):
    def no(c): raise ValueError("not JSON: " + c)
    return [json.loads(l, parse_constant=no) for l in open(p)]
b, a, v = (load(p) for p in sys.argv[1:4])
assert len(b) == 4 and len(a) == 2 and len(v) == 1
assert [o["status"] for o in b] == ["ok", "refused", "no_derivatives", "ok"], b
for o, ref in ((b[0], a[0]), (b[3], a[1])):
    assert "reason" not in o
    assert {k: o[k] for k in ref} == ref, (o, ref)  # exactly the same numbers
    assert set(o) == set(ref) | {"status"}
assert all("status" not in o for o in a + v)
r = b[1]
assert r["cell"] == 21 and r["point"] is None and r["jacobian"] is None, r
assert "does not exist" in r["reason"], r
e = b[2]
assert e["point"] == v[0]["point"] and e["jacobian"] is None, e
assert "Jacobian" in e["reason"], e
PY
  fail "json batch"
fi
# legacy VTK: the status array, nan for the refused point
"$exe" limit --scheme mlca "$mesh" -d --at "$g1" --at "$bad" --at "$ev" --at "$g2" --format vtk > "$tmp/batch.vtk" 2> /dev/null
checks=$((checks + 1))
[ "$(sed -n '/^SCALARS status int 1/,$p' "$tmp/batch.vtk" | tail -n +3 | tr '\n' ' ')" = "0 3 1 0 " ] || fail "vtk batch: status array"
checks=$((checks + 1)); [ "$(sed -n 7p "$tmp/batch.vtk")" = "nan nan nan" ] || fail "vtk batch: refused point not nan"

# a point that fails by itself (the reference walk finds no regular
# sub-cell at the vertex, with or without derivatives): failed, nan, the
# reason that of the point (not of its Jacobian), the other as alone
"$exe" limit --scheme mlca "$mesh" --reference -d --at "$g1" --at "$ev" > "$tmp/ref.txt" 2> "$tmp/ref.err"
rc=$?
"$exe" limit --scheme mlca "$mesh" --reference -d --at "$g1" > "$tmp/ref1.txt"
checks=$((checks + 1))
r=$(awk 'NR == FNR {a = $0; next} {st[FNR] = $NF; $NF = ""; sub(/ $/, ""); l[FNR] = $0}
  END {split(l[2], b, " "); for (i = 5; i <= 16; i++) if (b[i] != "nan") bad = 1
       print (l[1] == a && st[1] == "ok" && st[2] == "failed" && !bad) ? "ok" : "bad"}' "$tmp/ref1.txt" "$tmp/ref.txt")
[ $rc -eq 1 ] && [ "$r" = "ok" ] && grep -q "failed: .*no regular sub-cell in 60 steps" "$tmp/ref.err" || fail "--reference batch: exit $rc, $r, $(cat "$tmp/ref.err")"

# --- fields and non-finite parameters: null in JSON, never NaN
awk 'BEGIN {
  printf "MeshVersionFormatted 2\nDimension 4\nVertices\n64\n"
  for (k = 0; k < 4; k++) for (j = 0; j < 4; j++) for (i = 0; i < 4; i++) printf "%d %d %d %d 0\n", i, j, k, i + 2 * j
  printf "Hexahedra\n27\n"
  for (k = 0; k < 3; k++) for (j = 0; j < 3; j++) for (i = 0; i < 3; i++) {
    v = i + 4 * (j + 4 * k) + 1
    print v, v + 1, v + 5, v + 4, v + 16, v + 17, v + 21, v + 20, 0 }
  print "End" }' > "$tmp/w.mesh"
"$exe" limit --scheme mlca "$tmp/w.mesh" -d --at "14 0.5 0.5 0.5" --at "14 nan 0.5 0.5" --at "28 0.5 0.5 0.5" --format json > "$tmp/w.json" 2> /dev/null
rc=$?
checks=$((checks + 1))
if [ $rc -ne 1 ] || ! python3 - "$tmp/w.json" <<'PY'; then
import json, sys
def no(c): raise ValueError("not JSON: " + c)
b = [json.loads(l, parse_constant=no) for l in open(sys.argv[1])]
assert [o["status"] for o in b] == ["ok", "refused", "refused"], b
# the field w = x + 2y is affine: its limit is p_x + 2 p_y
o = b[0]
assert abs(o["fields"]["w"] - (o["point"][0] + 2 * o["point"][1])) < 1e-12, o
for o in b[1:]:
    assert o["point"] is None and o["jacobian"] is None, o
    assert o["fields"] == {"w": None} and o["field_gradients"] == {"w": None}, o
assert b[1]["u"] is None and "parameter u = nan" in b[1]["reason"], b[1]
PY
  fail "fields batch (exit $rc)"
fi

# --- samples with derivatives on the icosahedron star: the points on the
# 12 inner edges of valence 5 and at the vertex (each of the 20 cells: its
# corner there and 4 samples on each of its 3 edges there, 20 x 13 = 260)
# have no Jacobian; every point is written, at the positions of the run
# without --derivatives
"$exe" limit --scheme mlca "$mesh" --samples 5 -d > "$tmp/s.txt" 2> /dev/null
rc=$?
expect 0 "" "$exe" limit --scheme mlca "$mesh" --samples 5 -o "$tmp/s0.txt"
checks=$((checks + 1))
r=$(awk 'NR == FNR {p[FNR] = $1 " " $2 " " $3 " " $4 " " $5 " " $6 " " $7; next}
  { n++; if ($1 " " $2 " " $3 " " $4 " " $5 " " $6 " " $7 != p[FNR]) bad = bad " pos" FNR
    c[$NF]++; if ($NF == "ok" && $8 == "nan") bad = bad " okjac" FNR
    if ($NF == "no_derivatives") for (i = 8; i <= 16; i++) if ($i != "nan") bad = bad " jac" FNR }
  END { if (n != 2500 || c["ok"] != 2240 || c["no_derivatives"] != 260) bad = bad " counts " n " " c["ok"] " " c["no_derivatives"]
        print bad == "" ? "ok" : bad }' "$tmp/s0.txt" "$tmp/s.txt")
[ $rc -eq 1 ] && [ "$r" = "ok" ] || fail "samples -d on the star: exit $rc,$r"

# --- VTU: shared samples merged, checked with Python's XML parser
# vtu.py VTU VTK JSON NPTS: the VTU parses; NPTS points, each used, distinct
# (1e-9); its hexahedra, corner by corner, the legacy VTK's (same cells and
# order: the point of the legacy hex's corner, exactly where the VTU point
# comes from that cell); the tensor jacobian 9 components, equal to the JSON
# Jacobian of a point of the point's cell
cat > "$tmp/vtu.py" <<'PY'
import json, math, sys
import xml.etree.ElementTree as ET
vtu, vtk, js, npts = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
piece = ET.parse(vtu).getroot().find("UnstructuredGrid/Piece")
n, nc = int(piece.get("NumberOfPoints")), int(piece.get("NumberOfCells"))
assert n == npts, (n, npts)
def arr(path, name=None):
    for a in piece.findall(path):
        if a.get("Name") == name:
            return a, [float(x) for x in a.text.split()]
    raise KeyError(name)
_, X = arr("Points/DataArray")
_, conn = arr("Cells/DataArray", "connectivity")
_, cell = arr("PointData/DataArray", "cell")
ja, J = arr("PointData/DataArray", "jacobian")
_, st = arr("PointData/DataArray", "status")
assert ja.get("NumberOfComponents") == "9" and len(J) == 9 * n
assert len(X) == 3 * n and len(conn) == 8 * nc and len(st) == n
conn = [int(c) for c in conn]
assert set(conn) == set(range(n)), "points unused or out of range"
keys = {tuple(round(x * 1e9) for x in X[3 * i:3 * i + 3]) for i in range(n)}
assert len(keys) == n, "two VTU points at the same place"
# legacy VTK: every cell's own points, its hexahedra in the same order
lines = open(vtk).read().split("\n")
i = next(k for k, l in enumerate(lines) if l.startswith("POINTS"))
m = int(lines[i].split()[1])
P = [[float(x) for x in lines[i + 1 + k].split()] for k in range(m)]
i += 1 + m
assert lines[i].split()[1] == str(nc)
H = [[int(x) for x in lines[i + 1 + k].split()[1:]] for k in range(nc)]
pts = [json.loads(l) for l in open(js)]
assert len(pts) == m
seen = [False] * n
for h in range(nc):
    for q in range(8):
        a, b = conn[8 * h + q], H[h][q]
        for d in range(3):
            assert abs(X[3 * a + d] - P[b][d]) <= 1e-12 * (1 + abs(P[b][d])), (h, q)
        if int(cell[a]) == pts[b]["cell"] and st[a] == 0:
            assert X[3 * a:3 * a + 3] == P[b], (h, q)
            assert J[9 * a:9 * a + 9] == [x for row in pts[b]["jacobian"] for x in row], (h, q)
            seen[a] = True
assert all(seen[a] or st[a] != 0 for a in range(n)), "a tensor matched no JSON Jacobian"
PY
# a block of n^3 cells with s samples a side: (n (s - 1) + 1)^3 distinct
for ns in "3 4" "2 5" "1 2"; do
  set -- $ns
  limit_grid $1 > "$tmp/g.mesh"
  want=$(( ($1 * ($2 - 1) + 1) ** 3 ))
  for s in ccsolid mlca; do
    for f in vtu vtk json; do
      expect 0 "" "$exe" limit --scheme $s "$tmp/g.mesh" --samples $2 -d --format $f -o "$tmp/g.$f"
    done
    checks=$((checks + 1))
    python3 "$tmp/vtu.py" "$tmp/g.vtu" "$tmp/g.vtk" "$tmp/g.json" "$want" || fail "$s grid $1, samples $2: VTU"
  done
done
# the icosahedron star: V + E (s - 2) + F (s - 2)^2 + C (s - 2)^3 points,
# the mesh's vertices, edges, faces and cells counted from its hexahedra
want=$(python3 - "$mesh" <<'PY'
import sys
t = open(sys.argv[1]).read().split()
i = t.index("Hexahedra")
hexes = [[int(x) for x in t[i + 2 + 9 * c:i + 10 + 9 * c]] for c in range(int(t[i + 1]))]
E, F = set(), set()
edges = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4), (0, 4), (1, 5), (2, 6), (3, 7)]
faces = [(0, 1, 2, 3), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
for h in hexes:
    E |= {frozenset((h[a], h[b])) for a, b in edges}
    F |= {frozenset(h[a] for a in f) for f in faces}
V = {v for h in hexes for v in h}
s = 5
print(len(V) + len(E) * (s - 2) + len(F) * (s - 2) ** 2 + len(hexes) * (s - 2) ** 3)
PY
)
for f in vtu vtk json; do
  "$exe" limit --scheme mlca "$mesh" --samples 5 -d --format $f -o "$tmp/h.$f" 2> /dev/null
  rc=$?
  checks=$((checks + 1)); [ $rc -eq 1 ] || fail "star --samples 5 -d --format $f: exit $rc, not 1"
done
checks=$((checks + 1))
python3 "$tmp/vtu.py" "$tmp/h.vtu" "$tmp/h.vtk" "$tmp/h.json" "$want" || fail "star: VTU ($want points)"
# the 260 points without a Jacobian keep status 1 and nan in the VTU too:
# the vertex and 4 samples on each of the 12 edges, 1 + 12 x 4 = 49 distinct
# points (whichever cell each comes from)
checks=$((checks + 1))
r=$(python3 - "$tmp/h.vtu" <<'PY'
import math, sys
import xml.etree.ElementTree as ET
p = ET.parse(sys.argv[1]).getroot().find("UnstructuredGrid/Piece")
a = {d.get("Name"): d.text.split() for d in p.iter("DataArray")}
st = [int(x) for x in a["status"]]
J = [float(x) for x in a["jacobian"]]
bad = [i for i, s in enumerate(st) if s]
ok = all(math.isnan(x) for i in bad for x in J[9 * i:9 * i + 9])
print(len(bad), ok)
PY
)
[ "$r" = "49 True" ] || fail "star VTU: points without a Jacobian: $r (want 49 True)"
# --at: one vertex cell per point, status always
expect 1 "" "$exe" limit --scheme mlca "$mesh" --at "$g1" --at "$bad" --format vtu -o "$tmp/at.vtu"
checks=$((checks + 1))
r=$(python3 -c '
import sys, xml.etree.ElementTree as ET
p = ET.parse(sys.argv[1]).getroot().find("UnstructuredGrid/Piece")
a = {d.get("Name"): d.text.split() for d in p.iter("DataArray")}
print(p.get("NumberOfPoints"), p.get("NumberOfCells"), " ".join(a["status"]), " ".join(a["types"]))' "$tmp/at.vtu")
[ "$r" = "2 2 0 3 1 1" ] || fail "--at VTU: $r"
# gmsh (when installed) finds no duplicate vertex in the VTU's hexahedra
# (written as legacy VTK: gmsh reads no VTU), and does in the legacy VTK
if command -v gmsh > /dev/null; then
  python3 - "$tmp/h.vtu" "$tmp/hm.vtk" <<'PY'
import sys, xml.etree.ElementTree as ET
p = ET.parse(sys.argv[1]).getroot().find("UnstructuredGrid/Piece")
X = p.find("Points/DataArray").text.split()
C = [d for d in p.iter("DataArray") if d.get("Name") == "connectivity"][0].text.split()
n, m = len(X) // 3, len(C) // 8
with open(sys.argv[2], "w") as f:
    f.write("# vtk DataFile Version 3.0\nx\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS %d double\n" % n)
    f.writelines(" ".join(X[3 * i:3 * i + 3]) + "\n" for i in range(n))
    f.write("CELLS %d %d\n" % (m, 9 * m))
    f.writelines("8 " + " ".join(C[8 * i:8 * i + 8]) + "\n" for i in range(m))
    f.write("CELL_TYPES %d\n" % m + "12\n" * m)
PY
  # (in $tmp: gmsh -check writes duplicate_nodes.pos where it runs)
  a=$(cd "$tmp" && timeout 120 gmsh hm.vtk -check 2>&1 | grep -c "already exists")
  b=$(cd "$tmp" && timeout 120 gmsh h.vtk -check 2>&1 | grep -c "already exists")
  checks=$((checks + 1)); [ "$a" -eq 0 ] && [ "$b" -gt 0 ] || fail "gmsh -check: $a duplicates in the VTU, $b in the VTK"
fi
expect_done limit_batch
