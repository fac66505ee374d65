/* ss_cli_limit_write.c — `subspectra limit`'s writers: text, JSON lines,
 * legacy VTK and VTU, every point with its status (ss_cli_limit.h). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <json-c/json.h>

#include "ss_cli.h"
#include "ss_cli_limit.h"

const char *ss_cli_limit_status_name(int status) {
  static const char *const name[SS_LIMIT_CLI_NSTATUS] = {"ok", "no_derivatives", "failed",
                                                         "refused"};
  return status >= 0 && status < SS_LIMIT_CLI_NSTATUS ? name[status] : "?";
}

/* x as %.17g, a NaN as "nan" (never "-nan"), after the separator sep. */
static void num(FILE *f, const char *sep, double x) {
  if (isnan(x))
    fprintf(f, "%snan", sep);
  else
    fprintf(f, "%s%.17g", sep, x);
}

/* det of the 3x3 matrix J. */
static double det3(const double (*J)[3]) {
  return J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) -
         J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) +
         J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
}

void ss_cli_limit_write_text(FILE *f, const ss_limit_cli_out *o) {
  const ss_limit_cli_fields *fl = o->fl;
  for (size_t i = 0; i < o->n; i++) {
    const ss_limit_cli_point *p = o->pts + i;
    fprintf(f, "%zu", p->cell + 1);
    for (int a = 0; a < 3; a++)
      num(f, " ", p->x[a]);
    for (int d = 0; d < 3; d++)
      num(f, " ", p->r.p[d]);
    if (o->derivs)
      for (int a = 0; a < 3; a++)
        for (int d = 0; d < 3; d++)
          num(f, " ", p->r.jac[a][d]);
    for (size_t k = 0; k < fl->nf; k++)
      num(f, " ", p->f[k]);
    for (size_t k = 0; k < fl->nf && o->derivs; k++)
      for (int a = 0; a < 3; a++)
        num(f, " ", p->df[k][a]);
    if (o->with_status) fprintf(f, " %s", ss_cli_limit_status_name(p->status));
    fputc('\n', f);
  }
}

/* A JSON number, or NULL (written null) for NaN and infinities. */
static json_object *jnum(double x) {
  return isfinite(x) ? json_object_new_double(x) : NULL;
}

/* JSON "fields": {NAME: value} and with derivs "field_gradients": {NAME:
 * [3]} of point p into o; null for a value or gradient it does not have. */
static void json_fields(json_object *o, const ss_limit_cli_point *p, int derivs,
                        const ss_limit_cli_fields *fl) {
  if (!fl->nf) return;
  const int val = p->status <= SS_LIMIT_CLI_NO_DERIVATIVES,
            grad = p->status == SS_LIMIT_CLI_OK;
  json_object *v = json_object_new_object(),
              *g = derivs ? json_object_new_object() : NULL;
  for (size_t k = 0; k < fl->nf; k++) {
    json_object_object_add(v, fl->name[k], val ? jnum(p->f[k]) : NULL);
    if (!g) continue;
    json_object *row = grad ? json_object_new_array() : NULL;
    for (int a = 0; a < 3 && row; a++)
      json_object_array_add(row, jnum(p->df[k][a]));
    json_object_object_add(g, fl->name[k], row);
  }
  json_object_object_add(o, "fields", v);
  if (g) json_object_object_add(o, "field_gradients", g);
}

