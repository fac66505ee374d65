#!/usr/bin/env bash
# test_tetgen.sh EXE TETGEN MESHDIR — `subspectra enumerate mesh` on a real
# tetrahedral mesh: tetgen meshes a cube (quality bound q1.414, volume bound
# a0.01, Medit output g) and the JSON report must add up: vertex and cell
# counts as in the file, vertex classes summing to the vertex count, link
# multiplicities to the interior vertices, a sphere as boundary (E = 3V - 6),
# every link a valid canonical link, and plausible valences (the box-spline
# paper's Table 1 has means near 13.8 and 5.1).  Also the shipped stars in
# MESHDIR and the usage errors.  TETGEN missing is a failure, not a skip
# (./run installs it).
set -u
exe=$1
tetgen=$2
meshdir=$3
. "$(dirname "$0")/../ss_expect.sh"
if ! command -v "$tetgen" >/dev/null 2>&1; then
  echo "test_tetgen.sh: tetgen not found ('$tetgen'); install it (apt-get install tetgen, or ./run)" >&2
  exit 1
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT


# a closed surface: the cube [0,2]^3 as a piecewise linear complex
cat >"$tmp/cube.poly" <<'POLY'
8 3 0 0
1 0 0 0
2 2 0 0
3 2 2 0
4 0 2 0
5 0 0 2
6 2 0 2
7 2 2 2
8 0 2 2
6 0
1
4 1 2 3 4
1
4 5 6 7 8
1
4 1 2 6 5
1
4 2 3 7 6
1
4 3 4 8 7
1
4 4 1 5 8
0
0
POLY
checks=$((checks + 1))
if ! (cd "$tmp" && timeout 60 "$tetgen" -pq1.414a0.01gQ cube.poly >tetgen.log 2>&1) ||
  [ ! -s "$tmp/cube.1.mesh" ]; then
  fail "tetgen did not write cube.1.mesh: $(tail -3 "$tmp/tetgen.log")"
  echo "test_tetgen: $checks checks, $failed failed"
  exit 1
fi

checks=$((checks + 1))
if ! "$exe" enumerate mesh "$tmp/cube.1.mesh" --format json >"$tmp/out.json" 2>"$tmp/err"; then
  fail "enumerate mesh --format json: $(head -3 "$tmp/err")"
fi
checks=$((checks + 1))
"$exe" enumerate mesh "$tmp/cube.1.mesh" >"$tmp/out.txt" 2>&1 &&
  grep -q "distinct links of interior vertices" "$tmp/out.txt" ||
  fail "enumerate mesh (text): $(head -3 "$tmp/out.txt")"

# canonical forms through `enumerate canonical` when that command works
canon=0
"$exe" enumerate canonical --help >/dev/null 2>&1 && canon=1

checks=$((checks + 1))
python3 - "$tmp/cube.1.mesh" "$tmp/out.json" "$exe" "$canon" <<'PY' || fail "json report"
import json, subprocess, sys

mesh, report, exe, canon = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4] == "1"
d = json.load(open(report))
# counts declared in the Medit file
words = [w for line in open(mesh) if not line.lstrip().startswith("#")
         for w in line.split()]
def section(name):
    i = words.index(name)
    return int(words[i + 1])
nv, ntet = section("Vertices"), section("Tetrahedra")
bad = []
def need(cond, what):
    if not cond:
        bad.append(what)
need(d["cell_type"] == "tetrahedron", "cell type %s" % d["cell_type"])
need(d["vertices"] == nv, "vertices %d, file %d" % (d["vertices"], nv))
need(d["cells"] == ntet, "cells %d, file %d" % (d["cells"], ntet))
vi, vb = d["interior_vertices"], d["boundary_vertices"]
need(vi + vb + d["nonmanifold_vertices"] + d["unused_vertices"] == nv, "vertex classes")
need(d["nonmanifold_vertices"] == 0 and d["nonmanifold_edges"] == 0, "non-manifold parts")
need(d["interior_edges"] + d["boundary_edges"] + d["nonmanifold_edges"] == d["edges"],
     "edge classes")
# the boundary is a triangulated sphere; the ball has Euler characteristic 1
need(d["boundary_edges"] == 3 * vb - 6, "boundary: %d edges on %d vertices" %
     (d["boundary_edges"], vb))
