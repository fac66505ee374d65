/* test_oom.c — every allocation failure in the library's main paths ends in a
 * clean SS_ENOMEM: no crash, no leak (under ASan/LSan, `./run sanitize`), a
 * message, and the same answer as before once memory is back.
 *
 * The idea is CSparse's Tcov: a counter makes the n-th allocation fail.  This
 * executable is linked with -Wl,--wrap=malloc,--wrap=calloc,--wrap=realloc, so
 * every allocation of the library's own code (linked statically into it) goes
 * through the wrappers below; allocations inside shared libraries (SQLite,
 * GSL, LAPACK, libc's strdup) are not counted.  For each operation the
 * allocations are counted once; then for n = 1..N the operation runs with the
 * n-th and every later allocation failing (memory does not come back within a
 * call), and must return SS_ENOMEM.  Above 400 allocations the n are every one
 * up to 200 and then a stride that visits 200 more, spread over the rest, so
 * the suite stays fast; `test_oom --all` walks every n.
 *
 * A run whose status is SS_OK although an allocation failed is accepted only
 * where the operation has a fallback (it must then give the reference
 * answer); any other status than SS_ENOMEM is a failure. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <gsl/gsl_errno.h>

#include "ss_gsl.h"
#include "ss_link.h"
#include "ss_mesh.h"
#include "ss_result.h"
#include "ss_scheme.h"
#include "ss_stencil.h"
#include "ss_store.h"
#include "ss_test.h"

/* The wrappers' state: this test is single-threaded. */
static long oom_count;   /* allocations seen since oom_arm */
static long oom_fail_at; /* the first allocation to fail (0: none) */
static long oom_failed;  /* allocations refused since oom_arm */

void *__real_malloc(size_t n);
void *__real_calloc(size_t m, size_t n);
void *__real_realloc(void *p, size_t n);
void *__wrap_malloc(size_t n);
void *__wrap_calloc(size_t m, size_t n);
void *__wrap_realloc(void *p, size_t n);

static int oom_refuse(void) {
  ++oom_count;
  if (oom_fail_at > 0 && oom_count >= oom_fail_at) {
    ++oom_failed;
    return 1;
  }
  return 0;
}

void *__wrap_malloc(size_t n) {
  return oom_refuse() ? NULL : __real_malloc(n);
}
void *__wrap_calloc(size_t m, size_t n) {
  return oom_refuse() ? NULL : __real_calloc(m, n);
}
void *__wrap_realloc(void *p, size_t n) {
  /* realloc(p, 0) frees; never refuse that */
  return n && oom_refuse() ? NULL : __real_realloc(p, n);
}

static void oom_arm(long fail_at) {
  oom_count = 0;
  oom_failed = 0;
  oom_fail_at = fail_at;
}

/* One operation under test: runs, frees what it made, returns its status
 * and writes a digest of its answer (to compare with the reference). */
typedef ss_status (*op_fn)(const void *arg, double *digest, ss_error *err);

static int walk_all;

static void walk(const char *name, op_fn op, const void *arg) {
  ss_error err = {0};
  double ref = 0;
  oom_arm(0);
  ss_status st = op(arg, &ref, &err);
  const long total = oom_count;
  CHECK(st == SS_OK && total > 0, "%s: reference run: status %d, %ld allocations (%s)",
        name, (int)st, total, err.msg);
  if (st != SS_OK) return;
  long step = 1, visited = 0, enomem = 0, fallback = 0;
  for (long n = 1; n <= total; n += step) {
    memset(&err, 0, sizeof err);
    double d = 0;
    oom_arm(n);
    st = op(arg, &d, &err);
    const long refused = oom_failed;
    oom_arm(0);
    visited++;
    if (st == SS_ENOMEM) {
      enomem++;
      CHECK(err.msg[0] != '\0',
            "%s: allocation %ld of %ld refused: SS_ENOMEM without a message", name, n,
            total);
    } else if (st == SS_OK) {
      fallback++;
      CHECK(refused == 0 || d == ref,
            "%s: allocation %ld of %ld refused, status OK but another answer (%.17g, not "
            "%.17g)",
            name, n, total, d, ref);
    } else {
      CHECK(0, "%s: allocation %ld of %ld refused: status %d, not SS_ENOMEM (%s)", name,
            n, total, (int)st, err.msg);
    }
    if (!walk_all && total > 400 && n >= 200) step = (total - 200) / 200 + 1;
  }
  /* and memory back: the same answer */
  double again = 0;
  memset(&err, 0, sizeof err);
  st = op(arg, &again, &err);
  CHECK(st == SS_OK && again == ref, "%s: after the failures: status %d, %.17g vs %.17g",
        name, (int)st, again, ref);
  printf(
      "%s: %ld allocations, %ld failure points visited: %ld SS_ENOMEM, %ld fell back\n",
      name, total, visited, enomem, fallback);
}

/* --- the operations --------------------------------------------------------- */

typedef struct {
  const char *scheme; /* scheme name */
  ss_case_kind kind;  /* case kind */
  const char *link;   /* vertex case: a named link */
  int n;              /* edge / surface vertex: valence */
} case_arg;

