/* test_mesh_io.c — mesh formats: exact round trips of every cell type and
 * coordinate dimension, the split-octahedron and VTK pyramid conventions
 * (orientation and volume preserved), OBJ corner-reference forms, skipped
 * Medit sections, every malformed sample in bad/ rejected with SS_EINPUT
 * and a message naming file, line and problem, the scale-free flat-cell check,
 * and non-finite refinement results refused. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "ss_mesh.h"
#include "ss_scheme.h"
#include "ss_test.h"
#include "ss_testmesh.h"

/* Exact equality: same dimension, bitwise coordinates, same cells in the same
 * order, same references (vertex-cell references only if with_cell_vref). */
static int same_exact(const ss_cx *a, const ss_cx *b, int vertex_cell_refs) {
  if (a->dim != b->dim || a->nv != b->nv) return 0;
  if (memcmp(a->x, b->x, a->nv * (size_t)a->dim * sizeof(double))) return 0;
  if (memcmp(a->vref, b->vref, a->nv * sizeof(int32_t))) return 0;
  for (int t = 0; t < SS_NCELLTYPES; t++) {
    if (a->nc[t] != b->nc[t]) return 0;
    size_t n = a->nc[t] * (size_t)ss_cell_nverts((ss_cell_type)t);
    if (n && memcmp(a->cells[t], b->cells[t], n * sizeof(ss_idx))) return 0;
    if (t == SS_VERTEX && !vertex_cell_refs) continue;
    if (a->nc[t] && memcmp(a->cref[t], b->cref[t], a->nc[t] * sizeof(int32_t))) return 0;
  }
  return 1;
}

/* Write with `write`, read back with `read`, through an anonymous file. */
static ss_cx *medit_round_trip(const ss_cx *cx, int split) {
  FILE *f = tmpfile();
  ss_error err = {0};
  ss_mesh_write_opts o = {.octahedra_keyword = !split};
  ss_cx *back = NULL;
  if (!f) return NULL;
  if (ss_mesh_write_medit(f, cx, &o, &err) == SS_OK) {
    rewind(f);
    if (ss_mesh_read_medit(f, "round-trip", &back, &err)) {
      fprintf(stderr, "re-read failed: %s\n", err.msg);
      back = NULL;
    }
  }
  fclose(f);
  return back;
}

/* A complex with every cell type: a hex star, a tet star and an octahedron
 * side by side, plus crease cells of each lower dimension; random references. */
static ss_cx *every_type(void) {
  tm_link *l = tm_link_named("icosahedron");
  ss_cx *a = tm_hex_star(l), *b = tm_tet_star(l);
  ss_error err = {0};
  size_t off = a->nv;
  for (size_t i = 0; i < b->nv; i++) {
    double x[3] = {b->x[3 * i] + 5, b->x[3 * i + 1], b->x[3 * i + 2]};
    ss_cx_add_vertex(a, x, (int32_t)(i % 3), &err);
  }
  for (size_t i = 0; i < b->nc[SS_TET]; i++) {
    ss_idx v[4];
    for (int k = 0; k < 4; k++)
      v[k] = (ss_idx)(ss_cx_cell(b, SS_TET, i)[k] + off);
    ss_cx_add_cell(a, SS_TET, v, (int32_t)(7 * i % 5) - 2, &err);
  }
  static const double oct[6][3] = {{1, 0, 0},  {0, 1, 0},  {0, 0, 1},
                                   {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}};
  off = a->nv;
  for (int i = 0; i < 6; i++) {
    double x[3] = {oct[i][0] - 5, oct[i][1], oct[i][2]};
    ss_cx_add_vertex(a, x, -1, &err);
  }
  ss_idx ov[6];
  for (int i = 0; i < 6; i++)
    ov[i] = (ss_idx)(off + (size_t)i);
  ss_cx_add_cell(a, SS_OCT, ov, 42, &err);
  ss_idx seg[2] = {0, 1}, tri[3] = {0, 1, 2}, quad[4] = {0, 1, 2, 3}, vtx[1] = {5};
  ss_cx_add_cell(a, SS_SEGMENT, seg, 3, &err);
  ss_cx_add_cell(a, SS_TRIANGLE, tri, 4, &err);
  ss_cx_add_cell(a, SS_QUAD, quad, 5, &err);
  ss_cx_add_cell(a, SS_VERTEX, vtx, 0, &err);
  for (size_t i = 0; i < a->nc[SS_HEX]; i++)
    a->cref[SS_HEX][i] = (int32_t)i;
  tm_jitter(a, 0.01, 3);
  ss_cx_free(b);
  tm_link_free(l);
  return a;
}

