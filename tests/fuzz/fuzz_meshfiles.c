/* fuzz_meshfiles.c — structure-aware fuzzer of the gmsh and TetGen readers
 * (issue 35): files that lie about their counts, are cut, or have bytes
 * flipped must be refused or read whole, never read with cells lost.
 *
 *   fuzz_meshfiles [--seed S] [--iterations N] [--max-seconds T] [--only I]
 *                  [--dump]
 *
 * Iteration i (a generator seeded by (S, i) alone, so `--only I` replays it)
 * writes a random honest mesh, a grid of 1..3 x 1..2 x 1..2 cubes as
 * hexahedra or as 6 tetrahedra each (coordinates multiples of 1/2), in one
 * of five forms: gmsh version 2 or 4.1, ASCII or binary (the 4.1 elements in
 * two entity blocks), or TetGen .node/.ele (tetrahedra).  Then one change:
 *   none     the honest file: it must read as exactly that mesh;
 *   lie      a declared count (of nodes, elements, entity blocks or a block's
 *            elements) one more, one less or 0: it must be refused;
 *   nodes    an element line with one node more or less (ASCII): refused;
 *   cut      the file cut at a random byte or line end;
 *   flip     1..3 bytes set to random values;
 *   line     a line deleted or repeated.
 * After cut, flip and line the file may still be a mesh; then it must hold
 * every cell of the honest one (no fewer, no more).  A refusal must be
 * SS_EINPUT or SS_EIO with a message naming the file (for TetGen, the .node
 * or the .ele).  A crash of gmsh is
 * contained by its child process (counted); a crash of our own code kills
 * the run (under ASan, with a report).  Exit 0 if every check held, 1 if
 * not (each failure prints its seed and iteration), 2 on bad usage. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include <gsl/gsl_rng.h>

#include "fuzz_mutate.h"
#include "ss_mesh.h"

enum { GMSH2A, GMSH2B, GMSH41A, GMSH41B, TETGEN, NFORMS };
static const char *const form_name[NFORMS] = {
    "gmsh v2 ASCII", "gmsh v2 binary", "gmsh v4.1 ASCII", "gmsh v4.1 binary", "TetGen"};
enum { NONE, LIE, NODES, CUT, FLIP, LINE, NCHANGES };
static const char *const change_name[NCHANGES] = {"none", "lie",  "nodes",
                                                  "cut",  "flip", "line"};

#define MAXCOUNTS 8

/* A declared count in a file: where, and how it is written. */
typedef struct {
  size_t off; /* first byte */
  size_t len; /* bytes (ASCII digits, or 4 / 8 binary) */
  int binary; /* 1: a little-endian integer of len bytes */
  int file;   /* 0: the .msh or .node, 1: the .ele */
} count_at;

/* One generated input: one file, or a TetGen pair. */
typedef struct {
  fz_buf f[2];                /* the files' bytes */
  int nfiles;                 /* 1 or 2 */
  count_at counts[MAXCOUNTS]; /* declared counts found by the writer */
  int ncounts;                /* how many */
  size_t elem_off[2], elem_n; /* where the element lines start (file f[elem_file]) */
  int elem_file;              /* the file holding the element lines */
} input;

/* The honest mesh. */
typedef struct {
  int hex;          /* hexahedra (else tetrahedra) */
  int n[3];         /* cubes per axis */
  size_t nv, nc;    /* vertices, cells */
  double x[48 * 3]; /* coordinates of vertex k (node tag k + 1) */
  int c[72][8];     /* cells, 1-based node tags */
} mesh;

