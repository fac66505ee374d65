#!/usr/bin/env bash
# test_meshio.sh SUBSPECTRA — third-party readers take what subdivide writes
# (issue 21): meshio (Debian's python3-meshio, installed by ./run) reads the
# default Medit output of a tet/oct refinement with every octahedron split into
# four tets (cell and point counts from subdivide's own report), the legacy VTK
# (octahedra as two pyramids) and OBJ; the Octahedra extension written on
# request is what meshio refuses, which is why it is not the default.
# SKIPPED (77) without meshio.
set -u
exe=$1
. "$(dirname "$0")/../ss_expect.sh"
py=/usr/bin/python3
"$py" -c 'import meshio' 2>/dev/null || { echo "SKIP: python3-meshio not installed"; exit 77; }
src=$(cd "$(dirname "$0")/../.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
log=$("$exe" subdivide --scheme tetoct --levels 2 "$src/data/meshes/cube-6tets.mesh" -o "$tmp/t.mesh" 2>&1)
"$exe" subdivide --scheme tetoct --levels 2 "$src/data/meshes/cube-6tets.mesh" -o "$tmp/t.vtk" >/dev/null 2>&1
"$exe" subdivide --scheme tetoct --levels 2 "$src/data/meshes/cube-6tets.mesh" -o "$tmp/k.mesh" --octahedra-keyword >/dev/null 2>&1
"$exe" subdivide --scheme loop --levels 2 "$src/data/meshes/icosahedron.obj" -o "$tmp/i.obj" >/dev/null 2>&1
read -r nv ntet noct < <(sed -n 's/^tetoct level 2: \([0-9]*\) vertices, \([0-9]*\) tetrahedra, \([0-9]*\) octahedra.*/\1 \2 \3/p' <<<"$log")
checks=$((checks + 1))
[ -n "${noct:-}" ] && [ "$noct" -gt 0 ] || fail "no level-2 counts in: $log"
checks=$((checks + 1))
"$py" - "$tmp" "$nv" "$ntet" "$noct" <<'PY' || fail "meshio"
import sys, warnings
import meshio
warnings.simplefilter("ignore")
d, nv, ntet, noct = sys.argv[1], *map(int, sys.argv[2:])
def count(m, t):
    return sum(len(c.data) for c in m.cells if c.type == t)
m = meshio.read(d + "/t.mesh")
assert len(m.points) == nv and count(m, "tetra") == ntet + 4 * noct, (len(m.points), count(m, "tetra"))
v = meshio.read(d + "/t.vtk")
assert len(v.points) == nv and count(v, "tetra") == ntet and count(v, "pyramid") == 2 * noct
o = meshio.read(d + "/i.obj")
assert count(o, "triangle") == 20 * 16, count(o, "triangle")
# meshio 5 reports an unreadable file by exiting (SystemExit), later ones raise
try:
    meshio.read(d + "/k.mesh")
    refused = False
except BaseException:
    refused = True
assert refused, "meshio read the Octahedra extension: the default could keep it"
PY
expect_done "meshio"
