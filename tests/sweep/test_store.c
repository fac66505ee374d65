/* test_store.c — the results store from the library side: a result read back
 * equals the computed one bit for bit (eigenvalues, NaN scaled Jacobian of a
 * case with no map, improper pair counts, what each verdict was judged on); a key is
 * stored once; lookups return the stored verdict; --where filters and refuses what does
 * not compile; identities separate schemes and parameters, and hold the tolerance
 * exactly; merge adds only what is missing, reports conflicts (resolved by --prefer),
 * refuses a store's own file; foreign, corrupt and other-version files are refused with a
 * message naming the file.  Schema versions: a schema-2 store made by hand SQL is read
 * as it is (the file untouched), merged, upgraded when opened to write (its rows
 * unchanged, its tables a fresh store's), and takes rows with what each verdict was
 * judged on and psi's figures (schema_versions). */
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
      a->seconds != b->seconds || a->v.cond.on != b->v.cond.on ||
      a->v.reg.on != b->v.reg.on || a->v.inj.on != b->v.inj.on ||
      a->psi.ran != b->psi.ran)
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

/* Version 2's tables and view, as its program created them. */
static const char *const v2_sql =
    "CREATE TABLE meta(key TEXT PRIMARY KEY, value TEXT NOT NULL);\n"
    "CREATE TABLE scheme(id INTEGER PRIMARY KEY, identity TEXT NOT NULL UNIQUE,\n"
    "  name TEXT NOT NULL, stencil TEXT, stencil_hash TEXT, tol REAL NOT NULL,\n"
    "  depth INTEGER NOT NULL, ring_levels INTEGER NOT NULL, certify INTEGER NOT NULL,\n"
    "  diagonals TEXT);\n"
    "CREATE TABLE result(scheme_id INTEGER NOT NULL REFERENCES scheme(id),\n"
    "  kind TEXT NOT NULL CHECK (kind IN ('vertex','edge','face','surface-vertex',\n"
    "                                     'edge-point')),\n"
    "  k INTEGER NOT NULL, link TEXT NOT NULL, cells INTEGER NOT NULL,\n"
    "  two_ring INTEGER NOT NULL, one_ring INTEGER NOT NULL,\n"
    "  lambda1 REAL, lambda2 REAL, lambda3 REAL, lambda4 REAL,\n"
    "  eigenvalues TEXT NOT NULL, eigen_condition TEXT NOT NULL,\n"
    "  eigen_reason TEXT NOT NULL, eigen_certified INTEGER NOT NULL,\n"
    "  tolerance REAL NOT NULL, regularity TEXT NOT NULL,\n"
    "  regularity_reason TEXT NOT NULL, regularity_certified INTEGER NOT NULL,\n"
    "  min_scaled_jacobian REAL, depth INTEGER NOT NULL, ring_level INTEGER NOT NULL,\n"
    "  centre_corner_folds INTEGER NOT NULL, injectivity TEXT NOT NULL,\n"
    "  injectivity_reason TEXT NOT NULL, degree INTEGER NOT NULL,\n"
    "  injectivity_certified INTEGER NOT NULL, improper_pairs INTEGER,\n"
    "  adjacent_pairs INTEGER, seconds REAL NOT NULL,\n"
    "  PRIMARY KEY (scheme_id, kind, k, link)) WITHOUT ROWID;\n"
    "CREATE VIEW cases AS SELECT s.name AS scheme, s.identity AS identity, r.*,\n"
    "  CASE WHEN 'fail' IN (r.eigen_condition, r.regularity, r.injectivity) THEN 'fail'\n"
    "       WHEN r.eigen_condition = 'pass' AND r.regularity = 'pass' AND\n"
    "            r.injectivity = 'pass' THEN 'pass'\n"
    "       ELSE 'undecided' END AS verdict\n"
    "  FROM result r JOIN scheme s ON s.id = r.scheme_id;\n"
    "INSERT INTO meta VALUES('program','subspectra'),('schema','2'),\n"
    "  ('created','2026-01-01T00:00:00Z');\n"
    "INSERT INTO scheme VALUES(7, 'mlca tol=1e-06 depth=6 rings=3', 'mlca', NULL, NULL,\n"
    "  1e-06, 6, 3, 0, NULL);\n"
    "INSERT INTO result VALUES(7, 'vertex', 9, 'nine', 14, 200, 40, 0.5, 0.5, 0.5, "
    "0.25,\n"
    "  '[[1,0,1],[0.5,0,3],[0.5,0,3],[0.5,0,3],[0.25,0,1]]', 'pass', '', 0, 1e-06,\n"
    "  'fail', 'folds on ring level 1', 0, -0.125, 6, 1, 2, 'fail', 'overlaps', 0, 0,\n"
    "  NULL, NULL, 0.75);\n"
    "INSERT INTO result VALUES(7, 'edge', 8, '', 8, 100, 30, 0.75, 0.75, 0.5, 0.5,\n"
    "  '[[1,0,1],[0.75,0,2],[0.75,0,2],[0.5,0,2],[0.5,0,2]]', 'fail', 'lambda1 double',\n"
    "  0, 1e-06, 'undecided', 'no map', 0, NULL, 6, -1, 0, 'undecided', 'no map', 0, 0,\n"
    "  NULL, NULL, 0.5);\n"
    "PRAGMA application_id = 1397977968;\n" /* 0x53537370 */
    "PRAGMA user_version = 2;\n";