static void make_mesh(gsl_rng *r, int hex, mesh *m) {
  m->hex = hex;
  m->n[0] = 1 + (int)gsl_rng_uniform_int(r, 3);
  m->n[1] = 1 + (int)gsl_rng_uniform_int(r, 2);
  m->n[2] = 1 + (int)gsl_rng_uniform_int(r, 2);
  const int px = m->n[0] + 1, py = m->n[1] + 1;
  m->nv = (size_t)px * (size_t)py * (size_t)(m->n[2] + 1);
  for (size_t k = 0; k < m->nv; k++) {
    m->x[3 * k] = (double)(k % (size_t)px) / 2;
    m->x[3 * k + 1] = (double)(k / (size_t)px % (size_t)py) / 2;
    m->x[3 * k + 2] = (double)(k / (size_t)(px * py)) / 2;
  }
  /* the 6 positive tetrahedra of a cube along its diagonal 0-7 (corner bits
   * x = 1, y = 2, z = 4), each a path 0, a, a + b, 7 through the axes */
  static const int path[6][4] = {{0, 1, 3, 7}, {0, 2, 6, 7}, {0, 4, 5, 7},
                                 {0, 3, 2, 7}, {0, 6, 4, 7}, {0, 5, 1, 7}};
  static const int hexc[8] = {0, 1, 3, 2, 4, 5, 7, 6}; /* ss_cx order: bits */
  m->nc = 0;
  for (int k = 0; k < m->n[2]; k++)
    for (int j = 0; j < m->n[1]; j++)
      for (int i = 0; i < m->n[0]; i++) {
        int tag[8];
        for (int b = 0; b < 8; b++)
          tag[b] = 1 + (i + (b & 1)) + px * (j + (b >> 1 & 1)) + px * py * (k + (b >> 2));
        if (hex) {
          for (int c = 0; c < 8; c++)
            m->c[m->nc][c] = tag[hexc[c]];
          m->nc++;
        }
        for (int t = 0; t < 6 && !hex; t++, m->nc++)
          for (int c = 0; c < 4; c++)
            m->c[m->nc][c] = tag[path[t][c]];
      }
}

/* ---- writers ---- */

static void put(fz_buf *b, const void *p, size_t n) {
  if (b->len + n + 1 > b->cap) {
    size_t cap = 2 * (b->len + n + 1);
    char *d = realloc(b->data, cap);
    if (!d) abort(); /* a test program: out of memory ends it */
    b->data = d;
    b->cap = cap;
  }
  memcpy(b->data + b->len, p, n);
  b->len += n;
  b->data[b->len] = '\0';
}

static void puts_(fz_buf *b, const char *s) {
  put(b, s, strlen(s));
}

/* An integer written as text (ASCII) or 4 / 8 bytes, recorded as a count
 * when in is not NULL. */
static void num(fz_buf *b, input *in, int file, uint64_t v, int width) {
  const size_t off = b->len;
  if (width) {
    const uint32_t v4 = (uint32_t)v;
    put(b, width == 4 ? (const void *)&v4 : (const void *)&v, (size_t)width);
  } else {
    char t[24];
    snprintf(t, sizeof t, "%llu", (unsigned long long)v);
    puts_(b, t);
  }
  if (in && in->ncounts < MAXCOUNTS)
    in->counts[in->ncounts++] = (count_at){off, b->len - off, width != 0, file};
}

static void coords(fz_buf *b, const mesh *m, size_t k, int bin) {
  if (bin) {
    put(b, m->x + 3 * k, 3 * sizeof(double));
  } else {
    char t[80];
    snprintf(t, sizeof t, "%g %g %g\n", m->x[3 * k], m->x[3 * k + 1], m->x[3 * k + 2]);
    puts_(b, t);
  }
}

