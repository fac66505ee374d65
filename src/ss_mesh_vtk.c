/* ss_mesh_vtk.c — VTK writers for ParaView: legacy VTK (ASCII
 * UNSTRUCTURED_GRID) and VTK XML (.vtu: binary, appended raw, UInt64 headers).
 *
 * Points are padded to 3 coordinates; each coordinate past the third (a
 * field, ss_mesh.h) travels as a point scalar of its name (opts->fields, else
 * "w", "x5", ...).  VTK has no octahedron, so each is written as two pyramids on its
 * equator 1 2 4 5 (apexes 0 and 3), both with the base normal towards the apex
 * as VTK requires.  Cell data: "ref" (the Medit reference) and "kind" (the
 * ss_cell_type of the cell a VTK cell came from, so split octahedra can be
 * told from pyramids).  Both formats hold the same points, cells and data;
 * the VTU's reference arrays are Int32 like the complex's.  Octahedra are split
 * in VTU too rather than written as VTK_POLYHEDRON (42): a polyhedron needs
 * its faces spelled out, and meshio (5.x) refuses a grid that mixes polyhedra
 * with other cells, which every tet-oct mesh does. */
#include <inttypes.h>
#include <stdint.h>

#include <string.h>

#include "ss_mesh.h"

/* VTK cell type numbers (vtkCellType.h) by ss_cell_type. */
static const int vtk_type[SS_NCELLTYPES] = {1, 3, 5, 9, 10, 12, 14};
static const int oct_pyramids[2][5] = {{1, 2, 4, 5, 0}, {1, 5, 4, 2, 3}};

/* The names of cx's fields: opts's when it names them all, else the defaults
 * (in *tmp). */
static const ss_mesh_fields *names_of(const ss_cx *cx, const ss_mesh_write_opts *opts,
                                      ss_mesh_fields *tmp) {
  if (opts && opts->fields && opts->fields->n >= cx->dim - 3) return opts->fields;
  ss_mesh_fields_default(cx->dim, tmp);
  return tmp;
}

/* VTK cells per cell of type t: an octahedron is two pyramids. */
static size_t pieces(int t) {
  return t == SS_OCT ? 2 : 1;
}

/* The number of VTK cells of cx; *nints: of integers in the legacy CELLS
 * list (each cell's vertex count and its vertices). */
static size_t vtk_count(const ss_cx *cx, size_t *nints) {
  size_t ncells = 0;
  *nints = 0;
  for (int t = 0; t < SS_NCELLTYPES; t++) {
    int nv = t == SS_OCT ? 5 : ss_cell_nverts((ss_cell_type)t);
    ncells += pieces(t) * cx->nc[t];
    *nints += pieces(t) * cx->nc[t] * (size_t)(nv + 1);
  }
  return ncells;
}

