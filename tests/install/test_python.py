"""test_python.py SUBSPECTRA LAYOUT -- the installed Python package (issue 21).

Run by test_install.sh with the staged package on PYTHONPATH and
SUBSPECTRA_LIBRARY naming the staged shared library.  Checks
 - analyze() returns the dictionary of `subspectra analyze --format json` for
   an edge, a vertex (named link), a face and a surface vertex, with major
   diagonals, an edge point and the exact path (--certify; its timing key
   aside): the same keys
   everywhere, the same strings and integers, numbers within a relative 1e-12
   (both run the same library code, so they agree to rounding or better);
 - analyze()'s psi-level verdicts (psi_depth, psi_tubes) equal the command's
   (--psi-depth, --psi-tubes) and say what is known of those cases: a pass on
   psi's pieces for the regular vertex, a fold with two witnesses for MLCA's
   k = 8 finding, the tubes proven with certify;
 - local_matrix() equals the Matrix Market export of `subspectra matrix`, and
   its rows sum to 1 (partition of unity);
 - eigenvalues() against closed forms: Catmull-Clark at valence n, lambda1 =
   lambda2 = (5 + cos(2pi/n) + cos(pi/n) sqrt(2 (9 + cos(2pi/n))))/16 (double),
   and the regular MLCA edge's tricubic spectrum 1, 1/2 (x3), 1/4 (x6);
 - eigenvectors(): S R = R diag(v), L^T S = diag(v) L^T, L^T R = I, r_0 = 1,
   and Catmull-Clark's closed-form limit-position mask;
 - bad input raises SubspectraError naming the problem, arguments of the
   wrong type TypeError naming the argument (vertex=5, edge=5.9, tol="x",
   certify=1, scheme=None), a SUBSPECTRA_LIBRARY that does not load
   SubspectraError naming the path (no other library is taken);
 - local_labels() against linear precision on the regular grids (S P = P / 2);
 - enumerate_links() against the counts of A000109 and `enumerate links`;
 - jsr() equals `jsr --format json`;
 - subdivide() equals `subdivide -o FILE.mesh` (read back by meshio), makes
   the tet/oct split's counts, and is affine invariant;
 - the structure layouts the package declares to cffi equal the C compiler's
   (LAYOUT: lines "sizeof T N" and "offsetof T FIELD N" from the installed
   headers), so a field added to ss_case or ss_local is caught here.
"""
import io
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

import numpy as np
import scipy.io

import subspectra

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import ss_json_same  # noqa: E402 -- beside this file

exe, layout = sys.argv[1], sys.argv[2]
fails = 0


def fail(msg):
    global fails
    fails += 1
    print("FAIL: " + msg, file=sys.stderr)


def same(a, b, path):
    """Recursive comparison; numbers within a relative 1e-12 (ss_json_same)."""
    ss_json_same.same(a, b, path, fail)


def cli(*args):
    p = subprocess.run([exe] + list(args), capture_output=True, text=True)
    if p.returncode not in (0, 1):
        fail("%s: exit %d: %s" % (" ".join(args), p.returncode, p.stderr))
    return p.stdout


# the declarations against the headers, first: nothing else means anything
# if they disagree
with open(layout) as f:
    for line in f:
        w = line.split()
        if w[0] == "sizeof":
            got, want = subspectra._ffi.sizeof(w[1]), int(w[2])
        else:
            got, want = subspectra._ffi.offsetof(w[1], w[2]), int(w[3])
        if got != want:
            fail("layout: %s: cffi %d, C %d (update the cdef in subspectra/__init__.py)"
                 % (" ".join(w[:-1]), got, want))
if not fails:
    print("ok: cffi layouts equal the headers'")

