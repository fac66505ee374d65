/* ss_mesh.h — reading and writing meshes: Medit .mesh, legacy VTK, Wavefront OBJ.
 *
 * Medit (.mesh, ASCII "MeshVersionFormatted"): sections Vertices, Edges,
 * Triangles, Quadrilaterals, Tetrahedra, Hexahedra and Corners (vertex cells),
 * plus this project's extension keyword "Octahedra" (6 indices + reference,
 * vertex order of ss_cx.h), read always and written only on request
 * (ss_mesh_write_opts).  "Dimension" may be 1..4 (Medit itself knows 2 and 3).  Known
 * sections that carry no cells (Ridges, RequiredVertices, Normals, ...) are
 * skipped; an unknown keyword where one is expected is an error.
 * Legacy VTK (.vtk): written as UNSTRUCTURED_GRID for ParaView; octahedra
 * are written as two pyramids sharing their equator; read (ss_mesh_read_vtk).
 * VTK XML (.vtu): written with the same grid and data as .vtk, binary
 * (appended raw data, UInt64 byte counts, the machine's byte order): shared
 * points; octahedra split as in .vtk (ss_mesh_vtk.c says why not a polyhedron).
 * Read through libxml2 and zlib (ss_mesh_read_vtu).  Point data are fields
 * (ss_mesh_fields below) both ways.
 * OBJ (.obj): surfaces only — v, f (triangles and quadrilaterals), l (segments),
 * p (vertex cells); vt/vn/vp/o/g/s/usemtl/mtllib are ignored.
 * gmsh (.msh, versions 2 and 4, ASCII and binary): read only, by gmsh's own
 * C API (ss_mesh_gmsh.c); points, lines, triangles, quadrangles, tetrahedra,
 * hexahedra of first order.
 * TetGen (.node, .ele, .face; also Triangle's 2D .node/.ele): read only
 * (ss_mesh_tetgen.c).
 *
 * Every malformed file is SS_EINPUT with "file:line: problem" in err. */
#ifndef SS_MESH_H
#define SS_MESH_H

#include <stdio.h>

#include "ss_api.h"
#include "ss_cx.h"

SS_BEGIN_DECLS

typedef enum {
  SS_MESH_AUTO = 0, /* choose by file name extension */
  SS_MESH_MEDIT,    /* .mesh */
  SS_MESH_VTK,      /* .vtk, legacy VTK */
  SS_MESH_OBJ,      /* .obj */
  SS_MESH_GMSH,     /* .msh, through gmsh's API (ss_mesh_gmsh.c, _write.c) */
  SS_MESH_TETGEN,   /* .node / .ele / .face (read only: ss_mesh_tetgen.c) */
  SS_MESH_VTU       /* .vtu, VTK XML (read with libxml2) */
} ss_mesh_format;

/* Fields: coordinates past the third of a complex (dim > 3) are scalar values
 * per vertex that every scheme refines like the position (ss_cx.h), with
 * names.  Field i is coordinate 3 + i.  Formats that have names carry them:
 * VTK/VTU point data (an array of c components is c fields NAME_x, NAME_y,
 * NAME_z for c = 3, else NAME_0 .. NAME_(c-1)), gmsh views ($NodeData by
 * its name).  Medit has none: its 4th coordinate is "w", the 5th and later
 * "x5", "x6", ... (ss_mesh_fields_default). */
#define SS_FIELD_NAME_MAX 64 /* bytes of a field name with its NUL */
typedef struct {
  int n;                                   /* fields: dim - 3, or 0 for dim <= 3 */
  char name[SS_MAXDIM][SS_FIELD_NAME_MAX]; /* field i's name, NUL-terminated */
} ss_mesh_fields;

/* The names of a complex with dim coordinates as Medit gives them: n =
 * dim - 3 (0 if dim <= 3), "w", "x5", "x6", ... */
void ss_mesh_fields_default(int dim, ss_mesh_fields *f);

typedef struct {
  const ss_mesh_fields *fields; /* the names of the coordinates past the
                                   third (VTK, VTU, gmsh), or NULL (or fewer
                                   than dim - 3): the defaults above */
  int octahedra_keyword;        /* Medit: write octahedra under this project's
                                   "Octahedra" extension keyword; 0 (the default):
                                   as 4 positive tets each, about the octahedron's
                                   0-3 diagonal, in the Tetrahedra section, since
                                   no other Medit reader knows the keyword (meshio
                                   refuses the file, gmsh drops the cells) */
} ss_mesh_write_opts;