/* op_result's case through workspaces (ss_result_compute_ws): made in the
 * operation (the workspaces' growth is walked) or kept across the runs (a
 * workspace that a refused allocation left part empty serves the next run,
 * which must still give the reference answer). */
typedef struct {
  case_arg c;                /* the case */
  ss_pipeline_workspace *ws; /* kept workspaces, or NULL: made per run */
} ws_arg;

static ss_status result_of(const case_arg *a, ss_pipeline_workspace *ws, double *digest,
                           ss_error *err);

static ss_status op_result(const void *arg, double *digest, ss_error *err) {
  return result_of(arg, NULL, digest, err);
}

static ss_status op_result_ws(const void *arg, double *digest, ss_error *err) {
  const ws_arg *a = arg;
  if (a->ws) return result_of(&a->c, a->ws, digest, err);
  ss_pipeline_workspace *ws = ss_pipeline_workspace_new();
  if (!ws) return ss_error_nomem(err, "workspaces");
  const ss_status st = result_of(&a->c, ws, digest, err);
  ss_pipeline_workspace_free(ws);
  return st;
}

static ss_status result_of(const case_arg *a, ss_pipeline_workspace *ws, double *digest,
                           ss_error *err) {
  ss_scheme *s = NULL;
  ss_link *l = NULL;
  ss_status st = ss_scheme_new(a->scheme, &s, err);
  if (st == SS_OK && a->link) st = ss_link_named(a->link, &l, err);
  if (st == SS_OK) {
    ss_case c = {a->kind, l, a->n, SS_DIAG_BFS, 0};
    ss_result_opts o = ss_result_defaults();
    ss_result r;
    st = ws ? ss_result_compute_ws(s, &c, &o, ws, &r, err)
            : ss_result_compute(s, &c, &o, &r, err);
    if (st == SS_OK) {
      *digest = r.min_sj + (double)r.v.cond.verdict + 3.0 * (double)r.v.reg.verdict;
      for (int i = 0; i < r.neig; i++)
        *digest += r.eig[i].re * (i + 1);
      ss_result_clear(&r);
    }
  }
  ss_link_free(l);
  ss_scheme_free(s);
  return st;
}

static ss_status op_link_parse(const void *arg, double *digest, ss_error *err) {
  ss_link *l = NULL, *c = NULL;
  ss_status st = ss_link_parse(arg, &l, err);
  if (st == SS_OK) st = ss_link_canonical(l, &c, NULL, err);
  if (st == SS_OK) *digest = (double)c->k;
  ss_link_free(c);
  ss_link_free(l);
  return st;
}

static ss_status op_mesh(const void *arg, double *digest, ss_error *err) {
  ss_cx *cx = NULL;
  ss_status st = ss_mesh_read(arg, SS_MESH_AUTO, &cx, err);
  if (st == SS_OK) *digest = (double)cx->nv;
  ss_cx_free(cx);
  return st;
}

static ss_status op_stencil(const void *arg, double *digest, ss_error *err) {
  ss_scheme *s = NULL;
  uint64_t id = 0;
  ss_status st = ss_stencil_load(arg, &s, &id, err);
  if (st == SS_OK) *digest = (double)(id & 0xffffff);
  ss_scheme_free(s);
  return st;
}

/* A stencil file and a mesh it refines once. */
typedef struct {
  const char *stencil, *mesh; /* paths */
} refine_arg;

/* Load the stencil, read the mesh, refine it once with the operator: the
 * points and neighbours families' rules under allocation failures. */
static ss_status op_stencil_refine(const void *arg, double *digest, ss_error *err) {
  const refine_arg *a = arg;
  ss_scheme *s = NULL;
  ss_cx *cx = NULL, *fine = NULL;
  gsl_spmatrix *R = NULL;
  ss_status st = ss_stencil_load(a->stencil, &s, NULL, err);
  if (!st) st = ss_mesh_read(a->mesh, SS_MESH_AUTO, &cx, err);
  if (!st) st = ss_scheme_refine(s, cx, &fine, &R, err);
  if (!st) *digest = (double)R->nz + (double)fine->nv;
  if (R) gsl_spmatrix_free(R);
  ss_cx_free(fine);
  ss_cx_free(cx);
  ss_scheme_free(s);
  return st;
}

typedef struct {
  const char *path; /* the store file (removed before each run) */
  const ss_result *r;
} store_arg;

static ss_status op_store(const void *arg, double *digest, ss_error *err) {
  const store_arg *a = arg;
  unlink(a->path);
  ss_store *st = NULL;
  ss_status s = ss_store_open(a->path, SS_STORE_WRITE, &st, err);
  int64_t id = -1;
  if (s == SS_OK) {
    ss_store_scheme sc = {"mlca", NULL, 0, 0, SS_DIAG_BFS, ss_result_defaults()};
    s = ss_store_scheme_id(st, &sc, &id, err);
  }
  int added = 0;
  if (s == SS_OK) s = ss_store_put(st, id, a->r, &added, err);
  if (s == SS_OK) *digest = added;
  ss_store_close(st);
  return s;
}

