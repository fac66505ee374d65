/* ss_mesh_tetgen.c — TetGen's .node/.ele/.face files (and Shewchuk's Triangle,
 * whose 2D .node/.ele are the same format), read with the mesh lexer.
 *
 * Formats (TetGen 1.5 manual, section 5.2): '#' starts a comment; the first
 * line of each file is a header, then one entry per line.
 *   .node  "N dim nattr nmarkers", then "i x y [z] [nattr attributes] [marker]";
 *   .ele   "M npe nattr", then "i v1 .. v_npe [nattr attributes]";
 *   .face  "F nmarkers", then "i a b c [marker]".
 * Numbering starts at the first point's index (0 or 1, TetGen's -z) and runs
 * on by one; the .ele and .face files use the same base.  TetGen writes its
 * tetrahedra positively oriented in the convention of ss_cx.h (det(x1-x0,
 * x2-x0, x3-x0) > 0); they are kept as written, so an inverted file is
 * caught by the orientation check, not hidden.  Each entry must sit on one
 * line with exactly the fields its header announces: a count or a field
 * that disagrees is a malformed file, never guessed around. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ss_mesh.h"
#include "ss_mesh_lex.h"

/* Largest count accepted in a header (far beyond any real mesh). */
#define MAX_COUNT (1LL << 40)
/* Entries reserved on a header's word before they arrive. */
#define TRUST_LIMIT 65536
/* Attributes per entry accepted (TetGen writes a handful). */
#define MAX_ATTR 1024

/* The next header or entry line's first token; a message on end of file. */
static char *first_token(ss_lex *lx, const char *what, ss_status *st) {
  char *tok = ss_lex_next_line(lx, st);
  if (!tok && !*st) *st = ss_lex_fail(lx, "unexpected end of file: %s expected", what);
  return tok;
}

/* The next field of the current line; a message when the line ends early. */
static char *field(ss_lex *lx, const char *what, ss_status *st) {
  char *tok = ss_lex_next_on_line(lx);
  *st = tok ? SS_OK : ss_lex_fail(lx, "the line ends where %s was expected", what);
  return tok;
}

/* The current line must hold nothing more. */
static ss_status line_end(ss_lex *lx, const char *what) {
  char *tok = ss_lex_next_on_line(lx);
  if (tok)
    return ss_lex_fail(lx,
                       "'%.40s' after the last field of %s (the header announces "
                       "fewer fields)",
                       tok, what);
  return SS_OK;
}

/* A header count or flag on the current line. */
static ss_status header_int(ss_lex *lx, const char *what, long long lo, long long hi,
                            long long *out) {
  ss_status st;
  char *tok = field(lx, what, &st);
  if (!tok) return st;
  return ss_lex_int(lx, tok, what, lo, hi, out);
}

/* Entry i's own number: base + i. */
static ss_status entry_index(ss_lex *lx, const char *tok, const char *kind,
                             long long base, long long i) {
  long long idx;
  ss_status st = ss_lex_int(lx, tok, kind, -MAX_COUNT, MAX_COUNT, &idx);
  if (st) return st;
  if (idx != base + i)
    return ss_lex_fail(lx,
                       "%s number %lld where %lld was expected (numbers run on by "
                       "one from the first)",
                       kind, idx, base + i);
  return SS_OK;
}

/* An attribute used as a reference: an integer in int32 range (TetGen
 * writes region attributes as numbers; a fractional one is no label). */
static ss_status attr_ref(ss_lex *lx, const char *tok, const char *what, int32_t *ref) {
  double a;
  ss_status st = ss_lex_double(lx, tok, what, &a);
  if (st) return st;
  if (a != floor(a) || a < (double)INT32_MIN || a > (double)INT32_MAX)
    return ss_lex_fail(lx, "%s %.40s is not an integer label", what, tok);
  *ref = (int32_t)a;
  return SS_OK;
}

