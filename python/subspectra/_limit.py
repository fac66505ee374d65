"""The limit volume of a hex mesh from Python: Limit and limit() over the
library's evaluator (ss_limit.h), vectorised over points."""
import collections

import numpy as np

from . import SubspectraError, _check, _cx_from_arrays, _ffi, _flag, _lib, _text

# the per-point statuses, as `subspectra limit` names them (cli/ss_cli_limit.h)
OK, NO_DERIVATIVES, FAILED, REFUSED = 0, 1, 2, 3
STATUS_NAMES = ("ok", "no_derivatives", "failed", "refused")

_STATUS_EINPUT, _STATUS_ENUMERIC = _lib.SS_EINPUT, _lib.SS_ENUMERIC

LimitValues = collections.namedtuple(
    "LimitValues", "points jacobians fields field_gradients status reasons")
LimitValues.__doc__ = """What Limit.evaluate returns, for m points:

    points           (m, 3) float array, the limit points
    jacobians        (m, 3, 3): row a is d/du_a of the point (u, v, w);
                     None unless derivatives=True
    fields           (m, nf): the fields' limit values; None without fields
    field_gradients  (m, nf, 3): d/du, d/dv, d/dw of each field; None unless
                     fields and derivatives=True
    status           (m,) int array: 0 ok, 1 no_derivatives (the point and
                     field values, but the Jacobian is unbounded or undefined
                     there: an extraordinary vertex, some edges and boundary
                     points), 2 failed (a numerical failure of the point:
                     no value), 3 refused (a point the evaluator does not
                     take: a walk that does not end, a patch that is not
                     manifold; no value); STATUS_NAMES names them
    reasons          {index: the library's message} for every point not ok

Values a point does not have are NaN, as `subspectra limit` writes them."""


def _index_array(name, a):
    """a as a 1-D int64 array; floats (even 2.0), bools and strings raise
    TypeError naming the argument."""
    arr = np.asarray(a)
    if arr.dtype == bool or not np.issubdtype(arr.dtype, np.integer):
        if arr.size == 0 and arr.dtype == np.float64:  # [] is a float array
            return np.zeros(0, dtype=np.int64)
        raise TypeError("%s: expected integers (cell indices from 0), not %s"
                        % (name, arr.dtype))
    if arr.ndim > 1:
        raise ValueError("%s: expected an integer or a 1-D array, not shape %s"
                         % (name, arr.shape))
    return arr.astype(np.int64).reshape(-1)


def _real_array(name, a, shape_msg):
    arr = np.asarray(a)
    if arr.dtype == bool or not (np.issubdtype(arr.dtype, np.floating) or
                                 np.issubdtype(arr.dtype, np.integer)):
        raise TypeError("%s: expected real numbers, not %s" % (name, arr.dtype))
    arr = np.ascontiguousarray(arr, dtype=np.float64)
    if arr.ndim == 0 or arr.shape[-1:] != (3,) and shape_msg:
        raise ValueError("%s: expected %s, not shape %s" % (name, shape_msg, arr.shape))
    return arr