cases = [
    ("mlca", {"edge": 5}, ["--edge", "5"]),
    ("tetoct", {"vertex": "octahedron"}, ["--vertex", "octahedron"]),
    ("tetoct", {"face": True}, ["--face"]),
    ("catmull-clark", {"surface_vertex": 3}, ["--surface-vertex", "3"]),
    # major diagonals, a vertex judged as an edge point, the exact path
    ("boxspline", {"edge": 5, "diagonals": "skew"}, ["--edge", "5", "--diagonals", "skew"]),
    ("mlca", {"vertex": "bipyramid:5"}, ["--vertex", "bipyramid:5"]),
    ("tetoct", {"vertex": "octahedron", "certify": True}, ["--vertex", "octahedron",
                                                          "--certify"]),
    # quasi48: the 4-8 class, given and by default (valence 6: class 8)
    ("quasi48", {"surface_vertex": 5, "cls": 4}, ["--surface-vertex", "5", "--class", "4"]),
    ("quasi48", {"surface_vertex": 6}, ["--surface-vertex", "6"]),
]
for scheme, case, args in cases:
    want = json.loads(cli("analyze", "--scheme", scheme, *args, "--format", "json"))
    got = subspectra.analyze(scheme, **case)
    for d in (got, want):  # a wall-clock time, the one key that may differ
        d["eigen_condition"].pop("exact_seconds", None)
    same(got, want, "%s %s" % (scheme, case))
    if scheme == "quasi48" and got.get("class") != case.get("cls", 8):
        fail("quasi48 %s: class %r" % (case, got.get("class")))
    print("ok: analyze(%r, %s) == analyze --format json (%s)"
          % (scheme, case, got["eigen_condition"]["verdict"]))
# options reach the library: fewer eigenvalues, as --eigenvalues
got = subspectra.analyze("mlca", edge=5, eigenvalues=4, tol=1e-8)
want = json.loads(cli("analyze", "--scheme", "mlca", "--edge", "5", "--eigenvalues", "4",
                      "--tol", "1e-8", "--format", "json"))
same(got, want, "mlca edge 5 with options")
if len(got["eigenvalues"]) != 4:
    fail("eigenvalues=4 gave %d" % len(got["eigenvalues"]))

# the psi-level verdicts (issue 40): analyze() judges psi itself as the
# command does (psi_depth 4 by default), psi_depth=0 leaves it out, and
# psi_tubes with certify proves the spokes' tubes -- each against the
# command's JSON; and what they say, checked apart from the command: the
# regular vertex passes on psi (the tricubic B-spline, 8 pieces), MLCA's k = 8
# finding fails on psi with two witnesses of opposite det Dpsi signs
K8 = "8 bcdefgh,ahc,abhd,ache,adhf,aehg,afh,agfedcb"
K6 = "6 bcdef,afc,abfd,acfe,adf,aedcb"  # two spokes of valence 3: tubes to prove
psi = {}
for name, case, args in (
        ("default", {"vertex": "octahedron"}, ["--vertex", "octahedron"]),
        ("depth0", {"vertex": "octahedron", "psi_depth": 0},
         ["--vertex", "octahedron", "--psi-depth", "0"]),
        ("k8", {"vertex": K8, "psi_depth": 3}, ["--vertex", K8, "--psi-depth", "3"]),
        ("tubes", {"vertex": K6, "certify": True, "psi_depth": 1, "psi_tubes": True},
         ["--vertex", K6, "--certify", "--psi-depth", "1", "--psi-tubes"])):
    want = json.loads(cli("analyze", "--scheme", "mlca", *args, "--format", "json"))
    psi[name] = got = subspectra.analyze("mlca", **case)
    for d in (got, want):
        d["eigen_condition"].pop("exact_seconds", None)
    same(got, want, "mlca %s (psi)" % name)
g = psi["default"]["regularity"]
if g["judged_on"] != "psi" or g["psi"]["verdict"] != "pass" or g["psi"]["pieces"] != 8 \
        or g["psi"]["covered"] != 1.0:
    fail("mlca octahedron: regularity not a pass judged on psi's 8 pieces: %s" % g)
g = psi["depth0"]["regularity"]
if g["judged_on"] != "control-net" or g["psi"] is not None:
    fail("mlca octahedron, psi_depth=0: psi judged anyway: %s" % g)
g = psi["k8"]["regularity"]
w = g["witness"] or []
if g["judged_on"] != "psi" or g["psi"]["verdict"] != "fail" or g["psi"]["box_depth"] != 3 \
        or len(w) != 2 or not w[0]["det"][0] * w[1]["det"][1] < 0:
    fail("mlca k = 8: not a fold of psi with two witnesses: %s" % g)
g = psi["tubes"]["regularity"]
t = g["psi"]["tubes"] if g["psi"] else None
if not (g["verdict"] == "pass" and g["certified"] and g["judged_on"] == "psi") \
        or not t or t["proven"] != t["boxes"] or t["boxes"] == 0:
    fail("mlca %s, certified with tubes: %s" % (K6, g))
