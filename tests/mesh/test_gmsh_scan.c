/* test_gmsh_scan.c — gmsh files that lie are refused, not read with cells
 * lost (issue 35).
 *
 * The files are written here, as the tester wrote them: a 2x2x2 grid
 * of 8 hexahedra (27 nodes, node tag 1 + i + 3j + 9k at (i, j, k) / 2) in
 * versions 2 and 4.1, ASCII and binary.  The honest files read as 8
 * hexahedra with the grid's coordinates (checked from the formula, not from
 * the reader); each lie of the issue (an $Elements count one too low or too
 * high, numEntityBlocks one too low, a last block claiming 0 elements, a
 * file cut right after $EndNodes, one byte of $EndNodes changed, polygon
 * types 34 and 69, type 1-4 element lines listing 8 nodes, a version 2 file
 * cut after its nodes, the binary flag on an ASCII file, element type 99) is
 * SS_EINPUT whose message names the file, the line, the section and the
 * discrepancy; a duplicate element tag, which gmsh drops silently, is caught
 * by comparing gmsh's cells with the counts declared. */
#include <stdarg.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "ss_mesh.h"
#include "ss_test.h"

static char tmpdir[] = "/tmp/ss_gmsh_scan_XXXXXX";

/* A growing byte buffer. */
typedef struct {
  char d[16384]; /* the bytes */
  size_t n;      /* how many */
} buf;

static void add(buf *b, const void *p, size_t n) {
  if (b->n + n <= sizeof b->d) memcpy(b->d + b->n, p, n);
  b->n += n;
}

