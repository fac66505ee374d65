/* ss_mesh_medit.c — Medit .mesh (ASCII) reader and writer.
 *
 * The reader trusts nothing: every count, index and number is checked as it is
 * read, allocations follow what was actually read (a header claiming 10^12
 * vertices allocates nothing until they arrive), and each failure names the
 * file, the line and the problem. */
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "ss_mesh.h"
#include "ss_mesh_lex.h"

/* Sections holding cells: keyword, cell type, and whether entries end with a
 * reference (Corners lists bare vertex indices). */
static const struct {
  const char *kw;
  ss_cell_type type;
  int has_ref;
} cell_sections[] = {
    {"Corners", SS_VERTEX, 0},     {"Edges", SS_SEGMENT, 1},
    {"Triangles", SS_TRIANGLE, 1}, {"Quadrilaterals", SS_QUAD, 1},
    {"Tetrahedra", SS_TET, 1},     {"Hexahedra", SS_HEX, 1},
    {"Octahedra", SS_OCT, 1},
};
#define N_CELL_SECTIONS (sizeof cell_sections / sizeof cell_sections[0])

/* Sections carrying no cells, skipped: keyword and numbers per entry
 * (0 = the coordinate dimension). */
static const struct {
  const char *kw;
  int width;
} skip_sections[] = {
    {"RequiredVertices", 1},
    {"Ridges", 1},
    {"RequiredEdges", 1},
    {"RequiredTriangles", 1},
    {"RequiredQuadrilaterals", 1},
    {"Normals", 0},
    {"Tangents", 0},
    {"NormalAtVertices", 2},
    {"TangentAtVertices", 2},
    {"TangentAtEdges", 3},
    {"NormalAtTriangleVertices", 3},
    {"NormalAtQuadrilateralVertices", 3},
};
#define N_SKIP_SECTIONS (sizeof skip_sections / sizeof skip_sections[0])

/* Cell kinds Medit knows but this tool does not subdivide. */
static const char *const unsupported[] = {"Prisms", "Pyramids",   "Pentatopes",
                                          "Edges2", "Triangles2", "Tetrahedra2"};

/* Largest cell or entry count accepted (far beyond any real mesh). */
#define MAX_CELLS (1LL << 40)

/* A first read never reserves more than this many entries on a header's word. */
#define TRUST_LIMIT 65536

static int looks_numeric(const char *tok) {
  return (tok[0] >= '0' && tok[0] <= '9') || tok[0] == '-' || tok[0] == '+' ||
         tok[0] == '.';
}

/* A section keyword, "End" or a header keyword: inside a section it means the
 * section was shorter than its count. */
static int is_keyword(const char *tok) {
  static const char *const heads[] = {"End", "Vertices", "Dimension",
                                      "MeshVersionFormatted"};
  for (size_t s = 0; s < sizeof heads / sizeof heads[0]; s++)
    if (!strcasecmp(tok, heads[s])) return 1;
  for (size_t s = 0; s < N_CELL_SECTIONS; s++)
    if (!strcasecmp(tok, cell_sections[s].kw)) return 1;
  for (size_t s = 0; s < N_SKIP_SECTIONS; s++)
    if (!strcasecmp(tok, skip_sections[s].kw)) return 1;
  for (size_t s = 0; s < sizeof unsupported / sizeof unsupported[0]; s++)
    if (!strcasecmp(tok, unsupported[s])) return 1;
  return 0;
}

/* The next token inside a section of `count` entries, of which `done` are
 * complete: NULL with a message on end of file or a keyword in the way. */
static char *entry_token(ss_lex *lx, const char *section, size_t done, size_t count,
                         ss_status *st) {
  char *tok = ss_lex_next(lx, st);
  if (*st) return NULL;
  if (!tok) {
    *st = ss_lex_fail(lx, "unexpected end of file in %s: %zu of %zu entries read",
                      section, done, count);
    return NULL;
  }
  if (is_keyword(tok)) {
    *st = ss_lex_fail(lx, "%s ends after %zu of %zu entries (found '%.40s')", section,
                      done, count, tok);
    return NULL;
  }
  return tok;
}