/* The text of a one-column query's rows, joined by '|' (at most n bytes). */
static void sql_text(const char *path, const char *query, char *out, size_t n) {
  sqlite3 *db = NULL;
  sqlite3_stmt *q = NULL;
  size_t len = 0;
  out[0] = '\0';
  sqlite3_open_v2(path, &db, SQLITE_OPEN_READONLY, NULL);
  if (sqlite3_prepare_v2(db, query, -1, &q, NULL) == SQLITE_OK)
    while (sqlite3_step(q) == SQLITE_ROW && len + 1 < n) {
      const char *t = (const char *)sqlite3_column_text(q, 0);
      len += (size_t)snprintf(out + len, n - len, "%s%s", len ? "|" : "", t ? t : "NULL");
    }
  else
    snprintf(out, n, "error: %s", sqlite3_errmsg(db));
  sqlite3_finalize(q);
  sqlite3_close(db);
}

/* The whole file, malloc'd, its size in *n; NULL if unreadable. */
static char *slurp(const char *path, size_t *n) {
  FILE *f = fopen(path, "rb");
  if (!f) return NULL;
  fseek(f, 0, SEEK_END);
  *n = (size_t)ftell(f);
  rewind(f);
  char *b = malloc(*n ? *n : 1);
  if (b && fread(b, 1, *n, f) != *n) {
    free(b);
    b = NULL;
  }
  fclose(f);
  return b;
}

/* What the visit saw. */
typedef struct {
  int rows;       /* rows visited */
  int as_written; /* of which equal to the hand-written rows of v2_sql */
  int unjudged;   /* of which with every *_on and psi not recorded */
} v2_seen;

/* The hand-written rows of v2_sql, as ss_store_each must hand them out. */
static int is_hand_row(const ss_store_row *row) {
  const ss_result *r = &row->r;
  if (strcmp(row->scheme, "mlca") ||
      strcmp(row->identity, "mlca tol=1e-06 depth=6 rings=3"))
    return 0;
  if (r->kind == SS_CASE_VERTEX)
    return r->k == 9 && !strcmp(r->link, "nine") && r->cells == 14 &&
           r->two_ring == 200 && r->one_ring == 40 && r->neig == 5 &&
           r->eig[1].re == 0.5 && r->eig[1].mult == 3 && r->eig[4].re == 0.25 &&
           r->v.cond.verdict == SS_PASS && r->v.reg.verdict == SS_FAIL &&
           !strcmp(r->v.reg.reason, "folds on ring level 1") && r->min_sj == -0.125 &&
           r->depth == 6 && r->ring_level == 1 && r->centre_corner_folds == 2 &&
           r->v.inj.verdict == SS_FAIL && !strcmp(r->v.inj.reason, "overlaps") &&
           !r->has_diag && r->seconds == 0.75;
  return r->kind == SS_CASE_EDGE && r->k == 8 && !strcmp(r->link, "") &&
         r->valence == 8 && r->neig == 5 && r->eig[1].re == 0.75 &&
         r->v.cond.verdict == SS_FAIL && !strcmp(r->v.cond.reason, "lambda1 double") &&
         r->v.reg.verdict == SS_UNDECIDED && isnan(r->min_sj) && r->ring_level == -1 &&
         r->seconds == 0.5;
}

static int v2_visit(const ss_store_row *row, void *ctx) {
  v2_seen *s = ctx;
  const ss_result *r = &row->r;
  s->rows++;
  s->as_written += is_hand_row(row);
  s->unjudged += r->v.cond.on == SS_ON_NOTHING && r->v.reg.on == SS_ON_NOTHING &&
                 r->v.inj.on == SS_ON_NOTHING && !r->psi.ran;
  return 0;
}

