/* ss_mesh_vtk_read.c — legacy VTK (.vtk) unstructured grids, ASCII and
 * BINARY, with their point and cell data.
 *
 * A reader of our own, as no library in Debian reads this format's data
 * short of VTK itself (libvtk9-dev: 208 packages, ss_mesh_vtu_read.c): gmsh
 * opens a legacy .vtk but keeps only its points and cells (POINT_DATA is
 * dropped: `gmsh file.vtk -0 -o out.msh` writes no $NodeData), and meshio is
 * Python.  The format is a keyword stream (VTK's "File Formats" document):
 * what is read, and how the grid becomes a complex, is in ss_mesh.h
 * (ss_mesh_read_vtk) and ss_mesh_vtk_build.c, shared with the .vtu reader. */
#include <errno.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "ss_mesh.h"
#include "ss_mesh_vtk_impl.h"

/* A cursor over the file. */
typedef struct {
  const char *path; /* for messages */
  const char *buf;  /* the file, NUL-terminated */
  const char *p;    /* next unread byte */
  const char *e;    /* end */
  int binary;       /* BINARY (big-endian values) */
  char tok[256];    /* the last token */
  ss_error *err;    /* failures */
} vtk_cur;

/* "path:line: problem" at the cursor. */
static ss_status fail(const vtk_cur *c, const char *what, const char *detail) {
  long line = 1;
  for (const char *q = c->buf; q < c->p && q < c->e; q++)
    line += *q == '\n';
  return ss_error_set(c->err, SS_EINPUT, "%s:%ld: %s%s%s", c->path, line, what,
                      detail ? ": " : "", detail ? detail : "");
}

/* The next whitespace-delimited token into c->tok; 0 at the end. */
static int next(vtk_cur *c) {
  while (c->p < c->e && strchr(" \t\r\n", *c->p))
    c->p++;
  size_t n = 0;
  while (c->p < c->e && !strchr(" \t\r\n", *c->p)) {
    if (n + 1 < sizeof c->tok) c->tok[n++] = *c->p;
    c->p++;
  }
  c->tok[n] = '\0';
  return n > 0;
}

/* The next token as a count in [0, max]; -1 (message set) if not. */
static long long count(vtk_cur *c, const char *what, long long max) {
  char *end;
  if (!next(c)) return fail(c, what, "missing at the end of the file"), -1;
  errno = 0;
  const long long v = strtoll(c->tok, &end, 10);
  if (*end || errno || v < 0 || v > max) return fail(c, what, "not a count"), -1;
  return v;
}

/* The rest of the current line, skipped. */
static void end_line(vtk_cur *c) {
  while (c->p < c->e && *c->p != '\n')
    c->p++;
  if (c->p < c->e) c->p++;
}

/* Bytes and kind (0 signed, 1 unsigned, 2 float) of a legacy type name. */
static int type_size(const char *t, int *kind) {
  static const struct {
    const char *name;
    int size, kind;
  } types[] = {{"bit", 0, 1},          {"unsigned_char", 1, 1},
               {"char", 1, 0},         {"unsigned_short", 2, 1},
               {"short", 2, 0},        {"unsigned_int", 4, 1},
               {"int", 4, 0},          {"unsigned_long", 8, 1},
               {"long", 8, 0},         {"float", 4, 2},
               {"double", 8, 2},       {"vtktypeint64", 8, 0},
               {"vtktypeuint64", 8, 1}};
  for (size_t i = 0; i < sizeof types / sizeof types[0]; i++)
    if (!strcasecmp(t, types[i].name) && types[i].size) {
      *kind = types[i].kind;
      return types[i].size;
    }
  return 0;
}

/* One big-endian value of size bytes and kind at b. */
static double big_endian(const unsigned char *b, int size, int kind) {
  uint64_t u = 0;
  for (int k = 0; k < size; k++)
    u = u << 8 | b[k];
  if (kind == 2) {
    if (size == 4) {
      const uint32_t w = (uint32_t)u;
      float x;
      memcpy(&x, &w, 4);
      return x;
    }
    double x;
    memcpy(&x, &u, 8);
    return x;
  }
  if (kind == 1) return (double)u;
  const int shift = 64 - 8 * size; /* sign-extend */
  return (double)((int64_t)(u << shift) >> shift);
}

