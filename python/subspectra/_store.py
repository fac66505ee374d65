"""A sweep's results store from Python: store_table(), the rows of
`subspectra report --format csv --table cases` as a list of dicts (or a NumPy
structured array), typed, for pandas.DataFrame or plain Python."""
import csv
import io
import os

import numpy as np

from . import SubspectraError, _check, _ffi, _lib, _libc, _text

_ffi.cdef("FILE *open_memstream(char **ptr, size_t *sizeloc); int fclose(FILE *f);")

# the columns by type (cases table, ss_report_table.c); the rest are text
_BOOL = {"eigen_certified", "regularity_certified", "injectivity_certified"}
_INT = {"k", "cells", "two_ring", "one_ring", "depth", "improper_pairs",
        "adjacent_pairs", "ring_level", "centre_corner_folds", "degree", "psi_pieces"}
_FLOAT = {"tolerance", "min_scaled_jacobian", "seconds", "psi_covered", "psi_uncovered"}


def _kind(name):
    """'bool', 'int', 'float' or 'str': the type of a column."""
    if name in _BOOL:
        return "bool"
    if name in _INT or name.endswith("_mult"):
        return "int"
    if name in _FLOAT or name.endswith(("_re", "_im")):
        return "float"
    return "str"


def _value(kind, text):
    """A CSV field as its column's type: an empty number is None (no
    characteristic map, no diagonals, fewer eigenvalues), empty text ''."""
    if kind == "str":
        return text
    if text == "":
        return None
    if kind == "bool":
        return text != "0"
    return int(text) if kind == "int" else float(text)


def _csv_of(path, where):
    """The cases table of the store at path in CSV, by the library's writer
    (the one `report` uses): its text."""
    err = _ffi.new("ss_error *")
    pst = _ffi.new("ss_store **")
    _check(_lib.ss_store_open(path.encode(), _lib.SS_STORE_READ, pst, err), err)
    rows = _ffi.new("ss_report_rows *")
    buf, size = _ffi.new("char **"), _ffi.new("size_t *")
    f = _ffi.NULL
    try:
        _check(_lib.ss_report_rows_load(pst[0], where.encode() if where else _ffi.NULL,
                                        rows, err), err)
        f = _libc.open_memstream(buf, size)
        if f == _ffi.NULL:
            raise MemoryError("open_memstream")
        # 1: SS_REPORT_CASES (an unnamed enum, not in the declarations)
        st = _lib.ss_report_table_write(f, _lib.SS_REPORT_CSV, 1, rows.row, rows.n,
                                        _ffi.NULL, 0, _ffi.NULL, err)
        _libc.fclose(f)
        f = _ffi.NULL
        _check(st, err)
        return _ffi.string(buf[0], size[0]).decode()
    finally:
        if f != _ffi.NULL:
            _libc.fclose(f)
        if buf[0] != _ffi.NULL:
            _libc.free(buf[0])
        _lib.ss_report_rows_clear(rows)
        _lib.ss_store_close(pst[0])


def store_table(path, where=None, array=False):
    """The cases of a results store (`subspectra sweep --db PATH`), one row
    per case, with exactly the columns and values of `subspectra report --db
    PATH --format csv --table cases [--where WHERE]` (names in that CSV's
    header: scheme, identity, case, k, link, cells, two_ring, one_ring,
    lambda1_re, lambda1_im, lambda1_mult, ..., eigen_condition, regularity,
    verdict, min_scaled_jacobian, seconds, eigen_certified, ...), ordered by
    identity, case kind, k and link.  Values are typed: int (k, sizes,
    multiplicities, depth, ...), float (eigenvalue parts, tolerance, the
    minimum scaled Jacobian, seconds), bool (the *_certified columns), str
    (names, links, verdicts, reasons; '' where there is none); a number the
    row does not have (no characteristic map, no diagonals) is None.

    Returns a list of dicts (pandas.DataFrame(rows) is the table; pandas is
    not needed here), or with array=True a NumPy structured array (int64,
    float64 with NaN for None -- also an int column with a None --, bool,
    str).

    where: an SQL expression over the store's view `cases`, as report's
    --where (e.g. "k = 7 AND verdict = 'fail'").  TypeError for arguments
    of the wrong type; SubspectraError for a file that is not a store or
    cannot be read, or a bad where (status "bad input" or "i/o error")."""
    path = os.fspath(path) if isinstance(path, os.PathLike) else path
    path = _text("path", path, "the path of a results store")
    if where is not None:
        where = _text("where", where, "an SQL expression over the view cases")
    if not isinstance(array, bool):
        raise TypeError("array: expected True or False, not %r" % (array,))
    if not os.path.exists(path):
        # the library would create nothing (read mode), but say it plainly
        raise SubspectraError("i/o error", "%s: no such results store" % path)
    reader = csv.reader(io.StringIO(_csv_of(path, where), newline=""))
    header = next(reader)
    kinds = [_kind(n) for n in header]
    rows = [{n: _value(k, t) for n, k, t in zip(header, kinds, r)} for r in reader]
    return _structured(header, rows) if array else rows


def _structured(header, rows):
    """rows as a NumPy structured array: bools as bool, integers as int64
    (float64 with NaN when a row has none), floats as float64 (NaN for
    None), text as str."""
    cols = []
    for n in header:
        kind, vals = _kind(n), [r[n] for r in rows]
        if kind == "bool":
            cols.append((n, bool, vals))
        elif kind == "int" and None not in vals:
            cols.append((n, np.int64, vals))
        elif kind in ("int", "float"):
            cols.append((n, np.float64, [np.nan if v is None else v for v in vals]))
        else:
            cols.append((n, "U%d" % max([1] + [len(v) for v in vals]), vals))
    out = np.zeros(len(rows), dtype=[(n, t) for n, t, _ in cols])
    for n, _, vals in cols:
        out[n] = vals
    return out


__all__ = ["store_table"]
