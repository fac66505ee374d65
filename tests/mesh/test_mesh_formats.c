/* test_mesh_formats.c — the read-only formats: gmsh .msh (through gmsh's API)
 * and TetGen .node/.ele/.face.
 *
 * Usage: test_mesh_formats GMSH TETGEN, the programs' paths ("" when not
 * installed: the checks that need them are skipped, said on stdout).
 *
 * gmsh: files gmsh 4.8 wrote from gmsh/mixed.mesh in versions 2 and 4, ASCII
 * and binary, read back equal to the Medit file up to gmsh's renumbering of
 * the nodes (matched by their exact, dyadic coordinates), cells in order with
 * their references; the two encodings of one version read bitwise equal; the
 * same from several threads at once (the API's global state is behind a
 * mutex); the caller's locale survives; a box meshed by the gmsh binary from
 * a .geo, written in the four forms, reads the same four times and holds the
 * physical groups as references; malformed files, unsupported elements and a
 * .geo script named .msh (which gmsh would run) are refused with SS_EINPUT
 * naming the file; a tet/oct mesh written as Medit by default (octahedra
 * split) is read whole by gmsh (converted to binary .msh and read back: the
 * same tetrahedra, 4 per octahedron).  TetGen: a cube tetrahedralised by the tetgen
 * binary, read from .node/.ele/.face, equals TetGen's own Medit output (-g) in vertices
 * and tetrahedra, its tets all positive, its .face triangles exactly the
 * boundary faces of the tets; numbering from 0 (-z) reads the same; a 2D
 * Triangle file; malformed files with "file:line: problem". */
#include <locale.h>
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "ss_mesh.h"
#include "ss_scheme.h"
#include "ss_test.h"
#include "ss_testmesh.h"

static const char *gmsh_exe, *tetgen_exe;
static char tmpdir[] = "/tmp/ss_mesh_formats_XXXXXX";

/* Write text into tmpdir/name; the path into path. */
static void put(const char *name, const char *text, char *path, size_t n) {
  snprintf(path, n, "%s/%s", tmpdir, name);
  FILE *f = fopen(path, "w");
  if (f) {
    fputs(text, f);
    fclose(f);
  }
}

static ss_cx *read_or_report(const char *path) {
  ss_error err = {0};
  ss_cx *cx = NULL;
  ss_status st = ss_mesh_read(path, SS_MESH_AUTO, &cx, &err);
  CHECK(st == SS_OK, "%s reads: %s", path, err.msg);
  return cx;
}

/* Bitwise equality of vertices, cells (in order) and cell references. */
static int same_exact(const ss_cx *a, const ss_cx *b) {
  if (a->dim != b->dim || a->nv != b->nv) return 0;
  if (memcmp(a->x, b->x, a->nv * (size_t)a->dim * sizeof(double))) return 0;
  for (int t = 0; t < SS_NCELLTYPES; t++) {
    if (a->nc[t] != b->nc[t]) return 0;
    const size_t n = a->nc[t] * (size_t)ss_cell_nverts((ss_cell_type)t);
    if (n && memcmp(a->cells[t], b->cells[t], n * sizeof(ss_idx))) return 0;
    if (a->nc[t] && memcmp(a->cref[t], b->cref[t], a->nc[t] * sizeof(int32_t))) return 0;
  }
  return 1;
}

/* Equality up to a renumbering of the vertices, found by coordinates equal
 * within tol (0: exactly; the fixtures' are dyadic and distinct; gmsh writes
 * ASCII coordinates with 16 digits, so its binary and ASCII files of one mesh
 * differ by rounding): same dimension and vertex count, the same
 * cells of each type in the same order (vertex cells only if with_corners),
 * the same cell references if with_refs.  Why not: in why. */