static ss_status read_count(ss_lex *lx, const char *section, long long max,
                            long long *n) {
  ss_status st;
  char *tok = ss_lex_next(lx, &st);
  if (st) return st;
  if (!tok) return ss_lex_fail(lx, "unexpected end of file: %s needs a count", section);
  char what[64];
  snprintf(what, sizeof what, "%s count", section);
  return ss_lex_int(lx, tok, what, 0, max, n);
}

static ss_status read_vertices(ss_lex *lx, ss_cx *cx) {
  long long n;
  ss_status st = read_count(lx, "Vertices", (long long)SS_IDX_NONE - 1, &n);
  if (st) return st;
  if ((st = ss_cx_reserve_vertices(cx, (size_t)(n < TRUST_LIMIT ? n : TRUST_LIMIT),
                                   lx->err)))
    return st;
  for (long long i = 0; i < n; i++) {
    double x[SS_MAXDIM];
    for (int k = 0; k < cx->dim; k++) {
      char *tok = entry_token(lx, "Vertices", (size_t)i, (size_t)n, &st);
      if (!tok) return st;
      if ((st = ss_lex_double(lx, tok, "coordinate", &x[k]))) return st;
    }
    long long ref;
    char *tok = entry_token(lx, "Vertices", (size_t)i, (size_t)n, &st);
    if (!tok) return st;
    if ((st = ss_lex_int(lx, tok, "vertex reference", INT32_MIN, INT32_MAX, &ref)))
      return st;
    if ((st = ss_cx_add_vertex(cx, x, (int32_t)ref, lx->err))) return st;
  }
  return SS_OK;
}

static ss_status read_cells(ss_lex *lx, ss_cx *cx, ss_cell_type t, const char *kw,
                            int has_ref, long dim_line) {
  if (ss_cell_dim(t) > cx->dim)
    return ss_lex_fail(lx,
                       "%s need Dimension %d or more, but line %ld says Dimension %d "
                       "(with fewer coordinates every cell is flat)",
                       kw, ss_cell_dim(t), dim_line, cx->dim);
  long long n;
  ss_status st = read_count(lx, kw, MAX_CELLS, &n);
  if (st) return st;
  size_t want = cx->nc[t] + (size_t)(n < TRUST_LIMIT ? n : TRUST_LIMIT);
  if ((st = ss_cx_reserve_cells(cx, t, want, lx->err))) return st;
  int nv = ss_cell_nverts(t);
  for (long long i = 0; i < n; i++) {
    ss_idx v[SS_MAXCELLVERTS];
    for (int k = 0; k < nv; k++) {
      char *tok = entry_token(lx, kw, (size_t)i, (size_t)n, &st);
      if (!tok) return st;
      long long id;
      if (cx->nv == 0)
        return ss_lex_fail(lx,
                           "%s %lld refers to vertex %.20s, but no vertices were read "
                           "before %s",
                           ss_cell_name(t), i + 1, tok, kw);
      char what[64];
      snprintf(what, sizeof what, "%s %lld: vertex index", ss_cell_name(t), i + 1);
      if ((st = ss_lex_int(lx, tok, what, 1, (long long)cx->nv, &id))) return st;
      v[k] = (ss_idx)(id - 1);
    }
    long long ref = 0;
    if (has_ref) {
      char *tok = entry_token(lx, kw, (size_t)i, (size_t)n, &st);
      if (!tok) return st;
      if ((st = ss_lex_int(lx, tok, "reference", INT32_MIN, INT32_MAX, &ref))) return st;
    }
    const char *defect = ss_cell_defect(t, v, cx->nv);
    if (defect) return ss_lex_fail(lx, "%s %lld is %s", ss_cell_name(t), i + 1, defect);
    if ((st = ss_cx_add_cell(cx, t, v, (int32_t)ref, lx->err))) return st;
  }
  return SS_OK;
}

