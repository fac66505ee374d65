#!/usr/bin/env bash
# test_vtu.sh SUBSPECTRA — `subdivide -o FILE.vtu` (issue 40): meshio (Debian's
# python3-meshio) reads the VTK XML file back, and its points, cells and
# references equal, bit for bit and in order, those of the Medit file the same
# command writes: mlca (hexahedra and crease quadrilaterals), Loop (triangles
# in 3D) and tetoct, whose octahedra are two VTK pyramids each — checked
# against the octahedra of the --octahedra-keyword Medit file (read here by a
# reader of its own: meshio refuses that keyword): the pair's apexes are the
# octahedron's diagonal 0-3, their bases its equator, and each pyramid has
# positive volume in VTK's convention (base normal towards the apex) on a
# base whose diagonals are the equator's.
# `--output-format vtu -o /dev/stdout` writes the same bytes, the summary on
# stderr.  SKIPPED (77) without meshio.
set -u
exe=$1
. "$(dirname "$0")/../ss_expect.sh"
py=/usr/bin/python3
"$py" -c 'import meshio' 2>/dev/null || { echo "SKIP: python3-meshio not installed"; exit 77; }
src=$(cd "$(dirname "$0")/../.." && pwd)
m=$src/data/meshes
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
run() { # NAME SCHEME LEVELS IN [options]: NAME.vtu, NAME.mesh and NAME-k.mesh
  local name=$1 scheme=$2 levels=$3 in=$4
  shift 4
  for out in "$name.vtu" "$name.mesh"; do
    expect 0 "wrote .*$out" "$exe" subdivide --scheme "$scheme" --levels "$levels" "$in" \
      -o "$tmp/$out" "$@"
  done
  expect 0 "wrote" "$exe" subdivide --scheme "$scheme" --levels "$levels" "$in" \
    -o "$tmp/$name-k.mesh" --octahedra-keyword "$@"
}
run hex mlca 2 "$m/cube-creased.mesh"
run tri loop 2 "$m/icosahedron.obj"
run to tetoct 2 "$m/cube-6tets.mesh"

# standard output: the same bytes, the summary on stderr
checks=$((checks + 1))
"$exe" subdivide --scheme tetoct --levels 2 "$m/cube-6tets.mesh" -o /dev/stdout \
  --output-format vtu >"$tmp/stdout.vtu" 2>"$tmp/stderr" || fail "--output-format vtu -o /dev/stdout"
cmp -s "$tmp/stdout.vtu" "$tmp/to.vtu" || fail "-o /dev/stdout --output-format vtu differs from to.vtu"
checks=$((checks + 1))
grep -q '^wrote /dev/stdout (vtu)$' "$tmp/stderr" || fail "no summary on stderr: $(cat "$tmp/stderr")"
expect 2 "--output-format: expected medit, vtk, vtu, gmsh or obj, not 'xml'" \
  "$exe" subdivide --scheme tetoct "$m/cube-6tets.mesh" -o /dev/stdout --output-format xml
expect 2 "cannot tell the format of '/dev/stdout'" \
  "$exe" subdivide --scheme tetoct "$m/cube-6tets.mesh" -o /dev/stdout

checks=$((checks + 1))
"$py" - "$tmp" <<'PY' || fail "meshio: the VTU differs from the Medit file"
import sys, warnings
import numpy as np
import meshio
warnings.simplefilter("ignore")
d = sys.argv[1]
# meshio's names of this project's cell types, in the order the files hold them
ORDER = ["vertex", "line", "triangle", "quad", "tetra", "hexahedron"]

def bits(a):
    return np.ascontiguousarray(a, dtype=np.float64).view(np.uint64)