ss_status ss_mesh_write_vtk(FILE *f, const ss_cx *cx, const ss_mesh_write_opts *opts,
                            ss_error *err) {
  ss_mesh_fields tmp;
  const ss_mesh_fields *names = names_of(cx, opts, &tmp);
  size_t nints;
  const size_t ncells = vtk_count(cx, &nints);
  fprintf(
      f,
      "# vtk DataFile Version 3.0\nsubspectra mesh\nASCII\nDATASET UNSTRUCTURED_GRID\n");
  fprintf(f, "POINTS %zu double\n", cx->nv);
  for (size_t i = 0; i < cx->nv; i++) {
    double x[3] = {0, 0, 0};
    for (int k = 0; k < cx->dim && k < 3; k++)
      x[k] = cx->x[i * (size_t)cx->dim + k];
    fprintf(f, "%.17g %.17g %.17g\n", x[0], x[1], x[2]);
  }
  fprintf(f, "CELLS %zu %zu\n", ncells, nints);
  for (int t = 0; t < SS_NCELLTYPES; t++)
    for (size_t i = 0; i < cx->nc[t]; i++) {
      const ss_idx *v = ss_cx_cell(cx, (ss_cell_type)t, i);
      if (t == SS_OCT) {
        for (int p = 0; p < 2; p++) {
          fputc('5', f);
          for (int j = 0; j < 5; j++)
            fprintf(f, " %lu", (unsigned long)v[oct_pyramids[p][j]]);
          fputc('\n', f);
        }
        continue;
      }
      int nv = ss_cell_nverts((ss_cell_type)t);
      fprintf(f, "%d", nv);
      for (int j = 0; j < nv; j++)
        fprintf(f, " %lu", (unsigned long)v[j]);
      fputc('\n', f);
    }
  fprintf(f, "CELL_TYPES %zu\n", ncells);
  for (int t = 0; t < SS_NCELLTYPES; t++)
    for (size_t i = 0; i < cx->nc[t] * (t == SS_OCT ? 2u : 1u); i++)
      fprintf(f, "%d\n", vtk_type[t]);
  if (ncells) {
    fprintf(f, "CELL_DATA %zu\nSCALARS ref int 1\nLOOKUP_TABLE default\n", ncells);
    for (int t = 0; t < SS_NCELLTYPES; t++)
      for (size_t i = 0; i < cx->nc[t] * (t == SS_OCT ? 2u : 1u); i++)
        fprintf(f, "%ld\n", (long)cx->cref[t][t == SS_OCT ? i / 2 : i]);
    fprintf(f, "SCALARS kind int 1\nLOOKUP_TABLE default\n");
    for (int t = 0; t < SS_NCELLTYPES; t++)
      for (size_t i = 0; i < cx->nc[t] * (t == SS_OCT ? 2u : 1u); i++)
        fprintf(f, "%d\n", t);
  }
  if (cx->nv) {
    fprintf(f, "POINT_DATA %zu\nSCALARS vref int 1\nLOOKUP_TABLE default\n", cx->nv);
    for (size_t i = 0; i < cx->nv; i++)
      fprintf(f, "%ld\n", (long)cx->vref[i]);
    const size_t dim = (size_t)cx->dim;
    for (size_t k = 3; k < dim; k++) {
      fprintf(f, "SCALARS %s double 1\nLOOKUP_TABLE default\n", names->name[k - 3]);
      for (size_t i = 0; i < cx->nv; i++)
        fprintf(f, "%.17g\n", cx->x[i * dim + k]);
    }
  }
  if (ferror(f)) return ss_error_set(err, SS_EIO, "write error");
  return SS_OK;
}

/* ---- VTK XML (.vtu): the same cells and data, binary, appended raw ---- */

/* One array of the appended block: its element type and count. */
typedef struct {
  const char *type; /* VTK type name: "Float64", "Int64", "Int32", "UInt8" */
  size_t size;      /* bytes per element */
  size_t n;         /* elements (tuples times components) */
} vtu_array;

/* The arrays in the order they are declared and appended. */
enum { A_POINTS, A_CONN, A_OFFSETS, A_TYPES, A_REF, A_KIND, A_VREF, A_W, A_COUNT };
/* A_W stands for every field in turn (one array each, coordinate 3 + i). */

static void vtu_da(FILE *f, const vtu_array *a, int k, const char *name, int comps,
                   uint64_t *offset) {
  fprintf(f, "        <DataArray type=\"%s\"", a[k].type);
  if (name) fprintf(f, " Name=\"%s\"", name);
  if (comps > 1) fprintf(f, " NumberOfComponents=\"%d\"", comps);
  fprintf(f, " format=\"appended\" offset=\"%" PRIu64 "\"/>\n", *offset);
  *offset += 8 + (uint64_t)(a[k].n * a[k].size);
}

/* The byte count that opens an appended array (header_type UInt64). */
static void vtu_head(FILE *f, const vtu_array *a) {
  const uint64_t bytes = (uint64_t)(a->n * a->size);
  fwrite(&bytes, sizeof bytes, 1, f);
}

static void put64(FILE *f, int64_t v) {
  fwrite(&v, sizeof v, 1, f);
}