print("ok: analyze: psi-level verdicts (psi_depth, psi_tubes) == analyze --format json")

# the local matrix against the Matrix Market export
S = subspectra.local_matrix("catmull-clark", surface_vertex=5)
mtx = cli("matrix", "--scheme", "catmull-clark", "--surface-vertex", "5", "--format", "mtx")
T = scipy.io.mmread(io.StringIO(mtx))
T = T.toarray() if hasattr(T, "toarray") else np.asarray(T)
if S.shape != (31, 31):
    fail("catmull-clark n=5: shape %s, want (31, 31) (6n + 1)" % (S.shape,))
elif T.shape != S.shape or np.max(np.abs(S.toarray() - T)) > 1e-15:
    fail("local_matrix differs from `matrix --format mtx`")
rows = np.asarray(S.sum(axis=1)).ravel()
if np.max(np.abs(rows - 1)) > 1e-14:
    fail("rows do not sum to 1: %g" % np.max(np.abs(rows - 1)))
print("ok: local_matrix == matrix --format mtx, rows sum to 1")

# eigenvalues against closed forms
for n in (3, 5, 7):
    v, m = subspectra.eigenvalues("catmull-clark", surface_vertex=n)
    c2, c1 = math.cos(2 * math.pi / n), math.cos(math.pi / n)
    lam = (5 + c2 + c1 * math.sqrt(2 * (9 + c2))) / 16
    if abs(v[0] - 1) > 1e-12 or abs(v[1] - lam) > 1e-12 * lam or abs(v[2] - lam) > 1e-12 * lam \
            or m[1] != 2:
        fail("catmull-clark n=%d: %s (mult %s), want 1, %.15g twice" % (n, v[:3], m[:3], lam))
v, m = subspectra.eigenvalues("mlca", edge=4)
want = np.array([1] + [0.5] * 3 + [0.25] * 6)
if np.max(np.abs(v[:10] - want)) > 1e-12 or list(m[:10]) != [1] + [3] * 3 + [6] * 6:
    fail("mlca edge 4: %s (mult %s), want the tricubic 1, 1/2 x3, 1/4 x6" % (v[:10], m[:10]))
print("ok: eigenvalues against closed forms")

# eigenvectors: eigen-equations, biorthonormality, and Catmull-Clark's
# closed-form limit-position mask at valence n: the centre n/(n+5), each edge
# neighbour 4/(n(n+5)), each face neighbour 1/(n(n+5)), the rest 0
for n in (3, 5, 7):
    S = subspectra.local_matrix("catmull-clark", surface_vertex=n).toarray()
    v, R, L, bi = subspectra.eigenvectors("catmull-clark", k=3, surface_vertex=n)
    scale = np.abs(S).max()
    res = max(np.abs(S @ R - R * v).max(), np.abs(L.T @ S - v[:, None] * L.T).max())
    if len(v) != 3 or res > 1e-12 * scale or not bi.all() \
            or np.abs(L.T @ R - np.eye(len(v))).max() > 1e-12 or np.abs(R[:, 0] - 1).max() > 1e-12:
        fail("catmull-clark n=%d: eigenvectors (residual %g, biorthonormal %s)" % (n, res, bi))
    l0 = L[:, 0]
    got = np.sort(l0[np.abs(l0) > 1e-13])
    want = np.sort([n / (n + 5)] + [4 / (n * (n + 5))] * n + [1 / (n * (n + 5))] * n)
    if got.shape != want.shape or np.abs(got - want).max() > 1e-12:
        fail("catmull-clark n=%d: limit mask %s, closed form %s" % (n, got, want))
print("ok: eigenvectors, Catmull-Clark's limit-position mask")

# local_labels: the one-ring first, the centre at 0, all distinct; and the
# rows of S agree with them: on the regular grids (tricubic MLCA edge 4,
# bicubic Catmull-Clark and quartic box-spline Loop at the regular valence)
# the schemes reproduce linear functions, so with the chart's axes (spokes at
# angles 2 pi k / n, the edge along z) S P = P / 2 for the positions P
def spokes(n):
    return np.array([[math.cos(2 * math.pi * k / n), math.sin(2 * math.pi * k / n)]
                     for k in range(n)])


