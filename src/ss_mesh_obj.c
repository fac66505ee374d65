/* ss_mesh_obj.c — Wavefront OBJ surfaces: read and write.
 *
 * Only the polygonal subset a subdivision surface needs: vertices (v, 3
 * coordinates; a 4th weight or trailing colour values are ignored), faces (f)
 * with 3 or 4 corners, polylines (l, split into segments) and points (p, vertex
 * cells).  Corner references may be i, i/t, i//n or i/t/n, and negative
 * (relative to the last vertex read).  A face of zero area (collinear
 * corners; for a quadrilateral, at any corner) is an error naming its line.  Texture,
 * normal, grouping and material statements are ignored; anything else (free-form curves
 * and surfaces) is an error rather than silently dropped geometry. */
#include <stdlib.h>
#include <string.h>

#include "ss_mesh.h"
#include "ss_mesh_lex.h"

static const char *const ignored[] = {
    "vt",     "vn",  "vp",         "o",         "g",     "s",        "usemtl",
    "mtllib", "lod", "shadow_obj", "trace_obj", "bevel", "c_interp", "d_interp"};

/* Parse a corner reference "i[/t[/n]]" into a 0-based vertex index. */
static ss_status corner(ss_lex *lx, char *tok, size_t nv, const char *stmt, ss_idx *out) {
  char *slash = strchr(tok, '/');
  if (slash) *slash = '\0';
  long long i;
  char what[48];
  snprintf(what, sizeof what, "'%s' vertex reference", stmt);
  ss_status st = ss_lex_int(lx, tok, what, -(long long)nv - 1, (long long)nv + 1, &i);
  if (st) return st;
  long long abs = i < 0 ? (long long)nv + i + 1 : i;
  if (i == 0 || abs < 1 || abs > (long long)nv)
    return ss_lex_fail(
        lx, "'%s' refers to vertex %lld, but %zu vertices were read so far", stmt, i, nv);
  *out = (ss_idx)(abs - 1);
  return SS_OK;
}

static ss_status parse(ss_lex *lx, ss_cx *cx) {
  ss_status st;
  char *kw;
  while ((kw = ss_lex_next_line(lx, &st))) {
    if (!strcmp(kw, "v")) {
      double x[4];
      int n = 0;
      char *tok;
      while ((tok = ss_lex_next_on_line(lx))) {
        double val;
        if ((st = ss_lex_double(lx, tok, "coordinate", &val))) return st;
        if (n < 4) x[n] = val;
        n++;
      }
      if (n < 3) return ss_lex_fail(lx, "vertex with %d coordinates (3 needed)", n);
      if ((st = ss_cx_add_vertex(cx, x, 0, lx->err))) return st;
    } else if (!strcmp(kw, "f") || !strcmp(kw, "l") || !strcmp(kw, "p")) {
      ss_idx v[64];
      int n = 0;
      char *tok;
      while ((tok = ss_lex_next_on_line(lx))) {
        if (n == 64) return ss_lex_fail(lx, "'%s' with more than 64 vertices", kw);
        if ((st = corner(lx, tok, cx->nv, kw, &v[n]))) return st;
        n++;
      }
      if (kw[0] == 'f') {
        if (n < 3) return ss_lex_fail(lx, "face with %d vertices", n);
        if (n > 4)
          return ss_lex_fail(lx,
                             "face with %d vertices: only triangles and quadrilaterals "
                             "are supported",
                             n);
        ss_cell_type t = n == 3 ? SS_TRIANGLE : SS_QUAD;
        const char *defect = ss_cell_defect(t, v, cx->nv);
        if (defect) return ss_lex_fail(lx, "face is %s", defect);
        if (ss_cx_cell_flat(cx, t, v))
          return ss_lex_fail(lx, "face is flat (zero area%s, relative to its edges)",
                             n == 3 ? ": its corners are collinear" : " at a corner");
        if ((st = ss_cx_add_cell(cx, t, v, 0, lx->err))) return st;
      } else if (kw[0] == 'l') {
        if (n < 2) return ss_lex_fail(lx, "line with %d vertices", n);
        for (int k = 0; k + 1 < n; k++) {
          if (v[k] == v[k + 1])
            return ss_lex_fail(lx, "line segment is degenerate (a vertex repeated)");
          if ((st = ss_cx_add_cell(cx, SS_SEGMENT, v + k, 0, lx->err))) return st;
        }
      } else {
        if (n < 1) return ss_lex_fail(lx, "point statement without vertices");
        for (int k = 0; k < n; k++)
          if ((st = ss_cx_add_cell(cx, SS_VERTEX, v + k, 0, lx->err))) return st;
      }
    } else {
      int skip = 0;
      for (size_t i = 0; i < sizeof ignored / sizeof ignored[0]; i++)
        if (!strcmp(kw, ignored[i])) skip = 1;
      if (!skip) return ss_lex_fail(lx, "unsupported OBJ statement '%.40s'", kw);
    }
  }
  if (st) return st;
  if (cx->nv == 0) return ss_lex_fail(lx, "no vertices: not an OBJ mesh");
  return SS_OK;
}

ss_status ss_mesh_read_obj(FILE *f, const char *name, ss_cx **out, ss_error *err) {
  *out = NULL;
  ss_cx *cx;
  ss_status st = ss_cx_new(3, &cx, err);
  if (st) return st;
  ss_lex lx;
  ss_lex_init(&lx, f, name, 1, err);
  st = parse(&lx, cx);
  ss_lex_done(&lx);
  if (st) {
    ss_cx_free(cx);
    return st;
  }
  *out = cx;
  return SS_OK;
}

ss_status ss_mesh_write_obj(FILE *f, const ss_cx *cx, ss_error *err) {
  if (cx->dim > 3)
    return ss_error_set(err, SS_EINPUT, "OBJ holds at most 3 coordinates, not %d",
                        cx->dim);
  for (int t = 0; t < SS_NCELLTYPES; t++)
    if (cx->nc[t] && ss_cell_dim((ss_cell_type)t) > 2)
      return ss_error_set(err, SS_EINPUT, "OBJ holds surfaces only: the mesh has %zu %s",
                          cx->nc[t], ss_cell_plural((ss_cell_type)t));
  fprintf(f, "# written by subspectra: %zu vertices\n", cx->nv);
  for (size_t i = 0; i < cx->nv; i++) {
    double x[3] = {0, 0, 0};
    for (int k = 0; k < cx->dim; k++)
      x[k] = cx->x[i * (size_t)cx->dim + k];
    fprintf(f, "v %.17g %.17g %.17g\n", x[0], x[1], x[2]);
  }
  static const struct {
    ss_cell_type t;
    const char *stmt;
  } kinds[] = {{SS_VERTEX, "p"}, {SS_SEGMENT, "l"}, {SS_TRIANGLE, "f"}, {SS_QUAD, "f"}};
  for (size_t k = 0; k < sizeof kinds / sizeof kinds[0]; k++) {
    ss_cell_type t = kinds[k].t;
    int nv = ss_cell_nverts(t);
    for (size_t i = 0; i < cx->nc[t]; i++) {
      const ss_idx *v = ss_cx_cell(cx, t, i);
      fputs(kinds[k].stmt, f);
      for (int j = 0; j < nv; j++)
        fprintf(f, " %lu", (unsigned long)v[j] + 1);
      fputc('\n', f);
    }
  }
  if (ferror(f)) return ss_error_set(err, SS_EIO, "write error");
  return SS_OK;
}