/* n values of type `type` (its name, c->tok before the call) into a new
 * array *out. */
static ss_status values(vtk_cur *c, const char *what, const char *type, size_t n,
                        double **out) {
  int kind;
  const int size = type_size(type, &kind);
  if (!size) return fail(c, what, "unknown data type (or bit, which is not read)");
  if (n > (size_t)(c->e - c->p) + 1)
    return fail(c, what, "more values than the file has");
  double *v = malloc((n + 1) * sizeof *v);
  if (!v) return ss_error_nomem(c->err, "VTK values");
  if (c->binary) {
    end_line(c); /* the data start on the line after the keyword's */
    if ((size_t)(c->e - c->p) / (size_t)size < n) {
      free(v);
      return fail(c, what, "the binary data end early");
    }
    for (size_t i = 0; i < n; i++, c->p += size)
      v[i] = big_endian((const unsigned char *)c->p, size, kind);
  } else {
    for (size_t i = 0; i < n; i++) {
      char *end;
      if (!next(c) || (v[i] = strtod(c->tok, &end), *end)) {
        free(v);
        return fail(c, what, c->tok[0] ? "not a number" : "the values end early");
      }
    }
  }
  *out = v;
  return SS_OK;
}

/* One attribute (SCALARS, VECTORS, NORMALS, TENSORS, TEXTURE_COORDINATES,
 * FIELD) of POINT_DATA or CELL_DATA with tuples each; the keyword in
 * c->tok. */
static ss_status attribute(vtk_cur *c, size_t tuples, ss_vtk_array **list, size_t *n) {
  char kw[256], name[256], type[256];
  snprintf(kw, sizeof kw, "%s", c->tok);
  if (!strcasecmp(kw, "FIELD")) {
    const long long na = (next(c), count(c, "FIELD array count", 1 << 20));
    if (na < 0) return SS_EINPUT;
    for (long long i = 0; i < na; i++) {
      ss_vtk_array *a;
      if (!next(c)) return fail(c, "FIELD", "an array is missing");
      snprintf(name, sizeof name, "%s", c->tok);
      const long long nc = count(c, "FIELD components", SS_MAXDIM);
      const long long nt = nc < 0 ? -1 : count(c, "FIELD tuples", 1LL << 40);
      if (nt < 0) return SS_EINPUT;
      if (!next(c)) return fail(c, "FIELD", "no data type");
      if ((size_t)nt != tuples || nc < 1)
        return fail(c, "FIELD array", "its tuples are not one per point or cell");
      snprintf(type, sizeof type, "%s", c->tok);
      ss_status st = ss_vtk_array_add(c->path, list, n, name, (int)nc, &a, c->err);
      if (!st) st = values(c, name, type, tuples * (size_t)nc, &a->val);
      if (st) return st;
      int kind;
      a->integer = type_size(type, &kind) && kind != 2;
    }
    return SS_OK;
  }
  int nc = !strcasecmp(kw, "SCALARS") ? 1 : !strcasecmp(kw, "TENSORS") ? 9 : 3;
  if (strcasecmp(kw, "SCALARS") && strcasecmp(kw, "VECTORS") &&
      strcasecmp(kw, "NORMALS") && strcasecmp(kw, "TENSORS") &&
      strcasecmp(kw, "TEXTURE_COORDINATES"))
    return fail(c, kw,
                "not a data attribute that is read (SCALARS, VECTORS, NORMALS, "
                "TENSORS, TEXTURE_COORDINATES, FIELD)");
  if (!next(c)) return fail(c, kw, "no name");
  snprintf(name, sizeof name, "%s", c->tok);
  if (!strcasecmp(kw, "TEXTURE_COORDINATES") &&
      (nc = (int)count(c, "TEXTURE_COORDINATES dimension", 3)) < 1)
    return SS_EINPUT;
  if (!next(c)) return fail(c, kw, "no data type");
  snprintf(type, sizeof type, "%s", c->tok);
  if (!strcasecmp(kw, "SCALARS")) { /* [numComp] then LOOKUP_TABLE name */
    const char *save = c->p;
    if (next(c) && strcasecmp(c->tok, "LOOKUP_TABLE")) {
      char *end;
      const long v = strtol(c->tok, &end, 10);
      if (*end || v < 1 || v > 4) return fail(c, "SCALARS", "bad number of components");
      nc = (int)v;
      save = c->p;
      next(c);
    }
    if (!strcasecmp(c->tok, "LOOKUP_TABLE"))
      next(c); /* its name */
    else
      c->p = save;
  }
  ss_vtk_array *a;
  ss_status st = ss_vtk_array_add(c->path, list, n, name, nc, &a, c->err);
  if (!st) st = values(c, name, type, tuples * (size_t)nc, &a->val);
  int kind;
  if (!st) a->integer = type_size(type, &kind) && kind != 2;
  return st;
}

