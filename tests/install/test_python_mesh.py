"""test_python_mesh.py SUBSPECTRA SRC -- the Python package's mesh files and
the row labels of S against meshes (issue 40).

Run by test_install.sh beside test_python.py (the staged package on
PYTHONPATH, SUBSPECTRA_LIBRARY the staged library).  Checks
 - local_labels() names mesh points: on a regular grid (MLCA's edge of
   valence 4 in a hex grid, Catmull-Clark's quad grid, Loop's triangle grid)
   the point a label x names sits at x @ axes on the grid (a point of the
   mesh at that place, found by position), and on the same grid with
   jittered points the global refinement (subdivide) agrees row by row with
   the local matrix: fine[label i] = sum_j S[i, j] coarse[label j] -- wrong
   or permuted labels, or rows of S not the rule's, fail;
 - read_mesh() against meshio (another reader) on the project's Medit files:
   the same points, cells and references;
 - write_mesh() read back by meshio: .vtu with point data (scalars and a
   vector as NAME_x/_y/_z), .vtk and .mesh, and by read_mesh() (octahedra
   come back as octahedra from .vtu);
 - read_mesh -> subdivide -> write_mesh equals `subspectra subdivide ... -o
   FILE.vtu` (both read by meshio: the same points to the last bit);
 - errors: a missing file, a malformed one, an unknown format, volume cells
   in .obj, point data of the wrong length.
"""
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

import subspectra

exe, src = sys.argv[1], sys.argv[2]
fails = 0
meshes = os.path.join(src, "data", "meshes")
tmp = tempfile.mkdtemp()


def fail(msg):
    global fails
    fails += 1
    print("FAIL: " + msg, file=sys.stderr)


def spokes(n):
    return np.array([[math.cos(2 * math.pi * k / n), math.sin(2 * math.pi * k / n)]
                     for k in range(n)])


def hex_grid(r):
    """The hex grid [-r, r]^3 of side 1: points, hexahedra (VTK order)."""
    ax = np.arange(-r, r + 1, dtype=float)
    pts = np.array([[x, y, z] for z in ax for y in ax for x in ax])
    m = 2 * r + 1

    def v(i, j, k):
        return i + m * (j + m * k)
    hexes = [[v(i, j, k), v(i + 1, j, k), v(i + 1, j + 1, k), v(i, j + 1, k),
              v(i, j, k + 1), v(i + 1, j, k + 1), v(i + 1, j + 1, k + 1), v(i, j + 1, k + 1)]
             for k in range(2 * r) for j in range(2 * r) for i in range(2 * r)]
    return pts, {"hexahedron": np.array(hexes)}


def quad_grid(r):
    ax = np.arange(-r, r + 1, dtype=float)
    pts = np.array([[x, y] for y in ax for x in ax])
    m = 2 * r + 1
    quads = [[i + m * j, i + 1 + m * j, i + 1 + m * (j + 1), i + m * (j + 1)]
             for j in range(2 * r) for i in range(2 * r)]
    return pts, {"quad": np.array(quads)}


def tri_grid(r):
    """The regular triangle grid: point (i, j) at i (1, 0) + j (1/2, sqrt3/2)."""
    e1, e2 = np.array([1.0, 0.0]), np.array([0.5, math.sqrt(3) / 2])
    m = 2 * r + 1
    pts = np.array([i * e1 + j * e2 for j in range(-r, r + 1) for i in range(-r, r + 1)])
    tris = []
    for j in range(2 * r):
        for i in range(2 * r):
            a, b, c, d = i + m * j, i + 1 + m * j, i + m * (j + 1), i + 1 + m * (j + 1)
            tris += [[a, b, c], [b, d, c]]  # counter-clockwise
    return pts, {"triangle": np.array(tris)}


def index_by_position(points, where, scale):
    """The index of the point of `points` at each row of `where` (to 1e-9 of
    the grid's unit scale), or -1."""
    key = {tuple(np.round(p / scale * 4).astype(int)): i for i, p in enumerate(points)}
    out = []
    for p in where:
        q = np.round(p / scale * 4)
        hit = key.get(tuple(q.astype(int)), -1)
        if hit >= 0 and np.abs(points[hit] - p).max() > 1e-9 * scale:
            hit = -1
        out.append(hit)
    return np.array(out)