static int same_renumbered(const ss_cx *a, const ss_cx *b, double tol, int with_corners,
                           int with_refs, char *why, size_t n) {
  if (a->dim != b->dim || a->nv != b->nv) {
    snprintf(why, n, "dimension %d/%d, vertices %zu/%zu", a->dim, b->dim, a->nv, b->nv);
    return 0;
  }
  size_t *map = malloc(b->nv * sizeof *map); /* vertex of b -> vertex of a */
  int ok = map != NULL;
  for (size_t j = 0; ok && j < b->nv; j++) {
    map[j] = SIZE_MAX;
    for (size_t i = 0; i < a->nv && map[j] == SIZE_MAX; i++) {
      int near = 1;
      for (int d = 0; d < a->dim; d++)
        near &= fabs(a->x[i * (size_t)a->dim + (size_t)d] -
                     b->x[j * (size_t)b->dim + (size_t)d]) <= tol;
      if (near) map[j] = i;
    }
    if (map[j] == SIZE_MAX) {
      snprintf(why, n, "vertex %zu of the second has no twin", j + 1);
      ok = 0;
    }
  }
  for (int t = 0; ok && t < SS_NCELLTYPES; t++) {
    if (t == SS_VERTEX && !with_corners) continue;
    if (a->nc[t] != b->nc[t]) {
      snprintf(why, n, "%zu/%zu %s", a->nc[t], b->nc[t], ss_cell_plural((ss_cell_type)t));
      ok = 0;
      break;
    }
    const int nv = ss_cell_nverts((ss_cell_type)t);
    for (size_t c = 0; ok && c < a->nc[t]; c++) {
      for (int k = 0; k < nv; k++)
        if (ss_cx_cell(a, (ss_cell_type)t, c)[k] !=
            map[ss_cx_cell(b, (ss_cell_type)t, c)[k]])
          ok = 0;
      if (with_refs && a->cref[t][c] != b->cref[t][c]) ok = 0;
      if (!ok) snprintf(why, n, "%s %zu differs", ss_cell_name((ss_cell_type)t), c + 1);
    }
  }
  free(map);
  return ok;
}

static const char *const forms[4] = {"v2a", "v2b", "v4a", "v4b"};

/* ---- gmsh ---- */

static ss_cx *fixture[4]; /* the four committed files, read once */

static void test_gmsh_fixture(void) {
  char path[1200], why[200];
  snprintf(path, sizeof path, "%s/gmsh/mixed.mesh", SS_TEST_DATA);
  ss_cx *ref = read_or_report(path);
  if (!ref) return;
  const char *loc0 = setlocale(LC_ALL, NULL);
  char before[512];
  snprintf(before, sizeof before, "%s", loc0 ? loc0 : "");
  for (int i = 0; i < 4; i++) {
    snprintf(path, sizeof path, "%s/gmsh/mixed.%s.msh", SS_TEST_DATA, forms[i]);
    fixture[i] = read_or_report(path);
    if (!fixture[i]) continue;
    /* gmsh's Medit reader drops Corners: compare the other cells */
    CHECK(same_renumbered(ref, fixture[i], 0.0, 0, 1, why, sizeof why),
          "mixed.%s.msh equals mixed.mesh up to node numbering: %s", forms[i], why);
    CHECK(fixture[i]->dim == 3, "mixed.%s.msh: 3 coordinates", forms[i]);
  }
  const char *loc1 = setlocale(LC_ALL, NULL);
  CHECK(loc1 && !strcmp(before, loc1), "the locale survives gmsh: '%s' then '%s'", before,
        loc1 ? loc1 : "(null)");
  /* ASCII and binary of one version: the same file to the bit */
  CHECK(fixture[0] && fixture[1] && same_exact(fixture[0], fixture[1]),
        "v2 ASCII = binary");
  CHECK(fixture[2] && fixture[3] && same_exact(fixture[2], fixture[3]),
        "v4 ASCII = binary");
  ss_cx_free(ref);
}

/* Several threads read the four files at once: each result must equal the
 * single-threaded read (gmsh's global model behind the reader's mutex). */
static void *reader(void *arg) {
  long bad = 0;
  (void)arg;
  for (int r = 0; r < 3; r++)
    for (int i = 0; i < 4; i++) {
      char path[1200];
      snprintf(path, sizeof path, "%s/gmsh/mixed.%s.msh", SS_TEST_DATA,
               forms[(i + r) % 4]);
      ss_error err = {0};
      ss_cx *cx = NULL;
      if (ss_mesh_read(path, SS_MESH_AUTO, &cx, &err) || !fixture[(i + r) % 4] ||
          !same_exact(cx, fixture[(i + r) % 4]))
        bad++;
      ss_cx_free(cx);
    }
  return (void *)bad;
}