static void gmsh_v2(fz_buf *b, input *in, const mesh *m, int bin) {
  const int nv = m->hex ? 8 : 4;
  puts_(b, bin ? "$MeshFormat\n2.2 1 8\n" : "$MeshFormat\n2.2 0 8\n");
  if (bin) num(b, NULL, 0, 1, 4), puts_(b, "\n");
  puts_(b, "$EndMeshFormat\n$Nodes\n");
  num(b, in, 0, m->nv, 0);
  puts_(b, "\n");
  for (size_t k = 0; k < m->nv; k++) {
    if (!bin) {
      char t[24];
      snprintf(t, sizeof t, "%zu ", k + 1);
      puts_(b, t);
    } else {
      num(b, NULL, 0, k + 1, 4);
    }
    coords(b, m, k, bin);
  }
  puts_(b, bin ? "\n$EndNodes\n$Elements\n" : "$EndNodes\n$Elements\n");
  num(b, in, 0, m->nc, 0);
  puts_(b, "\n");
  if (bin)
    num(b, NULL, 0, m->hex ? 5 : 4, 4), num(b, in, 0, m->nc, 4), num(b, NULL, 0, 0, 4);
  in->elem_off[0] = b->len;
  for (size_t e = 0; e < m->nc; e++) {
    char t[120];
    int k = snprintf(t, sizeof t, "%zu %d 0", e + 1, m->hex ? 5 : 4);
    for (int c = 0; c < nv && !bin; c++)
      k += snprintf(t + k, sizeof t - (size_t)k, " %d", m->c[e][c]);
    if (bin) {
      num(b, NULL, 0, e + 1, 4);
      for (int c = 0; c < nv; c++)
        num(b, NULL, 0, (uint64_t)m->c[e][c], 4);
    } else {
      puts_(b, t), puts_(b, "\n");
    }
  }
  in->elem_off[1] = b->len;
  puts_(b, bin ? "\n$EndElements\n" : "$EndElements\n");
}

/* A 4.1 header or block line: four numbers, the first `ints` of them ints in
 * binary; those marked in `counted` (bits) recorded as counts. */
static void line4(fz_buf *b, input *in, int bin, int ints, const uint64_t v[4],
                  int counted) {
  for (int j = 0; j < 4; j++) {
    if (j && !bin) puts_(b, " ");
    num(b, counted >> j & 1 ? in : NULL, 0, v[j], bin ? (j < ints ? 4 : 8) : 0);
  }
  if (!bin) puts_(b, "\n");
}

static void gmsh_v41(fz_buf *b, input *in, const mesh *m, int bin) {
  const int nv = m->hex ? 8 : 4;
  puts_(b, bin ? "$MeshFormat\n4.1 1 8\n" : "$MeshFormat\n4.1 0 8\n");
  if (bin) num(b, NULL, 0, 1, 4), puts_(b, "\n");
  puts_(b, "$EndMeshFormat\n$Nodes\n");
  line4(b, in, bin, 0, (const uint64_t[4]){1, m->nv, 1, m->nv}, 3);
  line4(b, in, bin, 3, (const uint64_t[4]){3, 1, 0, m->nv}, 8);
  for (size_t k = 0; k < m->nv; k++) {
    char t[24];
    snprintf(t, sizeof t, "%zu\n", k + 1);
    bin ? num(b, NULL, 0, k + 1, 8) : puts_(b, t);
  }
  for (size_t k = 0; k < m->nv; k++)
    coords(b, m, k, bin);
  puts_(b, bin ? "\n$EndNodes\n$Elements\n" : "$EndNodes\n$Elements\n");
  const size_t first = m->nc > 1 ? m->nc - 1 : m->nc; /* two blocks when it can */
  line4(b, in, bin, 0, (const uint64_t[4]){m->nc > 1 ? 2 : 1, m->nc, 1, m->nc}, 3);
  in->elem_off[0] = b->len;
  for (size_t e = 0; e < m->nc; e++) {
    if (e == 0 || e == first)
      line4(b, in, bin, 3,
            (const uint64_t[4]){3, 1, m->hex ? 5 : 4, e ? m->nc - first : first}, 8);
    char t[120];
    int k = snprintf(t, sizeof t, "%zu", e + 1);
    for (int c = 0; c < nv; c++)
      k += snprintf(t + k, sizeof t - (size_t)k, " %d", m->c[e][c]);
    if (bin) {
      num(b, NULL, 0, e + 1, 8);
      for (int c = 0; c < nv; c++)
        num(b, NULL, 0, (uint64_t)m->c[e][c], 8);
    } else {
      puts_(b, t), puts_(b, "\n");
    }
  }
  in->elem_off[1] = b->len;
  puts_(b, bin ? "\n$EndElements\n" : "$EndElements\n");
}

