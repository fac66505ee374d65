"""Mesh files from Python: read_mesh() and write_mesh() over the library's
readers and writers (ss_mesh.h), NumPy arrays in and out, in meshio's form."""
import collections
import os

import numpy as np

from . import _CELL_TYPES, _check, _cx_from_arrays, _cx_to_arrays, _ffi, _lib, _text

MeshData = collections.namedtuple("MeshData", "points cells point_data cell_data")
MeshData.__doc__ = """What read_mesh returns, in the order of meshio.Mesh's
arguments (meshio.Mesh(*subspectra.read_mesh(path)) is the mesh):

    points      (n, d) float array, d = 2 or 3 (the file's coordinates
                without its fields)
    cells       {meshio cell type: (m, k) int64 array}, VTK's vertex orders
                ("vertex", "line", "triangle", "quad", "tetra",
                "hexahedron", and "octahedron" for this project's cell)
    point_data  {name: (n,) float array}: the file's fields (VTK/VTU point
                data, gmsh views, Medit's 4th and later coordinates "w",
                "x5", ...), as the command line refines them
    cell_data   {"ref": [(m,) int32 array per block of cells, in cells'
                order]}: the cells' references (Medit labels, gmsh physical
                groups, VTU "ref")"""


def _format(path, fmt):
    """The ss_mesh_format of fmt (a name such as "vtu", "medit", "msh") or,
    when fmt is None, of path's extension (SS_MESH_AUTO)."""
    if fmt is None:
        return _lib.SS_MESH_AUTO
    fmt = _text("fmt", fmt, "a mesh format name: medit, vtk, vtu, obj, gmsh, tetgen")
    f = _lib.ss_mesh_format_from_name(fmt.encode())
    if f == _lib.SS_MESH_AUTO:
        raise ValueError("fmt: unknown mesh format %r (expected medit, vtk, vtu, obj, gmsh "
                         "or tetgen)" % fmt)
    return f


def read_mesh(path, fmt=None):
    """Read a mesh file as `subspectra subdivide` reads its input: Medit
    .mesh, legacy VTK .vtk, VTK XML .vtu, Wavefront .obj, gmsh .msh (v2/v4,
    ASCII/binary; builds with gmsh), TetGen .node/.ele/.face -- by the
    extension, or fmt ("medit", "vtk", "vtu", "obj", "gmsh", "tetgen").
    Returns a MeshData (points, cells, point_data, cell_data) of NumPy
    arrays; meshio.Mesh(*read_mesh(path)) is the mesh as meshio holds it.
    To refine fields with subdivide(), give them as extra columns:
    np.column_stack([m.points] + list(m.point_data.values())).
    TypeError for a path that is not a str (or os.PathLike); SubspectraError
    for a file that cannot be opened ("i/o error") or is malformed ("bad
    input", with the file and line)."""
    path = _text("path", os.fspath(path) if isinstance(path, os.PathLike) else path,
                 "the path of a mesh file")
    f = _format(path, fmt)
    err = _ffi.new("ss_error *")
    pcx = _ffi.new("ss_cx **")
    names = _ffi.new("ss_mesh_fields *")
    _check(_lib.ss_mesh_read_fields(path.encode(), f, pcx, names, err), err)
    cx = pcx[0]
    try:
        x, cells = _cx_to_arrays(cx)
        nf = max(0, cx.dim - 3)
        point_data = {_ffi.string(names.name[i]).decode(): x[:, 3 + i].copy()
                      for i in range(min(nf, names.n))}
        refs = []
        for name in cells:
            t = getattr(_lib, _CELL_TYPES[name])
            refs.append(np.frombuffer(_ffi.buffer(cx.cref[t], cx.nc[t] * 4),
                                      dtype=np.int32).copy())
        return MeshData(x[:, :min(cx.dim, 3)].copy(), cells, point_data, {"ref": refs})
    finally:
        _lib.ss_cx_free(cx)