static void test_gmsh_threads(void) {
  pthread_t th[4];
  long bad = 0;
  for (int i = 0; i < 4; i++)
    CHECK(pthread_create(th + i, NULL, reader, NULL) == 0, "thread %d", i);
  for (int i = 0; i < 4; i++) {
    void *r = NULL;
    pthread_join(th[i], &r);
    bad += (long)r;
  }
  CHECK(bad == 0, "%ld of 48 concurrent reads differ", bad);
}

/* A box meshed by gmsh itself from a .geo, in the four forms. */
static void test_gmsh_geo(void) {
  if (!*gmsh_exe) {
    printf("gmsh binary not found: the .geo check is skipped\n");
    return;
  }
  char geo[1200], cmd[4000], path[1200], why[200];
  put("box.geo",
      "SetFactory(\"Built-in\");\n"
      "Point(1) = {0, 0, 0, 0.5}; Point(2) = {1, 0, 0, 0.5};\n"
      "Point(3) = {1, 1, 0, 0.5}; Point(4) = {0, 1, 0, 0.5};\n"
      "Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};\n"
      "Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};\n"
      "out[] = Extrude {0, 0, 1} { Surface{1}; };\n"
      "Physical Point(11) = {1}; Physical Curve(12) = {1};\n"
      "Physical Surface(13) = {1}; Physical Volume(14) = {out[1]};\n",
      geo, sizeof geo);
  ss_cx *box[4] = {NULL};
  for (int i = 0; i < 4; i++) {
    snprintf(cmd, sizeof cmd,
             "'%s' -3 -v 0 '%s' -format %s %s -o '%s/box.%s.msh' >/dev/null 2>&1",
             gmsh_exe, geo, forms[i][1] == '2' ? "msh22" : "msh41",
             forms[i][2] == 'b' ? "-bin" : "", tmpdir, forms[i]);
    CHECK(system(cmd) == 0, "gmsh meshes box.geo (%s)", forms[i]);
    snprintf(path, sizeof path, "%s/box.%s.msh", tmpdir, forms[i]);
    box[i] = read_or_report(path);
  }
  for (int i = 0; box[0] && i < 4; i++) {
    if (!box[i]) continue;
    CHECK(same_renumbered(box[0], box[i], 1e-15, 1, 1, why, sizeof why),
          "box.%s.msh = box.v2a.msh: %s", forms[i], why);
    const ss_cx *b = box[i];
    CHECK(b->nc[SS_VERTEX] == 1 && b->nc[SS_SEGMENT] > 0 && b->nc[SS_TRIANGLE] > 0 &&
              b->nc[SS_TET] > 0,
          "box.%s: the physical point, curve, surface and volume", forms[i]);
    int refs = 1;
    for (int t = 0; t < SS_NCELLTYPES; t++)
      for (size_t c = 0; c < b->nc[t]; c++)
        refs &= b->cref[t][c] == (t == SS_VERTEX     ? 11
                                  : t == SS_SEGMENT  ? 12
                                  : t == SS_TRIANGLE ? 13
                                                     : 14);
    CHECK(refs, "box.%s: references are the physical groups 11..14", forms[i]);
    ss_error err = {0};
    CHECK(ss_cx_check_orientation(b, &err) == SS_OK, "box.%s: gmsh's tets agree: %s",
          forms[i], err.msg);
  }
  /* the same mesh as gmsh's own Medit output (refs: gmsh writes entity tags;
   * coordinates: with 14 significant digits) */
  snprintf(cmd, sizeof cmd, "'%s' -3 -v 0 '%s' -o '%s/box.mesh' >/dev/null 2>&1",
           gmsh_exe, geo, tmpdir);
  CHECK(system(cmd) == 0, "gmsh writes box.mesh");
  snprintf(path, sizeof path, "%s/box.mesh", tmpdir);
  ss_cx *m = read_or_report(path);
  CHECK(m && box[2] && same_renumbered(m, box[2], 1e-12, 0, 0, why, sizeof why),
        "box.v4a.msh = gmsh's box.mesh: %s", why);
  ss_cx_free(m);
  for (int i = 0; i < 4; i++)
    ss_cx_free(box[i]);
}

/* gmsh reads the Medit files subdivide writes by default in full: its
 * conversion to .msh holds every cell, the octahedra as 4 tets each (with the
 * Octahedra keyword gmsh dropped them without a word). */
