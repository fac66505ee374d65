/* test_store.c — the results store from the library side: a result read back
 * equals the computed one bit for bit (eigenvalues, NaN scaled Jacobian of a
 * case with no map, improper pair counts); a key is stored once; lookups
 * return the stored verdict; --where filters and refuses what does not
 * compile; identities separate schemes and parameters, and hold the
 * tolerance exactly; merge adds only what is missing, reports conflicts
 * (resolved by --prefer), refuses a store's own file; foreign, corrupt and other-version
 * files are refused with a message naming the file. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <sqlite3.h>

#include "ss_link.h"
#include "ss_result.h"
#include "ss_store.h"
#include "ss_test.h"

#define NCASES 5

typedef struct {
  const ss_result *want; /* the computed results */
  int n;                 /* how many */
  int seen;              /* rows visited */
  int equal;             /* rows equal to one of want */
} match;

static int same_result(const ss_result *a, const ss_result *b) {
  if (a->kind != b->kind || a->k != b->k || strcmp(a->link, b->link) ||
      a->cells != b->cells || a->two_ring != b->two_ring || a->one_ring != b->one_ring ||
      a->neig != b->neig || a->v.cond.verdict != b->v.cond.verdict ||
      strcmp(a->v.cond.reason, b->v.cond.reason) || a->tol != b->tol ||
      a->v.reg.verdict != b->v.reg.verdict || strcmp(a->v.reg.reason, b->v.reg.reason) ||
      a->depth != b->depth || a->has_diag != b->has_diag ||
      (a->has_diag && (a->pairs != b->pairs || a->improper != b->improper)) ||
      a->seconds != b->seconds)
    return 0;
  if (isnan(a->min_sj) != isnan(b->min_sj) ||
      (!isnan(a->min_sj) && a->min_sj != b->min_sj))
    return 0;
  /* bit for bit: the store keeps 17 significant digits */
  return memcmp(a->eig, b->eig, sizeof a->eig[0] * (size_t)a->neig) == 0;
}

static int visit(const ss_store_row *row, void *ctx) {
  match *m = ctx;
  m->seen++;
  for (int i = 0; i < m->n; i++)
    if (same_result(&row->r, m->want + i)) {
      m->equal++;
      break;
    }
  return 0;
}

static int count_visit(const ss_store_row *row, void *ctx) {
  (void)row;
  ++*(int *)ctx;
  return 0;
}

static int file_fails(const char *path, ss_store_mode mode, const char *want) {
  ss_error err = {0};
  ss_store *st = NULL;
  const ss_status s = ss_store_open(path, mode, &st, &err);
  ss_store_close(st);
  CHECK(s == SS_EINPUT && strstr(err.msg, want) && strstr(err.msg, path),
        "%s: status %d, message '%s', want SS_EINPUT and '%s'", path, (int)s, err.msg,
        want);
  return s == SS_EINPUT;
}

static void sql(const char *path, const char *text) {
  sqlite3 *db = NULL;
  sqlite3_open(path, &db);
  CHECK(sqlite3_exec(db, text, NULL, NULL, NULL) == SQLITE_OK, "%s: %s", text,
        sqlite3_errmsg(db));
  sqlite3_close(db);
}