/* The appended arrays' contents, in the order of the enum above. */
static void vtu_data(FILE *f, const ss_cx *cx, const vtu_array *a) {
  vtu_head(f, &a[A_POINTS]);
  for (size_t i = 0; i < cx->nv; i++) {
    double x[3] = {0, 0, 0};
    for (int k = 0; k < cx->dim && k < 3; k++)
      x[k] = cx->x[i * (size_t)cx->dim + k];
    fwrite(x, sizeof x[0], 3, f);
  }
  vtu_head(f, &a[A_CONN]);
  for (int t = 0; t < SS_NCELLTYPES; t++)
    for (size_t i = 0; i < cx->nc[t]; i++) {
      const ss_idx *v = ss_cx_cell(cx, (ss_cell_type)t, i);
      if (t == SS_OCT)
        for (int j = 0; j < 10; j++)
          put64(f, v[oct_pyramids[j / 5][j % 5]]);
      else
        for (int j = 0; j < ss_cell_nverts((ss_cell_type)t); j++)
          put64(f, v[j]);
    }
  vtu_head(f, &a[A_OFFSETS]);
  int64_t end = 0;
  for (int t = 0; t < SS_NCELLTYPES; t++)
    for (size_t i = 0; i < cx->nc[t] * pieces(t); i++)
      put64(f, end += t == SS_OCT ? 5 : ss_cell_nverts((ss_cell_type)t));
  vtu_head(f, &a[A_TYPES]);
  for (int t = 0; t < SS_NCELLTYPES; t++)
    for (size_t i = 0; i < cx->nc[t] * pieces(t); i++)
      fputc(vtk_type[t], f);
  vtu_head(f, &a[A_REF]);
  for (int t = 0; t < SS_NCELLTYPES; t++)
    for (size_t i = 0; i < cx->nc[t] * pieces(t); i++) {
      const int32_t r = cx->cref[t][i / pieces(t)];
      fwrite(&r, sizeof r, 1, f);
    }
  vtu_head(f, &a[A_KIND]);
  for (int t = 0; t < SS_NCELLTYPES; t++)
    for (size_t i = 0; i < cx->nc[t] * pieces(t); i++) {
      const int32_t k = t;
      fwrite(&k, sizeof k, 1, f);
    }
  vtu_head(f, &a[A_VREF]);
  fwrite(cx->vref, sizeof *cx->vref, cx->nv, f);
  const size_t dim = (size_t)cx->dim;
  for (size_t k = 3; k < dim; k++) {
    vtu_head(f, &a[A_W]);
    for (size_t i = 0; i < cx->nv; i++)
      fwrite(&cx->x[i * dim + k], sizeof(double), 1, f);
  }
}

ss_status ss_mesh_write_vtu(FILE *f, const ss_cx *cx, const ss_mesh_write_opts *opts,
                            ss_error *err) {
  ss_mesh_fields tmp;
  const ss_mesh_fields *names = names_of(cx, opts, &tmp);
  size_t nints;
  const size_t ncells = vtk_count(cx, &nints);
  const vtu_array a[A_COUNT] = {
      [A_POINTS] = {"Float64", 8, 3 * cx->nv}, [A_CONN] = {"Int64", 8, nints - ncells},
      [A_OFFSETS] = {"Int64", 8, ncells},      [A_TYPES] = {"UInt8", 1, ncells},
      [A_REF] = {"Int32", 4, ncells},          [A_KIND] = {"Int32", 4, ncells},
      [A_VREF] = {"Int32", 4, cx->nv},         [A_W] = {"Float64", 8, cx->nv}};
  const uint16_t one = 1;
  const int little = *(const unsigned char *)&one == 1;
  uint64_t off = 0;
  fprintf(f,
          "<?xml version=\"1.0\"?>\n"
          "<!-- subspectra mesh; cell data kind: the ss_cell_type a cell came from "
          "(6: one of the two pyramids of an octahedron) -->\n"
          "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"%s\" "
          "header_type=\"UInt64\">\n"
          "  <UnstructuredGrid>\n"
          "    <Piece NumberOfPoints=\"%zu\" NumberOfCells=\"%zu\">\n"
          "      <Points>\n",
          little ? "LittleEndian" : "BigEndian", cx->nv, ncells);
  vtu_da(f, a, A_POINTS, NULL, 3, &off);
  fprintf(f, "      </Points>\n      <Cells>\n");
  vtu_da(f, a, A_CONN, "connectivity", 1, &off);
  vtu_da(f, a, A_OFFSETS, "offsets", 1, &off);
  vtu_da(f, a, A_TYPES, "types", 1, &off);
  fprintf(f, "      </Cells>\n      <CellData Scalars=\"ref\">\n");
  vtu_da(f, a, A_REF, "ref", 1, &off);
  vtu_da(f, a, A_KIND, "kind", 1, &off);
  fprintf(f, "      </CellData>\n      <PointData Scalars=\"vref\">\n");
  vtu_da(f, a, A_VREF, "vref", 1, &off);
  for (int k = 3; k < cx->dim; k++)
    vtu_da(f, a, A_W, names->name[k - 3], 1, &off);
  fprintf(f, "      </PointData>\n    </Piece>\n  </UnstructuredGrid>\n"
             "  <AppendedData encoding=\"raw\">\n   _");
  vtu_data(f, cx, a);
  fprintf(f, "\n  </AppendedData>\n</VTKFile>\n");
  if (ferror(f)) return ss_error_set(err, SS_EIO, "write error");
  return SS_OK;
}