for scheme, case, axes in (
        ("mlca", {"edge": 4}, np.block([[spokes(4), np.zeros((4, 1))],
                                        [np.zeros((1, 2)), np.ones((1, 1))]])),
        ("catmull-clark", {"surface_vertex": 4}, spokes(4)),
        ("loop", {"surface_vertex": 6}, spokes(6))):
    coords, n1 = subspectra.local_labels(scheme, **case)
    S = subspectra.local_matrix(scheme, **case).toarray()
    P = coords @ axes
    if coords.shape != (S.shape[0], axes.shape[0]) or coords[0].any() \
            or len(set(map(tuple, coords.tolist()))) != len(coords) \
            or np.abs(S[:n1, n1:]).max() != 0:
        fail("local_labels(%r, %s): shape %s, n1 %d" % (scheme, case, coords.shape, n1))
    elif np.abs(S @ P - P / 2).max() > 1e-13:
        fail("local_labels(%r, %s): S P != P / 2 (%g)" % (scheme, case,
                                                          np.abs(S @ P - P / 2).max()))
c5, n15 = subspectra.local_labels("mlca", edge=5)
if c5.shape != (155, 6) or n15 != 33:  # 30n + 5 and 6n + 3 points; n + 1 coordinates
    fail("local_labels mlca edge 5: %s, n1 %d" % (c5.shape, n15))
print("ok: local_labels: linear precision S P = P / 2 on the regular grids")

# enumerate_links: the numbers of triangulations of the sphere with k
# vertices (OEIS A000109: 1, 1, 2, 5, 14, 50, 233 for k = 4..10), the same
# links as `enumerate links`, lazy (closed early on k = 14's 339722)
want = {4: 1, 5: 1, 6: 2, 7: 5, 8: 14, 9: 50, 10: 233}
got = list(subspectra.enumerate_links(4, 10))
counts = {k: sum(1 for t in got if int(t.split()[0]) == k) for k in want}
if counts != want:
    fail("enumerate_links(4, 10): counts %s, want %s" % (counts, want))
if got != cli("enumerate", "links", "--vertices", "4..10").split("\n")[:-1]:
    fail("enumerate_links(4, 10) differs from `enumerate links --vertices 4..10`")
count = dict(tuple(map(int, line.split("\t"))) for line in
             cli("enumerate", "links", "--vertices", "4..10", "--count").splitlines()
             if not line.startswith("#"))
if count != counts:
    fail("enumerate_links(4, 10): counts %s, `enumerate links --count` %s" % (counts, count))
part = [sorted(subspectra.enumerate_links(9, part=i, nparts=3)) for i in range(3)]
if sorted(sum(part, [])) != sorted(t for t in got if t.startswith("9 ")):
    fail("enumerate_links(9, part=i, nparts=3): the parts are not a partition")
it = subspectra.enumerate_links(14)
first = [next(it) for _ in range(5)]
it.close()
if len(set(first)) != 5 or not all(t.startswith("14 ") for t in first):
    fail("enumerate_links(14): %s" % first)
for kw in ({"kmin": 3}, {"kmin": 5, "kmax": 4}, {"kmin": 21}, {"kmin": 5, "part": 2, "nparts": 2}):
    try:
        list(subspectra.enumerate_links(**kw))
        fail("enumerate_links(%s) did not raise" % kw)
    except ValueError:
        pass
print("ok: enumerate_links: A000109's counts, as `enumerate links`, lazy")

# jsr: the dictionary of `jsr --format json`
for scheme, case, args in (("tetoct", {"edge": 5}, ["--edge", "5"]),
                           ("tetoct", {"edge": 4}, ["--edge", "4"]),
                           ("boxspline", {"edge": 4, "diagonals": "proper"},
                            ["--edge", "4", "--diagonals", "proper"])):
    want = json.loads(cli("jsr", "--scheme", scheme, *args, "--depth", "3", "--format", "json"))
    got = subspectra.jsr(scheme, depth=3, **case)
    same(got, want, "jsr %s %s" % (scheme, case))
    if not got["lower"] <= got["upper"]:
        fail("jsr %s %s: lower %g > upper %g" % (scheme, case, got["lower"], got["upper"]))