static void test_gmsh_reads_our_medit(void) {
  if (!*gmsh_exe) {
    printf("gmsh binary not found: gmsh reading our Medit output is not checked\n");
    return;
  }
  tm_link *l = tm_link_named("icosahedron");
  ss_cx *star = tm_tet_star(l), *fine = NULL;
  ss_scheme *s = NULL;
  ss_error err = {0};
  char mesh[1200], msh[1200], cmd[4000], why[200];
  tm_jitter(star, 0.01, 5);
  if (ss_scheme_new("tetoct", &s, &err) || ss_scheme_refine(s, star, &fine, NULL, &err)) {
    CHECK(0, "tetoct refines the star: %s", err.msg);
    goto done;
  }
  snprintf(mesh, sizeof mesh, "%s/star.mesh", tmpdir);
  snprintf(msh, sizeof msh, "%s/star.msh", tmpdir);
  CHECK(fine->nc[SS_OCT] == 20, "20 octahedra to split");
  CHECK(ss_mesh_write(mesh, SS_MESH_AUTO, fine, NULL, &err) == SS_OK, "write: %s",
        err.msg);
  /* binary: doubles exactly as gmsh parsed them from our 17 digits */
  snprintf(cmd, sizeof cmd,
           "'%s' -0 -v 0 '%s' -format msh41 -bin -o '%s' >/dev/null 2>&1", gmsh_exe, mesh,
           msh);
  CHECK(system(cmd) == 0, "gmsh converts star.mesh");
  ss_cx *ours = read_or_report(mesh), *theirs = read_or_report(msh);
  CHECK(ours && ours->nc[SS_OCT] == 0 &&
            ours->nc[SS_TET] == fine->nc[SS_TET] + 4 * fine->nc[SS_OCT],
        "the octahedra written as 4 tets each");
  CHECK(ours && theirs && same_renumbered(ours, theirs, 0.0, 1, 1, why, sizeof why),
        "gmsh's reading of our Medit file = ours: %s", why);
  ss_cx_free(ours);
  ss_cx_free(theirs);
done:
  ss_scheme_free(s);
  ss_cx_free(fine);
  ss_cx_free(star);
  tm_link_free(l);
}

static void expect_bad_gmsh(const char *name, const char *text, size_t len,
                            const char *words) {
  char path[1200];
  snprintf(path, sizeof path, "%s/%s", tmpdir, name);
  FILE *f = fopen(path, "wb");
  if (f) {
    fwrite(text, 1, len, f);
    fclose(f);
  }
  ss_error err = {0};
  ss_cx *cx = NULL;
  ss_status st = ss_mesh_read(path, SS_MESH_AUTO, &cx, &err);
  CHECK(st == SS_EINPUT && !cx && strstr(err.msg, path) && strstr(err.msg, words),
        "%s: status %d, '%s' should name the file and say '%s'", name, (int)st, err.msg,
        words);
  ss_cx_free(cx);
}

