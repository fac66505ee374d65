"""subspectra: spectral analysis of subdivision schemes, from Python.

A thin layer over the shared library libsubspectra (cffi in ABI mode: nothing
is compiled).  A case is one of

    vertex=LINK            a 3D vertex: plantri ASCII ("4 bcd,adc,abd,acb") or a
                           name (tetrahedron, octahedron, icosahedron, bipyramid:N)
    edge=N                 a point on an edge of valence N
    face=True              a point inside the face of two tets
    surface_vertex=N       a 2D vertex of valence N

with diagonals="bfs"|"proper"|"skew"|"center" for schemes that read major
diagonals.  Integer arguments must be integers (edge=5.7 or 5.0 raises
TypeError naming the argument); arguments that do not apply are refused.

    local_matrix(scheme, **case)   the local subdivision matrix S (scipy.sparse CSR)
    eigenvalues(scheme, **case)    all eigenvalues of S (NumPy complex array,
                                   by decreasing modulus) and their multiplicities
    eigenvectors(scheme, k, **case)
                                   the k leading ones with right and left
                                   eigenvectors (limit and tangent masks)
    analyze(scheme, **case, **options)
                                   the dictionary `subspectra analyze --format
                                   json` prints; options tol, eigenvalues, depth,
                                   ring_levels, certify as its --tol, ...

The library is looked for in $SUBSPECTRA_LIBRARY, then where `meson install`
put it, then by the dynamic linker's search (libsubspectra.so.0).
"""
import json
import numbers
import operator
import os

import numpy as np
import scipy.sparse
from cffi import FFI

from . import _config

__all__ = ["SubspectraError", "scheme_names", "local_matrix", "eigenvalues", "eigenvectors",
           "analyze"]

_ffi = FFI()
#Declarations as in the installed headers(ss_error.h, ss_scheme.h, ss_link.h,
#ss_case.h, ss_local.h, ss_eig.h, ss_report_case.h).Enumerations are passed as int.
#ss_local and ss_eig are read through pointers only, so only their leading
#fields are declared(in the headers' order; the rest is never touched).
_ffi.cdef("""
typedef struct {
  int status;
  char msg[512]; } ss_error;
typedef struct ss_scheme ss_scheme;
typedef struct ss_link_ ss_link;
typedef struct {
  int kind;
  const ss_link *link;
  int n;
  int diag;
  int cls; } ss_case;
typedef struct {
  size_t n2;
  size_t n1;
  double *S;
  size_t nnz;
  void *label;
  int ncoord;
  int dim;
  int level;
} ss_local;
typedef struct {
  double re, im, rcond;
  int block, group, mult;
  double err, cluster;
} ss_eigval;
typedef struct {
  size_t n;
  ss_eigval *val; } ss_eig;
typedef struct {
  void *fn;
  void *ctx; } ss_progress;
typedef struct {
  double tol;
  double cluster;
  int dim;
  int basis;
  int force;
  ss_progress progress;
} ss_eig_opts;
typedef struct {
  double tol;
  int neig;
  int depth;
  int ring_levels;
  int certify; }
  ss_report_analyze_opts;
typedef struct {
  size_t n;
  int k;
  double *re, *im;
  int *group;
  int *biorth;
  double *right_re;
  double *right_im;
  double *left_re;
  double *left_im;
  int complex_any;
} ss_eigvec;

const char *const *ss_scheme_names(void);
int ss_scheme_new(const char *name, ss_scheme **out, ss_error *err);
void ss_scheme_free(ss_scheme *s);
int ss_link_parse(const char *text, ss_link **out, ss_error *err);
void ss_link_free(ss_link *l);
int ss_diag_parse(const char *name, int *out);
int ss_local_new(const ss_scheme *s, const ss_case *c, ss_local **out, ss_error *err);
void ss_local_free(ss_local *L);
ss_eig_opts ss_eig_defaults(int dim);
int ss_eig_new(const double *S, size_t n, size_t n1, const ss_eig_opts *opts,
               ss_eig **out, ss_error *err);
void ss_eig_free(ss_eig *e);
ss_report_analyze_opts ss_report_analyze_defaults(void);
int ss_report_analyze(const ss_scheme *s, const ss_case *c,
                      const ss_report_analyze_opts *o, char **json, ss_error *err);
int ss_eigvec_new(const double *S, size_t n, int k, double tol, ss_eigvec **out,
                  ss_error *err);
void ss_eigvec_free(ss_eigvec *v);
void free(void *p);
""")

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
    """The built-in schemes' names."""
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
                d = _ffi.new("int *")
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
            tol=None, eigenvalues=None, depth=None, ring_levels=None, certify=False, cls=None):
    """The dictionary `subspectra analyze --scheme SCHEME CASE --format json`
    prints (DESIGN section 7): matrix sizes, leading eigenvalues, the
    eigenvalue condition, regularity and injectivity of the characteristic
    map; options as analyze's --tol, --eigenvalues, --depth, --ring-levels,
    --certify, and cls as --class (quasi48 surface vertices: 4 or 8)."""
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
        out = _ffi.new("char **")
        _check(_lib.ss_report_analyze(c.scheme, c.c, o, out, c.err), c.err)
        try:
            return json.loads(_ffi.string(out[0]).decode())
        finally:
            _libc.free(out[0])