/* POINTS, CELLS and CELL_TYPES, then the data sections, into g. */
static ss_status grid(vtk_cur *c, ss_vtk_grid *g) {
  ss_status st = SS_OK;
  double *cl = NULL, *ct = NULL, *off = NULL;
  size_t ncl = 0;
  ss_vtk_array **list = NULL;
  size_t *nlist = NULL, tuples = 0;
  int have_cells = 0;
  while (!st && next(c)) {
    if ((!strcasecmp(c->tok, "POINTS") && g->pts) ||
        (!strcasecmp(c->tok, "CELLS") && cl)) {
      st = fail(c, c->tok, "a second time");
    } else if (!strcasecmp(c->tok, "POINTS")) {
      long long np = count(c, "POINTS", (long long)SS_IDX_NONE - 1);
      if (np < 0 || !next(c)) {
        st = np < 0 ? SS_EINPUT : fail(c, "POINTS", "no type");
        break;
      }
      g->np = (size_t)np;
      char type[256];
      snprintf(type, sizeof type, "%s", c->tok);
      st = values(c, "POINTS", type, 3 * g->np, &g->pts);
    } else if (!strcasecmp(c->tok, "CELLS")) {
      const long long a = count(c, "CELLS", 1LL << 40),
                      b = count(c, "CELLS size", 1LL << 42);
      if (a < 0 || b < 0) {
        st = SS_EINPUT;
        break;
      }
      const char *save = c->p;
      if (next(c) && !strcasecmp(c->tok, "OFFSETS")) { /* version 5.1 */
        char type[256];
        next(c);
        snprintf(type, sizeof type, "%s", c->tok);
        g->nc = a ? (size_t)a - 1 : 0;
        st = values(c, "OFFSETS", type, (size_t)a, &off);
        if (!st && (!next(c) || strcasecmp(c->tok, "CONNECTIVITY") || !next(c)))
          st = fail(c, "CELLS", "CONNECTIVITY expected after OFFSETS");
        snprintf(type, sizeof type, "%s", c->tok);
        if (!st) st = values(c, "CONNECTIVITY", type, (size_t)b, &cl);
        ncl = (size_t)b;
      } else {
        c->p = save;
        g->nc = (size_t)a;
        ncl = (size_t)b;
        st = values(c, "CELLS", "int", ncl, &cl);
      }
      have_cells = 1;
    } else if (!strcasecmp(c->tok, "CELL_TYPES")) {
      const long long n = count(c, "CELL_TYPES", 1LL << 40);
      if (n < 0 || !have_cells || (size_t)n != g->nc || ct) {
        st = n < 0 ? SS_EINPUT
                   : fail(c, "CELL_TYPES", "not once, after CELLS, with its count");
        break;
      }
      st = values(c, "CELL_TYPES", "int", (size_t)n, &ct);
    } else if (!strcasecmp(c->tok, "POINT_DATA") || !strcasecmp(c->tok, "CELL_DATA")) {
      const int pd = !strcasecmp(c->tok, "POINT_DATA");
      const long long n = count(c, c->tok, 1LL << 40);
      if (n < 0 || (size_t)n != (pd ? g->np : g->nc)) {
        st = n < 0 ? SS_EINPUT
                   : fail(c, pd ? "POINT_DATA" : "CELL_DATA",
                          "its count is not that of the points or cells");
        break;
      }
      list = pd ? &g->pdata : &g->cdata;
      nlist = pd ? &g->npd : &g->ncd;
      tuples = (size_t)n;
    } else if (!strcasecmp(c->tok, "METADATA")) {
      while (c->p < c->e && !(c->p[0] == '\n' && c->p + 1 < c->e && c->p[1] == '\n'))
        c->p++; /* information blocks end at an empty line */
    } else if (list) {
      st = attribute(c, tuples, list, nlist);
    } else {
      st = fail(c, c->tok, "not a section of an unstructured grid that is read");
    }
  }
  if (!st && (!g->pts || !ct))
    st = fail(c, "the file", g->pts ? "no CELL_TYPES" : "no POINTS");
  if (!st && (!(g->offsets = malloc((g->nc + 1) * sizeof *g->offsets)) ||
              !(g->types = malloc((g->nc + 1) * sizeof *g->types)) ||
              !(g->conn = malloc((ncl + 1) * sizeof *g->conn))))
    st = ss_error_nomem(c->err, "VTK cells");
  /* version 5.1: offsets and connectivity; before: counts each before its points */
  size_t at = 0, k = 0;
  for (size_t i = 0; !st && i < g->nc; i++) {
    g->types[i] = ct[i] >= 0 && ct[i] < 256 ? (int)ct[i] : -1;
    if (off) {
      g->offsets[i] = (int64_t)off[i + 1];
      if (off[i + 1] < off[i] || off[i + 1] > (double)ncl)
        st = fail(c, "OFFSETS", "not ascending within CONNECTIVITY");
      continue;
    }
    const double m = at < ncl ? cl[at] : -1;
    if (m < 0 || m > 64 || at + 1 + (size_t)m > ncl) {
      st = fail(c, "CELLS", "a cell's point count runs past the list");
      break;
    }
    for (size_t j = 0; j < (size_t)m; j++)
      cl[k++] = cl[at + 1 + j];
    at += 1 + (size_t)m;
    g->offsets[i] = (int64_t)k;
  }
  if (!off) ncl = k;
  for (size_t i = 0; !st && i < ncl; i++)
    g->conn[i] = cl[i] >= -1 && cl[i] < 1e15 ? (int64_t)cl[i] : -1;
  free(cl);
  free(ct);
  free(off);
  return st;
}

