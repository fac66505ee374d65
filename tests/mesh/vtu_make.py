"""vtu_make.py DIR -- VTK XML files written here, independently of subspectra's
writer, in every layout its reader takes (ascii; inline base64 with UInt32 and
UInt64 headers, header and data encoded apart or together; appended raw and
base64; zlib-compressed, several blocks; big-endian), each with the Medit file
of the same mesh (ref.mesh: Dimension 3 + fields, the fields in the order of
the VTU's point data, a 3-vector as 3 fields) -- and bad files for the error
messages.  A 3 x 3 x 3 grid of jittered hexahedra with a crease quad and two
corners; point data: density (an affine function of the position), velocity
(= the position) and vref; cell data ref."""
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