/* The JSON object of point p (point and Jacobian null where it has none). */
static json_object *json_point(const ss_limit_cli_point *p, const ss_limit_cli_out *out) {
  json_object *o = json_object_new_object();
  json_object_object_add(o, "cell", json_object_new_int64((int64_t)p->cell + 1));
  static const char *const key[3] = {"u", "v", "w"};
  for (int a = 0; a < 3; a++)
    json_object_object_add(o, key[a], jnum(p->x[a]));
  if (p->weight > 0)
    json_object_object_add(o, "weight", json_object_new_double(p->weight));
  json_object *pt = NULL;
  if (p->status <= SS_LIMIT_CLI_NO_DERIVATIVES) {
    pt = json_object_new_array();
    for (int d = 0; d < 3; d++)
      json_object_array_add(pt, jnum(p->r.p[d]));
  }
  json_object_object_add(o, "point", pt);
  if (out->derivs) {
    json_object *J = p->status == SS_LIMIT_CLI_OK ? json_object_new_array() : NULL;
    for (int a = 0; a < 3 && J; a++) {
      json_object *row = json_object_new_array();
      for (int d = 0; d < 3; d++)
        json_object_array_add(row, jnum(p->r.jac[a][d]));
      json_object_array_add(J, row);
    }
    json_object_object_add(o, "jacobian", J);
  }
  json_fields(o, p, out->derivs, out->fl);
  if (out->with_status) {
    json_object_object_add(o, "status",
                           json_object_new_string(ss_cli_limit_status_name(p->status)));
    if (p->status != SS_LIMIT_CLI_OK)
      json_object_object_add(o, "reason", json_object_new_string(p->why ? p->why : ""));
  }
  return o;
}

void ss_cli_limit_write_json(FILE *f, const ss_limit_cli_out *o) {
  for (size_t i = 0; i < o->n; i++) {
    json_object *j = json_point(o->pts + i, o);
    fprintf(f, "%s\n", json_object_to_json_string_ext(j, SS_CLI_JSON_FLAGS));
    json_object_put(j);
  }
}

/* Legacy VTK: points; with samples >= 2 (points cell by cell, i fastest) the
 * (N-1)^3 sample hexes of every cell, else one vertex cell per point.  Point
 * data: the cell number and, with derivatives, det J; each field and with
 * derivatives its gradient NAME_gradient (3 components: d/dU, d/dV, d/dW);
 * when some point failed, status (its code).  Missing values are nan. */
void ss_cli_limit_write_vtk(FILE *f, const ss_limit_cli_out *o) {
  const ss_limit_cli_point *p = o->pts;
  const ss_limit_cli_fields *fl = o->fl;
  const size_t n = o->n;
  fprintf(f,
          "# vtk DataFile Version 3.0\nsubspectra limit\nASCII\nDATASET "
          "UNSTRUCTURED_GRID\nPOINTS %zu double\n",
          n);
  for (size_t i = 0; i < n; i++) {
    num(f, "", p[i].r.p[0]);
    num(f, " ", p[i].r.p[1]);
    num(f, " ", p[i].r.p[2]);
    fputc('\n', f);
  }
  if (o->samples >= 2) {
    size_t N = (size_t)o->samples, per = N * N * N, m = N - 1,
           ncell = n / per * m * m * m;
    fprintf(f, "CELLS %zu %zu\n", ncell, ncell * 9);
    for (size_t c = 0; c < n / per; c++)
      for (size_t k = 0; k < m; k++)
        for (size_t j = 0; j < m; j++)
          for (size_t i = 0; i < m; i++) {
#define ID(a, b, d) (c * per + (i + (a)) + N * ((j + (b)) + N * (k + (d))))
            fprintf(f, "8 %zu %zu %zu %zu %zu %zu %zu %zu\n", ID(0, 0, 0), ID(1, 0, 0),
                    ID(1, 1, 0), ID(0, 1, 0), ID(0, 0, 1), ID(1, 0, 1), ID(1, 1, 1),
                    ID(0, 1, 1));
#undef ID
          }
    fprintf(f, "CELL_TYPES %zu\n", ncell);
    for (size_t c = 0; c < ncell; c++)
      fprintf(f, "12\n");
  } else {
    fprintf(f, "CELLS %zu %zu\n", n, 2 * n);
    for (size_t i = 0; i < n; i++)
      fprintf(f, "1 %zu\n", i);
    fprintf(f, "CELL_TYPES %zu\n", n);
    for (size_t i = 0; i < n; i++)
      fprintf(f, "1\n");
  }
  fprintf(f, "POINT_DATA %zu\nSCALARS cell int 1\nLOOKUP_TABLE default\n", n);
  for (size_t i = 0; i < n; i++)
    fprintf(f, "%zu\n", p[i].cell + 1);
  if (o->derivs) {
    fprintf(f, "SCALARS jacobian_det double 1\nLOOKUP_TABLE default\n");
    for (size_t i = 0; i < n; i++) {
      num(f, "", det3(p[i].r.jac));
      fputc('\n', f);
    }
  }
  for (size_t k = 0; k < fl->nf; k++) {
    fprintf(f, "SCALARS %s double 1\nLOOKUP_TABLE default\n", fl->name[k]);
    for (size_t i = 0; i < n; i++) {
      num(f, "", p[i].f[k]);
      fputc('\n', f);
    }
    if (!o->derivs) continue;
    fprintf(f, "SCALARS %s_gradient double 3\nLOOKUP_TABLE default\n", fl->name[k]);
    for (size_t i = 0; i < n; i++) {
      num(f, "", p[i].df[k][0]);
      num(f, " ", p[i].df[k][1]);
      num(f, " ", p[i].df[k][2]);
      fputc('\n', f);
    }
  }
  if (o->with_status) {
    fprintf(f, "SCALARS status int 1\nLOOKUP_TABLE default\n");
    for (size_t i = 0; i < n; i++)
      fprintf(f, "%d\n", p[i].status);
  }
}