static void tetgen(input *in, const mesh *m) {
  fz_buf *nb = &in->f[0], *eb = &in->f[1];
  num(nb, in, 0, m->nv, 0);
  puts_(nb, " 3 0 0\n");
  for (size_t k = 0; k < m->nv; k++) {
    char t[24];
    snprintf(t, sizeof t, "%zu ", k + 1);
    puts_(nb, t);
    coords(nb, m, k, 0);
  }
  num(eb, in, 1, m->nc, 0);
  puts_(eb, " 4 0\n");
  in->elem_off[0] = eb->len;
  for (size_t e = 0; e < m->nc; e++) {
    char t[120];
    snprintf(t, sizeof t, "%zu %d %d %d %d\n", e + 1, m->c[e][0], m->c[e][1], m->c[e][2],
             m->c[e][3]);
    puts_(eb, t);
  }
  in->elem_off[1] = eb->len;
  in->elem_file = 1;
}

/* ---- changes ---- */

static size_t pick(gsl_rng *r, size_t n) {
  return n ? (size_t)gsl_rng_uniform_int(r, (unsigned long)n) : 0;
}

/* Replace bytes [off, off + len) of b by n bytes at p. */
static void splice(fz_buf *b, size_t off, size_t len, const char *p, size_t n) {
  fz_buf t = {NULL, 0, 0};
  put(&t, b->data, off);
  put(&t, p, n);
  put(&t, b->data + off + len, b->len - off - len);
  fz_buf_free(b);
  *b = t;
}

/* A declared count one more, one less or 0. */
static void lie(gsl_rng *r, input *in) {
  const count_at *c = &in->counts[pick(r, (size_t)in->ncounts)];
  fz_buf *b = &in->f[c->file];
  uint64_t v = 0;
  if (c->binary)
    memcpy(&v, b->data + c->off, c->len); /* little-endian, as written */
  else
    v = strtoull(b->data + c->off, NULL, 10);
  const int how = (int)pick(r, 3);
  const uint64_t w = how == 0 || v == 0 ? v + 1 : how == 1 ? v - 1 : 0;
  if (c->binary) {
    const uint32_t w4 = (uint32_t)w;
    memcpy(b->data + c->off, c->len == 4 ? (const void *)&w4 : (const void *)&w, c->len);
  } else {
    char t[24];
    snprintf(t, sizeof t, "%llu", (unsigned long long)w);
    splice(b, c->off, c->len, t, strlen(t));
  }
}

/* The start of each line of b in [from, to): into at (at most max); how many. */
static size_t lines(const fz_buf *b, size_t from, size_t to, size_t *at, size_t max) {
  size_t n = 0;
  for (size_t i = from; i < to && n < max; i++)
    if (i == from || b->data[i - 1] == '\n') at[n++] = i;
  return n;
}

/* An element line (ASCII) with one node more or one less. */
static void nodes(gsl_rng *r, input *in) {
  fz_buf *b = &in->f[in->elem_file];
  size_t at[200];
  const size_t n = lines(b, in->elem_off[0], in->elem_off[1], at, 200);
  if (!n) return;
  const size_t s = at[pick(r, n)], e = strchr(b->data + s, '\n') - b->data;
  if (pick(r, 2)) {
    splice(b, e, 0, " 1", 2);
  } else {
    size_t k = e;
    while (k > s && b->data[k - 1] != ' ')
      k--;
    splice(b, k ? k - 1 : k, e - (k ? k - 1 : k), "", 0);
  }
}

static void change(gsl_rng *r, int what, input *in) {
  fz_buf *b = &in->f[pick(r, (size_t)in->nfiles)];
  size_t at[2000];
  const size_t nl = lines(b, 0, b->len, at, 2000);
  switch (what) {
  case LIE:
    lie(r, in);
    break;
  case NODES:
    nodes(r, in);
    break;
  case CUT: /* at a random byte, or a line's start */
    b->len = pick(r, 2) ? pick(r, b->len) : at[pick(r, nl)];
    b->data[b->len] = '\0';
    break;
  case FLIP:
    for (size_t k = 1 + pick(r, 3); k; k--)
      b->data[pick(r, b->len)] = (char)pick(r, 256);
    break;
  case LINE: {
    const size_t i = pick(r, nl), end = i + 1 < nl ? at[i + 1] : b->len;
    if (pick(r, 2))
      splice(b, at[i], end - at[i], "", 0);
    else
      splice(b, at[i], 0, b->data + at[i], end - at[i]);
    break;
  }
  default:
    break;
  }
}

