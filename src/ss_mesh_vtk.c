/* ss_mesh_vtk.c — legacy VTK (ASCII UNSTRUCTURED_GRID) writer for ParaView.
 *
 * Points are padded to 3 coordinates; a 4th coordinate travels as the point
 * scalar "w".  VTK has no octahedron, so each is written as two pyramids on its
 * equator 1 2 4 5 (apexes 0 and 3), both with the base normal towards the apex
 * as VTK requires.  Cell data: "ref" (the Medit reference) and "kind" (the
 * ss_cell_type of the cell a VTK cell came from, so split octahedra can be
 * told from pyramids). */
#include "ss_mesh.h"

/* VTK cell type numbers (vtkCellType.h) by ss_cell_type. */
static const int vtk_type[SS_NCELLTYPES] = {1, 3, 5, 9, 10, 12, 14};
static const int oct_pyramids[2][5] = {{1, 2, 4, 5, 0}, {1, 5, 4, 2, 3}};

ss_status ss_mesh_write_vtk(FILE *f, const ss_cx *cx, ss_error *err) {
  size_t ncells = 0, nints = 0;
  for (int t = 0; t < SS_NCELLTYPES; t++) {
    size_t pieces = t == SS_OCT ? 2 : 1;
    int nv = t == SS_OCT ? 5 : ss_cell_nverts((ss_cell_type)t);
    ncells += pieces * cx->nc[t];
    nints += pieces * cx->nc[t] * (size_t)(nv + 1);
  }
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
    if (cx->dim == 4) {
      fprintf(f, "SCALARS w double 1\nLOOKUP_TABLE default\n");
      for (size_t i = 0; i < cx->nv; i++)
        fprintf(f, "%.17g\n", cx->x[i * 4 + 3]);
    }
  }
  if (ferror(f)) return ss_error_set(err, SS_EIO, "write error");
  return SS_OK;
}
