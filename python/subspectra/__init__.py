"""subspectra: spectral analysis of subdivision schemes, from Python.

A thin layer over the shared library libsubspectra (cffi in ABI mode: nothing
is compiled).  A case is one of

    vertex=LINK            a 3D vertex: plantri ASCII ("4 bcd,adc,abd,acb") or a
                           name (tetrahedron, octahedron, icosahedron, bipyramid:N)
    edge=N                 a point on an edge of valence N
    face=True              a point inside the face of two tets
    surface_vertex=N       a 2D vertex of valence N

with diagonals="bfs"|"proper"|"skew"|"center" for schemes that read major
diagonals.  Arguments are checked: integers must be integers (edge=5.7 or
5.0 raises TypeError naming the argument), links and names strings
(vertex=5 raises TypeError), flags True or False; arguments that do not
apply are refused.

    local_matrix(scheme, **case)   the local subdivision matrix S (scipy.sparse CSR)
    local_labels(scheme, **case)   which point is which in S: exact chart
                                   coordinates (NumPy int array), one-ring size
    eigenvalues(scheme, **case)    all eigenvalues of S (NumPy complex array,
                                   by decreasing modulus) and their multiplicities
    eigenvectors(scheme, k, **case)
                                   the k leading ones with right and left
                                   eigenvectors (limit and tangent masks)
    analyze(scheme, **case, **options)
                                   the dictionary `subspectra analyze --format
                                   json` prints, psi-level verdicts included;
                                   options tol, eigenvalues, depth, ring_levels,
                                   certify, psi_depth, psi_tubes as its --tol, ...
    jsr(scheme, face=True | edge=N, **options)
                                   the dictionary of `subspectra jsr --format json`
    enumerate_links(kmin, kmax)    an iterator of every link (plantri ASCII), lazy
    subdivide(scheme, points, cells, levels)
                                   refined NumPy points and meshio-style cells
    read_mesh(path), write_mesh(path, points, cells, point_data)
                                   mesh files (.mesh, .vtk, .vtu, .obj, .msh,
                                   TetGen) as the command line reads and
                                   writes them, NumPy arrays in meshio's form
    limit(scheme, points, cells, cell, uvw, derivatives, fields)
                                   the limit volume of a hex mesh at many points:
                                   points, Jacobians, fields (NumPy arrays) as
                                   `subspectra limit`; Limit(...) keeps the
                                   evaluator (and its caches) for many calls
    store_table(path, where)       a sweep's results store as a list of dicts
                                   (report's CSV columns, typed; pandas.DataFrame
                                   takes it), or a NumPy structured array
    scheme_names()                 the built-in schemes

Errors of the library raise SubspectraError (.status, and its message).
The library is $SUBSPECTRA_LIBRARY when set (one that does not load raises
SubspectraError naming it), else the one the package was installed with
(inside the package when pip installed it), else the dynamic linker's
libsubspectra.so.0; library_path says which.  The cffi declarations come
from the public headers at build time (python/gen_cdef.py, _cdef.py).
"""
import json
import numbers
import operator
import os
import queue
import threading

import numpy as np
import scipy.sparse
from cffi import FFI

from . import _cdef, _config

__all__ = ["SubspectraError", "scheme_names", "local_matrix", "local_labels", "eigenvalues",
           "eigenvectors", "analyze", "jsr", "enumerate_links", "subdivide", "limit", "Limit",
           "LimitValues", "store_table", "read_mesh", "write_mesh", "MeshData"]

_ffi = FFI()
# The declarations of the types and functions used here, generated from the
# public headers when the package is built (python/gen_cdef.py), so that the
# structure layouts are the headers' own; and libc's free() for the strings
# the library allocates.
_ffi.cdef(_cdef.CDEF)
_ffi.cdef("void free(void *p);")

#ss_case_kind(ss_case.h)
_VERTEX, _EDGE, _FACE, _SURFACE_VERTEX = 0, 1, 2, 3


class SubspectraError(Exception):
    """A library call failed: .status is its ss_status name, str() its message."""

    def __init__(self, status, message):
        super().__init__(message)
        self.status = status