/* The formats (ss_mesh_format.c, below the readers and writers).
 * Format implied by a path's extension (case-insensitive); SS_MESH_AUTO if none. */
ss_mesh_format ss_mesh_format_from_path(const char *path);
/* Name of a format ("medit", "vtk", "vtu", "obj", "gmsh", "tetgen"). */
const char *ss_mesh_format_name(ss_mesh_format fmt);
/* The format of that name (as ss_mesh_format_name gives it, case-insensitive;
 * "mesh" is medit too, "msh" gmsh), or SS_MESH_AUTO for any other name. */
ss_mesh_format ss_mesh_format_from_name(const char *name);
/* Whether ss_mesh_read / ss_mesh_write take fmt (.msh only when built with
 * gmsh: ss_mesh_gmsh_available). */
int ss_mesh_format_readable(ss_mesh_format fmt);
int ss_mesh_format_writable(ss_mesh_format fmt);
/* The extensions that can be read / written, in words, for messages
 * ("'.mesh' (Medit), ..."); constant strings. */
const char *ss_mesh_readable_list(void);
const char *ss_mesh_writable_list(void);
/* 1 if this build reads .msh through gmsh (meson option gmsh). */
int ss_mesh_gmsh_available(void);

/* Read a mesh file into a new complex (*out, owned by the caller).  fmt =
 * SS_MESH_AUTO picks by extension.  SS_EIO if the file cannot be opened,
 * SS_EINPUT if it is malformed, SS_ENOMEM. */
ss_status ss_mesh_read(const char *path, ss_mesh_format fmt, ss_cx **out, ss_error *err);
/* ss_mesh_read, and the names of the complex's fields (coordinates past the
 * third) in *names: the file's where it has them, else the defaults. */
ss_status ss_mesh_read_fields(const char *path, ss_mesh_format fmt, ss_cx **out,
                              ss_mesh_fields *names, ss_error *err);
/* Write cx to path; opts may be NULL for defaults.  The file is written whole
 * or not at all (a temporary file renamed over path, ss_outfile.h): on failure
 * an existing path is left as it was.  SS_EIO, SS_EINPUT when the format
 * cannot hold the complex (e.g. OBJ with volume cells) or a coordinate is not
 * finite (then no file is created), SS_ENOMEM. */
ss_status ss_mesh_write(const char *path, ss_mesh_format fmt, const ss_cx *cx,
                        const ss_mesh_write_opts *opts, ss_error *err);

/* gmsh's .msh file at path (ss_mesh_gmsh.c).  The file must begin with a
 * $MeshFormat of version 2 or 4 (checked before gmsh sees it: gmsh would run
 * any other text as a .geo script).  Node k of the file (by increasing tag)
 * is vertex k; cells keep the file's element order within each type; a
 * cell's reference is the first physical group of its entity, else the
 * entity's tag; vertex references are 0.  Coordinates: 2 when the mesh has no
 * 3D element and every z is 0, else 3; every $NodeData view of 1 or 3
 * components (its first step) adds fields (ss_mesh_fields), in gmsh's order
 * of views, named by the view (a vector's NAME_x, _y, _z; ss_mesh_read_gmsh_fields
 * gives the names): one scalar is the 4th coordinate as in a Medit
 * "Dimension 4" (z = 0 in a plane).  Views of element data or tensors are
 * not read; a node without a value or a value that is not finite is
 * SS_EINPUT.  gmsh runs in a
 * child process (fork; gmsh 4.8 crashes on some malformed files: then SS_EINPUT "gmsh
 * crashed"), one read at a time (a mutex: gmsh's API has global state); gmsh prints
 * nothing.  SS_EIO if the
 * file cannot be opened; SS_EINPUT for a malformed file or an element type
 * that has no cell here (prisms, pyramids, higher order), and in a build
 * without gmsh; SS_ENOMEM. */
ss_status ss_mesh_read_gmsh(const char *path, ss_cx **out, ss_error *err);