static void test_gmsh_bad(void) {
  char mark[1200], script[1400], path[1200];
  snprintf(mark, sizeof mark, "%s/MARK", tmpdir);
  /* gmsh would run this (a .geo script under another name) */
  snprintf(script, sizeof script, "System \"touch %s\";\n", mark);
  expect_bad_gmsh("script.msh", script, strlen(script), "not a gmsh mesh");
  CHECK(access(mark, F_OK) != 0, "the script did not run");
  expect_bad_gmsh("empty.msh", "", 0, "not a gmsh mesh");
  expect_bad_gmsh("v1.msh", "$NOD\n1\n1 0 0 0\n$ENDNOD\n", 24, "not a gmsh mesh");
  const char v3[] = "$MeshFormat\n3.0 0 8\n$EndMeshFormat\n";
  expect_bad_gmsh("v3.msh", v3, sizeof v3 - 1, "MSH version 3.0 is not read");
  const char type[] = "$MeshFormat\n4.1 7 8\n$EndMeshFormat\n";
  expect_bad_gmsh("type.msh", type, sizeof type - 1, "malformed $MeshFormat");
  const char nodes[] = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n";
  expect_bad_gmsh("truncated.msh", nodes, sizeof nodes - 1, "truncated.msh");
  const char prism[] = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n6\n1 0 0 0\n2 1 0 "
                       "0\n3 0 1 0\n4 0 0 1\n5 1 0 1\n6 0 1 1\n$EndNodes\n$Elements\n1\n"
                       "1 6 2 0 1 1 2 3 4 5 6\n$EndElements\n";
  expect_bad_gmsh("prism.msh", prism, sizeof prism - 1, "Prism");
  const char tet10[] =
      "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n10\n1 0 0 0\n2 2 0 "
      "0\n3 0 2 0\n4 0 0 2\n5 1 0 0\n6 1 1 0\n7 0 1 0\n8 0 0 1\n9 0 1 1\n"
      "10 1 0 1\n$EndNodes\n$Elements\n1\n1 11 2 0 1 1 2 3 4 5 6 7 8 9 "
      "10\n$EndElements\n";
  expect_bad_gmsh("tet10.msh", tet10, sizeof tet10 - 1, "of first order");
  /* gmsh 4.8 dies of SIGSEGV on these mutants of mixed.v4b.msh (found by
   * mutating bytes): segv.v4b.msh is refused by the structural scan before
   * gmsh sees it (its element block is cut); segv2.v4b.msh (one byte of a
   * node tag changed) is consistent in structure, and the reader's child
   * process dies instead of the caller */
  const char *const segv[2][2] = {{"segv.v4b.msh", "$Elements: '$EndElements' expected"},
                                  {"segv2.v4b.msh", "gmsh crashed reading it"}};
  for (int i = 0; i < 2; i++) {
    ss_error e = {0};
    ss_cx *c = NULL;
    snprintf(path, sizeof path, "%s/gmsh/%s", SS_TEST_DATA, segv[i][0]);
    CHECK(ss_mesh_read(path, SS_MESH_AUTO, &c, &e) == SS_EINPUT && !c &&
              strstr(e.msg, segv[i][1]) && strstr(e.msg, path),
          "%s: '%s' should say '%s'", segv[i][0], e.msg, segv[i][1]);
  }
  /* a binary file cut short */
  snprintf(path, sizeof path, "%s/gmsh/mixed.v4b.msh", SS_TEST_DATA);
  FILE *f = fopen(path, "rb");
  char buf[400];
  size_t n = f ? fread(buf, 1, sizeof buf, f) : 0;
  if (f) fclose(f);
  CHECK(n == sizeof buf, "read the start of mixed.v4b.msh");
  expect_bad_gmsh("cut.msh", buf, n, "cut.msh");
  ss_error err = {0};
  ss_cx *cx = NULL;
  CHECK(ss_mesh_read("/nonexistent/x.msh", SS_MESH_AUTO, &cx, &err) == SS_EIO,
        "a missing .msh is SS_EIO: %s", err.msg);
}

/* ---- TetGen ---- */

static int cmp_tri(const void *a, const void *b) {
  return memcmp(a, b, 3 * sizeof(ss_idx));
}

static void sort3(ss_idx *v) {
  for (int i = 0; i < 2; i++)
    for (int j = 0; j < 2 - i; j++)
      if (v[j] > v[j + 1]) {
        ss_idx t = v[j];
        v[j] = v[j + 1];
        v[j + 1] = t;
      }
}