/* ---- one iteration ---- */

typedef struct {
  long inputs[NFORMS], refused[NFORMS], accepted[NFORMS], contained[NFORMS];
  long by_change[NCHANGES], refused_by_change[NCHANGES];
  long failures;
  unsigned long seed;
  int dump;
  char dir[64];
} stats;

static int write_input(const stats *S, int form, const input *in, char *path, size_t n) {
  const char *ext[2] = {form == TETGEN ? "node" : "msh", "ele"};
  for (int i = 0; i < in->nfiles; i++) {
    snprintf(path, n, "%s/in.%s", S->dir, ext[i]);
    FILE *f = fopen(path, "wb");
    if (!f || fwrite(in->f[i].data, 1, in->f[i].len, f) != in->f[i].len) {
      if (f) fclose(f);
      return -1;
    }
    fclose(f);
  }
  snprintf(path, n, "%s/in.%s", S->dir, ext[0]);
  return 0;
}

/* The mesh read equals m exactly (vertex k = node tag k + 1). */
static int same(const ss_cx *cx, const mesh *m) {
  const ss_cell_type t = m->hex ? SS_HEX : SS_TET;
  if (cx->dim != 3 || cx->nv != m->nv || cx->nc[t] != m->nc) return 0;
  if (memcmp(cx->x, m->x, m->nv * 3 * sizeof(double))) return 0;
  for (size_t e = 0; e < m->nc; e++)
    for (int c = 0; c < ss_cell_nverts(t); c++)
      if (ss_cx_cell(cx, t, e)[c] != (ss_idx)(m->c[e][c] - 1)) return 0;
  return 1;
}

static void fail_it(stats *S, unsigned long it, int form, int what, const char *why,
                    const input *in) {
  S->failures++;
  fprintf(stderr, "FAIL seed %lu iteration %lu (%s, change %s): %s\n", S->seed, it,
          form_name[form], change_name[what], why);
  if (S->failures <= 5 || S->dump)
    for (int i = 0; i < in->nfiles; i++) {
      fz_escape(stderr, in->f[i].data, in->f[i].len, 2000);
      fputc('\n', stderr);
    }
}

static void run_one(stats *S, unsigned long it) {
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  if (!r) abort();
  fz_rng_for(r, S->seed, it);
  const int form = (int)pick(r, NFORMS);
  mesh m;
  make_mesh(r, form == TETGEN ? 0 : (int)pick(r, 2), &m);
  input in;
  memset(&in, 0, sizeof in);
  in.nfiles = form == TETGEN ? 2 : 1;
  if (form == TETGEN)
    tetgen(&in, &m);
  else if (form <= GMSH2B)
    gmsh_v2(&in.f[0], &in, &m, form == GMSH2B);
  else
    gmsh_v41(&in.f[0], &in, &m, form == GMSH41B);
  int what = (int)pick(r, NCHANGES);
  if (what == NODES && (form == GMSH2B || form == GMSH41B)) what = FLIP;
  change(r, what, &in);
  char path[128], why[700];
  S->inputs[form]++;
  S->by_change[what]++;
  if (write_input(S, form, &in, path, sizeof path)) {
    fail_it(S, it, form, what, "cannot write the input", &in);
  } else {
    ss_error err = {0};
    ss_cx *cx = NULL;
    const ss_status st = ss_mesh_read(path, SS_MESH_AUTO, &cx, &err);
    const ss_cell_type t = m.hex ? SS_HEX : SS_TET;
    size_t total = 0;
    for (int k = 0; cx && k < SS_NCELLTYPES; k++)
      total += cx->nc[k];
    if (st) {
      S->refused[form]++;
      S->refused_by_change[what]++;
      S->contained[form] += strstr(err.msg, "gmsh crashed") != NULL;
      if ((st != SS_EINPUT && st != SS_EIO) || !strstr(err.msg, S->dir) || cx) {
        snprintf(why, sizeof why, "a refusal with status %d: '%s'", (int)st, err.msg);
        fail_it(S, it, form, what, why, &in);
      }
      if (what == NONE) {
        snprintf(why, sizeof why, "the honest file is refused: %s", err.msg);
        fail_it(S, it, form, what, why, &in);
      }
    } else {
      S->accepted[form]++;
      if (what == NONE ? !same(cx, &m) : total != m.nc || cx->nc[t] != m.nc) {
        snprintf(why, sizeof why, "read %zu cells (%zu %s) of the %zu written", total,
                 cx->nc[t], ss_cell_plural(t), m.nc);
        fail_it(S, it, form, what,
                what == NONE ? "the honest file reads differently" : why, &in);
      } else if (what == LIE || what == NODES) {
        fail_it(S, it, form, what, "a file that lies is accepted", &in);
      }
    }
    ss_cx_free(cx);
  }
  for (int i = 0; i < 2; i++)
    fz_buf_free(&in.f[i]);
  gsl_rng_free(r);
}