def _load():
    """The shared library: $SUBSPECTRA_LIBRARY when set (and nothing else:
    a path that does not load is an error, not a reason to take another
    library), else the one the package was installed with (_config.LIBRARY,
    relative to the package in a wheel), else the dynamic linker's
    libsubspectra.so.0 when that file is gone.  Returns (library, path)."""
    env = os.environ.get("SUBSPECTRA_LIBRARY")
    if env:
        try:
            return _ffi.dlopen(env), env
        except OSError as e:
            raise SubspectraError("i/o error", "SUBSPECTRA_LIBRARY=%s: cannot load the "
                                  "library: %s" % (env, e)) from None
    own = os.path.join(os.path.dirname(os.path.abspath(__file__)), _config.LIBRARY)
    if os.path.exists(own):
        try:
            return _ffi.dlopen(own), own
        except OSError as e:
            raise SubspectraError("i/o error", "%s: cannot load the library: %s"
                                  % (own, e)) from None
    try:
        return _ffi.dlopen("libsubspectra.so.0"), "libsubspectra.so.0"
    except OSError as e:
        raise SubspectraError("i/o error", "cannot load libsubspectra: %s is not there and "
                              "the dynamic linker says: %s (set SUBSPECTRA_LIBRARY to the "
                              "library's path)" % (own, e)) from None


_lib, library_path = _load()
_libc = _ffi.dlopen(None)  # free() for the library's malloc'd strings


_STATUS = ["ok", "out of memory", "bad input", "i/o error", "numerical failure",
           "internal error"]


def _check(st, err):
    if st:
        name = _STATUS[st] if 0 <= st < len(_STATUS) else str(st)
        raise SubspectraError(name, _ffi.string(err.msg).decode(errors="replace"))


def scheme_names():
    """The built-in schemes' names (a list of str), the values the scheme
    argument of every function takes: mlca, tetoct, catmull-clark, ..."""
    p = _lib.ss_scheme_names()
    out = []
    i = 0
    while p[i] != _ffi.NULL:
        out.append(_ffi.string(p[i]).decode())
        i += 1
    return out


def _integer(name, v):
    """v as an int, or TypeError naming the argument: a float (5.7, or 5.0)
    or a string is not silently truncated to an integer; bool is refused;
    integers of other types (numpy's) are taken through __index__."""
    if isinstance(v, bool):
        raise TypeError("%s: expected an integer, not %r" % (name, v))
    try:
        return operator.index(v)
    except TypeError:
        raise TypeError("%s: expected an integer, not %r" % (name, v)) from None


def _text(name, v, what):
    """v as a str, or TypeError naming the argument and what it should be
    (vertex=5 or scheme=None would otherwise fail inside str.encode)."""
    if not isinstance(v, str):
        raise TypeError("%s: expected %s (a str), not %r" % (name, what, v))
    return v


def _flag(name, v):
    """v as a bool, or TypeError naming the argument: face="no" or
    certify=1 are not guessed at."""
    if not isinstance(v, (bool, np.bool_)):
        raise TypeError("%s: expected True or False, not %r" % (name, v))
    return bool(v)


def _real(name, v):
    """v as a float, or TypeError naming the argument (a str or a bool is
    refused; ints and NumPy's numbers are taken)."""
    if isinstance(v, (bool, np.bool_)) or not isinstance(v, (numbers.Real, np.floating)):
        raise TypeError("%s: expected a real number, not %r" % (name, v))
    return float(v)


