/* ss_mesh.h — reading and writing meshes: Medit .mesh, legacy VTK, Wavefront OBJ.
 *
 * Medit (.mesh, ASCII "MeshVersionFormatted"): sections Vertices, Edges,
 * Triangles, Quadrilaterals, Tetrahedra, Hexahedra and Corners (vertex cells),
 * plus the extension keyword "Octahedra" (6 indices + reference, vertex order of
 * ss_cx.h).  "Dimension" may be 1..4 (Medit itself knows 2 and 3).  Known
 * sections that carry no cells (Ridges, RequiredVertices, Normals, ...) are
 * skipped; an unknown keyword where one is expected is an error.
 * Legacy VTK (.vtk): written only, UNSTRUCTURED_GRID for ParaView; octahedra
 * are written as two pyramids sharing their equator.
 * OBJ (.obj): surfaces only — v, f (triangles and quadrilaterals), l (segments),
 * p (vertex cells); vt/vn/vp/o/g/s/usemtl/mtllib are ignored.
 *
 * Every malformed file is SS_EINPUT with "file:line: problem" in err. */
#ifndef SS_MESH_H
#define SS_MESH_H

#include <stdio.h>

#include "ss_cx.h"

typedef enum {
  SS_MESH_AUTO = 0, /* choose by file name extension */
  SS_MESH_MEDIT,    /* .mesh */
  SS_MESH_VTK,      /* .vtk (write only) */
  SS_MESH_OBJ       /* .obj */
} ss_mesh_format;

typedef struct {
  int split_octahedra; /* Medit: write each octahedron as 4 tets about its 0-3
                          diagonal, for tools without the Octahedra keyword */
} ss_mesh_write_opts;

/* Format implied by a path's extension (case-insensitive); SS_MESH_AUTO if none. */
ss_mesh_format ss_mesh_format_from_path(const char *path);
/* Name of a format ("medit", "vtk", "obj"). */
const char *ss_mesh_format_name(ss_mesh_format fmt);

/* Read a mesh file into a new complex (*out, owned by the caller).  fmt =
 * SS_MESH_AUTO picks by extension.  SS_EIO if the file cannot be opened,
 * SS_EINPUT if it is malformed, SS_ENOMEM. */
ss_status ss_mesh_read(const char *path, ss_mesh_format fmt, ss_cx **out, ss_error *err);
/* Write cx to path; opts may be NULL for defaults.  The file is written whole
 * or not at all (a temporary file renamed over path, ss_outfile.h): on failure
 * an existing path is left as it was.  SS_EIO, SS_EINPUT when the format
 * cannot hold the complex (e.g. OBJ with volume cells) or a coordinate is not
 * finite (then no file is created), SS_ENOMEM. */
ss_status ss_mesh_write(const char *path, ss_mesh_format fmt, const ss_cx *cx,
                        const ss_mesh_write_opts *opts, ss_error *err);

/* Stream versions; `name` is used in messages. */
ss_status ss_mesh_read_medit(FILE *f, const char *name, ss_cx **out, ss_error *err);
ss_status ss_mesh_read_obj(FILE *f, const char *name, ss_cx **out, ss_error *err);
ss_status ss_mesh_write_medit(FILE *f, const ss_cx *cx, const ss_mesh_write_opts *opts,
                              ss_error *err);
ss_status ss_mesh_write_vtk(FILE *f, const ss_cx *cx, ss_error *err);
ss_status ss_mesh_write_obj(FILE *f, const ss_cx *cx, ss_error *err);

#endif