static void test_medit_round_trip(void) {
  ss_cx *a = every_type();
  ss_cx *b = medit_round_trip(a, 0);
  CHECK(b && same_exact(a, b, 0), "Medit round trip of every cell type is exact");
  ss_cx_free(b);

  /* Split octahedra: 4 positive tets of the same total volume replace it. */
  ss_cx *c = medit_round_trip(a, 1);
  CHECK(c && c->nc[SS_OCT] == 0 && c->nc[SS_TET] == a->nc[SS_TET] + 4,
        "split octahedron becomes 4 tets");
  if (c) {
    double voct, vsum = 0;
    CHECK(ss_cx_cell_orientation(a, SS_OCT, 0, &voct) == 1, "test octahedron positive");
    for (size_t i = a->nc[SS_TET]; i < c->nc[SS_TET]; i++) {
      double v;
      CHECK(ss_cx_cell_orientation(c, SS_TET, i, &v) == 1, "split tet %zu positive", i);
      CHECK(c->cref[SS_TET][i] == 42, "split tet keeps the octahedron's reference");
      vsum += v;
    }
    CHECK_CLOSE(vsum, voct, 1e-12, "split tets fill the octahedron");
  }
  ss_cx_free(c);
  ss_cx_free(a);

  /* Coordinate dimensions 1, 2 and 4 (scalar fields, planar and 4D data). */
  for (int d = 1; d <= 4; d++) {
    ss_cx *t = tm_torus(d < 4 ? d : 3, 3), *u = NULL;
    ss_error err = {0};
    if (d == 4) { /* lift the 3-torus to 4 coordinates */
      REQUIRE_OK_VOID(ss_cx_new(4, &u, &err), &err);
      for (size_t i = 0; i < t->nv; i++) {
        double x[4] = {t->x[3 * i], t->x[3 * i + 1], t->x[3 * i + 2], 0.1 * (double)i};
        ss_cx_add_vertex(u, x, 0, &err);
      }
      for (size_t i = 0; i < t->nc[SS_HEX]; i++)
        ss_cx_add_cell(u, SS_HEX, ss_cx_cell(t, SS_HEX, i), 0, &err);
      ss_cx_free(t);
      t = u;
    }
    t->x[0] = 1.0 / 3.0; /* a value that needs all 17 digits */
    ss_cx *r = medit_round_trip(t, 0);
    CHECK(r && same_exact(t, r, 1), "Medit round trip in dimension %d", d);
    ss_cx_free(r);
    ss_cx_free(t);
  }
}

static ss_cx *read_string(const char *text, int obj, ss_error *err) {
  FILE *f = fmemopen((void *)text, strlen(text), "r");
  ss_cx *cx = NULL;
  if (!f) return NULL;
  if (obj)
    ss_mesh_read_obj(f, "string", &cx, err);
  else
    ss_mesh_read_medit(f, "string", &cx, err);
  fclose(f);
  return cx;
}

/* One cell of type t on n vertices x (dim coordinates each) scaled by s and
 * moved by off in every coordinate. */
static ss_cx *one_cell(ss_cell_type t, int dim, const double *x, int n, double s,
                       double off) {
  ss_cx *c = NULL;
  ss_error err = {0};
  if (ss_cx_new(dim, &c, &err)) return NULL;
  ss_idx v[SS_MAXCELLVERTS];
  for (int i = 0; i < n; i++) {
    double y[SS_MAXDIM];
    for (int r = 0; r < dim; r++)
      y[r] = x[i * dim + r] * s + off;
    ss_cx_add_vertex(c, y, 0, &err);
    v[i] = (ss_idx)i;
  }
  ss_cx_add_cell(c, t, v, 0, &err);
  return c;
}

/* The degenerate-cell check is scale-free: cubes of side 1e-300 and 1e300 are
 * as valid as the unit cube (unscaled, their determinants under- or
 * overflow), a flat cell is flat at every scale, a cell flat up to rounding
 * has no sign, and a face of zero area is flat in any number of coordinates. */