for kw, exc in (({}, ValueError), ({"face": True, "edge": 4}, ValueError),
                ({"edge": 5, "norm": "1"}, ValueError), ({"edge": 5, "depth": 2.5}, TypeError),
                ({"edge": 5, "gap": "x"}, TypeError)):
    try:
        subspectra.jsr("tetoct", **kw)
        fail("jsr('tetoct', %s) did not raise" % kw)
    except exc:
        pass
try:
    subspectra.jsr("mlca", edge=5)
    fail("jsr('mlca', edge=5) did not raise")
except subspectra.SubspectraError as e:
    if "tet stars only" not in str(e):
        fail("jsr('mlca', edge=5): %s" % e)
print("ok: jsr == jsr --format json")

# subdivide: NumPy in and out, meshio's cells.  Against the command (the
# Medit file it writes, read by meshio: the same points to the last bit, the
# same cells); the tet/oct split's counts (a tet makes 4 tets and an
# octahedron, an octahedron 8 tets and 6 octahedra); affine invariance (every
# row of the rule sums to 1): subdividing A p + b gives A q + b
src = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
try:
    import meshio
except ImportError:
    meshio = None
    print("subdivide against the command: SKIPPED (no meshio)")
if meshio is not None:
    tmpdir = tempfile.mkdtemp()
    for scheme, mesh in (("mlca", "hexstar-icosahedron.mesh"), ("boxspline", "cube-6tets.mesh")):
        m = meshio.read(os.path.join(src, "data", "meshes", mesh))
        p, c = subspectra.subdivide(scheme, m.points, m.cells_dict)
        out = os.path.join(tmpdir, "out.mesh")
        cli("subdivide", "--scheme", scheme, os.path.join(src, "data", "meshes", mesh), "-o", out)
        o = meshio.read(out)
        oc = o.cells_dict
        if "octahedron" in c:  # Medit has none: the command splits each into 4 tets
            c = {"tetra": c["tetra"]}
            oc = {"tetra": oc["tetra"][:len(c["tetra"])]}
        if o.points.shape != p.shape or np.abs(o.points - p).max() != 0 \
                or sorted(oc) != sorted(c) or any((oc[k] != c[k]).any() for k in c):
            fail("subdivide(%r, %s) differs from the command's" % (scheme, mesh))
    shutil.rmtree(tmpdir)
    print("ok: subdivide == subdivide -o FILE.mesh")
cube = np.array([[x, y, z] for z in (0, 1) for y in (0, 1) for x in (0, 1)], dtype=float)
tets = np.array([[0, 1, 3, 7], [0, 1, 7, 5], [0, 5, 7, 4], [0, 3, 2, 7], [0, 2, 6, 7],
                 [0, 6, 4, 7]])
tets = np.array([t if np.linalg.det(cube[t[1:]] - cube[t[0]]) > 0 else t[[1, 0, 2, 3]]
                 for t in tets])
p1, c1 = subspectra.subdivide("tetoct", cube, {"tetra": tets}, levels=2)
if {k: len(v) for k, v in c1.items()} != {"tetra": 6 * 4 * 4 + 6 * 8, "octahedron": 6 * 4 + 6 * 6}:
    fail("tetoct on 6 tets, 2 levels: %s" % {k: len(v) for k, v in c1.items()})
rng = np.random.default_rng(40)
A, b = rng.normal(size=(3, 3)) + 3 * np.eye(3), rng.normal(size=3)
p2, c2 = subspectra.subdivide("tetoct", cube @ A.T + b, [("tetra", tets)], levels=2)
if np.abs(p2 - (p1 @ A.T + b)).max() > 1e-12 * np.abs(p2).max() or \
        any((c2[k] != c1[k]).any() for k in c1):
    fail("tetoct: subdivide(A p + b) != A subdivide(p) + b")
p0, c0 = subspectra.subdivide("tetoct", cube, {"tetra": tets}, levels=0)
if np.abs(p0 - cube).max() != 0 or (c0["tetra"] != tets).any():
    fail("subdivide(levels=0) is not the input")