/* VTK XML unstructured grid (.vtu) at path (ss_mesh_vtu_read.c, through
 * libxml2 and zlib): one Piece; DataArrays ascii, binary (base64) or appended
 * (raw or base64), header_type UInt32/UInt64, either byte order, zlib
 * compressed or not.  Points are vertices; VTK cells vertex, line,
 * triangle, quad, tetra, hexahedron (and the pyramid pairs of cell data
 * kind 6 that ss_mesh_write_vtu makes of an octahedron); cell data "ref" and
 * point data "vref" (integers) the references; every other point-data array
 * fields (ss_mesh_fields: NAME, or NAME_x/_y/_z of 3 components, NAME_0.. of
 * others), coordinates 3 + i; without fields, 2 coordinates when there is no
 * 3D cell and every z is 0.  names may be NULL.  SS_EIO if the file cannot be
 * opened; SS_EINPUT "path: problem" (malformed XML, an unsupported cell type,
 * compressor or dataset, an array of the wrong length, a value that is not
 * finite, more than SS_MAXDIM - 3 field components), also in a build without
 * libxml2 (ss_mesh_vtu_available); SS_ENOMEM. */
ss_status ss_mesh_read_vtu(const char *path, ss_cx **out, ss_mesh_fields *names,
                           ss_error *err);
/* 1 if this build reads .vtu (meson option vtu: libxml2 and zlib). */
int ss_mesh_vtu_available(void);
/* Legacy VTK (.vtk) at path (ss_mesh_vtk_read.c): DATASET UNSTRUCTURED_GRID,
 * ASCII or BINARY (big-endian, as VTK writes it); POINTS, CELLS (version
 * 2-4 counts, or 5.1's OFFSETS and CONNECTIVITY), CELL_TYPES; POINT_DATA
 * and CELL_DATA with SCALARS, VECTORS and FIELD arrays, mapped as in
 * ss_mesh_read_vtu.  Errors as there. */
ss_status ss_mesh_read_vtk(const char *path, ss_cx **out, ss_mesh_fields *names,
                           ss_error *err);
/* ss_mesh_read_gmsh, and the names of the fields (its views) in *names (may
 * be NULL). */
ss_status ss_mesh_read_gmsh_fields(const char *path, ss_cx **out, ss_mesh_fields *names,
                                   ss_error *err);

/* TetGen's X.node with X.ele and X.face when they exist (ss_mesh_tetgen.c);
 * path is any of the three.  .node: "N dim nattr nmarkers" then "i x y z
 * [attributes] [marker]" (the marker becomes the vertex reference; indices
 * start at the first line's, 0 or 1, and run on); .ele: "M 4|3 nattr" then
 * "i a b c d [attribute]" (tetrahedra in 3D, or triangles with dim 2 as
 * Triangle writes them; the first attribute, an integer, is the reference);
 * .face: "F nmarkers" then "i a b c [marker]" as triangles (TetGen's boundary
 * faces, as its own Medit output -g holds them).  '#' starts a comment.
 * SS_EIO if X.node cannot be opened; SS_EINPUT "file:line: problem";
 * SS_ENOMEM. */
ss_status ss_mesh_read_tetgen(const char *path, ss_cx **out, ss_error *err);

/* Stream versions; `name` is used in messages. */
ss_status ss_mesh_read_medit(FILE *f, const char *name, ss_cx **out, ss_error *err);
ss_status ss_mesh_read_obj(FILE *f, const char *name, ss_cx **out, ss_error *err);
ss_status ss_mesh_write_medit(FILE *f, const ss_cx *cx, const ss_mesh_write_opts *opts,
                              ss_error *err);
ss_status ss_mesh_write_vtk(FILE *f, const ss_cx *cx, const ss_mesh_write_opts *opts,
                            ss_error *err);
ss_status ss_mesh_write_vtu(FILE *f, const ss_cx *cx, const ss_mesh_write_opts *opts,
                            ss_error *err);
ss_status ss_mesh_write_obj(FILE *f, const ss_cx *cx, ss_error *err);
/* gmsh .msh 4.1 ASCII through gmsh's API (ss_mesh_gmsh_write.c: the layout,
 * references and fields as views); path names the file in messages.
 * SS_EINPUT for octahedra (gmsh has none) and in a build without gmsh,
 * SS_EIO, SS_ENOMEM. */
ss_status ss_mesh_write_gmsh(FILE *f, const char *path, const ss_cx *cx,
                             const ss_mesh_write_opts *opts, ss_error *err);

SS_END_DECLS

#endif
