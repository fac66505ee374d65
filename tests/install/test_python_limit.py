"""test_python_limit.py SUBSPECTRA SRCDIR -- the Python package's limit() /
Limit and store_table() (issue 40).

Run by test_install.sh as test_python.py is (the staged package on
PYTHONPATH, SUBSPECTRA_LIBRARY the staged library).  Checks
 - limit() against `subspectra limit --at ... --derivatives --format json` on
   the same mesh (the hex star of the icosahedron link, its points jittered,
   with a field as the Medit file's 4th coordinate): points, Jacobians, the
   field and its gradient within a relative 1e-12, the same status per point
   (the extraordinary vertex: no_derivatives) -- the command is a second
   path to the same numbers, through its own mesh reader and writer;
 - affine reproduction, against closed forms: limit(A x + b) = A limit(x) + b
   and its Jacobian J A^T; a field that is an affine function c.x + d of the
   control points has the limit c.p + d and the gradient J c; on a regular
   grid (B-spline cells) the limit of linear positions is linear in (u, v, w)
   and the Jacobian the identity;
 - arguments validated (TypeError, ValueError, SubspectraError with messages);
 - store_table() against `subspectra report --format json` (another writer)
   and against analyze() recomputing each case; array=True; where.
"""
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

import subspectra

exe, src = sys.argv[1], sys.argv[2]
fails = 0


def fail(msg):
    global fails
    fails += 1
    print("FAIL: " + msg, file=sys.stderr)