static void test_flat_scale_free(void) {
  static const double hex[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0,
                               0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1};
  static const double tet[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  static const double oct[] = {1, 0, 0, 0, 1, 0, 0, 0, 1, -1, 0, 0, 0, -1, 0, 0, 0, -1};
  static const double quad[] = {0, 0, 1, 0, 1, 1, 0, 1};
  static const double tri[] = {0, 0, 1, 0, 0, 1};
  static const struct {
    ss_cell_type t;
    int dim, n;
    const double *x;
  } cells[] = {{SS_HEX, 3, 8, hex},
               {SS_TET, 3, 4, tet},
               {SS_OCT, 3, 6, oct},
               {SS_QUAD, 2, 4, quad},
               {SS_TRIANGLE, 2, 3, tri}};
  const double scales[] = {1e-300, 1e-30, 1.0, 1e30, 1e300};
  for (size_t k = 0; k < sizeof cells / sizeof cells[0]; k++)
    for (size_t j = 0; j < sizeof scales / sizeof scales[0]; j++)
      for (int moved = 0; moved < 2; moved++) {
        double s = scales[j], off = moved ? 3.0 * s : 0.0;
        const char *name = ss_cell_name(cells[k].t);
        ss_cx *c = one_cell(cells[k].t, cells[k].dim, cells[k].x, cells[k].n, s, off);
        ss_error err = {0};
        CHECK(c && ss_cx_check_orientation(c, &err) == SS_OK,
              "%s of size %g accepted: %s", name, s, err.msg);
        CHECK(c && ss_cx_cell_orientation(c, cells[k].t, 0, NULL) == 1,
              "%s of size %g positive", name, s);
        CHECK(c && !ss_cx_cell_flat(c, cells[k].t, c->cells[cells[k].t]),
              "%s of size %g not flat", name, s);
        /* squash the last coordinate: flat at every scale */
        for (size_t i = 0; c && i < c->nv; i++)
          c->x[i * (size_t)c->dim + (size_t)c->dim - 1] = off;
        CHECK(c && ss_cx_check_orientation(c, &err) == SS_EINPUT &&
                  strstr(err.msg, "flat"),
              "flat %s of size %g refused: %s", name, s, err.msg);
        ss_cx_free(c);
      }
  /* a tet whose 4th vertex lies on the plane of the others up to rounding */
  double near[12] = {0.1, 0.2, 0.3, 0.7, 0.1, 0.9, 0.3, 0.8, 0.2, 0, 0, 0};
  for (int r = 0; r < 3; r++)
    near[9 + r] = 0.3 * near[r] + 0.3 * near[3 + r] + 0.4 * near[6 + r];
  ss_cx *c = one_cell(SS_TET, 3, near, 4, 1.0, 0.0);
  ss_error err = {0};
  CHECK(ss_cx_cell_orientation(c, SS_TET, 0, NULL) == 0,
        "rounding-level tet has no sign");
  CHECK(ss_cx_check_orientation(c, &err) == SS_EINPUT && strstr(err.msg, "flat"),
        "rounding-level tet refused: %s", err.msg);
  ss_cx_free(c);
  /* a thin but honest cell is not flat: a 1 x 1e-9 x 1e-9 box */
  double thin[24];
  for (int i = 0; i < 24; i++)
    thin[i] = hex[i] * (i % 3 ? 1e-9 : 1.0);
  c = one_cell(SS_HEX, 3, thin, 8, 1.0, 0.0);
  CHECK(ss_cx_check_orientation(c, &err) == SS_OK, "thin box accepted: %s", err.msg);
  ss_cx_free(c);
  /* zero-area triangle in 3D (a surface: no orientation, but flatness) */
  static const double line3[] = {0, 0, 0, 1, 1, 1, 2, 2, 2};
  c = one_cell(SS_TRIANGLE, 3, line3, 3, 1e-300, 0.0);
  CHECK(ss_cx_check_orientation(c, &err) == SS_EINPUT &&
            strstr(err.msg, "triangle 1 is flat"),
        "zero-area triangle in 3D refused: %s", err.msg);
  ss_cx_free(c);
  static const double tri3[] = {0, 0, 0, 1, 0, 0, 0, 1, 1};
  c = one_cell(SS_TRIANGLE, 3, tri3, 3, 1e300, 0.0);
  CHECK(ss_cx_check_orientation(c, &err) == SS_OK, "triangle in 3D accepted: %s",
        err.msg);
  ss_cx_free(c);
  /* tetrahedra with 2 coordinates: refused, never skipped */
  static const double tet2[] = {0, 0, 1, 0, 0, 1, 1, 1};
  c = one_cell(SS_TET, 2, tet2, 4, 1.0, 0.0);
  CHECK(ss_cx_check_orientation(c, &err) == SS_EINPUT &&
            strstr(err.msg, "2 coordinates per vertex but 1 tetrahedron"),
        "tets with 2 coordinates refused: %s", err.msg);
  ss_cx_free(c);
  /* Medit: Triangles under Dimension 1 name the lines */
  ss_cx *r =
      read_string("MeshVersionFormatted 2\nDimension 1\nVertices 3\n0 0\n1 0\n2 0\n"
                  "Triangles\n1\n1 2 3 0\nEnd\n",
                  0, &err);
  CHECK(!r && strstr(err.msg,
                     "string:7: Triangles need Dimension 2 or more, but line 2 says "
                     "Dimension 1"),
        "Medit dimension mismatch: %s", err.msg);
  ss_cx_free(r);
}

/* Results are checked, not only input: a finite hex whose top face sits at
 * 1.7e308 refines to overflowing positions, which every refinement refuses
 * (naming the fine vertex and the input vertices it derives from), and no
 * writer puts a non-finite coordinate in a file. */
static void test_nonfinite_results(void) {
  static const double hex[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0,
                               0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1};
  ss_cx *c = one_cell(SS_HEX, 3, hex, 8, 1.0, 0.0), *fine = NULL;
  ss_scheme *s = NULL;
  ss_error err = {0};
  REQUIRE_OK_VOID(ss_scheme_new("mlca", &s, &err), &err);
  /* level 2 of a finite cube: input vertices are their own origin, others
   * derive from corners of the cube */
  ss_idx anc[SS_MAXCELLVERTS];
  size_t n = 0;
  CHECK(ss_scheme_origin(s, c, 2, 5, anc, &n, &err) == SS_OK && n == 1 && anc[0] == 5,
        "an input vertex is its own origin (n = %zu)", n);
  CHECK(ss_scheme_origin(s, c, 2, 30, anc, &n, &err) == SS_OK && n >= 2 && n <= 8,
        "a level-2 vertex derives from 2..8 corners (n = %zu)", n);
  for (size_t i = 4; i < 8; i++)
    c->x[3 * i + 2] = 1.7e308;
  ss_status st = ss_scheme_refine(s, c, &fine, NULL, &err);
  CHECK(st == SS_EINPUT && !fine && strstr(err.msg, "non-finite") &&
            strstr(err.msg, "DBL_MAX"),
        "overflow refused: %s", err.msg);
  size_t bad = 0;
  st = ss_scheme_refine_at(s, c, &fine, &bad, &err);
  CHECK(st == SS_EINPUT && bad != SIZE_MAX && bad >= 8, "overflowing vertex %zu", bad);
  if (st == SS_EINPUT && bad != SIZE_MAX) {
    CHECK(ss_scheme_origin(s, c, 1, bad, anc, &n, &err) == SS_OK && n >= 2,
          "origin of the overflow: %s", err.msg);
    CHECK(n >= 2 && anc[n - 1] >= 4, "the overflow derives from the top face");
  }
  st = ss_scheme_refine_levels(s, c, 2, &fine, &err);
  CHECK(st == SS_EINPUT && !fine && strstr(err.msg, "level 1: refined vertex") &&
            strstr(err.msg, "derives from input vertices") &&
            strstr(err.msg, "largest input coordinate is 1.7e+308, at vertex 5"),
        "levels name the level and the input vertices: %s", err.msg);
  /* the writers: nothing non-finite reaches a file */
  c->x[3 * 6] = INFINITY;
  char dir[] = "/tmp/ss_test_nonfinite_XXXXXX", path[64];
  if (mkdtemp(dir)) {
    snprintf(path, sizeof path, "%s/o.mesh", dir);
    CHECK(ss_mesh_write(path, SS_MESH_AUTO, c, NULL, &err) == SS_EINPUT &&
              strstr(err.msg, "vertex 7 has a non-finite coordinate"),
          "non-finite mesh not written: %s", err.msg);
    CHECK(access(path, F_OK) != 0, "no file created");
    remove(path);
    rmdir(dir);
  }
  ss_cx_free(c);
  ss_scheme_free(s);
}

static void test_medit_sections(void) {
  ss_error err = {0};
  /* Corners become vertex cells; cell-less sections and comments are skipped;
   * keywords are case-insensitive and counts may sit on the keyword's line. */
  const char *text = "MeshVersionFormatted 1 # version\n"
                     "Dimension\n3\n"
                     "Vertices 4\n0 0 0 1\n1 0 0 2\n0 1 0 3\n0 0 1 4\n"
                     "Corners 2\n1 4\n"
                     "Ridges\n1\n1\n"
                     "RequiredVertices\n2 1 2\n"
                     "Normals\n1\n0 0 1\n"
                     "NormalAtVertices\n1\n1 1\n"
                     "tetrahedra\n1\n1 2 3 4 7\n"
                     "End\n"
                     "anything after End is ignored\n";
  ss_cx *cx = read_string(text, 0, &err);
  CHECK(cx != NULL, "sections file read: %s", err.msg);
  if (!cx) return;
  CHECK(cx->nv == 4 && cx->nc[SS_VERTEX] == 2 && cx->nc[SS_TET] == 1, "counts");
  CHECK(ss_cx_cell(cx, SS_VERTEX, 1)[0] == 3, "corner 4 is vertex 3 (0-based)");
  CHECK(cx->vref[2] == 3 && cx->cref[SS_TET][0] == 7, "references kept");
  ss_cx_free(cx);
}

static void test_obj(void) {
  ss_error err = {0};
  /* All corner forms, negative references, ignored statements, polylines. */
  const char *text = "# a quad, a triangle, a polyline and a point\n"
                     "mtllib x.mtl\no thing\ng group\ns off\nusemtl m\n"
                     "v 0 0 0\nv 1 0 0\nv 1 1 0 1.0\nv 0 1 0 0.5 0.5 0.5\nv 2 0 0\n"
                     "vt 0 0\nvn 0 0 1\n"
                     "f 1/1/1 2//1 3/1 4\n"
                     "f -4 5 -3\n"
                     "l 1 2 5\n"
                     "p 5\n";
  ss_cx *cx = read_string(text, 1, &err);
  CHECK(cx != NULL, "OBJ read: %s", err.msg);
  if (!cx) return;
  CHECK(cx->nv == 5 && cx->nc[SS_QUAD] == 1 && cx->nc[SS_TRIANGLE] == 1 &&
            cx->nc[SS_SEGMENT] == 2 && cx->nc[SS_VERTEX] == 1,
        "OBJ counts");
  const ss_idx *tri = ss_cx_cell(cx, SS_TRIANGLE, 0);
  CHECK(tri[0] == 1 && tri[1] == 4 && tri[2] == 2, "negative references are relative");
  const ss_idx *seg = ss_cx_cell(cx, SS_SEGMENT, 1);
  CHECK(seg[0] == 1 && seg[1] == 4, "polyline split into segments");
  CHECK(cx->x[3 * 2 + 2] == 0.0 && cx->x[3 * 3 + 1] == 1.0, "extra v values ignored");

  FILE *f = tmpfile();
  ss_cx *back = NULL;
  if (f) {
    REQUIRE_OK_VOID(ss_mesh_write_obj(f, cx, &err), &err);
    rewind(f);
    REQUIRE_OK_VOID(ss_mesh_read_obj(f, "round-trip", &back, &err), &err);
    fclose(f);
  }
  CHECK(back && same_exact(cx, back, 1), "OBJ round trip exact");
  ss_cx_free(back);
  ss_cx_free(cx);

  /* A jittered closed quad surface round-trips too; a volume mesh is refused. */
  tm_link *l = tm_link_named("bipyramid:7");
  ss_cx *s = tm_link_quads(l), *v = tm_hex_star(l);
  tm_jitter(s, 0.1, 9);
  f = tmpfile();
  back = NULL;
  if (f) {
    REQUIRE_OK_VOID(ss_mesh_write_obj(f, s, &err), &err);
    rewind(f);
    REQUIRE_OK_VOID(ss_mesh_read_obj(f, "round-trip", &back, &err), &err);
    CHECK(ss_mesh_write_obj(f, v, &err) == SS_EINPUT && strstr(err.msg, "surfaces only"),
          "OBJ refuses hexahedra: %s", err.msg);
    fclose(f);
  }
  CHECK(back && same_exact(s, back, 1), "OBJ round trip of a jittered quad surface");
  ss_cx_free(back);
  ss_cx_free(s);
  ss_cx_free(v);
  tm_link_free(l);
}

/* Signed volume of the tet (a, b, c, d). */
static double tetvol(const double *a, const double *b, const double *c, const double *d) {
  double u[3], v[3], w[3];
  for (int k = 0; k < 3; k++)
    u[k] = b[k] - a[k], v[k] = c[k] - a[k], w[k] = d[k] - a[k];
  return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
          u[2] * (v[0] * w[1] - v[1] * w[0])) /
         6.0;
}