/* The faces held by exactly one tet, sorted, against the triangles of cx. */
static int boundary_is_faces(const ss_cx *cx) {
  const size_t nt = cx->nc[SS_TET], nf = cx->nc[SS_TRIANGLE];
  ss_idx *all = malloc(4 * nt * 3 * sizeof *all), *tri = malloc(nf * 3 * sizeof *tri);
  ss_idx *bnd = malloc(4 * nt * 3 * sizeof *bnd);
  int ok = all && tri && bnd;
  size_t nb = 0;
  static const int face[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  for (size_t t = 0; ok && t < nt; t++)
    for (int k = 0; k < 4; k++) {
      for (int j = 0; j < 3; j++)
        all[(4 * t + (size_t)k) * 3 + (size_t)j] = ss_cx_cell(cx, SS_TET, t)[face[k][j]];
      sort3(all + (4 * t + (size_t)k) * 3);
    }
  if (ok) qsort(all, 4 * nt, 3 * sizeof *all, cmp_tri);
  for (size_t i = 0; ok && i < 4 * nt;) {
    size_t j = i + 1;
    while (j < 4 * nt && !cmp_tri(all + 3 * i, all + 3 * j))
      j++;
    if (j - i == 1) memcpy(bnd + 3 * nb++, all + 3 * i, 3 * sizeof *bnd);
    if (j - i > 2) ok = 0; /* a face of three tets */
    i = j;
  }
  for (size_t i = 0; ok && i < nf; i++) {
    memcpy(tri + 3 * i, ss_cx_cell(cx, SS_TRIANGLE, i), 3 * sizeof *tri);
    sort3(tri + 3 * i);
  }
  if (ok) qsort(tri, nf, 3 * sizeof *tri, cmp_tri);
  ok = ok && nb == nf && (!nf || !memcmp(bnd, tri, 3 * nf * sizeof *tri));
  free(all);
  free(tri);
  free(bnd);
  return ok;
}

static void test_tetgen_cube(void) {
  if (!*tetgen_exe) {
    printf("tetgen binary not found: the TetGen round trip is skipped\n");
    return;
  }
  char poly[1200], cmd[4000], path[1300];
  put("cube.poly",
      "8 3 0 1\n1 0 0 0 0\n2 1 0 0 0\n3 1 1 0 0\n4 0 1 0 0\n5 0 0 1 0\n6 1 0 1 0\n"
      "7 1 1 1 0\n8 0 1 1 0\n6 1\n1 0 1\n4 1 2 3 4\n1 0 2\n4 5 6 7 8\n1 0 3\n4 1 2 6 5\n"
      "1 0 4\n4 2 3 7 6\n1 0 5\n4 3 4 8 7\n1 0 6\n4 4 1 5 8\n0\n0\n",
      poly, sizeof poly);
  /* 1-based with TetGen's Medit file; 0-based (-z) in a directory of its own */
  snprintf(cmd, sizeof cmd,
           "cd '%s' && '%s' -pqa0.05gQ cube.poly >/dev/null 2>&1 && mkdir z && cp "
           "cube.poly z/ && cd z && '%s' -pqa0.05zQ cube.poly >/dev/null 2>&1",
           tmpdir, tetgen_exe, tetgen_exe);
  CHECK(system(cmd) == 0, "tetgen meshes the cube");
  snprintf(path, sizeof path, "%s/cube.1.ele", tmpdir);
  ss_cx *t = read_or_report(path);
  snprintf(path, sizeof path, "%s/cube.1.mesh", tmpdir);
  ss_cx *m = read_or_report(path);
  snprintf(path, sizeof path, "%s/z/cube.1.node", tmpdir);
  ss_cx *z = read_or_report(path);
  if (t && m) {
    CHECK(t->dim == 3 && t->nv == m->nv && t->nc[SS_TET] == m->nc[SS_TET] &&
              t->nc[SS_TET] > 20,
          "%zu/%zu vertices, %zu/%zu tets", t->nv, m->nv, t->nc[SS_TET], m->nc[SS_TET]);
    int same = t->nv == m->nv && t->nc[SS_TET] == m->nc[SS_TET];
    for (size_t i = 0; same && i < 3 * t->nv; i++)
      same = fabs(t->x[i] - m->x[i]) <= 1e-15 * (1 + fabs(m->x[i]));
    CHECK(same, ".node coordinates = TetGen's .mesh vertices (relative 1e-15)");
    CHECK(same && !memcmp(t->cells[SS_TET], m->cells[SS_TET],
                          4 * t->nc[SS_TET] * sizeof(ss_idx)),
          ".ele tets = TetGen's .mesh tetrahedra, in order");
    int pos = 1;
    for (size_t c = 0; c < t->nc[SS_TET]; c++)
      pos &= ss_cx_cell_orientation(t, SS_TET, c, NULL) == 1;
    CHECK(pos, "TetGen's tets are positive in ss_cx.h's convention");
    CHECK(t->nc[SS_TRIANGLE] > 0 && boundary_is_faces(t),
          ".face: exactly the %zu boundary faces of the tets", t->nc[SS_TRIANGLE]);
  }
  if (t && z) {
    /* -z numbers from 0, which changes nothing else TetGen does */
    int vref_same = z->nv == t->nv && !memcmp(z->vref, t->vref, t->nv * sizeof(int32_t));
    CHECK(same_exact(t, z) && vref_same, "0-based files read exactly like 1-based ones");
  }
  ss_cx_free(t);
  ss_cx_free(m);
  ss_cx_free(z);
}

/* Triangle's 2D files: two triangles of the unit square, from 0, with
 * boundary markers and a region attribute. */
static void test_triangle_2d(void) {
  char node[1200], ele[1200];
  put("sq.node",
      "# unit square\n4 2 1 1\n0 0 0 9.5 1\n1 1 0 9.5 2\n2 1 1 9.5 3\n3 0 1 9.5 4\n",
      node, sizeof node);
  put("sq.ele", "2 3 1\n0 0 1 2 7\n1 0 2 3 -3\n# Generated by triangle\n", ele,
      sizeof ele);
  ss_cx *cx = read_or_report(node);
  if (!cx) return;
  CHECK(cx->dim == 2 && cx->nv == 4 && cx->nc[SS_TRIANGLE] == 2 && cx->nc[SS_TET] == 0,
        "2D: 4 points, 2 triangles");
  CHECK(cx->x[2 * 2] == 1 && cx->x[2 * 2 + 1] == 1 && cx->vref[3] == 4,
        "point 2 at (1, 1), point 3 marked 4");
  const ss_idx *t1 = ss_cx_cell(cx, SS_TRIANGLE, 1);
  CHECK(t1[0] == 0 && t1[1] == 2 && t1[2] == 3 && cx->cref[SS_TRIANGLE][0] == 7 &&
            cx->cref[SS_TRIANGLE][1] == -3,
        "triangle 1 = 0 2 3, references 7 and -3");
  ss_error err = {0};
  CHECK(ss_cx_check_orientation(cx, &err) == SS_OK, "both counter-clockwise: %s",
        err.msg);
  ss_cx_free(cx);
}

static void expect_bad_tetgen(const char *node, const char *ele, const char *face,
                              const char *which, int line, const char *words) {
  char p[1200], want[1300];
  static int k;
  char stem[64];
  snprintf(stem, sizeof stem, "bad%d", k++);
  char name[80];
  snprintf(name, sizeof name, "%s.node", stem);
  put(name, node, p, sizeof p);
  if (ele) {
    snprintf(name, sizeof name, "%s.ele", stem);
    put(name, ele, p, sizeof p);
  }
  if (face) {
    snprintf(name, sizeof name, "%s.face", stem);
    put(name, face, p, sizeof p);
  }
  snprintf(p, sizeof p, "%s/%s.node", tmpdir, stem);
  snprintf(want, sizeof want, "%s/%s.%s:%d: ", tmpdir, stem, which, line);
  ss_error err = {0};
  ss_cx *cx = NULL;
  ss_status st = ss_mesh_read(p, SS_MESH_AUTO, &cx, &err);
  CHECK(st == SS_EINPUT && !cx && !strncmp(err.msg, want, strlen(want)) &&
            strstr(err.msg, words),
        "%s (%s): status %d, '%s' should start '%s' and say '%s'", stem, words, (int)st,
        err.msg, want, words);
  ss_cx_free(cx);
}

static void test_tetgen_bad(void) {
  const char *nodes = "4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n";
  expect_bad_tetgen("", NULL, NULL, "node", 0, "unexpected end of file");
  expect_bad_tetgen("4 3 0 0\n1 0 0 0\n2 1 0 0\n", NULL, NULL, "node", 3,
                    "2 of 4 points read");
  expect_bad_tetgen("4 3 0\n", NULL, NULL, "node", 1, "boundary marker flag");
  expect_bad_tetgen("4 5 0 0\n", NULL, NULL, "node", 1, "dimension 5 is out of range");
  expect_bad_tetgen("2 3 0 0\n1 0 0 0\n3 1 0 0\n", NULL, NULL, "node", 3,
                    "point number 3 where 2 was expected");
  expect_bad_tetgen("2 3 0 0\n1 0 0 x\n2 1 0 0\n", NULL, NULL, "node", 2,
                    "coordinate 'x' is not a number");
  expect_bad_tetgen("2 3 0 0\n1 0 0 0 5\n2 1 0 0\n", NULL, NULL, "node", 2,
                    "'5' after the last field");
  expect_bad_tetgen("2 3 0 0\n1 0 0 0\n2 1 0 0\n3 1 1 1\n", NULL, NULL, "node", 4,
                    "after the 2 entries");
  expect_bad_tetgen(nodes, "1 4 0\n1 1 2 3 5\n", NULL, "ele", 2, "out of range 1..4");
  expect_bad_tetgen(nodes, "1 4 0\n1 1 2 3 3\n", NULL, "ele", 2, "tetrahedron 1 is");
  expect_bad_tetgen(nodes, "1 10 0\n", NULL, "ele", 1, "second-order elements are not");
  expect_bad_tetgen(nodes, "1 4 1\n1 1 2 3 4 0.5\n", NULL, "ele", 2,
                    "region attribute 0.5 is not an integer label");
  expect_bad_tetgen(nodes, "2 4 0\n1 1 2 3 4\n", NULL, "ele", 2,
                    "1 of 2 tetrahedra read");
  expect_bad_tetgen(nodes, "1 4 0\n1 1 2 3 4\n", "1 1\n1 1 2 3\n", "face", 2,
                    "the line ends where a boundary marker was expected");
  char path[1200];
  snprintf(path, sizeof path, "%s/missing.ele", tmpdir);
  ss_error err = {0};
  ss_cx *cx = NULL;
  CHECK(ss_mesh_read(path, SS_MESH_AUTO, &cx, &err) == SS_EIO && strstr(err.msg, ".node"),
        "an .ele without its .node: SS_EIO naming the .node: %s", err.msg);
}

static void test_names(void) {
  ss_error err = {0};
  ss_cx *cx = NULL;
  CHECK(ss_mesh_format_from_path("a.MSH") == SS_MESH_GMSH, ".MSH");
  CHECK(ss_mesh_format_from_path("a.1.ele") == SS_MESH_TETGEN, ".ele");
  CHECK(ss_mesh_format_from_path("a.1.face") == SS_MESH_TETGEN, ".face");
  CHECK(ss_mesh_format_writable(SS_MESH_GMSH) == ss_mesh_gmsh_available() &&
            !ss_mesh_format_writable(SS_MESH_TETGEN),
        "gmsh written when built with it (issue 40), TetGen read only");
  /* the refusal of an unreadable format names the readable ones, .vtk and
   * .vtu among them since they are read (issue 36) */
  CHECK(ss_mesh_read("x.stl", SS_MESH_AUTO, &cx, &err) == SS_EINPUT &&
            strstr(err.msg, ".mesh") && strstr(err.msg, ".node/.ele") &&
            strstr(err.msg, ".msh") && strstr(err.msg, ".vtk") && strstr(err.msg, ".vtu"),
        "unknown extension: %s", err.msg);
  CHECK(ss_mesh_read("x.vtk", SS_MESH_AUTO, &cx, &err) == SS_EIO &&
            strstr(err.msg, "x.vtk: No such file"),
        "VTK: %s", err.msg);
  CHECK(ss_mesh_write("x.node", SS_MESH_AUTO, cx, NULL, &err) == SS_EINPUT &&
            strstr(err.msg, "read, not written"),
        "writing .node: %s", err.msg);
}

int main(int argc, char **argv) {
  gmsh_exe = argc > 1 ? argv[1] : "";
  tetgen_exe = argc > 2 ? argv[2] : "";
  if (!mkdtemp(tmpdir)) {
    perror("mkdtemp");
    return 1;
  }
  test_names();
  if (ss_mesh_gmsh_available()) {
    test_gmsh_fixture();
    test_gmsh_threads();
    test_gmsh_geo();
    test_gmsh_reads_our_medit();
    test_gmsh_bad();
    for (int i = 0; i < 4; i++)
      ss_cx_free(fixture[i]);
  } else {
    char path[1200];
    snprintf(path, sizeof path, "%s/gmsh/mixed.v4a.msh", SS_TEST_DATA);
    ss_error err = {0};
    ss_cx *cx = NULL;
    CHECK(ss_mesh_read(path, SS_MESH_AUTO, &cx, &err) == SS_EINPUT &&
              strstr(err.msg, "built without gmsh"),
          "a build without gmsh says so: %s", err.msg);
    printf("built without gmsh: only the refusal of .msh is checked\n");
  }
  test_tetgen_cube();
  test_triangle_2d();
  test_tetgen_bad();
  char cmd[200];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmpdir);
  if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", tmpdir);
  return ss_test_done("mesh_formats");
}