class _Case:
    """A scheme and a case, built in C; freed on exit (a context manager)."""

    def __init__(self, scheme, vertex=None, edge=None, face=False, surface_vertex=None,
                 diagonals=None, cls=None):
        given = [vertex is not None, edge is not None, _flag("face", face),
                 surface_vertex is not None]
        if sum(given) != 1:
            raise ValueError("give exactly one case: vertex=LINK, edge=N, face=True or "
                             "surface_vertex=N")
        self.err = _ffi.new("ss_error *")
        self.c = _ffi.new("ss_case *")
        self._s = _ffi.new("ss_scheme **")
        self._l = _ffi.new("ss_link **")
        self.scheme = None
        try:
            scheme = _text("scheme", scheme, "a scheme name, one of scheme_names()")
            _check(_lib.ss_scheme_new(scheme.encode(), self._s, self.err), self.err)
            self.scheme = self._s[0]
            if cls is not None and surface_vertex is None:
                raise ValueError("cls: the 4-8 class of a quasi48 surface_vertex; no "
                                 "other case has one")
            if diagonals is not None:
                if not isinstance(diagonals, str):
                    raise TypeError("diagonals: expected bfs, proper, skew or center, "
                                    "not %r" % (diagonals,))
                d = _ffi.new("ss_diag_mode *")
                if _lib.ss_diag_parse(diagonals.encode(), d):
                    raise ValueError("diagonals: expected bfs, proper, skew or center, not %r"
                                     % diagonals)
                self.c.diag = d[0]
            if vertex is not None:
                vertex = _text("vertex", vertex, "a link: plantri ASCII such as "
                               "'4 bcd,adc,abd,acb', or a name such as 'octahedron'")
                _check(_lib.ss_link_parse(vertex.encode(), self._l, self.err), self.err)
                self.c.kind, self.c.link = _VERTEX, self._l[0]
            elif edge is not None:
                self.c.kind, self.c.n = _EDGE, _integer("edge", edge)
            elif face:
                self.c.kind = _FACE
            else:
                self.c.kind, self.c.n = _SURFACE_VERTEX, _integer("surface_vertex",
                                                                  surface_vertex)
            if cls is not None:  # quasi48: the 4-8 class, as analyze --class
                if _integer("cls", cls) not in (4, 8):
                    raise ValueError("cls: expected 4 or 8, not %r" % (cls,))
                self.c.cls = cls
        except BaseException:
            self.close()
            raise

    def close(self):
        if self._l[0] != _ffi.NULL:
            _lib.ss_link_free(self._l[0])
            self._l[0] = _ffi.NULL
        if self._s[0] != _ffi.NULL:
            _lib.ss_scheme_free(self._s[0])
            self._s[0] = _ffi.NULL

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


def _with_local(scheme, case, use):
    with _Case(scheme, **case) as c:
        pm = _ffi.new("ss_local **")
        _check(_lib.ss_local_new(c.scheme, c.c, pm, c.err), c.err)
        try:
            return use(pm[0], c.err)
        finally:
            _lib.ss_local_free(pm[0])


def _dense(M):
    n = M.n2
    return np.frombuffer(_ffi.buffer(M.S, n * n * 8), dtype=np.float64).reshape(n, n).copy()


def local_matrix(scheme, **case):
    """The local subdivision matrix S of the case (fine point i from coarse
    point j: S[i, j]; the one-ring's points first; each row sums to 1), as a
    scipy.sparse.csr_matrix of the two-ring's size."""
    return _with_local(scheme, case, lambda M, err: scipy.sparse.csr_matrix(_dense(M)))


def eigenvalues(scheme, tol=1e-6, **case):
    """All eigenvalues of S by decreasing modulus (NumPy complex array), and
    the size of each one's group of equal eigenvalues (within relative tol),
    as a NumPy int array: (values, multiplicities)."""
    def use(M, err):
        opts = _lib.ss_eig_defaults(M.dim)
        opts.tol = _real("tol", tol)
        po = _ffi.new("ss_eig_opts *", opts)
        pe = _ffi.new("ss_eig **")
        _check(_lib.ss_eig_new(M.S, M.n2, M.n1, po, pe, err), err)
        try:
            e = pe[0]
            vals = np.array([complex(e.val[i].re, e.val[i].im) for i in range(e.n)])
            mult = np.array([e.val[i].mult for i in range(e.n)], dtype=int)
            return vals, mult
        finally:
            _lib.ss_eig_free(pe[0])
    return _with_local(scheme, case, use)