# local_labels against the mesh: the regular grids, S read from level 0 to
# level 1 (the regular cases are stationary everywhere inside the grid)
rng = np.random.default_rng(40)
for scheme, case, grid, axes in (
        # the edge star's hexes are 1 x 1 x 2 in the chart (its ends at
        # -+e_n, ss_star.h): on a grid of cubes the edge's axis is half long
        ("mlca", {"edge": 4}, hex_grid(5), np.block([[spokes(4), np.zeros((4, 1))],
                                                     [np.zeros((1, 2)), 0.5 * np.ones((1, 1))]])),
        ("catmull-clark", {"surface_vertex": 4}, quad_grid(4), spokes(4)),
        ("loop", {"surface_vertex": 6}, tri_grid(4), spokes(6))):
    coords, n1 = subspectra.local_labels(scheme, **case)
    S = subspectra.local_matrix(scheme, **case).toarray()
    pts, cells = grid
    fine, _ = subspectra.subdivide(scheme, pts, cells, levels=1)
    P = coords @ axes
    i0 = index_by_position(pts, P, 1.0)
    i1 = index_by_position(fine, P / 2, 0.5)
    what = "local_labels(%r, %s)" % (scheme, case)
    if (i0 < 0).any() or (i1 < 0).any():
        fail("%s: %d labels name no point of the grid, %d none of the refined grid"
             % (what, (i0 < 0).sum(), (i1 < 0).sum()))
        continue
    jit = pts + rng.uniform(-0.08, 0.08, size=pts.shape)
    jfine, _ = subspectra.subdivide(scheme, jit, cells, levels=1)
    err = np.abs(jfine[i1] - S @ jit[i0]).max()
    if err > 1e-12 * np.abs(jit).max():
        fail("%s: refined jittered grid != S @ coarse at the labelled points (%g)"
             % (what, err))
    else:
        print("ok: %s: %d labels name grid points; S = the refinement there (%.1e)"
              % (what, len(coords), err))

# read_mesh against meshio
try:
    import meshio
except ImportError:
    meshio = None
    print("read_mesh/write_mesh against meshio: SKIPPED (no meshio)")


def same_cells(a, b, what):
    if sorted(a) != sorted(b) or any(a[k].shape != b[k].shape or (a[k] != b[k]).any()
                                     for k in a):
        fail("%s: cells %s vs %s" % (what, {k: v.shape for k, v in a.items()},
                                     {k: v.shape for k, v in b.items()}))


if meshio is not None:
    for f in ("cube-6tets.mesh", "hexstar-icosahedron.mesh", "tetstar-icosahedron.mesh",
              "cube-creased.mesh"):
        m, mm = subspectra.read_mesh(os.path.join(meshes, f)), meshio.read(os.path.join(meshes, f))
        if m.points.shape != mm.points.shape or np.abs(m.points - mm.points).max() != 0:
            fail("read_mesh(%s): points differ from meshio's" % f)
        same_cells(m.cells, mm.cells_dict, "read_mesh(%s)" % f)
        want = {b.type: r for b, r in zip(mm.cells, mm.cell_data["medit:ref"])}
        for (t, r) in zip(m.cells, m.cell_data["ref"]):
            if (r != want[t]).any():
                fail("read_mesh(%s): %s references differ from meshio's" % (f, t))
    print("ok: read_mesh == meshio.read on the Medit meshes")

    # write_mesh read back by meshio and by read_mesh, with fields
    m = subspectra.read_mesh(os.path.join(meshes, "hexstar-icosahedron.mesh"))
    dens = np.sin(m.points[:, 0]) + m.points[:, 2]
    vel = m.points * [1, -2, 3]
    for ext in ("vtu", "vtk"):
        out = os.path.join(tmp, "w." + ext)
        subspectra.write_mesh(out, m.points, m.cells, point_data={"dens": dens, "vel": vel})
        r = meshio.read(out)
        if np.abs(r.points - m.points).max() != 0 or \
                np.abs(r.point_data["dens"].ravel() - dens).max() != 0 or \
                any(np.abs(r.point_data["vel_" + a].ravel() - vel[:, j]).max() != 0
                    for j, a in enumerate("xyz")):
            fail("write_mesh(.%s): meshio reads other points or point data: %s"
                 % (ext, list(r.point_data)))
        same_cells(r.cells_dict, m.cells, "write_mesh(.%s) read by meshio" % ext)
        b = subspectra.read_mesh(out)
        if sorted(b.point_data) != ["dens", "vel_x", "vel_y", "vel_z"] or \
                np.abs(b.point_data["vel_y"] - vel[:, 1]).max() != 0:
            fail("write_mesh(.%s) read back: point data %s" % (ext, list(b.point_data)))
    out = os.path.join(tmp, "w.mesh")
    subspectra.write_mesh(out, m.points, m.cells, cell_data={"ref": [np.arange(20) % 3 + 1]})
    r = meshio.read(out)
    if (r.cell_data["medit:ref"][0] != np.arange(20) % 3 + 1).any():
        fail("write_mesh(.mesh, cell_data): references %s" % r.cell_data["medit:ref"][0])
    print("ok: write_mesh: .vtu, .vtk with point data and .mesh with references, "
          "read back by meshio and read_mesh")

