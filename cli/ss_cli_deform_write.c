/* ss_cli_deform_write.c — `subspectra deform`'s output: text, JSON, legacy
 * VTK, VTU and a PNG picture (ss_cli_deform.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <json-c/json.h>

#include "ss_cli.h"
#include "ss_cli_deform.h"

const char *ss_cli_deform_status_name(int status) {
  static const char *const names[] = {"ok", "outside", "failed"};
  return status >= 0 && status <= 2 ? names[status] : "?";
}

static const char *type_name(ss_cell_type t) {
  return t == SS_HEX ? "hex" : t == SS_TET ? "tet" : "oct";
}

/* A number, or null when it is not finite. */
static json_object *jnum(double x) {
  return isfinite(x) ? json_object_new_double(x) : NULL;
}

static json_object *jvec(const double x[3]) {
  json_object *a = json_object_new_array();
  for (int i = 0; i < 3; i++)
    json_object_array_add(a, jnum(x[i]));
  return a;
}

static void write_json(FILE *f, const ss_deform_cli_out *o) {
  for (size_t i = 0; i < o->n; i++) {
    const ss_deform_cli_point *p = &o->pt[i];
    json_object *j = json_object_new_object();
    json_object_object_add(j, "index", json_object_new_int64((int64_t)i + 1));
    json_object_object_add(j, "status",
                           json_object_new_string(ss_cli_deform_status_name(p->status)));
    json_object_object_add(j, "input", jvec(p->x));
    if (p->status != SS_DEFORM_CLI_OUTSIDE) {
      json_object *c = json_object_new_object();
      json_object_object_add(c, "type", json_object_new_string(type_name(p->loc.type)));
      json_object_object_add(c, "index", json_object_new_int64((int64_t)p->loc.cell + 1));
      json_object_object_add(j, "cell", c);
      json_object_object_add(j, "params", jvec(p->loc.r));
    }
    json_object_object_add(j, "base", jvec(p->base));
    json_object_object_add(j, "point", jvec(p->p));
    if (!o->exact) {
      json_object_object_add(j, "error_estimate", jnum(p->est));
      json_object_object_add(j, "rate", jnum(p->rate));
    }
    if (p->label >= 0) json_object_object_add(j, "label", json_object_new_int(p->label));
    if (p->line >= 0)
      json_object_object_add(j, "line", json_object_new_int64(p->line + 1));
    fprintf(f, "%s\n", json_object_to_json_string_ext(j, SS_CLI_JSON_FLAGS));
    json_object_put(j);
  }
}

static void write_plain(FILE *f, const ss_deform_cli_out *o) {
  fprintf(f,
          "# %s limit (%s%s): x y z status cell_type cell u v w base_x base_y base_z "
          "px py pz%s%s\n",
          o->scheme, o->exact ? "exact" : "levels", o->exact ? "" : " of subdivision",
          o->exact ? "" : " error_estimate rate",
          o->n && o->pt[0].label >= 0  ? " label"
          : o->n && o->pt[0].line >= 0 ? " line"
                                       : "");
  for (size_t i = 0; i < o->n; i++) {
    const ss_deform_cli_point *p = &o->pt[i];
    const int in = p->status != SS_DEFORM_CLI_OUTSIDE;
    fprintf(f, "%.17g %.17g %.17g %s %s %zu", p->x[0], p->x[1], p->x[2],
            ss_cli_deform_status_name(p->status), in ? type_name(p->loc.type) : "-",
            in ? p->loc.cell + 1 : 0);
    for (int a = 0; a < 3; a++)
      fprintf(f, " %.17g", in ? p->loc.r[a] : (double)NAN);
    for (int a = 0; a < 3; a++)
      fprintf(f, " %.17g", p->base[a]);
    for (int a = 0; a < 3; a++)
      fprintf(f, " %.17g", p->p[a]);
    if (!o->exact) fprintf(f, " %.3g %.3g", p->est, p->rate);
    if (p->label >= 0) fprintf(f, " %d", p->label);
    if (p->line >= 0) fprintf(f, " %ld", p->line + 1);
    fputc('\n', f);
  }
}

/* The evaluated points' new numbers (-1 for the others) and how many. */
static size_t renumber(const ss_deform_cli_out *o, long *id) {
  size_t m = 0;
  for (size_t i = 0; i < o->n; i++)
    id[i] = o->pt[i].status == SS_DEFORM_CLI_OK ? (long)m++ : -1;
  return m;
}

/* What runs() writes for each run. */
enum { RUNS_COUNT, RUNS_VTK, RUNS_VTU_IDS, RUNS_VTU_OFFSETS };

/* The runs of consecutive evaluated points on one grid line (at least 2
 * points each), written to f in one of the forms above (nothing with
 * RUNS_COUNT): VTK "n id...", VTU connectivity, VTU cumulative offsets.
 * Returns the number of runs; adds their lengths to *len. */
static size_t runs(const ss_deform_cli_out *o, const long *id, FILE *f, int mode,
                   size_t *len) {
  size_t nr = 0, off = 0;
  for (size_t a = 0; a < o->n;) {
    size_t b = a;
    if (id[a] < 0 || o->pt[a].line < 0) {
      a++;
      continue;
    }
    while (b < o->n && id[b] >= 0 && o->pt[b].line == o->pt[a].line)
      b++;
    if (b - a >= 2) {
      nr++;
      *len += b - a;
      off += b - a;
      if (mode == RUNS_VTK) fprintf(f, "%zu", b - a);
      for (size_t i = a; (mode == RUNS_VTK || mode == RUNS_VTU_IDS) && i < b; i++)
        fprintf(f, " %ld", id[i]);
      if (mode == RUNS_VTU_OFFSETS) fprintf(f, "%zu", off);
      if (mode != RUNS_COUNT) fputc('\n', f);
    }
    a = b;
  }
  return nr;
}