def eigenvectors(scheme, k=4, tol=1e-6, **case):
    """The k leading eigenvalues of S and their right and left eigenvectors
    (ss_eigvec.h: S r = lambda r, l^T S = lambda l^T; right vectors scaled to
    maximum modulus 1, so r_0 = 1; each group of equal eigenvalues made
    biorthonormal, L^T R = I, unless defective; a tie or conjugate pair cut by
    k is kept whole, so there may be more than k).  Returns (values, right,
    left, biorthonormal): NumPy arrays of shapes (k',), (n, k'), (n, k') --
    complex when an eigenvalue is, else real -- and a bool per eigenvalue.
    left[:, 0] is the limit-position mask, the next columns the tangent masks."""
    def use(M, err):
        pv = _ffi.new("ss_eigvec **")
        _check(_lib.ss_eigvec_new(M.S, M.n2, _integer("k", k), _real("tol", tol), pv, err), err)
        try:
            v = pv[0]
            n, kk = v.n, v.k

            def arr(p, count):
                return np.frombuffer(_ffi.buffer(p, count * 8), dtype=np.float64).copy()

            vals = arr(v.re, kk) + 1j * arr(v.im, kk)
            right = (arr(v.right_re, n * kk) + 1j * arr(v.right_im, n * kk)).reshape(kk, n).T
            left = (arr(v.left_re, n * kk) + 1j * arr(v.left_im, n * kk)).reshape(kk, n).T
            bi = np.array([bool(v.biorth[i]) for i in range(kk)])
            if not v.complex_any:
                vals, right, left = vals.real, right.real.copy(), left.real.copy()
            return vals, right, left, bi
        finally:
            _lib.ss_eigvec_free(pv[0])
    return _with_local(scheme, case, use)


def analyze(scheme, vertex=None, edge=None, face=False, surface_vertex=None, diagonals=None,
            tol=None, eigenvalues=None, depth=None, ring_levels=None, certify=False, cls=None,
            psi_depth=None, psi_tubes=False):
    """The dictionary `subspectra analyze --scheme SCHEME CASE --format json`
    prints (DESIGN section 7): matrix sizes, leading eigenvalues, the
    eigenvalue condition, regularity and injectivity of the characteristic
    map; options as analyze's --tol, --eigenvalues, --depth, --ring-levels,
    --certify, --psi-depth, --psi-tubes, and cls as --class (quasi48 surface
    vertices: 4 or 8).

    The psi-level verdicts: as the command, psi itself is judged where it
    can be (vertices of mlca, ccsolid, tetoct, boxspline; psi_depth 4 by
    default, 1..8 boxes of side 2^-psi_depth; 0: the control net only).
    d["regularity"]["judged_on"] says on what the verdict rests ("psi" or
    "control-net"), d["regularity"]["net_verdict"] is the control net's own,
    d["regularity"]["witness"] two points of opposite det Dpsi signs when psi
    folds, and d["regularity"]["psi"] the psi test's own verdict, reason,
    covered, uncovered, pieces, box_depth (and "tubes", "injectivity" where
    they were decided), None where psi was not judged;
    d["injectivity"]["judged_on"] likewise.  psi_tubes=True (with
    certify=True and psi_depth > 0, mlca) proves the tubes round the spokes
    too."""
    with _Case(scheme, vertex, edge, face, surface_vertex, diagonals, cls) as c:
        o = _ffi.new("ss_report_analyze_opts *", _lib.ss_report_analyze_defaults())
        if tol is not None:
            o.tol = _real("tol", tol)
        if eigenvalues is not None:
            o.neig = _integer("eigenvalues", eigenvalues)
        if depth is not None:
            o.depth = _integer("depth", depth)
        if ring_levels is not None:
            o.ring_levels = _integer("ring_levels", ring_levels)
        o.certify = 1 if _flag("certify", certify) else 0
        if psi_depth is not None:
            o.psi_depth = _integer("psi_depth", psi_depth)
            if not 0 <= o.psi_depth <= 8:
                raise ValueError("psi_depth: expected 0..8, not %d" % o.psi_depth)
        if _flag("psi_tubes", psi_tubes):
            if not certify or o.psi_depth == 0:
                raise ValueError("psi_tubes: needs certify=True and psi_depth > 0, as "
                                 "`analyze --psi-tubes` needs --certify")
            o.psi_tubes = 1
        out = _ffi.new("char **")
        _check(_lib.ss_report_analyze(c.scheme, c.c, o, out, c.err), c.err)
        try:
            return json.loads(_ffi.string(out[0]).decode())
        finally:
            _libc.free(out[0])