/* ---- main ---- */

static int usage(const char *msg) {
  fprintf(stderr,
          "fuzz_meshfiles: %s\nusage: fuzz_meshfiles [--seed S] [--iterations N] "
          "[--max-seconds T] [--only I] [--dump]\n",
          msg);
  return 2;
}

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void summary(const stats *S, unsigned long ran, double secs) {
  long in = 0, ref = 0, acc = 0, con = 0;
  printf("fuzz_meshfiles: seed %lu, %lu inputs in %.1f s\n", S->seed, ran, secs);
  printf("  %-18s %8s %8s %8s %10s\n", "form", "inputs", "refused", "read", "gmsh-crash");
  for (int f = 0; f < NFORMS; f++) {
    printf("  %-18s %8ld %8ld %8ld %10ld\n", form_name[f], S->inputs[f], S->refused[f],
           S->accepted[f], S->contained[f]);
    in += S->inputs[f], ref += S->refused[f], acc += S->accepted[f],
        con += S->contained[f];
  }
  printf("  %-18s %8ld %8ld %8ld %10ld\n", "all", in, ref, acc, con);
  printf("  changes (refused/inputs):");
  for (int c = 0; c < NCHANGES; c++)
    printf(" %s %ld/%ld", change_name[c], S->refused_by_change[c], S->by_change[c]);
  printf("\n  failures (a crash of our code, a lie accepted, cells lost or invented, a "
         "bad refusal): %ld\n",
         S->failures);
}

int main(int argc, char **argv) {
  stats S;
  memset(&S, 0, sizeof S);
  S.seed = 1;
  unsigned long n = 200, first = 0;
  double max_seconds = 0;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    if (!strcmp(a, "--dump")) {
      S.dump = 1;
      continue;
    }
    if (i + 1 >= argc) return usage("an option lacks its value");
    char *end;
    const double v = strtod(argv[++i], &end);
    if (*end || v < 0) return usage("a value is not a number >= 0");
    if (!strcmp(a, "--seed"))
      S.seed = (unsigned long)v;
    else if (!strcmp(a, "--iterations"))
      n = (unsigned long)v;
    else if (!strcmp(a, "--max-seconds"))
      max_seconds = v;
    else if (!strcmp(a, "--only"))
      first = (unsigned long)v, n = 1;
    else
      return usage("unknown option");
  }
  snprintf(S.dir, sizeof S.dir, "/tmp/fuzz_meshfiles_XXXXXX");
  if (!mkdtemp(S.dir)) return usage("no temporary directory");
  const double t0 = now();
  unsigned long ran = 0;
  for (unsigned long it = first; it < first + n; it++, ran++) {
    if (max_seconds > 0 && now() - t0 > max_seconds) break;
    run_one(&S, it);
  }
  summary(&S, ran, now() - t0);
  char cmd[128];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", S.dir);
  if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", S.dir);
  return S.failures ? 1 : 0;
}