/* A sample on its cell's boundary, named by the smallest face of the cell
 * holding it: that face's corners (mesh vertices) with their multilinear
 * weights at the sample (integers: the product of t_a or N-1-t_a over the
 * face's free axes), sorted by vertex.  Neighbouring cells name a shared
 * sample alike whatever their frames; a corner has one pair, an edge point
 * two, a face point four (weights > 0; unused pairs 0). */
typedef struct {
  uint32_t w[8]; /* (vertex, weight) pairs */
  size_t idx;    /* the sample's index among the points */
} sample_key;

static int cmp_key(const void *a, const void *b) {
  const sample_key *x = a, *y = b;
  for (int i = 0; i < 8; i++)
    if (x->w[i] != y->w[i]) return x->w[i] < y->w[i] ? -1 : 1;
  return x->idx < y->idx ? -1 : x->idx > y->idx;
}

/* The key of sample t (grid indices 0..m) of hexahedron v (its 8 vertices);
 * 0 if the sample is inside the cell (no key: no other cell has it). */
static int sample_name(const ss_idx *v, const size_t t[3], size_t m, sample_key *k) {
  unsigned fixed = 0, bits = 0;
  for (int a = 0; a < 3; a++)
    if (t[a] == 0 || t[a] == m) {
      fixed |= 1u << a;
      bits |= (t[a] == m ? 1u : 0u) << a;
    }
  if (fixed == 0) return 0;
  uint32_t pair[4][2];
  int np = 0;
  for (unsigned b = 0; b < 8; b++) {
    if ((b & fixed) != bits) continue;
    uint32_t w = 1;
    for (int a = 0; a < 3; a++)
      if (!(fixed >> a & 1u)) w *= (uint32_t)((b >> a & 1u) ? t[a] : m - t[a]);
    pair[np][0] = v[ss_cube_corner_index(3, b)];
    pair[np++][1] = w;
  }
  for (int i = 1; i < np; i++) /* insertion sort by vertex */
    for (int j = i; j > 0 && pair[j][0] < pair[j - 1][0]; j--) {
      uint32_t s0 = pair[j][0], s1 = pair[j][1];
      pair[j][0] = pair[j - 1][0];
      pair[j][1] = pair[j - 1][1];
      pair[j - 1][0] = s0;
      pair[j - 1][1] = s1;
    }
  memset(k->w, 0, sizeof k->w);
  for (int i = 0; i < np; i++) {
    k->w[2 * i] = pair[i][0];
    k->w[2 * i + 1] = pair[i][1];
  }
  return 1;
}