def local_labels(scheme, **case):
    """Which point is which in S: (coords, n1).  coords is a NumPy int array
    of shape (n2, d): row i the exact coordinates of S's point i relative to
    the centre (row 0, all zeros), in units of the grid of the level S maps
    from, in the star's chart (ss_star.h): conical coordinates over the link
    for a vertex (d = k, one per link vertex), over the faces around the edge
    and the edge itself for an edge (d = n + 1; the edge's ends are at
    -+1 on the last coordinate, so the star's hexes are 1 x 1 x 2 in the
    chart and a grid of cubes has an edge axis of length 1/2), over the n
    rays for a
    surface vertex (d = n), barycentric for the face (d = 5).  Positions are
    a linear image of the chart: coords @ axes, axes one row per
    coordinate.  n1 is the one-ring's size, the first n1 rows.  The rows and
    columns of local_matrix() are in this order, so S @ (coords @ axes) =
    (coords @ axes) / 2 where the scheme reproduces linear functions on the
    regular grid."""
    def use(M, err):
        d = M.ncoord
        coords = np.zeros((M.n2, d), dtype=np.int64)
        for i in range(M.n2):
            lab = M.label[i]
            for j in range(lab.n):
                coords[i, lab.idx[j]] = lab.val[j]
        return coords, int(M.n1)
    return _with_local(scheme, case, use)


_NORMS = ["inf", "2", "auto", "ellipsoid", "polytope"]
_POLYTOPE = ["closed", "vertex cap", "time limit", "LP failed", "rho = 0"]


def _jsr_dict(scheme, c, L, r, o, verdict):
    """The dictionary of `subspectra jsr --format json` (cli/ss_cli_jsr.c)."""
    edge = c.kind == _lib.SS_CASE_EDGE
    d = {"scheme": scheme, "case": _ffi.string(_lib.ss_case_name(c.kind)).decode()}
    if edge:
        d["n"] = c.n
    d["diagonals"] = _ffi.string(_lib.ss_diag_name(c.diag)).decode()
    d.update(level=L.level, maps=L.m, support=L.n, subspace=L.r,
             subspace_basis=_ffi.string(L.basis).decode(), invariance_defect=L.defect,
             theta=[L.theta[i] for i in range(L.r)])
    if edge:
        d["lambda1"] = L.lambda1
    d["rho_k"] = [r.rho_inf[k] for k in range(r.depth)]
    d["rho_k_2"] = [r.rho_2[k] for k in range(r.depth)]
    if r.cut_len > 0:
        d.update(stopped_by="max-seconds", depth=o.depth, depth_complete=r.depth,
                 cut_length=r.cut_len, cut_words=r.cut_words,
                 cut_of=int(float(L.m) ** r.cut_len))
    d["lower"] = r.lower
    d["lower_word"] = [r.lower_word[k] + 1 for k in range(r.lower_len)]
    if not edge:
        thr = "1/4 (C^2 across the face)"
    elif abs(L.lambda1 - 0.5) <= 1e-8:
        thr = "lambda3 = lambda1 = 1/2"
    else:
        thr = "lambda3 = lambda1 (< 1/2)" if L.lambda1 < 0.5 else "lambda3 = 1/2 (< lambda1)"
    d.update(upper=r.upper, threshold=L.threshold, threshold_name=thr,
             verdict=_ffi.string(_lib.ss_verdict_name(verdict.verdict)).decode(),
             certified=bool(r.certified), converged=bool(r.converged), nodes=r.nodes,
             norm=_NORMS[r.norm], weighted=bool(r.weighted), fit_words=o.fit_words,
             bnb_depth=r.bnb_depth,
             polytope=_POLYTOPE[r.polytope] if 0 <= r.polytope < 5 else "not run",
             polytope_vertices=r.poly_vertices)
    if r.polytope == 0:
        d["polytope_upper"] = r.poly_upper
    return d