static ss_status read_node(ss_lex *lx, ss_cx **out, long long *base) {
  ss_status st;
  long long n, dim, nattr, nmark;
  char *tok = first_token(lx, "the .node header 'N dim nattr nmarkers'", &st);
  if (!tok) return st;
  if ((st = ss_lex_int(lx, tok, "point count", 1, (long long)SS_IDX_NONE - 1, &n)) ||
      (st = header_int(lx, "dimension", 2, 3, &dim)) ||
      (st = header_int(lx, "attribute count", 0, MAX_ATTR, &nattr)) ||
      (st = header_int(lx, "boundary marker flag", 0, 1, &nmark)) ||
      (st = line_end(lx, "the .node header")))
    return st;
  if ((st = ss_cx_new((int)dim, out, lx->err))) return st;
  ss_cx *cx = *out;
  if ((st = ss_cx_reserve_vertices(cx, (size_t)(n < TRUST_LIMIT ? n : TRUST_LIMIT),
                                   lx->err)))
    return st;
  for (long long i = 0; i < n; i++) {
    tok = ss_lex_next_line(lx, &st);
    if (st) return st;
    if (!tok)
      return ss_lex_fail(lx, "unexpected end of file: %lld of %lld points read", i, n);
    if (i == 0) {
      long long b;
      if ((st = ss_lex_int(lx, tok, "first point number", 0, 1, &b))) return st;
      *base = b;
    } else if ((st = entry_index(lx, tok, "point", *base, i))) {
      return st;
    }
    double x[3];
    for (int k = 0; k < dim; k++) {
      if (!(tok = field(lx, "a coordinate", &st))) return st;
      if ((st = ss_lex_double(lx, tok, "coordinate", &x[k]))) return st;
    }
    for (long long a = 0; a < nattr; a++) {
      double dummy;
      if (!(tok = field(lx, "an attribute", &st))) return st;
      if ((st = ss_lex_double(lx, tok, "attribute", &dummy))) return st;
    }
    long long mark = 0;
    if (nmark) {
      if (!(tok = field(lx, "a boundary marker", &st))) return st;
      if ((st = ss_lex_int(lx, tok, "boundary marker", INT32_MIN, INT32_MAX, &mark)))
        return st;
    }
    if ((st = line_end(lx, "a point")) ||
        (st = ss_cx_add_vertex(cx, x, (int32_t)mark, lx->err)))
      return st;
  }
  return SS_OK;
}

/* Cells of .ele (npe corners, nattr attributes) or .face (3 corners, a
 * marker when nmark): the shared part. */
static ss_status read_cells(ss_lex *lx, ss_cx *cx, long long base, ss_cell_type t,
                            long long n, long long nattr, long long nmark) {
  ss_status st;
  const int nv = ss_cell_nverts(t);
  const char *name = ss_cell_name(t);
  if ((st = ss_cx_reserve_cells(cx, t, (size_t)(n < TRUST_LIMIT ? n : TRUST_LIMIT),
                                lx->err)))
    return st;
  for (long long i = 0; i < n; i++) {
    char *tok = ss_lex_next_line(lx, &st);
    if (st) return st;
    if (!tok)
      return ss_lex_fail(lx, "unexpected end of file: %lld of %lld %s read", i, n,
                         ss_cell_plural(t));
    if ((st = entry_index(lx, tok, name, base, i))) return st;
    ss_idx v[SS_MAXCELLVERTS];
    for (int k = 0; k < nv; k++) {
      long long id;
      char what[64];
      snprintf(what, sizeof what, "%s %lld: point number", name, base + i);
      if (!(tok = field(lx, "a point number", &st))) return st;
      if ((st = ss_lex_int(lx, tok, what, base, base + (long long)cx->nv - 1, &id)))
        return st;
      v[k] = (ss_idx)(id - base);
    }
    int32_t ref = 0;
    for (long long a = 0; a < nattr; a++) {
      if (!(tok = field(lx, "an attribute", &st))) return st;
      double dummy;
      /* the first attribute (TetGen's region, -A) is the reference */
      if ((st = a == 0 ? attr_ref(lx, tok, "region attribute", &ref)
                       : ss_lex_double(lx, tok, "attribute", &dummy)))
        return st;
    }
    if (nmark) {
      long long mark;
      if (!(tok = field(lx, "a boundary marker", &st))) return st;
      if ((st = ss_lex_int(lx, tok, "boundary marker", INT32_MIN, INT32_MAX, &mark)))
        return st;
      ref = (int32_t)mark;
    }
    if ((st = line_end(lx, name))) return st;
    const char *defect = ss_cell_defect(t, v, cx->nv);
    if (defect) return ss_lex_fail(lx, "%s %lld is %s", name, base + i, defect);
    if ((st = ss_cx_add_cell(cx, t, v, ref, lx->err))) return st;
  }
  return SS_OK;
}