static void test_vtk(void) {
  ss_cx *a = every_type();
  ss_error err = {0};
  char *buf = NULL;
  size_t len = 0;
  FILE *f = open_memstream(&buf, &len);
  REQUIRE_OK_VOID(ss_mesh_write_vtk(f, a, NULL, &err), &err);
  fclose(f);
  size_t ncells = ss_cx_ncells(a) + a->nc[SS_OCT];
  char want[64];
  snprintf(want, sizeof want, "CELL_TYPES %zu\n", ncells);
  CHECK(strstr(buf, want) != NULL, "VTK cell count %zu (octahedron = 2 pyramids)",
        ncells);
  snprintf(want, sizeof want, "POINTS %zu double\n", a->nv);
  CHECK(strstr(buf, want) != NULL, "VTK point count");

  /* The two pyramid lines: base normal towards the apex (VTK's convention),
   * i.e. the tets (base0, base1, base2, apex) are positive, and together they
   * have the octahedron's volume. */
  char *p = strstr(buf, "\n5 ");
  double vsum = 0, voct;
  ss_cx_cell_orientation(a, SS_OCT, 0, &voct);
  for (int k = 0; k < 2 && p; k++) {
    unsigned long v[5];
    CHECK(sscanf(p + 3, "%lu %lu %lu %lu %lu", &v[0], &v[1], &v[2], &v[3], &v[4]) == 5,
          "pyramid line");
    const double *x[5];
    for (int j = 0; j < 5; j++)
      x[j] = a->x + 3 * v[j];
    double t1 = tetvol(x[0], x[1], x[2], x[4]), t2 = tetvol(x[0], x[2], x[3], x[4]);
    CHECK(t1 > 0 && t2 > 0, "pyramid %d base faces its apex", k);
    vsum += t1 + t2;
    p = strstr(p + 1, "\n5 ");
  }
  CHECK_CLOSE(vsum, voct, 1e-12, "the pyramids fill the octahedron");
  free(buf);
  ss_cx_free(a);
}