def medit(path):
    """The Medit file's vertices (3 columns), their refs, and each section's
    cells (0-based) and refs: a reader of its own for the Octahedra keyword."""
    tok = open(path).read().split()
    sec, i = {}, 0
    nv = {"Vertices": None, "Edges": 2, "Triangles": 3, "Quadrilaterals": 4,
          "Tetrahedra": 4, "Hexahedra": 8, "Octahedra": 6, "Corners": 1}
    while i < len(tok):
        k = tok[i]
        if k in ("MeshVersionFormatted", "Dimension"):
            if k == "Dimension":
                dim = int(tok[i + 1])
            i += 2
        elif k == "End":
            break
        elif k in nv:
            n = int(tok[i + 1])
            w = (dim + 1) if k == "Vertices" else nv[k] + (0 if k == "Corners" else 1)
            sec[k] = tok[i + 2:i + 2 + n * w]
            sec[k] = np.array(sec[k], dtype=float if k == "Vertices" else np.int64).reshape(n, w)
            i += 2 + n * w
        else:
            raise ValueError("unexpected " + k)
    return dim, sec

def vtu_blocks(v):
    out = {}
    for b, ref, kind in zip(v.cells, v.cell_data["ref"], v.cell_data["kind"]):
        out.setdefault(b.type, []).append((b.data, ref, kind))
    return {t: tuple(np.concatenate([x[j] for x in l]) for j in range(3)) for t, l in out.items()}

for name in ("hex", "tri", "to"):
    v = meshio.read(f"{d}/{name}.vtu")
    vb = vtu_blocks(v)
    dim, sec = medit(f"{d}/{name}-k.mesh")
    x = np.zeros((len(sec["Vertices"]), 3))
    x[:, :dim] = sec["Vertices"][:, :dim]
    assert np.array_equal(bits(v.points), bits(x)), name + ": points"
    assert np.array_equal(v.point_data["vref"], sec["Vertices"][:, dim]), name + ": vref"
    # every type but octahedra: meshio's reading of the default Medit file
    m = meshio.read(f"{d}/{name}.mesh")
    assert np.array_equal(bits(m.points), bits(v.points)), name + ": points (meshio)"
    kinds = {"line": 1, "triangle": 2, "quad": 3, "tetra": 4, "hexahedron": 5}
    for t in ORDER[1:]:
        mc = [c.data for c in m.cells if c.type == t]
        mr = [r for c, r in zip(m.cells, m.cell_data["medit:ref"]) if c.type == t]
        if t == "tetra" and "Octahedra" in sec:  # the default file splits them: 4 tets each
            n = len(sec["Tetrahedra"])
            mc, mr = [np.concatenate(mc)[:n]], [np.concatenate(mr)[:n]]
        if not mc:
            assert t not in vb, f"{name}: {t} only in the VTU"
            continue
        cells, ref, kind = vb[t]
        assert np.array_equal(cells, np.concatenate(mc)), f"{name}: {t} cells"
        assert np.array_equal(ref, np.concatenate(mr)), f"{name}: {t} refs"
        assert (kind == kinds[t]).all(), f"{name}: {t} kind"
    print(name, len(v.points), "points,", {t: len(c[0]) for t, c in vb.items()})
    if "Octahedra" not in sec:
        assert "pyramid" not in vb, name
        continue
    oc = sec["Octahedra"][:, :6] - 1
    cells, ref, kind = vb["pyramid"]
    assert len(cells) == 2 * len(oc) and (kind == 6).all(), name + ": two pyramids per octahedron"
    assert np.array_equal(ref, np.repeat(sec["Octahedra"][:, 6], 2)), name + ": pyramid refs"
    p = v.points
    for o, (a, b) in zip(oc, cells.reshape(-1, 2, 5)):
        assert {a[4], b[4]} == {o[0], o[3]}, "apexes = the 0-3 diagonal"
        assert set(a[:4]) == set(b[:4]) == {o[1], o[2], o[4], o[5]}, "bases = the equator"
        for q in (a, b):  # cyclic: the base's diagonals are the equator's opposite pairs
            assert {frozenset((q[0], q[2])), frozenset((q[1], q[3]))} == {
                frozenset((o[1], o[4])), frozenset((o[2], o[5]))}, "a crossed base"
        for q in (a, b):
            vol = np.linalg.det(np.array([p[q[1]] - p[q[0]], p[q[2]] - p[q[0]], p[q[4]] - p[q[0]]]))
            assert vol > 0, "a pyramid of negative volume"
PY
expect_done "vtu"