nfaces = (4 * ntet + 2 * vb - 4) // 2  # interior faces counted twice, boundary once
need(nv - d["edges"] + nfaces - ntet == 1, "Euler characteristic of the ball")
need(vi > 20, "only %d interior vertices" % vi)
links = d["links"]
need(len(links) == d["distinct_links"], "distinct_links")
need(sum(l["count"] for l in links) == vi, "link multiplicities sum to %d, not %d" %
     (sum(l["count"] for l in links), vi))
vh = {int(k): v for k, v in d["vertex_valence"]["histogram"].items()}
eh = {int(k): v for k, v in d["edge_valence"]["histogram"].items()}
need(sum(vh.values()) == vi, "vertex histogram")
need(sum(eh.values()) == d["interior_edges"], "edge histogram")
byk = {}
for l in links:
    k = int(l["link"].split()[0])
    need(k == l["vertices"], "k of %s" % l["link"])
    lists = l["link"].split()[1].split(",")
    need(len(lists) == k and sum(map(len, lists)) == 6 * k - 12, "degrees of %s" % l["link"])
    byk[k] = byk.get(k, 0) + l["count"]
need(byk == vh, "vertex histogram vs links")
vm, em = d["vertex_valence"]["mean"], d["edge_valence"]["mean"]
need(abs(vm - sum(k * v for k, v in vh.items()) / vi) < 1e-9, "vertex mean")
need(abs(em - sum(k * v for k, v in eh.items()) / d["interior_edges"]) < 1e-9, "edge mean")
need(10 <= vm <= 20, "mean vertex valence %g" % vm)
need(4 <= em <= 6, "mean edge valence %g" % em)
need(d["vertex_valence"]["max"] == max(vh), "vertex max")
need(d["edge_valence"]["max"] == max(eh), "edge max")
if canon:
    text = "\n".join(l["link"] for l in links) + "\n"
    r = subprocess.run([exe, "enumerate", "canonical"], input=text, capture_output=True,
                       text=True)
    need(r.returncode == 0, "enumerate canonical: %s" % r.stderr.strip())
    need(r.stdout == text, "links are not in canonical form")
if bad:
    print("; ".join(bad), file=sys.stderr)
    sys.exit(1)
print("tetgen cube: %d vertices (%d interior, %d boundary), %d edges (%d interior), "
      "%d tets; vertex valence mean %.2f max %d; edge valence mean %.2f max %d; "
      "%d distinct links" % (nv, vi, vb, d["edges"], d["interior_edges"], ntet, vm,
                             d["vertex_valence"]["max"], em, d["edge_valence"]["max"],
                             len(links)))
PY

# the shipped stars: one interior vertex whose link is the icosahedron
icosa=$(printf 'icosahedron\n' | "$exe" enumerate canonical 2>/dev/null)
for m in hexstar-icosahedron tetstar-icosahedron; do
  checks=$((checks + 1))
  "$exe" enumerate mesh "$meshdir/$m.mesh" --format json 2>&1 |
    python3 -c 'import json,sys; d=json.load(sys.stdin); want=sys.argv[1]
assert d["interior_vertices"] == 1 and d["distinct_links"] == 1, d
assert d["links"][0]["vertices"] == 12 and d["edge_valence"]["histogram"] == {"5": 12}, d
assert not want or d["links"][0]["link"] == want, d["links"][0]["link"]' "$icosa" ||
    fail "$m"
done

# usage and input errors name the problem (and the file)
expect 0 "enumerate mesh FILE" "$exe" enumerate mesh --help
expect 2 "no mesh file given" "$exe" enumerate mesh
expect 2 "more than one" "$exe" enumerate mesh a.mesh b.mesh
expect 2 "--format 'xml'" "$exe" enumerate mesh --format xml "$tmp/cube.1.mesh"
expect 2 "unknown option '--bogus'" "$exe" enumerate mesh --bogus "$tmp/cube.1.mesh"
expect 2 "$tmp/missing.mesh" "$exe" enumerate mesh "$tmp/missing.mesh"
expect 2 "icosahedron.obj: .*no tetrahedra or hexahedra" "$exe" enumerate mesh "$meshdir/icosahedron.obj"
printf 'MeshVersionFormatted 1\nDimension 3\nVertices\n1\n0 0 0 0\nTetrahedra\n1\n1 2 3 4 0\nEnd\n' >"$tmp/dangling.mesh"
expect 2 "dangling.mesh" "$exe" enumerate mesh "$tmp/dangling.mesh"

expect_done "test_tetgen"