/* The samples of o (samples >= 2, points cell by cell) merged: id[i] is
 * point i's number among the distinct samples (numbered in order of first
 * appearance), src[j] the point written for distinct sample j (of the points
 * sharing it, the first with the best status), *nm their count.  SS_ENOMEM. */
static ss_status merge_samples(const ss_limit_cli_out *o, size_t *id, size_t *src,
                               size_t *nm, ss_error *err) {
  const size_t N = (size_t)o->samples, m = N - 1, per = N * N * N, n = o->n,
               nb = n / per * (per - (N - 2) * (N - 2) * (N - 2));
  sample_key *key = malloc((nb + 1) * sizeof *key);
  size_t *lead = malloc((2 * n + 1) * sizeof *lead), *pick = lead + n, nk = 0;
  if (!key || !lead) {
    free(key);
    free(lead);
    return ss_error_nomem(err, "VTU samples");
  }
  for (size_t i = 0; i < n; i++) {
    const size_t c = i / per, r = i % per, t[3] = {r % N, r / N % N, r / N / N};
    lead[i] = pick[i] = i;
    if (sample_name(ss_cx_cell(o->mesh, SS_HEX, c), t, m, &key[nk])) key[nk++].idx = i;
  }
  qsort(key, nk, sizeof *key, cmp_key);
  for (size_t g = 0, h; g < nk; g = h) {
    size_t best = key[g].idx; /* the group's first point: its smallest index */
    for (h = g + 1; h < nk && !memcmp(key[h].w, key[g].w, sizeof key[g].w); h++) {
      lead[key[h].idx] = key[g].idx;
      if (o->pts[key[h].idx].status < o->pts[best].status) best = key[h].idx;
    }
    pick[key[g].idx] = best;
  }
  size_t k = 0;
  for (size_t i = 0; i < n; i++)
    if (lead[i] == i) {
      id[i] = k;
      src[k++] = pick[i];
    } else
      id[i] = id[lead[i]];
  *nm = k;
  free(key);
  free(lead);
  return SS_OK;
}

/* <DataArray ...> of n tuples of k components. */
static void vtu_begin(FILE *f, const char *type, const char *name, int k) {
  fprintf(f, "        <DataArray type=\"%s\"", type);
  if (name) fprintf(f, " Name=\"%s\"", name);
  if (k > 1) fprintf(f, " NumberOfComponents=\"%d\"", k);
  fprintf(f, " format=\"ascii\">\n");
}

static void vtu_end(FILE *f) {
  fprintf(f, "        </DataArray>\n");
}

/* The VTU point data of the nm points pts[src[j]] (src NULL: pts[j]). */
static void vtu_point_data(FILE *f, const ss_limit_cli_out *o, const size_t *src,
                           size_t nm) {
  const ss_limit_cli_fields *fl = o->fl;
#define P(j) (&o->pts[src ? src[j] : (j)])
  fprintf(f, "      <PointData Scalars=\"status\"%s>\n",
          o->derivs ? " Tensors=\"jacobian\"" : "");
  vtu_begin(f, "Int64", "cell", 1);
  for (size_t j = 0; j < nm; j++)
    fprintf(f, "%zu\n", P(j)->cell + 1);
  vtu_end(f);
  vtu_begin(f, "Int32", "status", 1);
  for (size_t j = 0; j < nm; j++)
    fprintf(f, "%d\n", P(j)->status);
  vtu_end(f);
  if (o->derivs) {
    vtu_begin(f, "Float64", "jacobian", 9);
    for (size_t j = 0; j < nm; j++) {
      for (int e = 0; e < 9; e++)
        num(f, e ? " " : "", P(j)->r.jac[e / 3][e % 3]);
      fputc('\n', f);
    }
    vtu_end(f);
    vtu_begin(f, "Float64", "jacobian_det", 1);
    for (size_t j = 0; j < nm; j++) {
      num(f, "", det3(P(j)->r.jac));
      fputc('\n', f);
    }
    vtu_end(f);
  }
  for (size_t k = 0; k < fl->nf; k++) {
    vtu_begin(f, "Float64", fl->name[k], 1);
    for (size_t j = 0; j < nm; j++) {
      num(f, "", P(j)->f[k]);
      fputc('\n', f);
    }
    vtu_end(f);
    if (!o->derivs) continue;
    char name[SS_FIELD_NAME_MAX + 16];
    snprintf(name, sizeof name, "%s_gradient", fl->name[k]);
    vtu_begin(f, "Float64", name, 3);
    for (size_t j = 0; j < nm; j++) {
      for (int a = 0; a < 3; a++)
        num(f, a ? " " : "", P(j)->df[k][a]);
      fputc('\n', f);
    }
    vtu_end(f);
  }
  fprintf(f, "      </PointData>\n      <Points>\n");
  vtu_begin(f, "Float64", NULL, 3);
  for (size_t j = 0; j < nm; j++) {
    for (int d = 0; d < 3; d++)
      num(f, d ? " " : "", P(j)->r.p[d]);
    fputc('\n', f);
  }
  vtu_end(f);
  fprintf(f, "      </Points>\n");
#undef P
}