ss_status ss_mesh_read_vtk(const char *path, ss_cx **out, ss_mesh_fields *names,
                           ss_error *err) {
  *out = NULL;
  char *buf = NULL;
  size_t len = 0;
  ss_status st = ss_vtk_slurp(path, &buf, &len, err);
  if (st) return st;
  vtk_cur c = {.path = path, .buf = buf, .p = buf, .e = buf + len, .err = err};
  ss_vtk_grid g;
  memset(&g, 0, sizeof g);
  if (strncmp(buf, "# vtk DataFile Version", 22)) {
    st = fail(&c, "not a legacy VTK file", "'# vtk DataFile Version' expected");
    goto done;
  }
  end_line(&c);
  end_line(&c); /* the title */
  if (!next(&c) || (strcasecmp(c.tok, "ASCII") && strcasecmp(c.tok, "BINARY"))) {
    st = fail(&c, "ASCII or BINARY expected", NULL);
    goto done;
  }
  c.binary = !strcasecmp(c.tok, "BINARY");
  if (!next(&c) || strcasecmp(c.tok, "DATASET") || !next(&c) ||
      strcasecmp(c.tok, "UNSTRUCTURED_GRID")) {
    st = fail(&c, "DATASET UNSTRUCTURED_GRID expected",
              c.tok[0] ? "other datasets are not read" : NULL);
    goto done;
  }
  if (!(st = grid(&c, &g))) st = ss_vtk_build(path, &g, out, names, err);
done:
  ss_vtk_grid_done(&g);
  free(buf);
  return st;
}