/* The rows of a stored result key, compared with a computed one. */
typedef struct {
  const ss_result *want; /* the computed result */
  int found;             /* rows with its key */
  int equal;             /* of which carrying its judged-on and psi exactly */
} lookup;

static int visit_lookup(const ss_store_row *row, void *ctx) {
  lookup *l = ctx;
  const ss_result *a = &row->r, *b = l->want;
  if (a->kind != b->kind || a->k != b->k || strcmp(a->link, b->link)) return 0;
  l->found++;
  l->equal += a->v.cond.on == b->v.cond.on && a->v.reg.on == b->v.reg.on &&
              a->v.inj.on == b->v.inj.on && a->psi.ran == b->psi.ran &&
              a->psi.verdict == b->psi.verdict && a->psi.covered == b->psi.covered &&
              a->psi.uncovered == b->psi.uncovered && a->psi.pieces == b->psi.pieces &&
              a->v.reg.verdict == b->v.reg.verdict;
  return 0;
}

static void refused_newer(const char *path) {
  ss_error err = {0};
  ss_store *st = NULL;
  for (int mode = 0; mode < 2; mode++) {
    const ss_status s =
        ss_store_open(path, mode ? SS_STORE_WRITE : SS_STORE_READ, &st, &err);
    ss_store_close(st);
    st = NULL;
    CHECK(s == SS_EINPUT && strstr(err.msg, "schema version 4") &&
              strstr(err.msg, "reads version 3") && strstr(err.msg, path),
          "newer store (mode %d): status %d, '%s'", mode, (int)s, err.msg);
  }
}

/* A schema-2 store read as it is: the file's bytes unchanged, the new
 * columns NULL; merged into a new store `other`. */
static int v2_read(const char *old, const char *other) {
  ss_error err = {0};
  size_t n0 = 0, n1 = 0;
  char *b0 = slurp(old, &n0);
  ss_store *st = NULL;
  REQUIRE_OK(ss_store_open(old, SS_STORE_READ, &st, &err), &err);
  v2_seen s = {0};
  REQUIRE_OK(ss_store_each(st, NULL, v2_visit, &s, &err), &err);
  CHECK(s.rows == 2 && s.as_written == 2 && s.unjudged == 2,
        "schema 2 read-only: %d rows, %d as written, %d not judged", s.rows, s.as_written,
        s.unjudged);
  s = (v2_seen){0};
  REQUIRE_OK(ss_store_each(st,
                           "regularity_on IS NULL AND psi_verdict IS NULL AND verdict = "
                           "'fail'",
                           v2_visit, &s, &err),
             &err);
  CHECK(s.rows == 2, "the new columns are NULL in the view: %d rows", s.rows);
  ss_store_close(st);
  char *b1 = slurp(old, &n1);
  CHECK(b0 && b1 && n0 == n1 && !memcmp(b0, b1, n0),
        "read-only leaves the file (%zu, %zu)", n0, n1);
  free(b0);
  free(b1);
  char text[64];
  sql_text(old, "PRAGMA user_version", text, sizeof text);
  CHECK(!strcmp(text, "2"), "still version 2: %s", text);
  ss_store_merge_stats ms;
  REQUIRE_OK(ss_store_open(other, SS_STORE_WRITE, &st, &err), &err);
  REQUIRE_OK(ss_store_merge(st, old, SS_STORE_PREFER_NONE, &ms, &err), &err);
  CHECK(ms.added == 2 && ms.conflicts == 0, "merge of schema 2: %zu added, %zu conflicts",
        ms.added, ms.conflicts);
  s = (v2_seen){0};
  REQUIRE_OK(ss_store_each(st, NULL, v2_visit, &s, &err), &err);
  CHECK(s.rows == 2 && s.as_written == 2 && s.unjudged == 2, "merged: %d, %d, %d", s.rows,
        s.as_written, s.unjudged);
  ss_store_close(st);
  return 0;
}

/* Opened to write: upgraded, its tables as a fresh store's, its rows as they
 * were. */