class Limit:
    """An evaluator of the limit volume of a hex mesh under a scheme
    (ss_limit.h): the limit point, and with derivatives its Jacobian, at
    parameters (u, v, w) in [0,1]^3 of a cell -- exactly what `subspectra
    limit` computes.

        L = Limit(scheme, points, cells, fields=None)

    scheme: a scheme that splits hexahedra multilinearly with a one-ring
    rule and is the tricubic B-spline on grids (mlca, ccsolid,
    ccsolid-tensor).  points: an (n, 3) array of control points.  cells:
    meshio's cells (a dict {"hexahedron": (m, 8) int array} or a list of
    (type, array) pairs or CellBlocks; VTK's vertex order, indices from 0)
    holding hexahedra only.
    fields: None, an (n,) or (n, nf) array of scalar values per control
    point (density, a temperature): they are subdivided with the same
    weights as the coordinates, so their limits come with every point.

    The evaluator caches what it learns about the mesh's patches, so many
    evaluations on one Limit cost far less than as many limit() calls; it is
    not thread-safe (one per thread).  close() frees it (also a context
    manager); it is freed with the object otherwise.

    Raises TypeError for arguments of the wrong type, ValueError for wrong
    shapes, and SubspectraError (status "bad input") where the command
    refuses the mesh: other cells than hexahedra, a face shared by three
    cells, flat, folded or inverted hexahedra, a scheme without the
    multilinear split, a field value that is not finite."""

    def __init__(self, scheme, points, cells, fields=None):
        self._L = _ffi.NULL
        self._scheme = _ffi.NULL
        err = _ffi.new("ss_error *")
        scheme = _text("scheme", scheme, "a scheme name such as 'mlca'")
        pts = _real_array("points", points, "an (n, 3) array")
        if pts.ndim != 2:
            raise ValueError("points: expected an (n, 3) array, not shape %s" % (pts.shape,))
        nv = pts.shape[0]
        if fields is None:
            fv = np.zeros((nv, 0))
        else:
            fv = np.asarray(fields)
            if fv.dtype == bool or not (np.issubdtype(fv.dtype, np.floating) or
                                        np.issubdtype(fv.dtype, np.integer)):
                raise TypeError("fields: expected real numbers, not %s" % fv.dtype)
            fv = np.ascontiguousarray(fv, dtype=np.float64)
            if fv.ndim == 1:
                fv = fv.reshape(-1, 1)
            if fv.ndim != 2 or fv.shape[0] != nv:
                raise ValueError("fields: expected %d values per field (one per point), "
                                 "shape (%d,) or (%d, nf), not %s" % (nv, nv, nv, fv.shape))
            if not np.isfinite(fv).all():
                i = int(np.argwhere(~np.isfinite(fv))[0][0])
                raise ValueError("fields: the value at point %d is not finite" % i)
        ps = _ffi.new("ss_scheme **")
        _check(_lib.ss_scheme_new(scheme.encode(), ps, err), err)
        self._scheme = ps[0]
        cx = _ffi.NULL
        try:
            cx = _cx_from_arrays(pts, cells, err)
            pl = _ffi.new("ss_limit **")
            nf = fv.shape[1]
            _check(_lib.ss_limit_new_fields(self._scheme, cx, nf,
                                            _ffi.from_buffer("double[]", fv) if nf
                                            else _ffi.NULL, pl, err), err)
            self._L = pl[0]
            # flat, folded or inverted cells: refused as the command does
            _check(_lib.ss_cx_check_orientation(cx, err), err)
        except BaseException:
            self.close()
            raise
        finally:
            _lib.ss_cx_free(cx)
        self.ncells = int(_lib.ss_limit_ncells(self._L))
        self.nfields = int(_lib.ss_limit_nfields(self._L))

    def close(self):
        """Free the evaluator (later calls raise ValueError)."""
        if self._L != _ffi.NULL:
            _lib.ss_limit_free(self._L)
            self._L = _ffi.NULL
        if self._scheme != _ffi.NULL:
            _lib.ss_scheme_free(self._scheme)
            self._scheme = _ffi.NULL

    def __del__(self):
        self.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def evaluate(self, cell, uvw, derivatives=False, reference=False):
        """The limit at m points: cell (an int or an (m,) int array, from 0)
        and uvw (a (3,) or (m, 3) array of parameters in [0,1]; u along
        corner 0 -> 1, v along 0 -> 3, w along 0 -> 4), broadcast against
        each other.  derivatives=True adds the Jacobians (and the fields'
        gradients); reference=True evaluates by repeated local subdivision
        instead (slow, at most 60 steps; `limit --reference`).  Returns a
        LimitValues; a point the evaluator cannot take in full gets its
        status and reason instead of an exception, as `subspectra limit`
        writes it.  ValueError, before anything is evaluated, for a cell
        outside 0..ncells-1 or a parameter outside [0,1] or not a number;
        SubspectraError when the library fails (out of memory)."""
        if self._L == _ffi.NULL:
            raise ValueError("this Limit is closed")
        derivatives = _flag("derivatives", derivatives)
        reference = _flag("reference", reference)
        cells = _index_array("cell", cell)
        x = _real_array("uvw", uvw, "a (3,) or (m, 3) array of parameters")
        if x.ndim > 2:
            raise ValueError("uvw: expected a (3,) or (m, 3) array, not shape %s" % (x.shape,))
        x = x.reshape(-1, 3)
        try:
            cells, _ = np.broadcast_arrays(cells, x[:, 0])
            x = np.broadcast_to(x, (len(cells), 3))
        except ValueError:
            raise ValueError("cell and uvw: %d cells and %d parameter triples do not "
                             "broadcast" % (np.asarray(cell).size, len(x))) from None
        bad = np.flatnonzero((cells < 0) | (cells >= self.ncells))
        if bad.size:
            raise ValueError("cell: %d (point %d) is not a cell of this mesh (0..%d)"
                             % (cells[bad[0]], bad[0], self.ncells - 1))
        bad = np.flatnonzero(~((x >= 0) & (x <= 1)).all(axis=1))
        if bad.size:
            raise ValueError("uvw: point %d has parameters %s, not in [0,1]^3"
                             % (bad[0], x[bad[0]].tolist()))
        return self._run(cells, x, derivatives, reference)

    def _run(self, cells, x, derivatives, reference):
        m, nf = len(cells), self.nfields
        pts = np.full((m, 3), np.nan)
        jac = np.full((m, 3, 3), np.nan) if derivatives else None
        fv = np.full((m, nf), np.nan) if nf else None
        fd = np.full((m, nf, 3), np.nan) if nf and derivatives else None
        status = np.zeros(m, dtype=np.int64)
        reasons = {}
        out = _ffi.new("ss_limit_point *")
        f = _ffi.new("double[]", max(nf, 1))
        df = _ffi.new("double[][3]", max(nf, 1))
        err = _ffi.new("ss_error *")

        def one(i, d):
            c, (u, v, w) = int(cells[i]), x[i]
            if reference:
                return _lib.ss_limit_eval_reference_fields(
                    self._L, c, u, v, w, d, 60, out, f if nf else _ffi.NULL,
                    df if nf and d else _ffi.NULL, err)
            return _lib.ss_limit_eval_fields(self._L, c, u, v, w, d, out,
                                             f if nf else _ffi.NULL,
                                             df if nf and d else _ffi.NULL, err)

        for i in range(m):
            st = one(i, 1 if derivatives else 0)
            if st == _STATUS_ENUMERIC and derivatives:
                msg = _ffi.string(err.msg).decode(errors="replace")
                st = one(i, 0)  # the point may exist without its Jacobian
                if not st:
                    status[i], reasons[i] = NO_DERIVATIVES, msg
            if st in (_STATUS_EINPUT, _STATUS_ENUMERIC):
                status[i] = FAILED if st == _STATUS_ENUMERIC else REFUSED
                reasons[i] = _ffi.string(err.msg).decode(errors="replace")
                continue
            _check(st, err)  # out of memory, internal: the batch ends
            pts[i] = list(out.p)
            if nf:
                fv[i] = [f[k] for k in range(nf)]
            if derivatives and status[i] == OK:
                jac[i] = [list(out.jac[a]) for a in range(3)]
                if nf:
                    fd[i] = [list(df[k]) for k in range(nf)]
        return LimitValues(pts, jac, fv, fd, status, reasons)


def limit(scheme, points, cells, cell, uvw, derivatives=False, fields=None):
    """The limit volume of a hex mesh at m points, in one call:
    Limit(scheme, points, cells, fields).evaluate(cell, uvw, derivatives).
    Returns a LimitValues (points (m, 3); jacobians (m, 3, 3) with
    derivatives=True; fields and their gradients when fields are given;
    per-point status and reasons).  For many calls on one mesh keep a Limit:
    it caches the patches.  See Limit for the arguments and errors."""
    with Limit(scheme, points, cells, fields) as L:
        return L.evaluate(cell, uvw, derivatives)


__all__ = ["Limit", "LimitValues", "limit", "STATUS_NAMES", "SubspectraError"]