def jsr(scheme, face=False, edge=None, diagonals=None, depth=None, gap=None, norm=None,
        fit_words=None, max_seconds=None):
    """The Levin-Levin joint-spectral-radius test across a tet/oct face
    (face=True) or along an edge of valence N (edge=N): the dictionary
    `subspectra jsr --scheme SCHEME (--face | --edge N) --format json`
    prints -- the sub-patch maps' sizes, the invariant subspace, the profiles
    rho_k (inf- and 2-norm), proven bounds lower <= JSR <= upper with the word
    attaining lower, the threshold and the verdict ("pass" when upper is
    below it).  Options as jsr's --depth, --gap, --norm (inf, 2, auto,
    ellipsoid, polytope), --fit-words, --max-seconds and --diagonals; the
    command's defaults otherwise.  Raises SubspectraError where the command
    fails (the reduction does not apply: status "internal error")."""
    if edge is None and not _flag("face", face):
        raise ValueError("give face=True or edge=N")
    if edge is not None and face:
        raise ValueError("give face=True or edge=N, not both")
    case = {"edge": edge} if edge is not None else {"face": True}
    with _Case(scheme, diagonals=diagonals, **case) as c:
        o = _ffi.new("ss_jsr_opts *", _lib.ss_jsr_defaults())
        if depth is not None:
            o.depth = _integer("depth", depth)
        if gap is not None:
            o.gap = _real("gap", gap)
        if norm is not None:
            if norm not in _NORMS:
                raise ValueError("norm: expected one of %s, not %r" % (", ".join(_NORMS), norm))
            o.norm = _NORMS.index(norm)
        if fit_words is not None:
            o.fit_words = _integer("fit_words", fit_words)
        if max_seconds is not None:
            o.max_seconds = _real("max_seconds", max_seconds)
        pl = _ffi.new("ss_levin **")
        _check(_lib.ss_levin_new(c.scheme, c.c, pl, c.err), c.err)
        r = _ffi.new("ss_jsr_result *")
        try:
            L = pl[0]
            _check(_lib.ss_jsr_compute(L.m, L.n - L.r, _ffi.cast("const double *const *", L.Y),
                                       o, r, c.err), c.err)
            v = _ffi.new("ss_verdict *")
            _lib.ss_levin_verdict(L, r, v)
            return _jsr_dict(scheme, c.c, L, r, o, v)
        finally:
            _lib.ss_jsr_result_clear(r)
            _lib.ss_levin_free(pl[0])


def enumerate_links(kmin, kmax=None, part=0, nparts=1):
    """Every link (triangulation of the sphere, mirror images identified) with
    kmin..kmax vertices (kmax = kmin by default; 4 <= kmin <= kmax <= 20),
    each exactly once, as `subspectra enumerate links --vertices KMIN..KMAX
    [--part PART/NPARTS]` lists them: an iterator of plantri ASCII strings
    ("4 bcd,adc,abd,acb"), each usable as analyze(..., vertex=LINK).  Lazy:
    the enumeration runs in a thread a few links ahead of the loop and stops
    when the iterator is closed or dropped, so memory stays flat however many
    links there are (k = 16 has 17490241)."""
    kmin = _integer("kmin", kmin)
    kmax = kmin if kmax is None else _integer("kmax", kmax)
    opts = _ffi.new("ss_enum_opts *", {"kmin": kmin, "kmax": kmax,
                                       "part": _integer("part", part),
                                       "nparts": _integer("nparts", nparts)})
    err = _ffi.new("ss_error *")
    q = queue.Queue(maxsize=256)
    stop = threading.Event()
    failed = []

    def offer(item):
        """Put item on the queue unless the consumer has gone; False if it has."""
        while not stop.is_set():
            try:
                q.put(item, timeout=0.1)
                return True
            except queue.Full:
                pass
        return False

    @_ffi.callback("int(const ss_link *, void *)", onerror=lambda *exc: 1)
    def visit(link, ctx):
        p = _ffi.new("char **")
        st = _lib.ss_link_format(link, p, err)
        if st:
            failed.append(st)
            return 1
        text = _ffi.string(p[0]).decode()
        _libc.free(p[0])
        return 0 if offer(text) else 1

    def run():
        st = _lib.ss_enum_links(opts, visit, _ffi.NULL, _ffi.NULL, err)
        offer(_Done(failed[0] if failed else st))

    # the options are checked before anything runs, in this thread
    if not 4 <= kmin <= kmax <= _lib.SS_ENUM_MAXK or not 0 <= part < nparts:
        raise ValueError("expected 4 <= kmin <= kmax <= %d and 0 <= part < nparts, not "
                         "kmin=%d kmax=%d part=%d nparts=%d"
                         % (_lib.SS_ENUM_MAXK, kmin, kmax, part, nparts))
    return _links(q, stop, threading.Thread(target=run, daemon=True), err, visit)