static int v2_upgrade(const char *old, const char *fresh) {
  ss_error err = {0};
  ss_store *st = NULL;
  REQUIRE_OK(ss_store_open(fresh, SS_STORE_WRITE, &st, &err), &err);
  ss_store_close(st);
  REQUIRE_OK(ss_store_open(old, SS_STORE_WRITE, &st, &err), &err);
  char text[2048], want[2048];
  sql_text(old, "PRAGMA user_version", text, sizeof text);
  CHECK(!strcmp(text, "3"), "upgraded to version 3: %s", text);
  sql_text(old, "SELECT value FROM meta WHERE key = 'schema'", text, sizeof text);
  CHECK(!strcmp(text, "3"), "meta schema: %s", text);
  const char *const shapes[] = {"SELECT name || ' ' || type || ' ' || \"notnull\" || ' ' "
                                "|| ifnull(dflt_value, '-') "
                                "|| ' ' || pk FROM pragma_table_info('result')",
                                "SELECT name || ' ' || type || ' ' || \"notnull\" || ' ' "
                                "|| ifnull(dflt_value, '-') "
                                "|| ' ' || pk FROM pragma_table_info('scheme')",
                                "SELECT name FROM pragma_table_info('cases')"};
  for (int i = 0; i < 3; i++) {
    sql_text(old, shapes[i], text, sizeof text);
    sql_text(fresh, shapes[i], want, sizeof want);
    CHECK(!strcmp(text, want) && strstr(want, "psi"),
          "columns %d: upgraded '%s', fresh '%s'", i, text, want);
  }
  v2_seen s = {0};
  REQUIRE_OK(ss_store_each(st, NULL, v2_visit, &s, &err), &err);
  CHECK(s.rows == 2 && s.as_written == 2 && s.unjudged == 2, "upgraded rows: %d, %d, %d",
        s.rows, s.as_written, s.unjudged);
  ss_store_close(st);
  return 0;
}

/* New rows in the upgraded store: judged-on and psi, under the old identity
 * (its id kept) and a psi one, read back bit for bit. */
static int v2_new_rows(const char *old, const ss_scheme *mlca, const ss_link *oct) {
  ss_error err = {0};
  ss_result_opts ro = ss_result_defaults(), rp = ro;
  rp.psi_depth = 2;
  const ss_case c = {SS_CASE_VERTEX, oct, 0, SS_DIAG_BFS, 0};
  ss_result r0, r2;
  REQUIRE_OK(ss_result_compute(mlca, &c, &ro, &r0, &err), &err);
  REQUIRE_OK(ss_result_compute(mlca, &c, &rp, &r2, &err), &err);
  /* the regular vertex: psi is tricubic on every box of its ring, of one sign */
  CHECK(!r0.psi.ran && r0.v.reg.on == SS_ON_NET && r0.v.cond.on == SS_ON_SPECTRUM,
        "psi_depth 0: psi %d, regularity on %s", r0.psi.ran,
        ss_judged_on_name(r0.v.reg.on));
  CHECK(r2.psi.ran && r2.psi.verdict == SS_PASS && r2.psi.covered == 1.0 &&
            r2.psi.uncovered == 0.0 && r2.psi.pieces > 0 && r2.v.reg.on == SS_ON_PSI,
        "psi_depth 2: psi %d %s covered %g, regularity on %s", r2.psi.ran,
        ss_verdict_name(r2.psi.verdict), r2.psi.covered, ss_judged_on_name(r2.v.reg.on));
  ss_store_scheme sm = {"mlca", NULL, 0, 0, SS_DIAG_BFS, ro};
  ss_store_scheme sp = {"mlca", NULL, 0, 0, SS_DIAG_BFS, rp};
  int64_t idm = 0, idp = 0;
  ss_store *st = NULL;
  REQUIRE_OK(ss_store_open(old, SS_STORE_WRITE, &st, &err), &err);
  REQUIRE_OK(ss_store_scheme_id(st, &sm, &idm, &err), &err);
  REQUIRE_OK(ss_store_scheme_id(st, &sp, &idp, &err), &err);
  CHECK(idm == 7 && idp != 7, "the old identity keeps its id: %lld, psi's %lld",
        (long long)idm, (long long)idp);
  char text[256];
  ss_store_identity(&sp, text, sizeof text);
  CHECK(!strcmp(text, "mlca tol=1e-06 depth=6 rings=3 psi-depth=2"), "psi identity '%s'",
        text);
  REQUIRE_OK(ss_store_put(st, idm, &r0, NULL, &err), &err);
  REQUIRE_OK(ss_store_put(st, idp, &r2, NULL, &err), &err);
  ss_store_close(st);
  REQUIRE_OK(ss_store_open(old, SS_STORE_READ, &st, &err), &err);
  lookup l0 = {&r0, 0, 0}, l2 = {&r2, 0, 0};
  REQUIRE_OK(ss_store_each(st, "identity NOT LIKE '%psi%'", visit_lookup, &l0, &err),
             &err);
  REQUIRE_OK(ss_store_each(st, "identity LIKE '%psi-depth=2'", visit_lookup, &l2, &err),
             &err);
  CHECK(l0.found == 1 && l0.equal == 1 && l2.found == 1 && l2.equal == 1,
        "read back: %d/%d without psi, %d/%d with", l0.equal, l0.found, l2.equal,
        l2.found);
  v2_seen s = {0};
  REQUIRE_OK(ss_store_each(st, "eigen_on IS NULL", v2_visit, &s, &err), &err);
  CHECK(s.rows == 2 && s.as_written == 2, "the old rows keep NULL: %d", s.rows);
  ss_store_close(st);
  ss_result_clear(&r0);
  ss_result_clear(&r2);
  return 0;
}