static ss_status skip_section(ss_lex *lx, const char *kw, int width) {
  long long n;
  ss_status st = read_count(lx, kw, MAX_CELLS, &n);
  if (st) return st;
  for (long long i = 0; i < n; i++)
    for (int k = 0; k < width; k++) {
      char *tok = entry_token(lx, kw, (size_t)i, (size_t)n, &st);
      if (!tok) return st;
      double dummy;
      if ((st = ss_lex_double(lx, tok, kw, &dummy))) return st;
    }
  return SS_OK;
}

static ss_status parse(ss_lex *lx, ss_cx **cxp) {
  ss_status st;
  int dim = 0, have_vertices = 0;
  long dim_line = 0; /* line of the Dimension keyword */
  for (;;) {
    char *kw = ss_lex_next(lx, &st);
    if (st) return st;
    if (!kw || !strcasecmp(kw, "End")) break;
    if (!strcasecmp(kw, "MeshVersionFormatted")) {
      long long ver;
      char *tok = ss_lex_next(lx, &st);
      if (st) return st;
      if (!tok)
        return ss_lex_fail(lx, "unexpected end of file after MeshVersionFormatted");
      if ((st = ss_lex_int(lx, tok, "MeshVersionFormatted", 1, 4, &ver))) return st;
      continue;
    }
    if (!strcasecmp(kw, "Dimension")) {
      if (!dim_line) dim_line = lx->tok_line;
      long long d;
      char *tok = ss_lex_next(lx, &st);
      if (st) return st;
      if (!tok) return ss_lex_fail(lx, "unexpected end of file after Dimension");
      if ((st = ss_lex_int(lx, tok, "Dimension", 1, SS_MAXDIM, &d))) return st;
      if (dim && d != dim)
        return ss_lex_fail(lx, "Dimension %lld contradicts the earlier Dimension %d", d,
                           dim);
      if (!*cxp && (st = ss_cx_new((int)d, cxp, lx->err))) return st;
      dim = (int)d;
      continue;
    }
    if (!strcasecmp(kw, "Vertices")) {
      if (!dim) return ss_lex_fail(lx, "Vertices before Dimension");
      if (have_vertices) return ss_lex_fail(lx, "a second Vertices section");
      have_vertices = 1;
      if ((st = read_vertices(lx, *cxp))) return st;
      continue;
    }
    int known = 0;
    for (size_t s = 0; s < N_CELL_SECTIONS && !known; s++)
      if (!strcasecmp(kw, cell_sections[s].kw)) {
        known = 1;
        if (!dim) return ss_lex_fail(lx, "%s before Dimension", cell_sections[s].kw);
        if ((st = read_cells(lx, *cxp, cell_sections[s].type, cell_sections[s].kw,
                             cell_sections[s].has_ref, dim_line)))
          return st;
      }
    for (size_t s = 0; s < N_SKIP_SECTIONS && !known; s++)
      if (!strcasecmp(kw, skip_sections[s].kw)) {
        known = 1;
        if (!dim) return ss_lex_fail(lx, "%s before Dimension", skip_sections[s].kw);
        int w = skip_sections[s].width ? skip_sections[s].width : dim;
        if ((st = skip_section(lx, skip_sections[s].kw, w))) return st;
      }
    if (known) continue;
    for (size_t s = 0; s < sizeof unsupported / sizeof unsupported[0]; s++)
      if (!strcasecmp(kw, unsupported[s]))
        return ss_lex_fail(lx,
                           "%s are not supported (cells: Corners, Edges, Triangles, "
                           "Quadrilaterals, Tetrahedra, Hexahedra, Octahedra)",
                           unsupported[s]);
    if (looks_numeric(kw))
      return ss_lex_fail(lx,
                         "number '%.40s' where a keyword was expected (a section with "
                         "more entries than its count?)",
                         kw);
    return ss_lex_fail(lx, "unknown keyword '%.40s'", kw);
  }
  if (!dim) return ss_lex_fail(lx, "no Dimension: not a Medit mesh");
  if (!have_vertices) return ss_lex_fail(lx, "no Vertices section");
  return SS_OK;
}