# octahedra through .vtu (meshio has no octahedron: read_mesh only)
m = subspectra.read_mesh(os.path.join(meshes, "cube-6tets.mesh"))
p, c = subspectra.subdivide("tetoct", m.points, m.cells, levels=1)
subspectra.write_mesh(os.path.join(tmp, "o.vtu"), p, c)
b = subspectra.read_mesh(os.path.join(tmp, "o.vtu"))
if np.abs(b.points - p).max() != 0:
    fail("tet/oct mesh through .vtu: points")
same_cells(b.cells, c, "tet/oct mesh through .vtu")
print("ok: octahedra through write_mesh/read_mesh (.vtu)")

# read_mesh -> subdivide -> write_mesh == subspectra subdivide
if meshio is not None:
    inp = os.path.join(meshes, "hexstar-icosahedron.mesh")
    m = subspectra.read_mesh(inp)
    x = np.column_stack([m.points, m.points[:, 0] * m.points[:, 1]])
    cmd_in = os.path.join(tmp, "in.vtu")
    subspectra.write_mesh(cmd_in, m.points, m.cells, point_data={"f": x[:, 3]})
    p, c = subspectra.subdivide("mlca", x, m.cells, levels=2)
    subspectra.write_mesh(os.path.join(tmp, "py.vtu"), p[:, :3], c, point_data={"f": p[:, 3]})
    r = subprocess.run([exe, "subdivide", "--scheme", "mlca", "--levels", "2", cmd_in,
                        "-o", os.path.join(tmp, "cli.vtu")], capture_output=True, text=True)
    if r.returncode:
        fail("subdivide: exit %d: %s" % (r.returncode, r.stderr))
    else:
        a, b = meshio.read(os.path.join(tmp, "py.vtu")), meshio.read(os.path.join(tmp, "cli.vtu"))
        if a.points.shape != b.points.shape or np.abs(a.points - b.points).max() != 0 or \
                np.abs(a.point_data["f"] - b.point_data["f"]).max() != 0:
            fail("read_mesh/subdivide/write_mesh differs from `subdivide -o FILE.vtu`")
        same_cells(a.cells_dict, b.cells_dict, "subdivide vs the command")
        print("ok: read_mesh -> subdivide -> write_mesh == subspectra subdivide (.vtu, a field)")


def raises(exc, what, f, *a, **kw):
    try:
        f(*a, **kw)
        fail("%s(%s) did not raise" % (f.__name__, what))
    except exc as e:
        if what not in str(e):
            fail("%s: %r does not say %r" % (f.__name__, str(e), what))


bad = os.path.join(tmp, "bad.mesh")
with open(bad, "w") as f:
    f.write("MeshVersionFormatted 2\nDimension 3\nVertices\n2\n0 0 0 0\n")
raises(subspectra.SubspectraError, "nope.mesh: No such file", subspectra.read_mesh,
       os.path.join(tmp, "nope.mesh"))
raises(subspectra.SubspectraError, "bad.mesh", subspectra.read_mesh, bad)
raises(ValueError, "unknown mesh format 'stl'", subspectra.read_mesh, bad, fmt="stl")
raises(TypeError, "path: expected", subspectra.read_mesh, 5)
m = subspectra.read_mesh(os.path.join(meshes, "cube-6tets.mesh"))
raises(subspectra.SubspectraError, "", subspectra.write_mesh, os.path.join(tmp, "t.obj"),
       m.points, m.cells)
raises(ValueError, "point_data['d']: expected", subspectra.write_mesh,
       os.path.join(tmp, "t.vtu"), m.points, m.cells, point_data={"d": np.zeros(3)})
if os.path.exists(os.path.join(tmp, "t.obj")) or os.path.exists(os.path.join(tmp, "t.vtu")):
    fail("write_mesh left a file behind after an error")
print("ok: read_mesh/write_mesh: bad input")

for f in os.listdir(tmp):
    os.remove(os.path.join(tmp, f))
os.rmdir(tmp)
print("test_python_mesh: %s" % ("all checks passed" if not fails else "%d failed" % fails))
sys.exit(1 if fails else 0)