def _columns(points, point_data):
    """points with point_data's arrays as extra columns, and their names:
    an (n,) array is one field, an (n, c) array c fields NAME_x, NAME_y,
    NAME_z (c = 3) or NAME_0 .. (as the VTK readers name them)."""
    pts = np.asarray(points, dtype=np.float64)
    cols, names = [pts], []
    for name, a in (point_data or {}).items():
        name = _text("point_data key", name, "a field name")
        if not 0 < len(name.encode()) < _lib.SS_FIELD_NAME_MAX - 2:
            raise ValueError("point_data: field name %r: 1..%d bytes"
                             % (name, _lib.SS_FIELD_NAME_MAX - 3))
        a = np.asarray(a, dtype=np.float64)
        if a.ndim == 1:
            a = a.reshape(-1, 1)
            names.append(name)
        elif a.ndim == 2:
            names += [name + ("_" + "xyz"[j] if a.shape[1] == 3 else "_%d" % j)
                      for j in range(a.shape[1])]
        if a.ndim != 2 or pts.ndim != 2 or a.shape[0] != pts.shape[0]:
            raise ValueError("point_data[%r]: expected %s values, one per point, not shape %s"
                             % (name, pts.shape[:1], a.shape))
        cols.append(a)
    if names and pts.shape[1:] != (3,):
        raise ValueError("point_data: fields need 3 coordinates (points of shape (n, 3)), "
                         "not %s" % (pts.shape,))
    return np.column_stack(cols) if names else pts, names


def write_mesh(path, points, cells, point_data=None, cell_data=None, fmt=None):
    """Write a mesh file as `subspectra subdivide -o PATH` writes its output:
    by the extension (.mesh, .vtk, .vtu, .obj; .msh in builds with gmsh) or
    fmt.  points: (n, d) array, d = 1..3; cells: meshio's (a dict or a list
    of (type, array) pairs or CellBlocks; the types of subdivide()).
    point_data: {name: (n,) or (n, c) array}, written as point data (VTK,
    VTU, gmsh views; Medit: extra coordinates, names lost).  cell_data:
    {"ref": [(m,) int array per block, in cells' order]} for the cells'
    references (Medit labels; 0 without).  The file is written whole or not
    at all.  Octahedra are written as the command writes them (two pyramids
    in VTK/VTU, four tets in Medit).  ValueError for arrays of the wrong
    shape; SubspectraError when the format cannot hold the mesh (volume
    cells in OBJ), a coordinate is not finite, or the file cannot be written."""
    path = _text("path", os.fspath(path) if isinstance(path, os.PathLike) else path,
                 "the path of the mesh file to write")
    f = _format(path, fmt)
    x, names = _columns(points, point_data)
    if len(names) > _lib.SS_MAXDIM - 3:
        raise ValueError("point_data: %d fields, at most %d" % (len(names), _lib.SS_MAXDIM - 3))
    blocks = list(cells.items()) if isinstance(cells, dict) else list(cells)
    refs = (cell_data or {}).get("ref")
    if refs is not None and len(refs) != len(blocks):
        raise ValueError("cell_data['ref']: %d arrays for %d blocks of cells"
                         % (len(refs), len(blocks)))
    err = _ffi.new("ss_error *")
    cx = _cx_from_arrays(x, blocks, err)
    try:
        if refs is not None:
            _set_refs(cx, blocks, refs)
        fields = _ffi.new("ss_mesh_fields *")
        fields.n = len(names)
        for i, n in enumerate(names):
            b = n.encode()
            _ffi.memmove(fields.name[i], b + b"\0", len(b) + 1)
        opts = _ffi.new("ss_mesh_write_opts *", {"fields": fields})
        _check(_lib.ss_mesh_write(path.encode(), f, cx, opts, err), err)
    finally:
        _lib.ss_cx_free(cx)


def _set_refs(cx, blocks, refs):
    """The cells' references, block by block in the order _cx_from_arrays
    appended them (several blocks of one type follow each other)."""
    at = {}
    for (b, r) in zip(blocks, refs):
        name, data = (b.type, b.data) if hasattr(b, "type") else b
        t = getattr(_lib, _CELL_TYPES[name])
        r = np.ascontiguousarray(r, dtype=np.int32)
        start = at.get(t, 0)
        if r.ndim != 1 or len(r) != len(data):
            raise ValueError("cell_data['ref']: block %r: expected one reference per cell"
                             % name)
        _ffi.memmove(cx.cref[t] + start, r, r.nbytes)
        at[t] = start + len(r)


__all__ = ["MeshData", "read_mesh", "write_mesh"]