def close(a, b, rel, what):
    """a == b within rel of the largest |b| (NaN where both are NaN)."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    if a.shape != b.shape or (np.isnan(a) != np.isnan(b)).any():
        fail("%s: shapes %s %s or NaNs differ" % (what, a.shape, b.shape))
        return
    scale = max(np.nanmax(np.abs(b)) if b.size else 0.0, 1e-300)
    d = np.nanmax(np.abs(a - b)) if a.size else 0.0
    if d > rel * scale:
        fail("%s: differs by %g (relative %g > %g)" % (what, d, d / scale, rel))


def read_medit(path):
    """(points (n, 3), hexahedra (m, 8) from 0) of a Medit file with only
    Vertices and Hexahedra (as VTK's order: the library's)."""
    words = []
    with open(path) as f:
        for line in f:
            words += line.split("#")[0].split()
    i = words.index("Vertices")
    nv = int(words[i + 1])
    pts = np.array(words[i + 2:i + 2 + 4 * nv], dtype=float).reshape(nv, 4)[:, :3]
    i = words.index("Hexahedra")
    nc = int(words[i + 1])
    hexes = np.array(words[i + 2:i + 2 + 9 * nc], dtype=int).reshape(nc, 9)[:, :8] - 1
    return pts, hexes


def write_medit(path, pts, hexes, field):
    with open(path, "w") as f:
        f.write("MeshVersionFormatted 2\nDimension 4\nVertices\n%d\n" % len(pts))
        for p, w in zip(pts, field):
            f.write("%.17g %.17g %.17g %.17g 0\n" % (p[0], p[1], p[2], w))
        f.write("Hexahedra\n%d\n" % len(hexes))
        for h in hexes:
            f.write(" ".join(str(v + 1) for v in h) + " 0\n")
        f.write("End\n")


tmp = tempfile.mkdtemp()
rng = np.random.default_rng(40)
pts0, hexes = read_medit(os.path.join(src, "data", "meshes", "hexstar-icosahedron.mesh"))
pts = pts0 + rng.uniform(-0.01, 0.01, pts0.shape)
field = rng.uniform(-1, 1, len(pts))
mesh = os.path.join(tmp, "star.mesh")
write_medit(mesh, pts, hexes, field)

# ---- against the command line ----
m = 40
cells = rng.integers(0, len(hexes), m)
uvw = rng.uniform(0, 1, (m, 3))
uvw[:6] = [[0, 0, 0], [1, 1, 1], [0.5, 0, 0], [0, 0.25, 1], [1, 0.5, 0.5], [0.125, 0.875, 0.5]]
got = subspectra.limit("mlca", pts, {"hexahedron": hexes}, cells, uvw, derivatives=True,
                       fields=field)
args = [exe, "limit", "-s", "mlca", mesh, "-d", "--format", "json"]
for c, x in zip(cells, uvw):
    args += ["--at", "%d %.17g %.17g %.17g" % (c + 1, x[0], x[1], x[2])]
p = subprocess.run(args, capture_output=True, text=True)
lines = [json.loads(t) for t in p.stdout.splitlines()]
if p.returncode not in (0, 1) or len(lines) != m:
    fail("limit: exit %d, %d lines: %s" % (p.returncode, len(lines), p.stderr[:300]))
else:
    want_pts = np.array([t["point"] if t["point"] else [np.nan] * 3 for t in lines])
    want_jac = np.array([t["jacobian"] if t["jacobian"] else np.full((3, 3), np.nan)
                         for t in lines])
    fname = list(lines[0]["fields"])
    if len(fname) != 1:
        fail("limit: the command sees fields %s" % fname)
    want_f = np.array([[t["fields"][fname[0]]] for t in lines], dtype=float)
    want_df = np.array([[t["field_gradients"][fname[0]] or [np.nan] * 3] for t in lines],
                       dtype=float)
    close(got.points, want_pts, 1e-12, "limit points against the command")
    close(got.jacobians, want_jac, 1e-12, "limit Jacobians against the command")
    close(got.fields, want_f, 1e-12, "limit field against the command")
    close(got.field_gradients, want_df, 1e-12, "limit field gradients against the command")
    names = [t.get("status", "ok") for t in lines]
    if [subspectra._limit.STATUS_NAMES[s] for s in got.status] != names:
        fail("limit statuses %s, the command's %s" % (list(got.status), names))
    if names.count("no_derivatives") < 1 or sorted(got.reasons) != \
            [i for i, n in enumerate(names) if n != "ok"]:
        fail("limit: the extraordinary vertex (cell corner 0) should be no_derivatives: %s"
             % names)

# ---- affine reproduction ----
A = np.array([[1.2, 0.3, -0.1], [0.2, 0.9, 0.4], [-0.3, 0.1, 1.1]])
b = np.array([0.5, -2.0, 3.0])
c, d = np.array([0.7, -1.3, 0.4]), 2.5
with subspectra.Limit("mlca", pts @ A.T + b, [("hexahedron", hexes)],
                      fields=pts @ c + d) as L:
    if L.ncells != len(hexes) or L.nfields != 1:
        fail("Limit: %d cells, %d fields" % (L.ncells, L.nfields))
    aff = L.evaluate(cells, uvw, derivatives=True)
ok = got.status == 0
close(aff.points, got.points @ A.T + b, 1e-12, "limit of A x + b")
close(aff.jacobians[ok], got.jacobians[ok] @ A.T, 1e-12, "Jacobian of A x + b")
close(aff.fields[:, 0], got.points @ c + d, 1e-12, "affine field c.x + d")
close(aff.field_gradients[ok][:, 0], got.jacobians[ok] @ c, 1e-12, "affine field's gradient")
# a regular grid: 3 x 3 x 3 unit cells; the middle one is a B-spline patch
g = np.array([[i, j, k] for k in range(4) for j in range(4) for i in range(4)], dtype=float)
vid = lambda i, j, k: i + 4 * j + 16 * k  # noqa: E731
grid = np.array([[vid(i, j, k), vid(i + 1, j, k), vid(i + 1, j + 1, k), vid(i, j + 1, k),
                  vid(i, j, k + 1), vid(i + 1, j, k + 1), vid(i + 1, j + 1, k + 1),
                  vid(i, j + 1, k + 1)]
                 for k in range(3) for j in range(3) for i in range(3)])
mid = 13  # cell (1, 1, 1)
x = rng.uniform(0, 1, (10, 3))
r = subspectra.limit("ccsolid", g * 0.5, {"hexahedron": grid}, mid, x, derivatives=True)
close(r.points, 0.5 * (1 + x), 1e-14, "linear precision on the grid")
close(r.jacobians, np.broadcast_to(0.5 * np.eye(3), (10, 3, 3)), 1e-13, "grid Jacobian")
r2 = subspectra.limit("mlca", g * 0.5, {"hexahedron": grid}, mid, x[0])
close(r2.points, 0.5 * (1 + x[:1]), 1e-14, "one point, uvw of shape (3,)")
if r2.jacobians is not None or r2.fields is not None:
    fail("limit without derivatives or fields returned them")


# ---- arguments ----
def raises(exc, what, f, *a, **kw):
    try:
        f(*a, **kw)
    except exc as e:
        if what not in str(e):
            fail("%s: message %r lacks %r" % (exc.__name__, str(e), what))
    except Exception as e:
        fail("expected %s (%s), got %s: %s" % (exc.__name__, what, type(e).__name__, e))
    else:
        fail("expected %s (%s), nothing raised" % (exc.__name__, what))


H = {"hexahedron": grid}
G = g * 0.5
raises(TypeError, "cell: expected integers", subspectra.limit, "mlca", G, H, 2.0, x[0])
raises(TypeError, "uvw: expected real numbers", subspectra.limit, "mlca", G, H, 0, "abc")
raises(ValueError, "cell: 27 (point 1) is not a cell", subspectra.limit, "mlca", G, H,
       [0, 27], x[:2])
raises(ValueError, "not in [0,1]^3", subspectra.limit, "mlca", G, H, 0, [0.5, 1.5, 0])
raises(ValueError, "not in [0,1]^3", subspectra.limit, "mlca", G, H, 0, [0.5, np.nan, 0])
raises(ValueError, "do not broadcast", subspectra.limit, "mlca", G, H, [0, 1, 2], x[:2])
raises(TypeError, "derivatives: expected True or False", subspectra.limit, "mlca", G, H, 0,
       x[0], derivatives=1)
raises(TypeError, "scheme: expected", subspectra.Limit, None, G, H)
raises(subspectra.SubspectraError, "unknown scheme", subspectra.Limit, "nope", G, H)
raises(subspectra.SubspectraError, "", subspectra.Limit, "tetoct", G, H)
raises(ValueError, "points: expected an (n, 3) array", subspectra.Limit, "mlca", G[:, :2], H)
raises(ValueError, "fields: expected 64 values", subspectra.Limit, "mlca", G, H,
       fields=np.zeros(5))
raises(ValueError, "fields: the value at point 3 is not finite", subspectra.Limit, "mlca", G,
       H, fields=np.where(np.arange(64) == 3, np.inf, 0.0))
raises(subspectra.SubspectraError, "", subspectra.Limit, "mlca", G,
       {"tetra": np.array([[0, 1, 4, 16]])})
inverted = grid.copy()
inverted[0] = inverted[0][[4, 5, 6, 7, 0, 1, 2, 3]]
raises(subspectra.SubspectraError, "", subspectra.Limit, "mlca", G, {"hexahedron": inverted})
L = subspectra.Limit("mlca", G, H)
L.close()
raises(ValueError, "closed", L.evaluate, 0, x[0])

# ---- the results store ----
db = os.path.join(tmp, "s.db")
p = subprocess.run([exe, "sweep", "-s", "mlca", "--edges", "3..5", "--links", "-", "--db", db,
                    "-j", "1"], input="bipyramid:3\nbipyramid:5\noctahedron\n",
                   capture_output=True, text=True)
if p.returncode != 0:
    fail("sweep: exit %d: %s" % (p.returncode, p.stderr))
rows = subspectra.store_table(db)
rep = json.loads(subprocess.run([exe, "report", "--db", db, "--format", "json", "--table",
                                 "cases"], capture_output=True, text=True).stdout)["cases"]
if len(rows) != 6 or len(rep) != 6:
    fail("store_table: %d rows, report %d (want 6)" % (len(rows), len(rep)))
for t, j in zip(rows, rep):
    key = (t["case"], t["k"], t["link"])
    if key != (j["case"], j["k"], j.get("link", "")):
        fail("store_table row %s, report's %s" % (key, (j["case"], j["k"], j.get("link"))))
        continue
    for q in range(1, 5):
        e = j["eigenvalues"][q]
        if (t["lambda%d_re" % q], t["lambda%d_im" % q], t["lambda%d_mult" % q]) != \
                (e["re"], e["im"], e["multiplicity"]):
            fail("store_table %s lambda%d differs from report's" % (key, q))
    if (t["eigen_condition"], t["regularity"], t["injectivity"], t["verdict"],
            t["min_scaled_jacobian"], t["tolerance"], t["regularity_certified"]) != \
            (j["eigen_condition"]["verdict"], j["regularity"]["verdict"],
             j["injectivity"]["verdict"], j["verdict"],
             j["regularity"]["min_scaled_jacobian"], j["eigen_condition"]["tolerance"],
             j["regularity"]["certified"]):
        fail("store_table %s verdicts differ from report's" % (key,))
    # recomputed: an edge point is the edge of valence k - 2
    case = {"vertex": t["link"]} if t["case"] != "edge" else {"edge": t["k"]}
    a = subspectra.analyze("mlca", **case)
    close([t["lambda%d_re" % q] for q in range(1, 5)],
          [a["eigenvalues"][q]["re"] for q in range(1, 5)], 1e-12, "store %s vs analyze" % (key,))
kinds = [t["case"] for t in rows]
if kinds.count("edge-point") != 2 or kinds.count("vertex") != 1:
    fail("store_table cases %s" % kinds)
arr = subspectra.store_table(db, array=True)
if arr.shape != (6,) or list(arr["k"]) != [t["k"] for t in rows] or \
        arr["k"].dtype != np.int64 or not np.isnan(arr["improper_pairs"]).all() or \
        arr["regularity_certified"].dtype != bool:
    fail("store_table(array=True): %s" % (arr.dtype,))
if [t["k"] for t in subspectra.store_table(db, where="k = 5")] != [5, 5]:
    fail("store_table(where='k = 5')")
raises(TypeError, "path: expected", subspectra.store_table, 5)
raises(TypeError, "where: expected", subspectra.store_table, db, where=5)
raises(subspectra.SubspectraError, "no such results store", subspectra.store_table,
       os.path.join(tmp, "none.db"))
raises(subspectra.SubspectraError, "not a subspectra results store", subspectra.store_table,
       mesh)
raises(subspectra.SubspectraError, "syntax error", subspectra.store_table, db, where="k = (")

# docstrings: what help() shows
for f in (subspectra.limit, subspectra.Limit, subspectra.Limit.evaluate,
          subspectra.store_table, subspectra.LimitValues):
    if not f.__doc__ or len(f.__doc__) < 200:
        fail("%s: no useful docstring" % f.__name__)

for f in os.listdir(tmp):
    os.remove(os.path.join(tmp, f))
os.rmdir(tmp)
print("test_python_limit: %s" % ("all checks passed" if not fails else "%d failed" % fails))
sys.exit(1 if fails else 0)