/* Merge: NULL (not recorded) against a value is no conflict; another value
 * is. */
static int v2_merge_nulls(const char *old, const char *other) {
  ss_error err = {0};
  ss_store *st = NULL;
  ss_store_merge_stats ms;
  sql(other, "UPDATE result SET eigen_on = 'spectrum', regularity_on = 'control-net'");
  REQUIRE_OK(ss_store_open(other, SS_STORE_WRITE, &st, &err), &err);
  REQUIRE_OK(ss_store_merge(st, old, SS_STORE_PREFER_NONE, &ms, &err), &err);
  CHECK(ms.added == 2 && ms.present == 2 && ms.conflicts == 0,
        "NULL is no conflict: %zu added, %zu present, %zu conflicts", ms.added,
        ms.present, ms.conflicts);
  ss_store_close(st);
  sql(old, "UPDATE result SET regularity_on = 'psi' WHERE kind = 'edge'");
  REQUIRE_OK(ss_store_open(other, SS_STORE_WRITE, &st, &err), &err);
  REQUIRE_OK(ss_store_merge(st, old, SS_STORE_PREFER_NONE, &ms, &err), &err);
  CHECK(ms.conflicts == 1 && ms.present == 3, "another value conflicts: %zu, %zu present",
        ms.conflicts, ms.present);
  ss_store_close(st);
  return 0;
}

/* Schema versions (issue 34): a schema-2 store built here by hand SQL (the
 * tables of version 2 as that program created them, not by the code under
 * test) is read as it is, merged, upgraded, written with what version 3
 * added; a store newer than the program is refused naming both versions. */
static void schema_versions(const char *dir, const ss_scheme *mlca, const ss_link *oct) {
  char old[256], fresh[256], other[256], newer[256];
  snprintf(old, sizeof old, "%s/v2.db", dir);
  snprintf(fresh, sizeof fresh, "%s/v3.db", dir);
  snprintf(other, sizeof other, "%s/v2-merged.db", dir);
  snprintf(newer, sizeof newer, "%s/v4.db", dir);
  sql(old, v2_sql);
  CHECK(!v2_read(old, other), "schema 2 read as it is");
  CHECK(!v2_upgrade(old, fresh), "schema 2 upgraded");
  CHECK(!v2_new_rows(old, mlca, oct), "new rows in an upgraded store");
  CHECK(!v2_merge_nulls(old, other), "merge against an upgraded store");
  sql(newer, v2_sql);
  sql(newer, "PRAGMA user_version = 4");
  refused_newer(newer);
}

/* One hand edit of a copy of the valid store at path: open (read and write)
 * and merge refuse it, saying each of want (NULL-terminated) and the copy's
 * name; the original still merges. */
