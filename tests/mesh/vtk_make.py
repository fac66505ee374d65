"""vtk_make.py DIR -- VTK XML files written here, independently of subspectra's
writer, in every layout its reader takes (ascii; inline base64 with UInt32 and
UInt64 headers, header and data encoded apart or together; appended raw and
base64; zlib-compressed, several blocks; big-endian), each with the Medit file
of the same mesh (ref.mesh: Dimension 3 + fields, the fields in the order of
the VTU's point data, a 3-vector as 3 fields) -- and bad files for the error
messages.  A 3 x 3 x 3 grid of jittered hexahedra with a crease quad and two
corners; point data: density (an affine function of the position), velocity
(= the position) and vref; cell data ref.  Legacy VTK files of the same mesh too: ASCII and
BINARY (big-endian), version 3 (CELLS with counts) and 5.1 (OFFSETS and
CONNECTIVITY), point data as SCALARS + VECTORS or as one FIELD."""
import base64, os, random, struct, sys, zlib

d = sys.argv[1]
random.seed(36)
n = 4
P = []
for k in range(n):
    for j in range(n):
        for i in range(n):
            P.append((i + random.uniform(-.1, .1), j + random.uniform(-.1, .1),
                      k + random.uniform(-.1, .1)))
dens = [2 * x - 3 * y + z / 2 + 1 for x, y, z in P]
vref = [v % 3 for v in range(len(P))]
ix = lambda i, j, k: k * n * n + j * n + i
cells = []  # (vtk type, points, ref)
for k in range(n - 1):
    for j in range(n - 1):
        for i in range(n - 1):
            cells.append((12, [ix(i, j, k), ix(i + 1, j, k), ix(i + 1, j + 1, k), ix(i, j + 1, k),
                               ix(i, j, k + 1), ix(i + 1, j, k + 1), ix(i + 1, j + 1, k + 1),
                               ix(i, j + 1, k + 1)], 1 + (i + j + k) % 4))
cells.append((9, [ix(0, 0, 2), ix(1, 0, 2), ix(1, 1, 2), ix(0, 1, 2)], 5))
cells.append((1, [ix(0, 0, 0)], 6))
cells.append((1, [ix(3, 3, 3)], 7))

# the Medit file of the same mesh: fields density, velocity_x, _y, _z
with open(os.path.join(d, "ref.mesh"), "w") as f:
    f.write("MeshVersionFormatted 2\nDimension 7\nVertices\n%d\n" % len(P))
    for v, p in enumerate(P):
        f.write(" ".join(repr(c) for c in p + (dens[v],) + p) + " %d\n" % vref[v])
    for t, kw in ((1, "Corners"), (9, "Quadrilaterals"), (12, "Hexahedra")):
        cs = [c for c in cells if c[0] == t]
        f.write("%s\n%d\n" % (kw, len(cs)))
        for c in cs:
            f.write(" ".join(str(v + 1) for v in c[1]) + ("" if t == 1 else " %d" % c[2]) + "\n")
    f.write("End\n")
# Medit's Corners carry no reference: the VTU's corner cells get ref 0 below
cells = [(t, pts, 0 if t == 1 else r) for t, pts, r in cells]

conn = [v for c in cells for v in c[1]]
offs, e = [], 0
for c in cells:
    e += len(c[1])
    offs.append(e)
arrays = [  # (section, name, type code, vtk type, ncomp, values)
    ("Points", None, "d", "Float64", 3, [c for p in P for c in p]),
    ("Cells", "connectivity", "q", "Int64", 1, conn),
    ("Cells", "offsets", "i", "Int32", 1, offs),
    ("Cells", "types", "B", "UInt8", 1, [c[0] for c in cells]),
    ("PointData", "density", "f" if False else "d", "Float64", 1, dens),
    ("PointData", "velocity", "d", "Float64", 3, [c for p in P for c in p]),
    ("PointData", "vref", "h", "Int16", 1, vref),
    ("CellData", "ref", "I", "UInt32", 1, [c[2] for c in cells]),
]