class _Done:
    """The end of an enumeration, with its status."""

    def __init__(self, status):
        self.status = status


def _links(q, stop, thread, err, keep):
    """The generator of enumerate_links (keep: the callback, alive while it runs)."""
    thread.start()
    try:
        while True:
            item = q.get()
            if isinstance(item, _Done):
                _check(item.status, err)
                return
            yield item
    finally:
        stop.set()
        thread.join()
        del keep


# meshio's cell type names (VTK's vertex orders, which ss_cx.h follows) and
# the library's cell types; meshio has no octahedron, so its key is ours
_CELL_TYPES = {"vertex": "SS_VERTEX", "line": "SS_SEGMENT", "triangle": "SS_TRIANGLE",
               "quad": "SS_QUAD", "tetra": "SS_TET", "hexahedron": "SS_HEX",
               "octahedron": "SS_OCT"}


def _cx_from_arrays(points, cells, err):
    """A new ss_cx holding points (nv x dim) and cells (meshio's dict or list
    of (type, array) pairs, or CellBlocks); its arrays filled directly."""
    points = np.ascontiguousarray(points, dtype=np.float64)
    if points.ndim != 2 or not 1 <= points.shape[1] <= 16:
        raise ValueError("points: expected an array of shape (n, dim), dim 1..16 "
                         "(SS_MAXDIM), not %s"
                         % (points.shape,))
    if isinstance(cells, dict):
        cells = list(cells.items())
    blocks = [(b.type, b.data) if hasattr(b, "type") else b for b in cells]
    pcx = _ffi.new("ss_cx **")
    _check(_lib.ss_cx_new(points.shape[1], pcx, err), err)
    cx = pcx[0]
    try:
        nv, dim = points.shape
        _check(_lib.ss_cx_reserve_vertices(cx, nv, err), err)
        _ffi.memmove(cx.x, points, points.nbytes)
        _ffi.memmove(cx.vref, bytes(4 * nv), 4 * nv)
        cx.nv = nv
        for name, data in blocks:
            if name not in _CELL_TYPES:
                raise ValueError("cells: unknown cell type %r (expected one of %s)"
                                 % (name, ", ".join(_CELL_TYPES)))
            t = getattr(_lib, _CELL_TYPES[name])
            k = _lib.ss_cell_nverts(t)
            data = np.asarray(data)
            if data.ndim != 2 or data.shape[1] != k or not np.issubdtype(data.dtype, np.integer):
                raise ValueError("cells[%r]: expected integers of shape (m, %d), not %s %s"
                                 % (name, k, data.dtype, data.shape))
            if data.size and (data.min() < 0 or data.max() >= nv):
                raise ValueError("cells[%r]: vertex indices outside 0..%d" % (name, nv - 1))
            old = cx.nc[t]
            data = np.ascontiguousarray(data, dtype=np.uint32)
            _check(_lib.ss_cx_reserve_cells(cx, t, old + len(data), err), err)
            _ffi.memmove(cx.cells[t] + old * k, data, data.nbytes)
            _ffi.memmove(cx.cref[t] + old, bytes(4 * len(data)), 4 * len(data))
            cx.nc[t] = old + len(data)
        _check(_lib.ss_cx_validate(cx, err), err)
        return cx
    except BaseException:
        _lib.ss_cx_free(cx)
        raise