static void edited(const char *dir, const char *path, const char *edit, ...) {
  char copy[300], q[700];
  static int n;
  snprintf(copy, sizeof copy, "%s/edited%d.db", dir, n++);
  snprintf(q, sizeof q, "VACUUM INTO '%s'", copy);
  sql(path, q);
  sql(copy, edit);
  const char *want[8];
  int nw = 0;
  va_list ap;
  va_start(ap, edit);
  for (const char *w; nw < 8 && (w = va_arg(ap, const char *));)
    want[nw++] = w;
  va_end(ap);
  ss_error err = {0};
  ss_store *st = NULL;
  for (int mode = 0; mode < 3; mode++) {
    ss_status s;
    memset(&err, 0, sizeof err);
    if (mode < 2) {
      s = ss_store_open(copy, mode ? SS_STORE_WRITE : SS_STORE_READ, &st, &err);
      ss_store_close(st);
      st = NULL;
    } else { /* merged into a fresh store: refused, nothing written */
      char out[300];
      snprintf(out, sizeof out, "%s/merged%d.db", dir, n);
      if (ss_store_open(out, SS_STORE_WRITE, &st, &err)) {
        CHECK(0, "%s: %s", out, err.msg);
        return;
      }
      s = ss_store_merge(st, copy, SS_STORE_PREFER_NONE, NULL, &err);
      int rows = 0;
      ss_error e2 = {0};
      CHECK(ss_store_each(st, NULL, count_visit, &rows, &e2) == SS_OK && rows == 0,
            "%s: %d rows merged from a refused store", edit, rows);
      ss_store_close(st);
      st = NULL;
    }
    int ok = s == SS_EINPUT && strstr(err.msg, copy);
    for (int i = 0; i < nw; i++)
      ok = ok && strstr(err.msg, want[i]);
    CHECK(ok, "%s (%s): status %d, '%s'", edit, mode == 2 ? "merge" : "open", (int)s,
          err.msg);
  }
}

/* Hand-edited stores: every invalid row is refused by name (issue 35). */
static void hand_edited(const char *dir, const char *path) {
  edited(dir, path, "UPDATE result SET k = 'x' WHERE kind = 'edge' AND k = 8",
         "1 invalid row", "table result, row (scheme_id 1, kind 'edge', k 'x', link '')",
         "k = 'x' is not an integer in 0..2147483647", NULL);
  edited(dir, path, "UPDATE result SET cells = -1 WHERE kind = 'edge' AND k = 8",
         "kind 'edge', k 8", "cells = -1 is not an integer in 0..", NULL);
  edited(dir, path,
         "UPDATE result SET regularity = 'maybe' WHERE kind = 'edge' AND k = 8",
         "regularity = 'maybe' is not one of 'pass','fail','undecided'", NULL);
  edited(dir, path, "UPDATE result SET eigen_certified = 2.5 WHERE kind = 'edge'",
         "eigen_certified = 2.5 is not an integer in 0..1", NULL);
  edited(dir, path, "UPDATE result SET regularity_on = 'guess' WHERE kind = 'edge'",
         "regularity_on = 'guess' is not NULL or one of", NULL);
  edited(dir, path, "DELETE FROM scheme WHERE name = 'mlca'",
         "scheme_id = 1 is not the id of a row of table scheme", NULL);
  edited(dir, path,
         "PRAGMA ignore_check_constraints = 1; UPDATE result SET kind = 'vortex' WHERE "
         "kind = 'edge' AND k = 8",
         "kind 'vortex'", "kind = 'vortex' is not one of 'vertex','edge'", NULL);
  edited(dir, path, "UPDATE scheme SET diagonals = 'diag' WHERE name = 'mlca'",
         "table scheme, row id 1: diagonals = 'diag' is not NULL or one of 'bfs'", NULL);
  edited(dir, path, "UPDATE scheme SET tol = 0 WHERE name = 'mlca'",
         "table scheme, row id 1: tol = 0.0 is not a finite number > 0", NULL);
  edited(dir, path, "UPDATE result SET seconds = -1", "5 invalid rows",
         "seconds = -1.0 is not a finite number >= 0", "; and more", NULL);
  /* a malformed eigenvalue list: found as the rows are read */
  char copy[300], q[700];
  snprintf(copy, sizeof copy, "%s/eig.db", dir);
  snprintf(q, sizeof q, "VACUUM INTO '%s'", copy);
  sql(path, q);
  sql(copy, "UPDATE result SET eigenvalues = '[1' WHERE kind = 'edge' AND k = 8");
  ss_error err = {0};
  ss_store *st = NULL;
  int rows = 0;
  CHECK(ss_store_open(copy, SS_STORE_READ, &st, &err) == SS_OK, "%s: %s", copy, err.msg);
  CHECK(st && ss_store_each(st, NULL, count_visit, &rows, &err) == SS_EINPUT &&
            strstr(err.msg, "kind 'edge', k 8") &&
            strstr(err.msg, "eigenvalues = '[1' is not a JSON list"),
        "malformed eigenvalues: %s", err.msg);
  ss_store_close(st);
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

  schema_versions(dir, mlca, oct);
  hand_edited(dir, path);

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