def block(vals, code, endian, head, zblocks, apart):
    """The binary form of one array: header and data (zlib: in zblocks blocks)."""
    raw = struct.pack(endian + "%d%s" % (len(vals), code), *vals)
    h = endian + head
    if not zblocks:
        hd = struct.pack(h, len(raw))
        return [hd, raw] if apart else [hd + raw]
    bs = -(-len(raw) // zblocks)
    parts = [raw[i:i + bs] for i in range(0, len(raw), bs)]
    comp = [zlib.compress(p) for p in parts]
    last = len(parts[-1]) if len(parts[-1]) != bs else 0
    hd = struct.pack(endian + head[0] * (3 + len(comp)), len(comp), bs, last,
                     *[len(c) for c in comp])
    return [hd, b"".join(comp)] if apart else [hd + b"".join(comp)]


def write(name, fmt, endian="<", head="Q", zblocks=0, apart=True, app_enc="raw",
          mutate=None):
    hd_attr = ' header_type="%s"' % ("UInt64" if head == "Q" else "UInt32")
    comp_attr = ' compressor="vtkZLibDataCompressor"' if zblocks else ""
    order = "LittleEndian" if endian == "<" else "BigEndian"
    out = ['<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="1.0" '
           'byte_order="%s"%s%s>\n<UnstructuredGrid>\n<Piece NumberOfPoints="%d" '
           'NumberOfCells="%d">\n' % (order, hd_attr, comp_attr, len(P), len(cells))]
    app, sec = b"", None
    for s, nm, code, vt, nc, vals in arrays:
        if s != sec:
            if sec:
                out.append("</%s>\n" % sec)
            out.append("<%s>\n" % s)
            sec = s
        a = '<DataArray type="%s"%s NumberOfComponents="%d"' % (
            vt, ' Name="%s"' % nm if nm else "", nc)
        if fmt == "ascii":
            out.append(a + ' format="ascii">\n%s\n</DataArray>\n' %
                       " ".join(repr(v) for v in vals))
        elif fmt == "binary":
            enc = "".join(base64.b64encode(p).decode() for p in
                          block(vals, code, endian, head, zblocks, apart))
            out.append(a + ' format="binary">\n%s\n</DataArray>\n' % enc)
        else:
            b = block(vals, code, endian, head, zblocks, apart)
            if app_enc == "base64":
                chunk = "".join(base64.b64encode(p).decode() for p in b).encode()
            else:
                chunk = b"".join(b)
            out.append(a + ' format="appended" offset="%d"/>\n' % len(app))
            app += chunk
    out.append("</%s>\n</Piece>\n</UnstructuredGrid>\n" % sec)
    text = "".join(out).encode()
    if fmt == "appended":
        text += b'<AppendedData encoding="%s">\n_' % app_enc.encode() + app + \
            b"\n</AppendedData>\n"
    text += b"</VTKFile>\n"
    if mutate:
        text = mutate(text)
    with open(os.path.join(d, name + ".vtu"), "wb") as f:
        f.write(text)


write("ascii", "ascii")
write("b64-u32-apart", "binary", head="I")
write("b64-u64-joint", "binary", head="Q", apart=False)
write("app-raw", "appended")
write("app-raw-be", "appended", endian=">", head="I")
write("app-b64", "appended", app_enc="base64")
write("zlib-b64", "binary", zblocks=3)
write("zlib-app", "appended", zblocks=2, head="I")
write("zlib-app-be", "appended", endian=">", zblocks=1)

# bad files: (name, what the message must say)
sub = lambda a, b: (lambda t: t.replace(a, b, 1))
write("bad-wedge", "ascii", mutate=sub(b'format="ascii">\n12 ', b'format="ascii">\n13 '))
write("bad-pyramid", "ascii", mutate=sub(b'format="ascii">\n12 ', b'format="ascii">\n14 '))
write("bad-short", "ascii", mutate=sub(b"%r\n</DataArray>" % dens[-1], b"\n</DataArray>"))
write("bad-lz4", "binary", zblocks=2, mutate=sub(b"vtkZLibDataCompressor", b"vtkLZ4DataCompressor"))
write("bad-zlib", "appended", zblocks=1, mutate=lambda t: t[:-60] + b"\x00" * 20 + t[-40:])
write("bad-offset", "appended", mutate=sub(b'offset="0"', b'offset="99999999"'))
write("bad-index", "ascii", mutate=sub(b'format="ascii">\n%d ' % conn[0], b'format="ascii">\n640 '))
write("bad-nan", "ascii", mutate=sub(b'format="ascii">\n%r ' % dens[0], b'format="ascii">\nnan '))
write("bad-xml", "ascii", mutate=sub(b"</Piece>", b"</Peace>"))
write("bad-type", "ascii", mutate=sub(b'type="UnstructuredGrid"', b'type="PolyData"'))


def legacy(name, binary, v51=False, field=False, mutate=None):
    """A legacy .vtk of the same mesh."""
    out = [b"# vtk DataFile Version %s\nsubspectra test\n%s\nDATASET UNSTRUCTURED_GRID\n"
           % (b"5.1" if v51 else b"3.0", b"BINARY" if binary else b"ASCII")]

    def data(vals, code):
        if binary:
            return struct.pack(">%d%s" % (len(vals), code), *vals) + b"\n"
        return (" ".join(repr(v) for v in vals) + "\n").encode()
    out.append(b"POINTS %d %s\n" % (len(P), b"double" if not binary else b"float"))
    pts = [c for p in P for c in p]
    if binary:  # float32 points: the Medit reference holds the rounded values
        pts = list(struct.unpack(">%df" % len(pts), struct.pack(">%df" % len(pts), *pts)))
    out.append(data(pts, "d" if not binary else "f"))
    if v51:
        out.append(b"CELLS %d %d\nOFFSETS vtktypeint64\n" % (len(cells) + 1, len(conn)))
        out.append(data([0] + offs, "q"))
        out.append(b"CONNECTIVITY vtktypeint64\n")
        out.append(data(conn, "q"))
    else:
        flat = [v for c in cells for v in [len(c[1])] + c[1]]
        out.append(b"CELLS %d %d\n" % (len(cells), len(flat)))
        out.append(data(flat, "i"))
    out.append(b"CELL_TYPES %d\n" % len(cells))
    out.append(data([c[0] for c in cells], "i"))
    out.append(b"CELL_DATA %d\nSCALARS ref int 1\nLOOKUP_TABLE default\n" % len(cells))
    out.append(data([c[2] for c in cells], "i"))
    out.append(b"POINT_DATA %d\n" % len(P))
    if field:
        out.append(b"FIELD FieldData 3\ndensity 1 %d double\n" % len(P))
        out.append(data(dens, "d"))
        out.append(b"velocity 3 %d double\n" % len(P))
        out.append(data(pts, "d"))
        out.append(b"vref 1 %d short\n" % len(P))
        out.append(data(vref, "h"))
    else:
        out.append(b"SCALARS density double\nLOOKUP_TABLE default\n")
        out.append(data(dens, "d"))
        out.append(b"VECTORS velocity double\n")
        out.append(data(pts, "d"))
        out.append(b"SCALARS vref short 1\nLOOKUP_TABLE default\n")
        out.append(data(vref, "h"))
    text = b"".join(out)
    if mutate:
        text = mutate(text)
    with open(os.path.join(d, name + ".vtk"), "wb") as f:
        f.write(text)


legacy("leg-ascii", False)
legacy("leg-ascii-51", False, v51=True, field=True)
legacy("leg-bin", True, field=True)
legacy("leg-bin-51", True, v51=True)
# the binary files' points are float32: their reference
with open(os.path.join(d, "ref32.mesh"), "w") as f:
    f.write(open(os.path.join(d, "ref.mesh")).read())
P32 = []
for p in P:
    P32.append(struct.unpack(">3f", struct.pack(">3f", *p)))
with open(os.path.join(d, "ref32.mesh"), "w") as f:
    lines = open(os.path.join(d, "ref.mesh")).read().split("\n")
    for v, p in enumerate(P32):  # coordinates rounded; fields as they were
        w = lines[4 + v].split()
        lines[4 + v] = " ".join([repr(c) for c in p] + w[3:4] + [repr(c) for c in p] + w[7:])
    f.write("\n".join(lines))
def drop_last_density(t):
    a = t.index(b"SCALARS density double\nLOOKUP_TABLE default\n") + 44
    e = t.index(b"\n", a)
    return t[:a] + t[a:e].rsplit(b" ", 1)[0] + t[e:]


legacy("leg-bad-short", False, mutate=drop_last_density)
legacy("leg-bad-wedge", False, mutate=lambda t: t.replace(b"CELL_TYPES 30\n12", b"CELL_TYPES 30\n13"))
legacy("leg-bad-count", False, mutate=lambda t: t.replace(b"POINT_DATA 64", b"POINT_DATA 63"))
legacy("leg-bad-bin", True, mutate=lambda t: t[:len(t) // 3])
legacy("leg-bad-dataset", False, mutate=lambda t: t.replace(b"UNSTRUCTURED_GRID", b"POLYDATA"))