/* The VTU cells: with id (samples >= 2) every cell's (N-1)^3 sample hexes on
 * the merged points, else one vertex cell per point. */
static void vtu_cells(FILE *f, const ss_limit_cli_out *o, const size_t *id,
                      size_t ncell) {
  fprintf(f, "      <Cells>\n");
  vtu_begin(f, "Int64", "connectivity", 1);
  if (id) {
    const size_t N = (size_t)o->samples, per = N * N * N, m = N - 1;
    for (size_t c = 0; c < o->n / per; c++)
      for (size_t k = 0; k < m; k++)
        for (size_t j = 0; j < m; j++)
          for (size_t i = 0; i < m; i++) {
#define ID(a, b, d) id[c * per + (i + (a)) + N * ((j + (b)) + N * (k + (d)))]
            fprintf(f, "%zu %zu %zu %zu %zu %zu %zu %zu\n", ID(0, 0, 0), ID(1, 0, 0),
                    ID(1, 1, 0), ID(0, 1, 0), ID(0, 0, 1), ID(1, 0, 1), ID(1, 1, 1),
                    ID(0, 1, 1));
#undef ID
          }
  } else
    for (size_t j = 0; j < ncell; j++)
      fprintf(f, "%zu\n", j);
  vtu_end(f);
  const size_t nv = id ? 8 : 1;
  vtu_begin(f, "Int64", "offsets", 1);
  for (size_t c = 0; c < ncell; c++)
    fprintf(f, "%zu\n", (c + 1) * nv);
  vtu_end(f);
  vtu_begin(f, "UInt8", "types", 1);
  for (size_t c = 0; c < ncell; c++)
    fprintf(f, "%d\n", id ? 12 : 1);
  vtu_end(f);
  fprintf(f, "      </Cells>\n");
}

ss_status ss_cli_limit_write_vtu(FILE *f, const ss_limit_cli_out *o, ss_error *err) {
  size_t *id = NULL, *src = NULL, nm = o->n, ncell = o->n;
  if (o->samples >= 2) {
    const size_t N = (size_t)o->samples, m = N - 1;
    id = malloc((2 * o->n + 1) * sizeof *id);
    if (!id) return ss_error_nomem(err, "VTU samples");
    src = id + o->n;
    const ss_status st = merge_samples(o, id, src, &nm, err);
    if (st) {
      free(id);
      return st;
    }
    ncell = o->n / (N * N * N) * m * m * m;
  }
  fprintf(f, "<?xml version=\"1.0\"?>\n"
             "<!-- subspectra limit; point data status: 0 ok, 1 no_derivatives, "
             "2 failed, 3 refused -->\n"
             "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
             "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
             "  <UnstructuredGrid>\n");
  fprintf(f, "    <Piece NumberOfPoints=\"%zu\" NumberOfCells=\"%zu\">\n", nm, ncell);
  vtu_point_data(f, o, src, nm);
  vtu_cells(f, o, id, ncell);
  fprintf(f, "    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n");
  free(id);
  return SS_OK;
}