int main(void) {
  char dir[] = "/tmp/ss_test_storeXXXXXX";
  if (!mkdtemp(dir)) return 1;
  char path[256], other[256], bad[256];
  snprintf(path, sizeof path, "%s/a.db", dir);
  snprintf(other, sizeof other, "%s/b.db", dir);
  ss_error err = {0};
  ss_scheme *mlca = NULL, *box = NULL;
  REQUIRE_OK(ss_scheme_new("mlca", &mlca, &err), &err);
  REQUIRE_OK(ss_scheme_new("boxspline", &box, &err), &err);
  ss_link *oct = NULL, *k8 = NULL, *tet = NULL;
  REQUIRE_OK(ss_link_named("octahedron", &oct, &err), &err);
  REQUIRE_OK(ss_link_named("tetrahedron", &tet, &err), &err);
  REQUIRE_OK(ss_link_parse("8 bcdefgh,ahc,abhd,ache,adhf,aehg,afh,agfedcb", &k8, &err),
             &err);
  /* pass (vertex), fail by regularity (the k = 8 finding), fail by the
   * eigenvalue condition with no map (edge 8), box-spline with diagonals */
  const ss_result_opts ro = ss_result_defaults();
  ss_result r[NCASES];
  const ss_case cases[NCASES] = {{SS_CASE_VERTEX, oct, 0, SS_DIAG_BFS, 0},
                                 {SS_CASE_VERTEX, k8, 0, SS_DIAG_BFS, 0},
                                 {SS_CASE_EDGE, NULL, 8, SS_DIAG_BFS, 0},
                                 {SS_CASE_EDGE, NULL, 4, SS_DIAG_BFS, 0},
                                 {SS_CASE_VERTEX, tet, 0, SS_DIAG_BFS, 0}};
  for (int i = 0; i < NCASES; i++)
    REQUIRE_OK(
        ss_result_compute(i == NCASES - 1 ? box : mlca, cases + i, &ro, r + i, &err),
        &err);
  CHECK(ss_result_verdict(r + 0) == SS_PASS, "octahedron passes");
  CHECK(ss_result_verdict(r + 1) == SS_FAIL && r[1].v.reg.verdict == SS_FAIL,
        "k = 8 finding fails regularity");
  CHECK(r[2].v.cond.verdict == SS_FAIL && isnan(r[2].min_sj), "edge 8: no map");
  CHECK(r[4].has_diag && r[4].pairs > 0, "box-spline vertex reports its pairs");

  ss_store *st = NULL;
  REQUIRE_OK(ss_store_open(path, SS_STORE_WRITE, &st, &err), &err);
  ss_store_scheme sm = {"mlca", NULL, 0, 0, SS_DIAG_BFS, ro};
  ss_store_scheme sb = {"boxspline", NULL, 0, 1, SS_DIAG_BFS, ro};
  ss_store_scheme sm4 = sm;
  sm4.opts.tol = 1e-4;
  int64_t idm = 0, idb = 0, idm4 = 0, again = 0;
  REQUIRE_OK(ss_store_scheme_id(st, &sm, &idm, &err), &err);
  REQUIRE_OK(ss_store_scheme_id(st, &sb, &idb, &err), &err);
  REQUIRE_OK(ss_store_scheme_id(st, &sm4, &idm4, &err), &err);
  REQUIRE_OK(ss_store_scheme_id(st, &sm, &again, &err), &err);
  CHECK(idm != idb && idm != idm4 && idb != idm4 && again == idm,
        "identities: %lld %lld %lld, again %lld", (long long)idm, (long long)idb,
        (long long)idm4, (long long)again);
  char ident[256];
  ss_store_identity(&sb, ident, sizeof ident);
  CHECK(!strcmp(ident, "boxspline tol=1e-06 depth=6 rings=3 diagonals=bfs"),
        "identity '%s'", ident);
  ss_store_scheme ss = {"mlca-file", "x.ini", 0x0123456789abcdefULL, 0, SS_DIAG_BFS, ro};
  ss_store_identity(&ss, ident, sizeof ident);
  CHECK(!strcmp(ident, "stencil:0123456789abcdef tol=1e-06 depth=6 rings=3"),
        "identity '%s'", ident);

  for (int i = 0; i < NCASES; i++) {
    int added = -1;
    REQUIRE_OK(ss_store_put(st, i == NCASES - 1 ? idb : idm, r + i, &added, &err), &err);
    CHECK(added == 1, "case %d added", i);
    REQUIRE_OK(ss_store_put(st, i == NCASES - 1 ? idb : idm, r + i, &added, &err), &err);
    CHECK(added == 0, "case %d stored twice", i);
  }
  int found = 0;
  ss_verdict_kind v = SS_PASS;
  REQUIRE_OK(ss_store_has(st, idm, SS_CASE_VERTEX, 8, r[1].link, &found, &v, &err), &err);
  CHECK(found && v == SS_FAIL, "k = 8 link found as failing (%d, %d)", found, (int)v);
  REQUIRE_OK(ss_store_has(st, idm4, SS_CASE_VERTEX, 8, r[1].link, &found, &v, &err),
             &err);
  CHECK(!found, "another identity has no rows");
  REQUIRE_OK(ss_store_has(st, idb, SS_CASE_EDGE, 4, "", &found, &v, &err), &err);
  CHECK(!found, "edge 4 was stored for mlca only");
  REQUIRE_OK(ss_store_has(st, idm, SS_CASE_EDGE, 4, "", &found, &v, &err), &err);
  CHECK(found && v == SS_PASS, "edge 4 of mlca found, passing");
  size_t nk[SS_NCASEKINDS];
  REQUIRE_OK(ss_store_count(st, -1, nk, &err), &err);
  CHECK(nk[SS_CASE_VERTEX] == 3 && nk[SS_CASE_EDGE] == 2 && nk[SS_CASE_FACE] == 0,
        "counts %zu %zu %zu", nk[0], nk[1], nk[2]);
  ss_store_close(st);

  /* read back: every row equal, bit for bit, to what was computed */
  REQUIRE_OK(ss_store_open(path, SS_STORE_READ, &st, &err), &err);
  match m = {r, NCASES, 0, 0};
  REQUIRE_OK(ss_store_each(st, NULL, visit, &m, &err), &err);
  CHECK(m.seen == NCASES && m.equal == NCASES, "%d rows read, %d equal", m.seen, m.equal);
  int n = 0, nfail = 0, nomap = 0;
  for (int i = 0; i < NCASES; i++) {
    nfail += ss_result_verdict(r + i) == SS_FAIL;
    nomap += isnan(r[i].min_sj);
  }
  CHECK(nfail >= 2 && nomap >= 1, "the cases were chosen to fail");
  REQUIRE_OK(ss_store_each(st, "verdict = 'fail'", count_visit, &n, &err), &err);
  CHECK(n == nfail, "%d failing rows, want %d", n, nfail);
  n = 0;
  REQUIRE_OK(ss_store_each(st, "kind = 'vertex' AND scheme = 'mlca' AND k = 6",
                           count_visit, &n, &err),
             &err);
  CHECK(n == 1, "%d rows at k = 6", n);
  n = 0;
  REQUIRE_OK(ss_store_each(st, "min_scaled_jacobian IS NULL", count_visit, &n, &err),
             &err);
  CHECK(n == nomap, "%d rows without a map, want %d", n, nomap);
  CHECK(ss_store_each(st, "k = ", count_visit, &n, &err) == SS_EINPUT &&
            strstr(err.msg, "--where"),
        "bad expression: %s", err.msg);
  CHECK(ss_store_each(st, "1); DROP TABLE result; SELECT (1", count_visit, &n, &err) ==
            SS_EINPUT,
        "two statements refused");
  CHECK(ss_store_put(st, idm, r, NULL, &err) == SS_EINPUT, "read-only store refuses");
  ss_store_close(st);

  /* merge: into an empty store everything, into a full one nothing */
  ss_store_merge_stats ms;
  REQUIRE_OK(ss_store_open(other, SS_STORE_WRITE, &st, &err), &err);
  REQUIRE_OK(ss_store_merge(st, path, SS_STORE_PREFER_NONE, &ms, &err), &err);
  CHECK(ms.added == NCASES && ms.present == 0 && ms.conflicts == 0,
        "merge added %zu, present %zu, conflicts %zu", ms.added, ms.present,
        ms.conflicts);
  REQUIRE_OK(ss_store_merge(st, path, SS_STORE_PREFER_NONE, &ms, &err), &err);
  CHECK(ms.added == 0 && ms.present == NCASES && ms.conflicts == 0,
        "merge again added %zu, present %zu, conflicts %zu", ms.added, ms.present,
        ms.conflicts);
  m = (match){r, NCASES, 0, 0};
  REQUIRE_OK(ss_store_each(st, NULL, visit, &m, &err), &err);
  CHECK(m.seen == NCASES && m.equal == NCASES, "merged: %d rows, %d equal", m.seen,
        m.equal);
  /* a conflict: the same key with another value; not a different timing */
  CHECK(ss_store_merge(st, other, SS_STORE_PREFER_NONE, &ms, &err) == SS_EINPUT &&
            strstr(err.msg, "itself"),
        "merging a store into itself: %s", err.msg);
  ss_store_close(st);
  sql(other, "UPDATE result SET seconds = seconds + 1;"
             "UPDATE result SET regularity_reason = 'changed' WHERE kind = 'edge' AND "
             "k = 8");
  REQUIRE_OK(ss_store_open(other, SS_STORE_WRITE, &st, &err), &err);
  REQUIRE_OK(ss_store_merge(st, path, SS_STORE_PREFER_NONE, &ms, &err), &err);
  CHECK(ms.added == 0 && ms.present == NCASES - 1 && ms.conflicts == 1 &&
            ms.replaced == 0 &&
            !strcmp(ms.first[0], "(mlca tol=1e-06 depth=6 rings=3) edge 8"),
        "conflict: added %zu, present %zu, conflicts %zu, replaced %zu, first '%s'",
        ms.added, ms.present, ms.conflicts, ms.replaced, ms.first[0]);
  REQUIRE_OK(ss_store_merge(st, path, SS_STORE_PREFER_OLD, &ms, &err), &err);
  CHECK(ms.conflicts == 1 && ms.replaced == 0,
        "--prefer old: %zu conflicts, %zu replaced", ms.conflicts, ms.replaced);
  n = 0;
  REQUIRE_OK(ss_store_each(st, "regularity_reason = 'changed'", count_visit, &n, &err),
             &err);
  CHECK(n == 1, "the old row is kept (%d)", n);
  REQUIRE_OK(ss_store_merge(st, path, SS_STORE_PREFER_NEW, &ms, &err), &err);
  CHECK(ms.conflicts == 1 && ms.replaced == 1,
        "--prefer new: %zu conflicts, %zu replaced", ms.conflicts, ms.replaced);
  n = 0;
  REQUIRE_OK(ss_store_each(st, "regularity_reason = 'changed'", count_visit, &n, &err),
             &err);
  CHECK(n == 0, "the new row replaces it (%d)", n);
  REQUIRE_OK(ss_store_merge(st, path, SS_STORE_PREFER_NONE, &ms, &err), &err);
  CHECK(ms.conflicts == 0 && ms.present == NCASES, "after --prefer new: %zu conflicts",
        ms.conflicts);
  ss_store_close(st);

  /* identities hold the tolerance exactly: text that reads back as it */
  ss_store_scheme st1 = sm, st2 = sm;
  st2.opts.tol = 1.0000006e-6;
  char id1[256], id2[256];
  ss_store_identity(&st1, id1, sizeof id1);
  ss_store_identity(&st2, id2, sizeof id2);
  CHECK(!strcmp(id1, "mlca tol=1e-06 depth=6 rings=3") &&
            !strcmp(id2, "mlca tol=1.0000006e-06 depth=6 rings=3"),
        "identities '%s', '%s'", id1, id2);
  unsigned seed = 16;
  for (int i = 0; i < 200; i++) {
    seed = seed * 1103515245u + 12345u;
    st2.opts.tol = 1e-9 + 0.09 * (seed >> 8) / 16777216.0 * (i % 2 ? 1 : 1e-5);
    ss_store_identity(&st2, id2, sizeof id2);
    const char *t = strstr(id2, "tol=");
    CHECK(t && strtod(t + 4, NULL) == st2.opts.tol, "tol %.17g: '%s'", st2.opts.tol, id2);
  }

  /* files that are not stores */
  snprintf(bad, sizeof bad, "%s/noise.db", dir);
  FILE *f = fopen(bad, "w");
  for (int i = 0; i < 4096; i++)
    fputc((i * 7919) % 251, f);
  fclose(f);
  file_fails(bad, SS_STORE_WRITE, "not a subspectra results store");
  file_fails(bad, SS_STORE_READ, "not a subspectra results store");
  snprintf(bad, sizeof bad, "%s/foreign.db", dir);
  sql(bad, "CREATE TABLE result(x)");
  file_fails(bad, SS_STORE_WRITE, "a foreign SQLite database");
  snprintf(bad, sizeof bad, "%s/empty.db", dir);
  f = fopen(bad, "w");
  fclose(f);
  file_fails(bad, SS_STORE_READ, "an empty file");
  sql(other, "PRAGMA user_version = 1"); /* the schema before the ring columns */
  file_fails(other, SS_STORE_READ, "schema version 1");
  REQUIRE_OK(ss_store_open(path, SS_STORE_WRITE, &st, &err), &err);
  CHECK(ss_store_merge(st, other, SS_STORE_PREFER_NONE, &ms, &err) == SS_EINPUT,
        "merge refuses another schema version");
  ss_store_close(st);
  snprintf(bad, sizeof bad, "%s/none.db", dir);
  CHECK(ss_store_open(bad, SS_STORE_READ, &st, &err) == SS_EIO &&
            strstr(err.msg, "no such results store"),
        "missing file: %s", err.msg);

  for (int i = 0; i < NCASES; i++)
    ss_result_clear(r + i);
  ss_link_free(oct);
  ss_link_free(k8);
  ss_link_free(tet);
  ss_scheme_free(mlca);
  ss_scheme_free(box);
  char cmd[300];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", dir);
  return ss_test_done("test_store");
}