/* Every malformed sample: the expected line and phrase of its message. */
static const struct {
  const char *file;
  int line;          /* expected line in the message; 0 = read succeeds */
  const char *words; /* phrase the message must contain */
} bad[] = {
    {"count-too-large.mesh", 13, "Tetrahedra ends after 2 of 3 entries"},
    {"count-too-small.mesh", 6, "where a keyword was expected"},
    {"index-out-of-range.mesh", 11, "vertex index 9 is out of range 1..4"},
    {"index-zero.mesh", 11, "vertex index 0 is out of range 1..4"},
    {"unknown-keyword.mesh", 9, "unknown keyword 'Tetrahedrons'"},
    {"degenerate-tet.mesh", 11, "degenerate (a vertex repeated)"},
    {"non-numeric-coordinate.mesh", 6, "coordinate 'abc' is not a number"},
    {"truncated.mesh", 7, "unexpected end of file in Vertices: 2 of 4 entries read"},
    {"negative-count.mesh", 4, "Vertices count -4 is out of range"},
    {"bad-dimension.mesh", 2, "Dimension 17 is out of range 1..16"},
    {"prisms.mesh", 11, "Prisms are not supported"},
    {"vertices-before-dimension.mesh", 2, "Vertices before Dimension"},
    {"nan-coordinate.mesh", 6, "coordinate 'nan' is not a finite number"},
    {"flat-tet.mesh", 0, "flat"},
    {"huge-count.mesh", 6, "unexpected end of file in Vertices: 2 of 4000000000"},
    {"empty.mesh", 1, "no Dimension: not a Medit mesh"},
    {"reference-not-integer.mesh", 11, "reference '1.5' is not an integer"},
    {"missing-count.mesh", 9, "unexpected end of file: Tetrahedra needs a count"},
    {"face-index-out-of-range.obj", 4, "refers to vertex 4, but 3 vertices were read"},
    {"face-pentagon.obj", 6, "face with 5 vertices"},
    {"face-non-numeric.obj", 4, "'f' vertex reference 'x' is not an integer"},
    {"face-degenerate.obj", 4, "face is degenerate"},
    {"vertex-two-coordinates.obj", 2, "vertex with 2 coordinates"},
    {"curve-statement.obj", 4, "unsupported OBJ statement 'cstype'"},
    {"face-index-zero.obj", 4, "refers to vertex 0"},
    {"face-zero-area.obj", 4, "face is flat (zero area: its corners are collinear"},
    {"quad-zero-area-corner.obj", 6, "face is flat (zero area at a corner"},
    {"dimension-mismatch.mesh", 9,
     "Tetrahedra need Dimension 3 or more, but line 2 says "
     "Dimension 2"},
    {"flat-surface-triangle.mesh", 0, "triangle 2 is flat"},
};