static void text(buf *b, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
static void text(buf *b, const char *fmt, ...) {
  char line[512];
  va_list ap;
  va_start(ap, fmt);
  const int k = vsnprintf(line, sizeof line, fmt, ap);
  va_end(ap);
  add(b, line, (size_t)k);
}

static void i32(buf *b, int32_t v) {
  add(b, &v, sizeof v);
}
static void u64(buf *b, uint64_t v) {
  add(b, &v, sizeof v);
}
static void f64(buf *b, double v) {
  add(b, &v, sizeof v);
}

/* Node tag of grid point (i, j, k); the 8 corners of hex e in ss_cx order. */
static int tag(int i, int j, int k) {
  return 1 + i + 3 * j + 9 * k;
}
static void corners(int e, int v[8]) {
  const int i = e % 2, j = e / 2 % 2, k = e / 4;
  const int d[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                       {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (int c = 0; c < 8; c++)
    v[c] = tag(i + d[c][0], j + d[c][1], k + d[c][2]);
}

/* How a file lies (0: it does not). */
enum {
  HONEST,
  COUNT_LOW,     /* $Elements 7 for 8 */
  COUNT_HIGH,    /* $Elements 9 for 8 */
  BLOCKS_LOW,    /* numEntityBlocks 1 for 2 */
  LAST_ZERO,     /* the last block claims 0 elements */
  CUT_NODES,     /* the file ends after $EndNodes */
  END_NODES,     /* $EndNodez */
  NO_END,        /* the file ends before $EndElements */
  ELEMENTS_ZERO, /* $Elements declares none (and lists none) */
  DUP_TAG        /* two elements of tag 7 */
};

/* $MeshFormat of version ver; binary (with its integer 1) when bin. */
static void format(buf *b, const char *ver, int bin) {
  text(b, "$MeshFormat\n%s %d 8\n", ver, bin);
  if (bin) {
    i32(b, 1);
    text(b, "\n");
  }
  text(b, "$EndMeshFormat\n");
}

/* The grid in version 2; binary when bin. */
static void grid_v2(buf *b, int bin, int lie) {
  format(b, "2.2", bin);
  text(b, "$Nodes\n27\n");
  for (int t = 1; t <= 27; t++) {
    const double x = (t - 1) % 3 * 0.5, y = (t - 1) / 3 % 3 * 0.5, z = (t - 1) / 9 * 0.5;
    if (bin) {
      i32(b, t);
      f64(b, x);
      f64(b, y);
      f64(b, z);
    } else {
      text(b, "%d %g %g %g\n", t, x, y, z);
    }
  }
  text(b, "%s$EndNodes\n", bin ? "\n" : "");
  if (lie == CUT_NODES) return;
  const int m = lie == COUNT_LOW       ? 7
                : lie == COUNT_HIGH    ? 9
                : lie == ELEMENTS_ZERO ? 0
                                       : 8;
  text(b, "$Elements\n%d\n", m);
  if (bin && m) { /* one block: type 5, 8 elements, 2 tags */
    i32(b, 5);
    i32(b, 8);
    i32(b, 2);
  }
  for (int e = 0; e < 8 && lie != ELEMENTS_ZERO; e++) {
    int v[8];
    corners(e, v);
    const int t = lie == DUP_TAG && e == 7 ? 7 : e + 1;
    if (bin) {
      i32(b, t);
      i32(b, 1);
      i32(b, 1);
      for (int c = 0; c < 8; c++)
        i32(b, v[c]);
    } else {
      text(b, "%d 5 2 1 1 %d %d %d %d %d %d %d %d\n", t, v[0], v[1], v[2], v[3], v[4],
           v[5], v[6], v[7]);
    }
  }
  if (lie != NO_END) text(b, "%s$EndElements\n", bin ? "\n" : "");
}

/* The grid in version 4.1: one node block on volume 1, two element blocks
 * there (7 hexahedra, then 1); binary when bin. */
static void grid_v41(buf *b, int bin, int lie) {
  format(b, "4.1", bin);
  text(b, "$Nodes\n");
  if (bin) {
    u64(b, 1), u64(b, 27), u64(b, 1), u64(b, 27);
    i32(b, 3), i32(b, 1), i32(b, 0), u64(b, 27);
  } else {
    text(b, "1 27 1 27\n3 1 0 27\n");
  }
  for (int t = 1; t <= 27; t++)
    bin ? u64(b, (uint64_t)t) : text(b, "%d\n", t);
  for (int t = 1; t <= 27; t++) {
    const double x[3] = {(t - 1) % 3 * 0.5, (t - 1) / 3 % 3 * 0.5, (t - 1) / 9 * 0.5};
    if (bin)
      f64(b, x[0]), f64(b, x[1]), f64(b, x[2]);
    else
      text(b, "%g %g %g\n", x[0], x[1], x[2]);
  }
  text(b, "%s%s\n", bin ? "\n" : "", lie == END_NODES ? "$EndNodez" : "$EndNodes");
  if (lie == CUT_NODES) return;
  const int nb = lie == BLOCKS_LOW ? 1 : 2;
  text(b, "$Elements\n");
  bin ? (u64(b, (uint64_t)nb), u64(b, 8), u64(b, 1), u64(b, 8))
      : text(b, "%d 8 1 8\n", nb);
  for (int e = 0; e < 8; e++) {
    if (e == 0 || e == 7) {
      const int n = e == 0 ? 7 : lie == LAST_ZERO ? 0 : 1;
      bin ? (i32(b, 3), i32(b, 1), i32(b, 5), u64(b, (uint64_t)n))
          : text(b, "3 1 5 %d\n", n);
    }
    int v[8];
    corners(e, v);
    if (bin) {
      u64(b, (uint64_t)e + 1);
      for (int c = 0; c < 8; c++)
        u64(b, (uint64_t)v[c]);
    } else {
      text(b, "%d %d %d %d %d %d %d %d %d\n", e + 1, v[0], v[1], v[2], v[3], v[4], v[5],
           v[6], v[7]);
    }
  }
  text(b, "%s$EndElements\n", bin ? "\n" : "");
}

static void write_file(const char *name, const buf *b, char *path, size_t n) {
  snprintf(path, n, "%s/%s", tmpdir, name);
  FILE *f = fopen(path, "wb");
  if (f) {
    fwrite(b->d, 1, b->n, f);
    fclose(f);
  }
}

/* name reads as the grid: 27 vertices at their coordinates (vertex k is node
 * tag k + 1), 8 hexahedra with the corners of corners(), nothing else. */
static void expect_grid(const char *name, const buf *b) {
  char path[1200];
  write_file(name, b, path, sizeof path);
  ss_error err = {0};
  ss_cx *cx = NULL;
  const ss_status st = ss_mesh_read(path, SS_MESH_AUTO, &cx, &err);
  CHECK(st == SS_OK, "%s reads: %s", name, err.msg);
  if (st) return;
  int ok = cx->dim == 3 && cx->nv == 27 && cx->nc[SS_HEX] == 8;
  for (int t = 0; t < SS_NCELLTYPES; t++)
    ok &= t == SS_HEX || cx->nc[t] == 0;
  for (size_t k = 0; ok && k < 27; k++)
    ok = cx->x[3 * k] == (double)(k % 3) / 2 &&
         cx->x[3 * k + 1] == (double)(k / 3 % 3) / 2 &&
         cx->x[3 * k + 2] == (double)(k / 9) / 2;
  for (int e = 0; ok && e < 8; e++) {
    int v[8];
    corners(e, v);
    for (int c = 0; c < 8; c++)
      ok &= ss_cx_cell(cx, SS_HEX, (size_t)e)[c] == (ss_idx)(v[c] - 1);
  }
  CHECK(ok, "%s is the 2x2x2 grid of 8 hexahedra", name);
  ss_cx_free(cx);
}

/* name is refused with SS_EINPUT, naming the file and saying each of words
 * (NULL-terminated), and not saying `never` (may be NULL). */
static void expect_refused(const char *name, const buf *b, const char *never, ...) {
  char path[1200];
  write_file(name, b, path, sizeof path);
  ss_error err = {0};
  ss_cx *cx = NULL;
  const ss_status st = ss_mesh_read(path, SS_MESH_AUTO, &cx, &err);
  int ok = st == SS_EINPUT && !cx && strstr(err.msg, path);
  va_list ap;
  va_start(ap, never);
  for (const char *w = va_arg(ap, const char *); w; w = va_arg(ap, const char *))
    ok = ok && strstr(err.msg, w);
  va_end(ap);
  CHECK(ok && (!never || !strstr(err.msg, never)), "%s: status %d, '%s'", name, (int)st,
        err.msg);
  ss_cx_free(cx);
}

/* The grid's version 2 ASCII text with element line e replaced by `line`. */
static void v2_with_line(buf *b, int e, const char *line) {
  buf g = {.n = 0};
  grid_v2(&g, 0, HONEST);
  g.d[g.n] = '\0';
  char key[16];
  snprintf(key, sizeof key, "\n%d 5 2 ", e);
  const char *at = strstr(g.d, key), *end = at ? strchr(at + 1, '\n') : NULL;
  if (!at || !end) return;
  add(b, g.d, (size_t)(at - g.d) + 1);
  text(b, "%s", line);
  add(b, end, g.n - (size_t)(end - g.d));
}

static void test_honest(void) {
  for (int bin = 0; bin < 2; bin++) {
    buf b = {.n = 0};
    grid_v2(&b, bin, HONEST);
    expect_grid(bin ? "hex8.v2b.msh" : "hex8.v2a.msh", &b);
    b.n = 0;
    grid_v41(&b, bin, HONEST);
    expect_grid(bin ? "hex8.v4b.msh" : "hex8.v4a.msh", &b);
  }
}

static void test_counts(void) {
  for (int bin = 0; bin < 2; bin++) {
    buf b = {.n = 0};
    grid_v2(&b, bin, COUNT_LOW);
    expect_refused(bin ? "hex8_lie7.v2b.msh" : "hex8_lie7.msh", &b, NULL, "$Elements",
                   bin ? "do not fit"
                       : "'$EndElements' expected after the 7 elements declared",
                   NULL);
    b.n = 0;
    grid_v2(&b, bin, COUNT_HIGH);
    expect_refused("hex8_lie9.msh", &b, NULL, "$Elements",
                   bin ? "after 8 of the 9 declared"
                       : "element 9 of the 9 declared expected, found '$EndElements'",
                   NULL);
    b.n = 0;
    grid_v41(&b, bin, BLOCKS_LOW);
    expect_refused("blocks_low.msh", &b, NULL, "$Elements",
                   "the 1 entity blocks hold 7 elements; the header declares 8", NULL);
    b.n = 0;
    grid_v41(&b, bin, LAST_ZERO);
    expect_refused("last_zero.msh", &b, NULL, "$Elements",
                   "the 2 entity blocks hold 7 elements; the header declares 8", NULL);
    b.n = 0;
    grid_v2(&b, bin, NO_END);
    expect_refused("no_end.msh", &b, NULL, "$Elements",
                   "the file ends where '$EndElements' is expected", NULL);
    b.n = 0;
    grid_v2(&b, bin, ELEMENTS_ZERO);
    expect_refused("zero.msh", &b, NULL, "$Elements declares no elements", NULL);
  }
}

static void test_cuts(void) {
  for (int bin = 0; bin < 2; bin++) {
    buf b = {.n = 0};
    grid_v41(&b, bin, CUT_NODES);
    expect_refused("cut_nodes.v4.msh", &b, NULL, "no $Elements section",
                   "the 27 nodes make no cells", NULL);
    b.n = 0;
    grid_v2(&b, bin, CUT_NODES);
    expect_refused("cut_nodes.v2.msh", &b, "empty mesh", "no $Elements section",
                   "the 27 nodes make no cells", NULL);
    b.n = 0;
    grid_v41(&b, bin, END_NODES);
    expect_refused("endnodez.msh", &b, NULL, "$Nodes: '$EndNodes' expected",
                   "found '$EndNodez'", NULL);
    /* the binary file cut inside its elements */
    b.n = 0;
    grid_v41(&b, bin, HONEST);
    b.n -= 40;
    expect_refused("cut_elements.msh", &b, NULL, "$Elements", NULL);
  }
  /* the binary flag on an ASCII file */
  buf b = {.n = 0};
  grid_v2(&b, 0, HONEST);
  b.d[b.n] = '\0';
  char *flag = strstr(b.d, "2.2 0 8");
  flag[4] = '1';
  expect_refused("binflag.msh", &b, "empty mesh", "$MeshFormat",
                 "an ASCII file marked binary", NULL);
}

static void test_elements(void) {
  buf b = {.n = 0};
  v2_with_line(&b, 3, "3 99 2 1 1 7 8 11 10 16 17 20 19");
  expect_refused("type99.msh", &b, "Wrong node index", "$Elements", "gmsh type 99",
                 "has no cell here", NULL);
  const int poly[2] = {34, 69};
  for (int i = 0; i < 2; i++) {
    char line[80];
    b.n = 0;
    snprintf(line, sizeof line, "3 %d 2 1 1 7 8 11 10", poly[i]);
    v2_with_line(&b, 3, line);
    expect_refused("polygon.msh", &b, NULL, "$Elements",
                   i ? "(Polygon Border)" : "(Polygon)", "has no cell here", NULL);
  }
  /* a line, triangle, quadrangle or tetrahedron listing 8 nodes */
  const char *const names[4] = {"a segment", "a triangle", "a quadrilateral",
                                "a tetrahedron"};
  const int nv[4] = {2, 3, 4, 4};
  for (int t = 1; t <= 4; t++) {
    char line[80], words[80];
    b.n = 0;
    snprintf(line, sizeof line, "3 %d 2 1 1 7 8 11 10 16 17 20 19", t);
    v2_with_line(&b, 3, line);
    snprintf(words, sizeof words, "lists 8 nodes after its 2 tags; %s has %d",
             names[t - 1], nv[t - 1]);
    expect_refused("eight.msh", &b, NULL, "$Elements", words, NULL);
  }
  /* a version 4.1 hexahedron line with 9 nodes */
  b.n = 0;
  grid_v41(&b, 0, HONEST);
  b.d[b.n] = '\0';
  const char third[] = "\n3 4 5 8 7 13 14 17 16\n";
  char *l = strstr(b.d, third);
  CHECK(l != NULL, "found the third element line of hex8.v4a.msh");
  if (l) {
    l += sizeof third - 2; /* at its newline */
    memmove(l + 2, l, b.n - (size_t)(l - b.d));
    memcpy(l, " 9", 2);
    b.n += 2;
  }
  expect_refused("nine.msh", &b, NULL, "$Elements",
                 "element 3 of 7 in entity block 1: 9 tags expected", NULL);
  /* two elements of one tag: gmsh keeps one, the counts catch it */
  b.n = 0;
  grid_v2(&b, 0, DUP_TAG);
  expect_refused("duptag.msh", &b, NULL,
                 "gmsh read 7 hexahedra where $Elements declares 8", NULL);
}

/* gmsh 4.8's `-format msh40`: one hexahedron in version 4.0's layout (entity
 * blocks "tag dim parametric count" before the nodes, "tag dim type count"
 * before the elements), its header "4.0" or "4", ASCII or marked binary.  The
 * scan does not check 4.0's blocks, so it is refused, plainly, before gmsh
 * reads it (it used to say "version 4 is not read (versions 2 and 4 are)"). */
static void test_v40(void) {
  static const char *const vers[] = {"4", "4.0", "4.00"};
  for (int i = 0; i < 3; i++)
    for (int bin = 0; bin < 2; bin++) {
      buf b = {.n = 0};
      format(&b, vers[i], bin);
      text(&b, "$Entities\n0 0 0 1\n1 0 0 0 1 1 1 0 0\n$EndEntities\n"
               "$Nodes\n1 8\n1 3 0 8\n");
      for (int k = 0; k < 8; k++)
        text(&b, "%d %d %d %d\n", k + 1, (k & 1) ^ (k >> 1 & 1), k >> 1 & 1, k >> 2);
      text(&b, "$EndNodes\n$Elements\n1 1\n1 3 5 1\n1 1 2 3 4 5 6 7 8\n"
               "$EndElements\n");
      char name[64];
      snprintf(name, sizeof name, "hex_%s%s.msh", vers[i], bin ? "b" : "");
      expect_refused(name, &b, "not read", ":2: MSH 4.0 is not supported; re-save as 4.1",
                     "gmsh -format msh41", "or 2.2", NULL);
    }
}

int main(void) {
  if (!ss_mesh_gmsh_available()) {
    printf("built without gmsh: nothing to check\n");
    return 77;
  }
  if (!mkdtemp(tmpdir)) {
    perror("mkdtemp");
    return 1;
  }
  test_honest();
  test_counts();
  test_cuts();
  test_elements();
  test_v40();
  char cmd[200];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmpdir);
  if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", tmpdir);
  return ss_test_done("gmsh_scan");
}