for args, exc, what in (
        ((cube, {"pyramid": tets}), ValueError, "unknown cell type 'pyramid'"),
        ((cube, {"tetra": tets[:, :3]}), ValueError, "expected integers of shape (m, 4)"),
        ((cube, {"tetra": tets + 1}), ValueError, "vertex indices outside 0..7"),
        ((cube, {"tetra": tets * 1.0}), ValueError, "expected integers"),
        ((np.zeros((8, 17)), {"tetra": tets}), ValueError, "dim 1..16"),
        ((cube, {"tetra": np.vstack([tets[:1, [1, 0, 2, 3]], tets[1:]])}),
         subspectra.SubspectraError, "tetrahedron 1"),
        ((cube, {"hexahedron": np.array([[0, 1, 3, 2, 4, 5, 7, 6]])}),
         subspectra.SubspectraError, "does not take")):
    try:
        subspectra.subdivide("tetoct", *args)
        fail("subdivide(%s) did not raise" % what)
    except exc as e:
        if what not in str(e):
            fail("subdivide: %r does not say %r" % (str(e), what))
print("ok: subdivide: the tet/oct counts, affine invariance, bad input")

# bad input
for kw, what in (({"edge": 3, "scheme": "nope"}, "unknown scheme 'nope'"),
                 ({"vertex": "4 bcd,adc", "scheme": "mlca"}, "")):
    scheme = kw.pop("scheme")
    try:
        subspectra.analyze(scheme, **kw)
        fail("analyze(%r, %s) did not raise" % (scheme, kw))
    except subspectra.SubspectraError as e:
        if what not in str(e) or e.status != "bad input":
            fail("analyze(%r, %s): %s: %s" % (scheme, kw, e.status, e))
try:
    subspectra.analyze("mlca", edge=4, face=True)
    fail("two cases did not raise")
except ValueError:
    pass
# arguments that are not integers, or do not apply, are refused by name
# (issue 35: edge=5.7 was read as 5, cls=8 ignored for mlca, diagonals="skew"
# on mlca's edge said "only for the edge case")
for kw, exc, what in (
        ({"edge": 5.7}, TypeError, "edge: expected an integer, not 5.7"),
        ({"edge": 5.9}, TypeError, "edge: expected an integer, not 5.9"),
        ({"vertex": 5}, TypeError, "vertex: expected a link: plantri ASCII"),
        ({"vertex": b"octahedron"}, TypeError, "vertex: expected a link"),
        ({"face": "yes"}, TypeError, "face: expected True or False, not 'yes'"),
        ({"edge": 5, "certify": 1}, TypeError, "certify: expected True or False, not 1"),
        ({"edge": 5, "tol": "1e-6"}, TypeError, "tol: expected a real number, not '1e-6'"),
        ({"edge": 5, "tol": True}, TypeError, "tol: expected a real number, not True"),
        ({"edge": 5.0}, TypeError, "edge: expected an integer, not 5.0"),
        ({"edge": "5"}, TypeError, "edge: expected an integer, not '5'"),
        ({"edge": True}, TypeError, "edge: expected an integer, not True"),
        ({"surface_vertex": 4.5}, TypeError, "surface_vertex: expected an integer"),
        ({"edge": 5, "depth": 2.5}, TypeError, "depth: expected an integer, not 2.5"),
        ({"edge": 5, "eigenvalues": 3.5}, TypeError, "eigenvalues: expected an integer"),
        ({"edge": 5, "ring_levels": 1.5}, TypeError, "ring_levels: expected an integer"),
        ({"vertex": "octahedron", "psi_depth": 9}, ValueError, "psi_depth: expected 0..8"),
        ({"vertex": "octahedron", "psi_depth": 2.0}, TypeError,
         "psi_depth: expected an integer, not 2.0"),
        ({"vertex": "octahedron", "psi_tubes": True}, ValueError,
         "psi_tubes: needs certify=True"),
        ({"vertex": "octahedron", "certify": True, "psi_depth": 0, "psi_tubes": True},
         ValueError, "psi_tubes: needs certify=True and psi_depth > 0"),
        ({"vertex": "octahedron", "psi_tubes": 1}, TypeError, "psi_tubes: expected True"),
        ({"edge": 5, "cls": 8}, ValueError, "cls: the 4-8 class of a quasi48 surface_vertex"),
        ({"vertex": "octahedron", "cls": 4}, ValueError, "cls: the 4-8 class"),
        ({"edge": 5, "diagonals": 1}, TypeError, "diagonals: expected bfs"),
        ({"edge": 5, "diagonals": "skew"}, subspectra.SubspectraError,
         "scheme mlca does not read major diagonals: diagonals 'skew' do not apply")):
    try:
        subspectra.analyze("mlca", **kw)
        fail("analyze('mlca', %s) did not raise" % kw)
    except exc as e:
        if what not in str(e) or "only for the edge case" in str(e):
            fail("analyze('mlca', %s): %s" % (kw, e))
    except Exception as e:  # noqa: BLE001 -- the wrong kind of error
        fail("analyze('mlca', %s): %s, not %s: %s" % (kw, type(e).__name__, exc.__name__, e))
