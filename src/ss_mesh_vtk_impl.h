/* ss_mesh_vtk_impl.h — private to the VTK readers (ss_mesh_vtu_read.c for
 * VTK XML, ss_mesh_vtk_read.c for legacy VTK): an unstructured grid as the
 * files hold it, and its conversion to a complex (ss_mesh_vtk_build.c), so
 * that both formats map cells, references and point data alike. */
#ifndef SS_MESH_VTK_IMPL_H
#define SS_MESH_VTK_IMPL_H

#include <stdint.h>

#include "ss_mesh.h"

/* The longest name of a data array (a field's name adds a component suffix). */
#define SS_VTK_NAME_MAX 48

/* One point-data or cell-data array, its values as doubles. */
typedef struct {
  char name[SS_FIELD_NAME_MAX]; /* the array's name */
  int ncomp;                    /* components per tuple, >= 1 */
  int integer;                  /* 1 if the file stores integers */
  double *val;                  /* tuples * ncomp values (owned) */
} ss_vtk_array;

/* The grid: points, cells in VTK's numbering, and their data. */
typedef struct {
  size_t np;           /* points */
  double *pts;         /* np * 3 coordinates (owned) */
  size_t nc;           /* cells */
  int64_t *offsets;    /* nc ends of each cell's vertex list in conn (owned) */
  int64_t *conn;       /* offsets[nc-1] point indices (owned) */
  int *types;          /* nc VTK cell types (owned) */
  ss_vtk_array *pdata; /* npd point-data arrays (owned) */
  size_t npd;          /* how many */
  ss_vtk_array *cdata; /* ncd cell-data arrays (owned) */
  size_t ncd;          /* how many */
} ss_vtk_grid;

/* The whole file at path in a new buffer *buf (NUL-terminated after its
 * *len bytes).  SS_EIO, SS_ENOMEM. */
ss_status ss_vtk_slurp(const char *path, char **buf, size_t *len, ss_error *err);

/* Free g's arrays (not g). */
void ss_vtk_grid_done(ss_vtk_grid *g);

/* Append an empty array named name of ncomp components to *list (*n of them)
 * and return it through *a.  SS_EINPUT for a name too long for a field
 * (message names path), SS_ENOMEM. */
ss_status ss_vtk_array_add(const char *path, ss_vtk_array **list, size_t *n,
                           const char *name, int ncomp, ss_vtk_array **a, ss_error *err);

/* The complex of the grid: vertex i is point i; cells by type in the file's
 * order (VTK types 1, 3, 5, 9, 10, 12; two pyramids (14) whose cell data
 * "kind" is 6 are the octahedron ss_mesh_write_vtk split); cell data "ref"
 * (integers) the cell references, point data "vref" the vertex references;
 * every other point-data array a field (ss_mesh.h: coordinates 3 + i, named
 * in *names).  2 coordinates when there is no field, no 3D cell and every
 * z is 0, else 3 + fields.  SS_EINPUT naming path and the problem (a cell
 * type that has no cell here, a point index out of range, a value that is
 * not finite, more than SS_MAXDIM - 3 field components); SS_ENOMEM. */
ss_status ss_vtk_build(const char *path, const ss_vtk_grid *g, ss_cx **out,
                       ss_mesh_fields *names, ss_error *err);

#endif