ss_status ss_mesh_read_medit(FILE *f, const char *name, ss_cx **out, ss_error *err) {
  ss_lex lx;
  ss_lex_init(&lx, f, name, 1, err);
  *out = NULL;
  ss_cx *cx = NULL;
  ss_status st = parse(&lx, &cx);
  ss_lex_done(&lx);
  if (st) {
    ss_cx_free(cx);
    return st;
  }
  *out = cx;
  return SS_OK;
}

/* ---- writer ---- */

/* The four tets of an octahedron about its 0-3 diagonal, each positive when
 * the octahedron is (ss_cx.h conventions). */
static const int oct_tets[4][4] = {
    {3, 0, 1, 2}, {3, 0, 2, 4}, {3, 0, 4, 5}, {3, 0, 5, 1}};

static const char *section_of(ss_cell_type t) {
  for (size_t s = 0; s < N_CELL_SECTIONS; s++)
    if (cell_sections[s].type == t) return cell_sections[s].kw;
  return "Unknown"; /* unreachable: every type has a section */
}

static void write_cells(FILE *f, const ss_cx *cx, ss_cell_type t) {
  int nv = ss_cell_nverts(t);
  for (size_t i = 0; i < cx->nc[t]; i++) {
    const ss_idx *v = ss_cx_cell(cx, t, i);
    for (int k = 0; k < nv; k++)
      fprintf(f, "%s%lu", k ? " " : "", (unsigned long)v[k] + 1);
    if (t != SS_VERTEX) fprintf(f, " %ld", (long)cx->cref[t][i]);
    fputc('\n', f);
  }
}

ss_status ss_mesh_write_medit(FILE *f, const ss_cx *cx, const ss_mesh_write_opts *opts,
                              ss_error *err) {
  const int split = !(opts && opts->octahedra_keyword);
  fprintf(f, "MeshVersionFormatted 2\n\nDimension %d\n\nVertices\n%zu\n", cx->dim,
          cx->nv);
  for (size_t i = 0; i < cx->nv; i++) {
    for (int k = 0; k < cx->dim; k++)
      fprintf(f, "%.17g ", cx->x[i * (size_t)cx->dim + k]);
    fprintf(f, "%ld\n", (long)cx->vref[i]);
  }
  /* Octahedra written split join the Tetrahedra section. */
  size_t extra_tets = split ? 4 * cx->nc[SS_OCT] : 0;
  static const ss_cell_type order[] = {SS_VERTEX, SS_SEGMENT, SS_TRIANGLE, SS_QUAD,
                                       SS_TET,    SS_HEX,     SS_OCT};
  for (size_t o = 0; o < sizeof order / sizeof order[0]; o++) {
    ss_cell_type t = order[o];
    size_t n = cx->nc[t] + (t == SS_TET ? extra_tets : 0);
    if (t == SS_OCT && split) continue;
    if (!n) continue;
    fprintf(f, "\n%s\n%zu\n", section_of(t), n);
    write_cells(f, cx, t);
    if (t == SS_TET && split)
      for (size_t i = 0; i < cx->nc[SS_OCT]; i++) {
        const ss_idx *v = ss_cx_cell(cx, SS_OCT, i);
        for (int j = 0; j < 4; j++)
          fprintf(f, "%lu %lu %lu %lu %ld\n", (unsigned long)v[oct_tets[j][0]] + 1,
                  (unsigned long)v[oct_tets[j][1]] + 1,
                  (unsigned long)v[oct_tets[j][2]] + 1,
                  (unsigned long)v[oct_tets[j][3]] + 1, (long)cx->cref[SS_OCT][i]);
      }
  }
  fprintf(f, "\nEnd\n");
  if (ferror(f)) return ss_error_set(err, SS_EIO, "write error");
  return SS_OK;
}