def _cx_to_arrays(cx):
    """(points, cells) of an ss_cx as NumPy arrays, cells a dict by meshio's names."""
    pts = np.frombuffer(_ffi.buffer(cx.x, cx.nv * cx.dim * 8), dtype=np.float64)
    cells = {}
    for name, tname in _CELL_TYPES.items():
        t = getattr(_lib, tname)
        if cx.nc[t]:
            k = _lib.ss_cell_nverts(t)
            a = np.frombuffer(_ffi.buffer(cx.cells[t], cx.nc[t] * k * 4), dtype=np.uint32)
            cells[name] = a.reshape(-1, k).astype(np.int64)
    return pts.reshape(cx.nv, cx.dim).copy(), cells


def subdivide(scheme, points, cells, levels=1, diagonals=None):
    """Refine a mesh `levels` times with the scheme, as `subspectra subdivide
    --scheme SCHEME --levels L IN -o OUT` does between reading IN and writing
    OUT: (points, cells) in, (points, cells) out.  points is an (n, dim)
    array (dim 1..16: every coordinate is refined alike, so extra columns
    carry fields); cells is meshio's: a dict {type: (m, k) int array} or a
    list of (type, array) pairs or CellBlocks, with meshio's (VTK's) types
    and vertex orders -- vertex, line, triangle, quad, tetra, hexahedron --
    and "octahedron" (opposite corners (0,3), (1,4), (2,5)) for what the
    tet/oct split makes.  Returns new arrays, cells as a dict, so
    meshio.Mesh(*subspectra.subdivide("mlca", m.points, m.cells_dict)) is
    the refined mesh.  Cells must be positively oriented (SubspectraError
    naming the first that is not, as the command); diagonals as subdivide's
    --diagonals for the box-spline schemes: bfs (default), proper or given."""
    levels = _integer("levels", levels)
    if not 0 <= levels <= 12:
        raise ValueError("levels: expected 0..12, not %d" % levels)
    err = _ffi.new("ss_error *")
    ps = _ffi.new("ss_scheme **")
    _check(_lib.ss_scheme_new(_text("scheme", scheme, "a scheme name").encode(), ps, err), err)
    cx, pf = _ffi.NULL, _ffi.new("ss_cx **")
    try:
        cx = _cx_from_arrays(points, cells, err)
        _check(_lib.ss_cx_check_orientation(cx, err), err)
        if _lib.ss_scheme_reads_diagonals(ps[0]):
            _choose_diagonals(cx, diagonals, err)
        elif diagonals is not None:
            raise ValueError("diagonals: scheme %s reads no major diagonals" % scheme)
        _check(_lib.ss_scheme_refine_levels(ps[0], cx, levels, pf, err), err)
        return _cx_to_arrays(pf[0])
    finally:
        _lib.ss_cx_free(pf[0])
        _lib.ss_cx_free(cx)
        _lib.ss_scheme_free(ps[0])


def _choose_diagonals(cx, diagonals, err):
    """subdivide's --diagonals: bfs (default) or proper chosen here, given
    kept as the tets' vertex orders carry them."""
    diagonals = _text("diagonals", "bfs" if diagonals is None else diagonals,
                      "bfs, proper or given")
    if diagonals == "given":
        return
    d = _ffi.new("ss_diag_mode *")
    if diagonals not in ("bfs", "proper") or _lib.ss_diag_parse(diagonals.encode(), d):
        raise ValueError("diagonals: expected bfs, proper or given, not %r" % (diagonals,))
    _check(_lib.ss_diag_choose(cx, d[0], 0, 0, err), err)


# the limit volume, the results store and mesh files, in modules of their own (they use
# the helpers above, hence imported last)
from ._limit import Limit, LimitValues, limit  # noqa: E402
from ._store import store_table  # noqa: E402
from ._mesh import MeshData, read_mesh, write_mesh  # noqa: E402
