/* ss_mesh_gmsh_scan.c — the structure a gmsh .msh file declares, checked by a
 * scan of our own before gmsh reads it (ss_mesh_gmsh_scan.h says why).
 *
 * The layouts are those of gmsh's manual, "MSH file format" (version 4.1)
 * and "Legacy formats" (version 2).  ASCII sections are read line by line: an
 * element is one line, of exactly the tokens its type needs; blank lines are
 * skipped.  Binary sections are read as the manual's records (int = 4 bytes,
 * size_t and double = 8), in the byte order the $MeshFormat's integer 1
 * shows; their numbers are counted, not interpreted.  A line is read whole up
 * to LINE_CAP bytes: longer ones are refused where a line is expected and
 * skipped inside a section that is only required to end. */
#include "ss_mesh_gmsh_scan.h"

#include <errno.h>
#include <inttypes.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define LINE_CAP 4096                /* bytes of a line read whole */
#define MAXTOK   300                 /* tokens of an ASCII line looked at */
#define MAXTAGS  256                 /* tags of a version 2 element */
#define BIG      (UINT64_C(1) << 62) /* counts beyond this are refused */

/* The state of one scan. */
typedef struct {
  FILE *f;               /* the file (owned) */
  const char *path;      /* its name, for messages */
  ss_error *err;         /* where a failure goes */
  long line;             /* the line being read (1-based; binary data counted too) */
  int binary;            /* data sections are binary */
  int swap;              /* binary numbers are in the other byte order */
  int longline;          /* the last line was longer than LINE_CAP - 1 bytes */
  const char *sec;       /* the section being read ("$Nodes"), "" outside */
  char buf[LINE_CAP];    /* the last line, NUL-terminated, without \r\n */
  size_t len;            /* its length (it may hold NUL bytes) */
  char q[4 * 60 + 4];    /* the start of it quoted (quote) */
  char tb[LINE_CAP];     /* its copy cut into tokens */
  char *tok[MAXTOK + 1]; /* the tokens of tb */
} scan;

int ss_mesh_gmsh_cell_type(int gt, ss_cell_type *t) {
  switch (gt) {
  case 15: /* 1-node point */
    *t = SS_VERTEX;
    return 1;
  case 1: /* 2-node line */
    *t = SS_SEGMENT;
    return 1;
  case 2: /* 3-node triangle */
    *t = SS_TRIANGLE;
    return 1;
  case 3: /* 4-node quadrangle */
    *t = SS_QUAD;
    return 1;
  case 4: /* 4-node tetrahedron: corner order and orientation as ss_cx.h */
    *t = SS_TET;
    return 1;
  case 5: /* 8-node hexahedron: bottom 0-3, top 4-7 above them, as ss_cx.h */
    *t = SS_HEX;
    return 1;
  default:
    return 0;
  }
}

const char *ss_mesh_gmsh_type_name(int gt) {
  /* gmsh 4.8's names (gmshModelMeshGetElementProperties) */
  static const char *const names[] = {NULL,
                                      "Line 2",
                                      "Triangle 3",
                                      "Quadrilateral 4",
                                      "Tetrahedron 4",
                                      "Hexahedron 8",
                                      "Prism 6",
                                      "Pyramid 5",
                                      "Line 3",
                                      "Triangle 6",
                                      "Quadrilateral 9",
                                      "Tetrahedron 10",
                                      "Hexahedron 27",
                                      "Prism 18",
                                      "Pyramid 14",
                                      "Point",
                                      "Quadrilateral 8",
                                      "Hexahedron 20",
                                      "Prism 15",
                                      "Pyramid 13",
                                      "Triangle 9",
                                      "Triangle 10",
                                      "Triangle 12",
                                      "Triangle 15",
                                      "Triangle 15I",
                                      "Triangle 21",
                                      "Line 4",
                                      "Line 5",
                                      "Line 6",
                                      "Tetrahedron 20",
                                      "Tetrahedron 35",
                                      "Tetrahedron 56",
                                      "Tetrahedron 22",
                                      "Tetrahedron 28",
                                      "Polygon",
                                      "Polyhedron",
                                      "Quadrilateral 16",
                                      "Quadrilateral 25"};
  if (gt > 0 && gt < (int)(sizeof names / sizeof *names)) return names[gt];
  return gt == 69   ? "Polygon Border"
         : gt == 92 ? "Hexahedron 64"
         : gt == 93 ? "Hexahedron 125"
                    : NULL;
}