for kw, what in (({"surface_vertex": 5, "cls": 8}, "a 4-8 vertex class exists only for "
                  "quasi48"),):
    try:
        subspectra.analyze("loop", **kw)
        fail("analyze('loop', %s) did not raise" % kw)
    except subspectra.SubspectraError as e:
        if what not in str(e):
            fail("analyze('loop', %s): %s" % (kw, e))
try:
    subspectra.eigenvalues("mlca", "x", edge=4)
    fail("eigenvalues(tol='x') did not raise")
except TypeError as e:
    if "tol: expected a real number, not 'x'" not in str(e):
        fail("eigenvalues(tol='x'): %s" % e)
for scheme in (5, None, b"mlca"):
    try:
        subspectra.analyze(scheme, edge=5)
        fail("analyze(%r) did not raise" % (scheme,))
    except TypeError as e:
        if "scheme: expected a scheme name" not in str(e):
            fail("analyze(%r): %s" % (scheme, e))
    except Exception as e:  # noqa: BLE001
        fail("analyze(%r): %s, not TypeError: %s" % (scheme, type(e).__name__, e))
try:
    subspectra.eigenvectors("mlca", k=2.5, edge=4)
    fail("eigenvectors(k=2.5) did not raise")
except TypeError as e:
    if "k: expected an integer, not 2.5" not in str(e):
        fail("eigenvectors(k=2.5): %s" % e)
# what still holds: integers of numpy's types, quasi48's class 4
if subspectra.analyze("mlca", edge=np.int64(5))["case"] != "edge":
    fail("edge=np.int64(5) is not the edge case")
if subspectra.analyze("quasi48", surface_vertex=5, cls=np.int32(4)).get("class") != 4:
    fail("quasi48 cls=np.int32(4) is not class 4")
print("ok: bad input")

# the library: the one SUBSPECTRA_LIBRARY names; a path there that does not
# load raises SubspectraError naming it, even when another library would load
# (the staged one on LD_LIBRARY_PATH, where the dynamic linker finds it)
lib = os.environ.get("SUBSPECTRA_LIBRARY", "")
if subspectra.library_path != lib:
    fail("library_path %r, SUBSPECTRA_LIBRARY %r" % (subspectra.library_path, lib))
for bad in ("/nonexistent/dir/libsubspectra.so.0", os.path.abspath(__file__)):
    env = dict(os.environ, SUBSPECTRA_LIBRARY=bad,
               LD_LIBRARY_PATH=os.path.dirname(lib) + ":" + os.environ.get("LD_LIBRARY_PATH", ""))
    p = subprocess.run([sys.executable, "-c", "import subspectra; print(subspectra.library_path)"],
                       env=env, capture_output=True, text=True)
    want = "subspectra.SubspectraError: SUBSPECTRA_LIBRARY=%s: cannot load the library" % bad
    if p.returncode == 0 or want not in p.stderr:
        fail("SUBSPECTRA_LIBRARY=%s: exit %d, %r%r" % (bad, p.returncode, p.stdout, p.stderr[-300:]))
print("ok: SUBSPECTRA_LIBRARY that does not load: SubspectraError naming it, no other library")

# help(): the module and every public name documented
for name in ["__init__"] + subspectra.__all__:
    obj = subspectra if name == "__init__" else getattr(subspectra, name)
    if len((obj.__doc__ or "").strip()) < 40:
        fail("subspectra.%s has no docstring to speak of" % name)
missing = [n for n in ("local_labels", "jsr", "enumerate_links", "subdivide")
           if n not in subspectra.__doc__]
if missing:
    fail("the module's docstring does not list %s" % missing)
print("ok: docstrings")

sys.exit(1 if fails else 0)