static void test_bad_files(void) {
  size_t n = sizeof bad / sizeof bad[0];
  for (size_t i = 0; i < n; i++) {
    char path[1024], prefix[1100];
    snprintf(path, sizeof path, "%s/bad/%s", SS_TEST_DATA, bad[i].file);
    ss_error err = {0};
    ss_cx *cx = NULL;
    ss_status st = ss_mesh_read(path, SS_MESH_AUTO, &cx, &err);
    if (bad[i].line == 0) {
      /* Geometrically bad but well-formed: the reader accepts it and the
       * orientation check rejects it. */
      CHECK(st == SS_OK, "%s reads: %s", bad[i].file, err.msg);
      if (cx) {
        st = ss_cx_check_orientation(cx, &err);
        CHECK(st == SS_EINPUT && strstr(err.msg, bad[i].words), "%s: %s", bad[i].file,
              err.msg);
      }
      ss_cx_free(cx);
      continue;
    }
    snprintf(prefix, sizeof prefix, "%s:%d: ", path, bad[i].line);
    CHECK(st == SS_EINPUT && cx == NULL, "%s rejected (status %d)", bad[i].file, (int)st);
    CHECK(strncmp(err.msg, prefix, strlen(prefix)) == 0 && strstr(err.msg, bad[i].words),
          "%s: message '%s' should start '%s' and say '%s'", bad[i].file, err.msg, prefix,
          bad[i].words);
    ss_cx_free(cx);
  }
  /* Every file in bad/ is in the table (checked by count; the CLI test runs
   * them all through the tool as well). */
  char cmd[1200];
  snprintf(cmd, sizeof cmd, "ls '%s/bad' | wc -l", SS_TEST_DATA);
  FILE *p = popen(cmd, "r");
  unsigned long files = 0;
  if (p) {
    if (fscanf(p, "%lu", &files) != 1) files = 0;
    pclose(p);
  }
  CHECK(files == n, "bad/ holds %lu files, the table %zu", files, n);

  ss_error err = {0};
  ss_cx *cx = NULL;
  CHECK(ss_mesh_read("/nonexistent/x.mesh", SS_MESH_AUTO, &cx, &err) == SS_EIO &&
            strstr(err.msg, "/nonexistent/x.mesh"),
        "missing file is SS_EIO naming the path: %s", err.msg);
  CHECK(ss_mesh_read("/nonexistent/x.vtk", SS_MESH_AUTO, &cx, &err) == SS_EIO &&
            strstr(err.msg, "/nonexistent/x.vtk"),
        "VTK is read (issue 36): a missing file is SS_EIO: %s", err.msg);
  CHECK(ss_mesh_read("x.stl", SS_MESH_AUTO, &cx, &err) == SS_EINPUT, "unknown extension");
}

static void test_formats(void) {
  CHECK(ss_mesh_format_from_path("a/b.MESH") == SS_MESH_MEDIT, ".MESH");
  CHECK(ss_mesh_format_from_path("b.vtk") == SS_MESH_VTK, ".vtk");
  CHECK(ss_mesh_format_from_path("b.obj") == SS_MESH_OBJ, ".obj");
  CHECK(ss_mesh_format_from_path("dir.mesh/b") == SS_MESH_AUTO, "dot in a directory");
  CHECK(!strcmp(ss_mesh_format_name(SS_MESH_MEDIT), "medit"), "name");
}

int main(void) {
  test_formats();
  test_medit_round_trip();
  test_medit_sections();
  test_obj();
  test_vtk();
  test_bad_files();
  test_flat_scale_free();
  test_nonfinite_results();
  return ss_test_done("mesh_io");
}