/* Fail with "path:LINE: $Section: problem". */
static ss_status fail(scan *s, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
static ss_status fail(scan *s, const char *fmt, ...) {
  char msg[400];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  return ss_error_set(s->err, SS_EINPUT, "%s:%ld: %s%s%s", s->path, s->line, s->sec,
                      *s->sec ? ": " : "", msg);
}

/* The next line into s->buf (s->len bytes, NUL bytes kept): 1, or 0 at the
 * end of the file. */
static int get_line(scan *s) {
  size_t n = 0;
  int c = getc(s->f);
  s->longline = 0;
  if (c == EOF) return 0;
  s->line++;
  while (c != EOF && c != '\n') {
    if (n + 1 < LINE_CAP)
      s->buf[n++] = (char)c;
    else
      s->longline = 1;
    c = getc(s->f);
  }
  if (n && s->buf[n - 1] == '\r') n--;
  s->buf[n] = '\0';
  s->len = n;
  return 1;
}

/* The line is exactly text (a NUL byte in it never matches). */
static int is(const scan *s, const char *text) {
  return !s->longline && s->len == strlen(text) && !memcmp(s->buf, text, s->len);
}

/* The start of the line, escaped for a message (NUL bytes too), in s->q. */
static const char *quote(scan *s) {
  static const char hex[] = "0123456789abcdef";
  size_t k = 0;
  for (size_t i = 0; i < s->len && i < 60; i++) {
    const unsigned char c = (unsigned char)s->buf[i];
    if (c >= 0x20 && c < 0x7f) {
      s->q[k++] = (char)c;
    } else {
      s->q[k++] = '\\';
      s->q[k++] = 'x';
      s->q[k++] = hex[c >> 4];
      s->q[k++] = hex[c & 15];
    }
  }
  if (s->len > 60 || s->longline) memcpy(s->q + k, "...", 3), k += 3;
  s->q[k] = '\0';
  return s->q;
}

/* The line holds only white space. */
static int blank(const scan *s) {
  return !s->longline && strspn(s->buf, " \t\r\v\f") == s->len;
}

/* Cut a copy of the line into s->tok; their number (MAXTOK + 1: more). */
static int tokens(scan *s) {
  for (size_t i = 0; i <= s->len; i++) /* a NUL byte inside is junk, not an end */
    s->tb[i] = i < s->len && !s->buf[i] ? '\x01' : s->buf[i];
  int n = 0;
  char *save = NULL; /* strtok_r: strtok's hidden static broke concurrent reads */
  for (char *p = strtok_r(s->tb, " \t\r\v\f", &save); p;
       p = strtok_r(NULL, " \t\r\v\f", &save)) {
    if (n == MAXTOK) return MAXTOK + 1;
    s->tok[n++] = p;
  }
  return n;
}

/* The next non-blank line of a data section and its tokens: the number of
 * tokens, or -1 after failing (the file ends, the line is too long, or a
 * section line comes first): `what` says what was expected. */
static int data_line(scan *s, const char *what) {
  do {
    if (!get_line(s)) {
      fail(s, "the file ends where %s is expected", what);
      return -1;
    }
  } while (blank(s));
  if (s->longline) {
    fail(s, "a line of over %d bytes where %s is expected", LINE_CAP - 1, what);
    return -1;
  }
  if (s->buf[0] == '$') {
    fail(s, "%s expected, found '%s'", what, quote(s));
    return -1;
  }
  return tokens(s);
}

/* A count: decimal digits only, below BIG. */
static int count_of(const char *t, uint64_t *out) {
  if (!*t || strspn(t, "0123456789") != strlen(t) || strlen(t) > 18) return 0;
  *out = strtoull(t, NULL, 10);
  return *out < BIG;
}

/* An int: an optional '-' and decimal digits, within int's range. */
static int int_of(const char *t, int *out) {
  const char *d = t + (*t == '-');
  if (!*d || strspn(d, "0123456789") != strlen(d) || strlen(d) > 10) return 0;
  const long long v = strtoll(t, NULL, 10);
  if (v < INT32_MIN || v > INT32_MAX) return 0;
  *out = (int)v;
  return 1;
}

/* A number as strtod reads it, whole token. */
static int number_of(const char *t) {
  char *end;
  (void)strtod(t, &end);
  return end != t && !*end;
}

/* The line s->tok holds (n tokens) is a single count: into *out. */
static ss_status count_line(scan *s, int n, const char *what, uint64_t *out) {
  if (n < 0) return SS_EINPUT;
  if (n != 1 || !count_of(s->tok[0], out))
    return fail(s, "%s (one number) expected, found '%s'", what, quote(s));
  return SS_OK;
}

/* The next non-blank line is `end`. */
static ss_status end_line(scan *s, const char *end, const char *after) {
  do {
    if (!get_line(s))
      return fail(s, "the file ends where '%s' is expected %s", end, after);
  } while (blank(s));
  if (!is(s, end)) return fail(s, "'%s' expected %s, found '%s'", end, after, quote(s));
  return SS_OK;
}

/* Skip the rest of section `name` (its "$Name" line read): up to its $End line. */
static ss_status skip_section(scan *s, const char *name) {
  char end[80];
  snprintf(end, sizeof end, "$End%.70s", name + 1);
  while (get_line(s))
    if (is(s, end)) return SS_OK;
  return fail(s, "the file ends before '%s'", end);
}

/* ---- binary records ---- */

/* n bytes into p (newlines counted as lines). */
static ss_status rd(scan *s, void *p, size_t n, const char *what) {
  const size_t got = fread(p, 1, n, s->f);
  for (const char *c = p, *e = c + got; (c = memchr(c, '\n', (size_t)(e - c))); c++)
    s->line++;
  if (got == n) return SS_OK;
  if (ferror(s->f))
    return ss_error_set(s->err, SS_EIO, "%s: %s", s->path, strerror(errno));
  return fail(s, "the file ends inside %s", what);
}

static ss_status rd_int(scan *s, int32_t *v, const char *what) {
  uint32_t u;
  ss_status st = rd(s, &u, sizeof u, what);
  if (s->swap) u = __builtin_bswap32(u);
  memcpy(v, &u, sizeof u);
  return st;
}

static ss_status rd_size(scan *s, uint64_t *v, const char *what) {
  ss_status st = rd(s, v, sizeof *v, what);
  if (s->swap) *v = __builtin_bswap64(*v);
  return st;
}

/* Skip n records of `rec` bytes. */
static ss_status skip(scan *s, uint64_t n, uint64_t rec, const char *what) {
  char chunk[8192];
  if (rec && n > BIG / rec) return fail(s, "%" PRIu64 " %s: too many", n, what);
  ss_status st = SS_OK;
  for (uint64_t left = n * rec; left && !st;
       left -= left < sizeof chunk ? left : sizeof chunk)
    st = rd(s, chunk, left < sizeof chunk ? (size_t)left : sizeof chunk, what);
  return st;
}

/* ---- element types ---- */

/* Gmsh type gt of `where` is a cell here: its type in *ct; else fail. */
static ss_status supported(scan *s, int gt, ss_cell_type *ct, const char *where) {
  if (ss_mesh_gmsh_cell_type(gt, ct)) return SS_OK;
  const char *name = ss_mesh_gmsh_type_name(gt);
  return fail(s,
              "%s is of gmsh type %d%s%s%s, which has no cell here (read: points, "
              "lines, triangles, quadrangles, tetrahedra, hexahedra, of first order)",
              where, gt, name ? " (" : "", name ? name : "", name ? ")" : "");
}

/* ---- version 2: $Nodes N, N nodes; $Elements M, M elements ---- */

static ss_status nodes_v2(scan *s, int parametric, ss_gmsh_decl *d) {
  uint64_t n = 0;
  ss_status st =
      count_line(s, data_line(s, "the number of nodes"), "the number of nodes", &n);
  if (st) return st;
  if (s->binary) {
    if (parametric) return fail(s, "binary parametric nodes are not read");
    st = skip(s, n, 4 + 3 * 8, "the nodes (int tag, 3 doubles each)");
  }
  for (uint64_t i = 0; i < n && !s->binary; i++) {
    char what[80];
    snprintf(what, sizeof what, "node %" PRIu64 " of the %" PRIu64 " declared", i + 1, n);
    const int k = data_line(s, what);
    if (k < 0) return SS_EINPUT;
    uint64_t tag;
    int ok = (parametric ? k >= 4 : k == 4) && count_of(s->tok[0], &tag);
    for (int j = 1; j < 4 && ok; j++)
      ok = number_of(s->tok[j]);
    if (!ok) return fail(s, "%s: 'TAG X Y Z' expected, found '%s'", what, quote(s));
  }
  d->nodes = n;
  char after[80];
  snprintf(after, sizeof after, "after the %" PRIu64 " nodes declared", n);
  return st ? st : end_line(s, parametric ? "$EndParametricNodes" : "$EndNodes", after);
}

/* One ASCII version 2 element line, element i of m: its type counted in d. */
static ss_status element_v2(scan *s, uint64_t i, uint64_t m, ss_gmsh_decl *d) {
  char what[80];
  snprintf(what, sizeof what, "element %" PRIu64 " of the %" PRIu64 " declared", i + 1,
           m);
  const int k = data_line(s, what);
  if (k < 0) return SS_EINPUT;
  uint64_t tag, ntags;
  int gt;
  ss_cell_type ct;
  if (k < 3 || !count_of(s->tok[0], &tag) || !int_of(s->tok[1], &gt) ||
      !count_of(s->tok[2], &ntags) || ntags > MAXTAGS)
    return fail(s, "%s: 'TAG TYPE NTAGS TAGS... NODES...' expected, found '%s'", what,
                quote(s));
  ss_status st = supported(s, gt, &ct, what);
  if (st) return st;
  const int nv = ss_cell_nverts(ct);
  if ((uint64_t)k != 3 + ntags + (uint64_t)nv)
    return fail(s,
                "%s (gmsh type %d, a %s) lists %" PRId64 " nodes after its %" PRIu64
                " tags; a %s has %d",
                what, gt, ss_cell_name(ct), (int64_t)k - 3 - (int64_t)ntags, ntags,
                ss_cell_name(ct), nv);
  for (int j = 3; j < k; j++)
    if (!count_of(s->tok[j], &tag))
      return fail(s, "%s: '%.30s' is not a tag or a node", what, s->tok[j]);
  d->cells[ct]++;
  return SS_OK;
}

/* Binary version 2 elements: blocks of (type, count, ntags), m in all. */
static ss_status elements_v2_binary(scan *s, uint64_t m, ss_gmsh_decl *d) {
  ss_status st = SS_OK;
  for (uint64_t got = 0; got < m && !st;) {
    int32_t gt, cnt, ntags;
    ss_cell_type ct;
    char where[120];
    if ((st = rd_int(s, &gt, "an element block header")) ||
        (st = rd_int(s, &cnt, "an element block header")) ||
        (st = rd_int(s, &ntags, "an element block header")))
      return st;
    snprintf(where, sizeof where,
             "the block of %d elements after %" PRIu64 " of the %" PRIu64 " declared",
             cnt, got, m);
    if (cnt < 1 || (uint64_t)cnt > m - got || ntags < 0 || ntags > MAXTAGS)
      return fail(s, "%s: %d elements with %d tags each do not fit", where, cnt, ntags);
    if ((st = supported(s, gt, &ct, where))) return st;
    st = skip(s, (uint64_t)cnt, 4 * (1 + (uint64_t)ntags + (uint64_t)ss_cell_nverts(ct)),
              "the elements");
    d->cells[ct] += (size_t)cnt;
    got += (uint64_t)cnt;
  }
  return st;
}

static ss_status elements_v2(scan *s, ss_gmsh_decl *d) {
  uint64_t m = 0;
  ss_status st =
      count_line(s, data_line(s, "the number of elements"), "the number of elements", &m);
  if (st) return st;
  if (s->binary) st = elements_v2_binary(s, m, d);
  for (uint64_t i = 0; i < m && !st && !s->binary; i++)
    st = element_v2(s, i, m, d);
  if (st) return st;
  d->elements = m;
  char after[80];
  snprintf(after, sizeof after, "after the %" PRIu64 " elements declared", m);
  return end_line(s, "$EndElements", after);
}

/* ---- version 4.1: a header (blocks, total, min tag, max tag), then entity
 * blocks (dim, tag, parametric or type, count) ---- */

/* The four numbers of a header or block line, ASCII or binary: h[0..3] (a
 * block's first three are ints in binary). */
static ss_status four(scan *s, int block, const char *what, uint64_t h[4]) {
  ss_status st = SS_OK;
  if (s->binary) {
    for (int j = 0; j < 4 && !st; j++) {
      int32_t v = 0;
      if (block && j < 3) {
        st = rd_int(s, &v, what);
        h[j] = (uint64_t)(int64_t)v;
      } else {
        st = rd_size(s, h + j, what);
      }
    }
    return st;
  }
  const int k = data_line(s, what);
  if (k < 0) return SS_EINPUT;
  int ok = k == 4;
  for (int j = 0; j < 4 && ok; j++) {
    int v = 0;
    if (block && j < 3) {
      ok = int_of(s->tok[j], &v);
      h[j] = (uint64_t)(int64_t)v;
    } else {
      ok = count_of(s->tok[j], h + j);
    }
  }
  return ok ? SS_OK : fail(s, "%s (four numbers) expected, found '%s'", what, quote(s));
}

/* n ASCII lines of `ntok` tokens each: tags or elements (integers > 0 and
 * node tags), or coordinates (numbers); `what` names one, in block b. */
static ss_status lines_of(scan *s, uint64_t n, int ntok, int integers, const char *what,
                          uint64_t b) {
  for (uint64_t i = 0; i < n; i++) {
    char w[120];
    uint64_t v;
    snprintf(w, sizeof w, "%s %" PRIu64 " of %" PRIu64 " in entity block %" PRIu64, what,
             i + 1, n, b + 1);
    const int k = data_line(s, w);
    if (k < 0) return SS_EINPUT;
    int ok = k == ntok;
    for (int j = 0; j < k && ok; j++)
      ok = integers ? count_of(s->tok[j], &v) : number_of(s->tok[j]);
    if (!ok)
      return fail(s, "%s: %d %s expected, found '%s'", w, ntok,
                  integers ? "tags" : "numbers", quote(s));
  }
  return SS_OK;
}

/* After the entity blocks of a 4.1 section (header h, total items in the
 * blocks): the total is the header's, and `end` follows. */
static ss_status blocks_end(scan *s, const uint64_t h[4], uint64_t total,
                            const char *what, const char *end) {
  if (total != h[1])
    return fail(s,
                "the %" PRIu64 " entity blocks hold %" PRIu64
                " %s; the header declares %" PRIu64,
                h[0], total, what, h[1]);
  char after[80];
  snprintf(after, sizeof after, "after the %" PRIu64 " entity blocks declared", h[0]);
  return end_line(s, end, after);
}

static ss_status nodes_v41(scan *s, ss_gmsh_decl *d) {
  uint64_t h[4], b[4], total = 0;
  ss_status st = four(s, 0, "the header 'BLOCKS NODES MINTAG MAXTAG'", h);
  for (uint64_t i = 0; i < h[0] && !st; i++) {
    char what[80];
    snprintf(what, sizeof what, "entity block %" PRIu64 " of %" PRIu64, i + 1, h[0]);
    if ((st = four(s, 1, what, b))) break;
    const int dim = (int)(int64_t)b[0];
    if (dim < 0 || dim > 3 || b[2] > 1 || b[3] > h[1] - total)
      return fail(s,
                  "%s: dimension %d, parametric %" PRIu64 ", %" PRIu64
                  " nodes (of %" PRIu64 " left)",
                  what, dim, b[2], b[3], h[1] - total);
    const int ncoord = 3 + (b[2] ? dim : 0);
    if (s->binary)
      st = skip(s, b[3], 8 * (1 + (uint64_t)ncoord), "the nodes of an entity block");
    else if (!(st = lines_of(s, b[3], 1, 1, "node tag", i)))
      st = lines_of(s, b[3], ncoord, 0, "node coordinates", i);
    total += b[3];
  }
  if (st) return st;
  d->nodes = h[1];
  return blocks_end(s, h, total, "nodes", "$EndNodes");
}

static ss_status elements_v41(scan *s, ss_gmsh_decl *d) {
  uint64_t h[4], b[4], total = 0;
  ss_status st = four(s, 0, "the header 'BLOCKS ELEMENTS MINTAG MAXTAG'", h);
  for (uint64_t i = 0; i < h[0] && !st; i++) {
    char what[80];
    ss_cell_type ct;
    snprintf(what, sizeof what, "entity block %" PRIu64 " of %" PRIu64, i + 1, h[0]);
    if ((st = four(s, 1, what, b))) break;
    const int dim = (int)(int64_t)b[0];
    if (dim < 0 || dim > 3 || b[3] > h[1] - total)
      return fail(s, "%s: dimension %d, %" PRIu64 " elements (of %" PRIu64 " left)", what,
                  dim, b[3], h[1] - total);
    if ((st = supported(s, (int)(int64_t)b[2], &ct, what))) break;
    const int nv = ss_cell_nverts(ct);
    if (s->binary)
      st = skip(s, b[3], 8 * (1 + (uint64_t)nv), "the elements of an entity block");
    else
      st = lines_of(s, b[3], 1 + nv, 1, "element", i);
    d->cells[ct] += (size_t)b[3];
    total += b[3];
  }
  if (st) return st;
  d->elements = h[1];
  return blocks_end(s, h, total, "elements", "$EndElements");
}

/* ---- $MeshFormat, then the sections ---- */

/* "$MeshFormat", "VERSION TYPE SIZE", in binary the integer 1 on a line of its
 * own, "$EndMeshFormat". */
static ss_status mesh_format(scan *s, ss_gmsh_decl *d) {
  s->sec = "$MeshFormat";
  if (!get_line(s) || !is(s, "$MeshFormat"))
    return fail(s, "'$MeshFormat' expected on the first line");
  int type, size;
  double ver;
  if (!get_line(s) || s->longline || tokens(s) != 3 || !number_of(s->tok[0]) ||
      !int_of(s->tok[1], &type) || !int_of(s->tok[2], &size) || (type != 0 && type != 1))
    return fail(s, "'VERSION 0|1 DATA-SIZE' expected");
  ver = strtod(s->tok[0], NULL);
  d->version = (int)ver;
  if (d->version != 2 && d->version != 4) return fail(s, "version %.20s", s->tok[0]);
  if (d->version == 4 && ver < 4.05) /* (ss_mesh_gmsh.c refuses it first) */
    return fail(s,
                "MSH 4.0 is not supported; re-save as 4.1 (gmsh -format msh41) or 2.2");
  d->binary = s->binary = type;
  if (s->binary) {
    uint32_t one;
    ss_status st = rd(s, &one, sizeof one, "the binary check (the integer 1)");
    if (st) return st;
    if (size != 8) return fail(s, "data-size %d: binary files are read with 8", size);
    if (one != 1 && __builtin_bswap32(one) != 1)
      return fail(s, "the file says binary (file-type 1), but the 4 bytes after that "
                     "line are not the integer 1 (an ASCII file marked binary?)");
    s->swap = one != 1;
    if (!get_line(s) || s->buf[0])
      return fail(s, "the integer 1 of a binary file must end its line");
  }
  return end_line(s, "$EndMeshFormat", "after the format");
}

/* One section whose "$Name" line was just read. */
static ss_status section(scan *s, ss_gmsh_decl *d, int *seen) {
  if (is(s, "$Nodes") || is(s, "$ParametricNodes")) {
    const int par = s->buf[1] == 'P';
    s->sec = par ? "$ParametricNodes" : "$Nodes";
    if (seen[0]++) return fail(s, "a second node section");
    if (par && d->version != 2) return fail(s, "parametric nodes are read in version 2");
    return d->version == 2 ? nodes_v2(s, par, d) : nodes_v41(s, d);
  }
  if (is(s, "$Elements")) {
    s->sec = "$Elements";
    if (seen[1]++) return fail(s, "a second $Elements section");
    if (!seen[0]) return fail(s, "elements before any nodes");
    return d->version == 2 ? elements_v2(s, d) : elements_v41(s, d);
  }
  static const char word[] =
      "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_";
  if (s->longline || s->len < 2 || s->len > 70 || s->buf[0] != '$' ||
      strspn(s->buf + 1, word) != s->len - 1 || !strncmp(s->buf, "$End", 4) ||
      is(s, "$MeshFormat"))
    return fail(s, "'%s' where a section ('$Name') should begin", quote(s));
  s->sec = "";
  char sec[80];
  snprintf(sec, sizeof sec, "%.70s", s->buf);
  return skip_section(s, sec);
}

ss_status ss_mesh_gmsh_scan(const char *path, ss_gmsh_decl *decl, ss_error *err) {
  memset(decl, 0, sizeof *decl);
  scan *s = calloc(1, sizeof *s);
  if (!s) return ss_error_nomem(err, "gmsh scan");
  *s = (scan){.path = path, .err = err, .sec = ""};
  s->f = fopen(path, "rb");
  if (!s->f) {
    const int e = errno;
    free(s);
    return ss_error_set(err, SS_EIO, "%s: %s", path, strerror(e));
  }
  int seen[2] = {0, 0};
  ss_status st = mesh_format(s, decl);
  while (!st && get_line(s)) {
    if (blank(s)) continue;
    st = section(s, decl, seen);
    s->sec = "";
  }
  if (!st && ferror(s->f))
    st = ss_error_set(err, SS_EIO, "%s: %s", path, strerror(errno));
  if (!st && !seen[0])
    st = fail(s, "no $Nodes section: an empty mesh");
  else if (!st && !seen[1])
    st = fail(s, "no $Elements section: the %zu nodes make no cells", decl->nodes);
  else if (!st && !decl->elements)
    st = fail(s, "$Elements declares no elements: a mesh needs cells");
  fclose(s->f);
  free(s);
  return st;
}