static void write_vtk(FILE *f, const ss_deform_cli_out *o, long *id) {
  const size_t m = renumber(o, id);
  fprintf(f,
          "# vtk DataFile Version 3.0\nsubspectra deform (%s, %s)\nASCII\nDATASET "
          "POLYDATA\nPOINTS %zu double\n",
          o->scheme, o->exact ? "exact limit" : "levels", m);
  for (size_t i = 0; i < o->n; i++)
    if (id[i] >= 0)
      fprintf(f, "%.17g %.17g %.17g\n", o->pt[i].p[0], o->pt[i].p[1], o->pt[i].p[2]);
  size_t len = 0;
  const size_t nr = runs(o, id, NULL, RUNS_COUNT, &len);
  if (nr) {
    fprintf(f, "LINES %zu %zu\n", nr, nr + len);
    len = 0;
    runs(o, id, f, RUNS_VTK, &len);
  } else {
    fprintf(f, "VERTICES %zu %zu\n", m, 2 * m);
    for (size_t i = 0; i < m; i++)
      fprintf(f, "1 %zu\n", i);
  }
  fprintf(f, "POINT_DATA %zu\n", m);
  if (m && o->pt[0].label >= 0) {
    fprintf(f, "SCALARS label int 1\nLOOKUP_TABLE default\n");
    for (size_t i = 0; i < o->n; i++)
      if (id[i] >= 0) fprintf(f, "%d\n", o->pt[i].label);
  }
  if (!o->exact) {
    fprintf(f, "SCALARS error_estimate double 1\nLOOKUP_TABLE default\n");
    for (size_t i = 0; i < o->n; i++)
      if (id[i] >= 0) fprintf(f, "%.6g\n", o->pt[i].est);
  }
  fprintf(f, "VECTORS base double\n");
  for (size_t i = 0; i < o->n; i++)
    if (id[i] >= 0)
      fprintf(f, "%.17g %.17g %.17g\n", o->pt[i].base[0], o->pt[i].base[1],
              o->pt[i].base[2]);
}

static void write_vtu(FILE *f, const ss_deform_cli_out *o, long *id) {
  const size_t m = renumber(o, id);
  size_t len = 0;
  const size_t nr = runs(o, id, NULL, RUNS_COUNT, &len), nc = nr ? nr : m;
  fprintf(
      f,
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" "
      "byte_order=\"LittleEndian\">\n<UnstructuredGrid>\n<Piece NumberOfPoints=\"%zu\" "
      "NumberOfCells=\"%zu\">\n<Points>\n<DataArray type=\"Float64\" "
      "NumberOfComponents=\"3\" format=\"ascii\">\n",
      m, nc);
  for (size_t i = 0; i < o->n; i++)
    if (id[i] >= 0)
      fprintf(f, "%.17g %.17g %.17g\n", o->pt[i].p[0], o->pt[i].p[1], o->pt[i].p[2]);
  fprintf(f, "</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int64\" "
             "Name=\"connectivity\" format=\"ascii\">\n");
  if (nr) {
    len = 0;
    runs(o, id, f, RUNS_VTU_IDS, &len);
  } else
    for (size_t i = 0; i < m; i++)
      fprintf(f, "%zu\n", i);
  fprintf(f,
          "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n");
  if (nr)
    runs(o, id, f, RUNS_VTU_OFFSETS, &len);
  else
    for (size_t i = 0; i < m; i++)
      fprintf(f, "%zu\n", i + 1);
  fprintf(f,
          "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n");
  for (size_t i = 0; i < nc; i++)
    fprintf(f, "%d\n", nr ? 4 : 1); /* VTK_POLY_LINE, VTK_VERTEX */
  fprintf(f, "</DataArray>\n</Cells>\n<PointData>\n");
  if (m && o->pt[0].label >= 0) {
    fprintf(f, "<DataArray type=\"Int32\" Name=\"label\" format=\"ascii\">\n");
    for (size_t i = 0; i < o->n; i++)
      if (id[i] >= 0) fprintf(f, "%d\n", o->pt[i].label);
    fprintf(f, "</DataArray>\n");
  }
  if (!o->exact) {
    fprintf(f, "<DataArray type=\"Float64\" Name=\"error_estimate\" format=\"ascii\">\n");
    for (size_t i = 0; i < o->n; i++)
      if (id[i] >= 0) fprintf(f, "%.6g\n", o->pt[i].est);
    fprintf(f, "</DataArray>\n");
  }
  fprintf(f, "<DataArray type=\"Float64\" Name=\"base\" NumberOfComponents=\"3\" "
             "format=\"ascii\">\n");
  for (size_t i = 0; i < o->n; i++)
    if (id[i] >= 0)
      fprintf(f, "%.17g %.17g %.17g\n", o->pt[i].base[0], o->pt[i].base[1],
              o->pt[i].base[2]);
  fprintf(f, "</DataArray>\n</PointData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n");
}

ss_status ss_cli_deform_write_text(FILE *f, const ss_deform_cli_out *o, int format,
                                   ss_error *err) {
  if (format == SS_DEFORM_FMT_JSON) {
    write_json(f, o);
    return SS_OK;
  }
  if (format == SS_DEFORM_FMT_TEXT) {
    write_plain(f, o);
    return SS_OK;
  }
  long *id = malloc((o->n + 1) * sizeof *id);
  if (!id) return ss_error_nomem(err, "point numbers");
  if (format == SS_DEFORM_FMT_VTK)
    write_vtk(f, o, id);
  else
    write_vtu(f, o, id);
  free(id);
  return SS_OK;
}