static ss_status read_ele(ss_lex *lx, ss_cx *cx, long long base) {
  ss_status st;
  long long m, npe, nattr;
  char *tok = first_token(lx, "the .ele header 'M nodes-per-element nattr'", &st);
  if (!tok) return st;
  if ((st = ss_lex_int(lx, tok, "element count", 0, MAX_COUNT, &m)) ||
      (st = header_int(lx, "nodes per element", 3, 10, &npe)) ||
      (st = header_int(lx, "attribute count", 0, MAX_ATTR, &nattr)) ||
      (st = line_end(lx, "the .ele header")))
    return st;
  const long long want = cx->dim == 3 ? 4 : 3;
  if (npe != want)
    return ss_lex_fail(lx,
                       "%lld nodes per element with %d-dimensional points: read are "
                       "%lld (linear %s; second-order elements are not)",
                       npe, cx->dim, want, cx->dim == 3 ? "tetrahedra" : "triangles");
  return read_cells(lx, cx, base, cx->dim == 3 ? SS_TET : SS_TRIANGLE, m, nattr, 0);
}

static ss_status read_face(ss_lex *lx, ss_cx *cx, long long base) {
  ss_status st;
  long long f, nmark;
  char *tok = first_token(lx, "the .face header 'F nmarkers'", &st);
  if (!tok) return st;
  if ((st = ss_lex_int(lx, tok, "face count", 0, MAX_COUNT, &f)) ||
      (st = header_int(lx, "boundary marker flag", 0, 1, &nmark)) ||
      (st = line_end(lx, "the .face header")))
    return st;
  return read_cells(lx, cx, base, SS_TRIANGLE, f, 0, nmark);
}

/* Nothing but comments may follow the last entry. */
static ss_status trailing(ss_lex *lx, long long n) {
  ss_status st;
  char *tok = ss_lex_next_line(lx, &st);
  if (st) return st;
  if (tok)
    return ss_lex_fail(lx, "'%.40s' after the %lld entries the header announces", tok, n);
  return SS_OK;
}

/* Lex one file of the set: open stem+ext (required or not), run fn. */
typedef enum { PART_NODE, PART_ELE, PART_FACE } part;

static ss_status read_part(const char *stem, size_t stem_len, const char *ext, part p,
                           int required, ss_cx **cx, long long *base, ss_error *err) {
  char *name = malloc(stem_len + strlen(ext) + 1);
  if (!name) return ss_error_nomem(err, "file name");
  memcpy(name, stem, stem_len);
  strcpy(name + stem_len, ext);
  FILE *f = fopen(name, "r");
  if (!f) {
    ss_status st = SS_OK;
    if (required || errno != ENOENT)
      st = ss_error_set(err, SS_EIO, "%s: %s", name, strerror(errno));
    free(name);
    return st;
  }
  ss_lex lx;
  ss_lex_init(&lx, f, name, 1, err);
  const size_t before = p == PART_NODE  ? 0
                        : p == PART_ELE ? (*cx)->nc[SS_TET] + (*cx)->nc[SS_TRIANGLE]
                                        : (*cx)->nc[SS_TRIANGLE];
  ss_status st = p == PART_NODE  ? read_node(&lx, cx, base)
                 : p == PART_ELE ? read_ele(&lx, *cx, *base)
                                 : read_face(&lx, *cx, *base);
  if (!st) {
    const size_t after = p == PART_NODE  ? (*cx)->nv
                         : p == PART_ELE ? (*cx)->nc[SS_TET] + (*cx)->nc[SS_TRIANGLE]
                                         : (*cx)->nc[SS_TRIANGLE];
    st = trailing(&lx, (long long)(after - before));
  }
  ss_lex_done(&lx);
  fclose(f);
  free(name);
  return st;
}

ss_status ss_mesh_read_tetgen(const char *path, ss_cx **out, ss_error *err) {
  *out = NULL;
  const char *dot = strrchr(path, '.'), *slash = strrchr(path, '/');
  const size_t stem_len =
      dot && (!slash || dot > slash) ? (size_t)(dot - path) : strlen(path);
  ss_cx *cx = NULL;
  long long base = 0;
  ss_status st = read_part(path, stem_len, ".node", PART_NODE, 1, &cx, &base, err);
  if (!st) st = read_part(path, stem_len, ".ele", PART_ELE, 0, &cx, &base, err);
  if (!st) st = read_part(path, stem_len, ".face", PART_FACE, 0, &cx, &base, err);
  if (st) {
    ss_cx_free(cx);
    return st;
  }
  *out = cx;
  return SS_OK;
}