/* GSL at the library boundary (ss_gsl.h): a GSL error inside the library does
 * not abort although this program never touched GSL's handler (GSL's own
 * allocations cannot be made to fail from here, a refused dimension calls the
 * same handler); a handler the caller installed stays. */
static int custom_calls;
static void custom_handler(const char *reason, const char *file, int line,
                           int gsl_errno) {
  (void)reason, (void)file, (void)line, (void)gsl_errno;
  custom_calls++;
}

static void test_gsl_boundary(void) {
  CHECK(ss_gsl_csr_alloc(0, 1, 1) == NULL, "a 0 x 1 matrix: GSL refuses, NULL returned");
  gsl_error_handler_t *now = gsl_set_error_handler(custom_handler);
  CHECK(now != NULL, "GSL's aborting default handler is still installed");
  ss_gsl_init();
  CHECK(ss_gsl_csr_alloc(0, 1, 1) == NULL && custom_calls == 1,
        "the caller's handler was replaced (%d calls)", custom_calls);
  gsl_set_error_handler(now);
}

int main(int argc, char **argv) {
  test_gsl_boundary();
  walk_all = argc > 1 && !strcmp(argv[1], "--all");
  const char *src = SS_OOM_SRC;
  char path[4096];

  static const case_arg cases[] = {
      {"mlca", SS_CASE_VERTEX, "bipyramid:5", 0},  {"mlca", SS_CASE_EDGE, NULL, 5},
      {"tetoct", SS_CASE_VERTEX, "octahedron", 0}, {"tetoct", SS_CASE_FACE, NULL, 0},
      {"loop", SS_CASE_SURFACE_VERTEX, NULL, 5},
  };
  for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
    char name[128];
    if (cases[i].link)
      snprintf(name, sizeof name, "result %s %s %s", cases[i].scheme,
               ss_case_name(cases[i].kind), cases[i].link);
    else
      snprintf(name, sizeof name, "result %s %s %d", cases[i].scheme,
               ss_case_name(cases[i].kind), cases[i].n);
    walk(name, op_result, &cases[i]);
  }
  /* workspaces: made per run (mlca edge 5), and kept across the runs (tetoct
   * face) */
  for (int kept = 0; kept < 2; kept++) {
    const size_t i = kept ? 3 : 1;
    ws_arg a = {cases[i], kept ? ss_pipeline_workspace_new() : NULL};
    char name[128];
    snprintf(name, sizeof name, "result_ws (%s) %s %s", kept ? "kept" : "per run",
             cases[i].scheme, ss_case_name(cases[i].kind));
    CHECK(!kept || a.ws, "a workspace");
    walk(name, op_result_ws, &a);
    ss_pipeline_workspace_free(a.ws);
  }
  walk("link parse + canonical form", op_link_parse,
       "8 bcdefgh,ahc,abhd,ache,adhf,aehg,afh,agfedcb");
  snprintf(path, sizeof path, "%s/data/meshes/hexstar-icosahedron.mesh", src);
  walk("mesh read (Medit)", op_mesh, path);
  snprintf(path, sizeof path, "%s/data/meshes/icosahedron.obj", src);
  walk("mesh read (OBJ)", op_mesh, path);
  snprintf(path, sizeof path, "%s/data/stencils/mlca.ini", src);
  walk("stencil load", op_stencil, path);
  {
    static const char *const pairs[][3] = {
        {"ccsolid.ini", "hexstar-icosahedron.mesh", "stencil points (hexes)"},
        {"loop.ini", "icosahedron.obj", "stencil points (triangles)"},
        {"boxspline.ini", "tetstar-icosahedron.mesh", "stencil neighbours"}};
    for (int i = 0; i < 3; i++) {
      char sp[4096], mp[4096];
      snprintf(sp, sizeof sp, "%s/data/stencils/%s", src, pairs[i][0]);
      snprintf(mp, sizeof mp, "%s/data/meshes/%s", src, pairs[i][1]);
      const refine_arg ra = {sp, mp};
      walk(pairs[i][2], op_stencil_refine, &ra);
    }
  }

  /* the store: a real result put into a fresh file */
  {
    ss_error err = {0};
    ss_scheme *s = NULL;
    ss_result r;
    REQUIRE_OK(ss_scheme_new("mlca", &s, &err), &err);
    ss_case c = {SS_CASE_EDGE, NULL, 4, SS_DIAG_BFS, 0};
    ss_result_opts o = ss_result_defaults();
    REQUIRE_OK(ss_result_compute(s, &c, &o, &r, &err), &err);
    char db[] = "/tmp/ss_oom_XXXXXX";
    int fd = mkstemp(db);
    CHECK(fd >= 0, "mkstemp");
    if (fd >= 0) {
      close(fd);
      store_arg a = {db, &r};
      walk("store open + scheme + put", op_store, &a);
      char side[sizeof db + 8];
      unlink(db);
      snprintf(side, sizeof side, "%s-wal", db);
      unlink(side);
      snprintf(side, sizeof side, "%s-shm", db);
      unlink(side);
    }
    ss_result_clear(&r);
    ss_scheme_free(s);
  }
  return ss_test_done("oom");
}
