/* ss_store.c — the SQLite results store (ss_store.h). */
#include "ss_store.h"

#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include <json-c/json.h>
#include <sqlite3.h>

struct ss_store {
  sqlite3 *db;       /* the connection */
  char *path;        /* the file, for messages */
  sqlite3_stmt *has; /* the verdicts of one key */
  sqlite3_stmt *put; /* INSERT OR IGNORE INTO result */
  int readonly;      /* opened with SS_STORE_READ */
};

/* The schema.  Column comments are repeated in the README. */
static const char *const schema_sql =
    "CREATE TABLE meta(key TEXT PRIMARY KEY, value TEXT NOT NULL);\n"
    "CREATE TABLE scheme(\n"
    "  id INTEGER PRIMARY KEY,\n"
    "  identity TEXT NOT NULL UNIQUE,\n"
    "  name TEXT NOT NULL,\n"
    "  stencil TEXT,\n"
    "  stencil_hash TEXT,\n"
    "  tol REAL NOT NULL,\n"
    "  depth INTEGER NOT NULL,\n"
    "  ring_levels INTEGER NOT NULL,\n"
    "  certify INTEGER NOT NULL,\n"
    "  diagonals TEXT);\n"
    "CREATE TABLE result(\n"
    "  scheme_id INTEGER NOT NULL REFERENCES scheme(id),\n"
    "  kind TEXT NOT NULL CHECK (kind IN ('vertex','edge','face','surface-vertex',\n"
    "                                     'edge-point')),\n"
    "  k INTEGER NOT NULL,\n"
    "  link TEXT NOT NULL,\n"
    "  cells INTEGER NOT NULL,\n"
    "  two_ring INTEGER NOT NULL,\n"
    "  one_ring INTEGER NOT NULL,\n"
    "  lambda1 REAL, lambda2 REAL, lambda3 REAL, lambda4 REAL,\n"
    "  eigenvalues TEXT NOT NULL,\n"
    "  eigen_condition TEXT NOT NULL,\n"
    "  eigen_reason TEXT NOT NULL,\n"
    "  eigen_certified INTEGER NOT NULL,\n"
    "  tolerance REAL NOT NULL,\n"
    "  regularity TEXT NOT NULL,\n"
    "  regularity_reason TEXT NOT NULL,\n"
    "  regularity_certified INTEGER NOT NULL,\n"
    "  min_scaled_jacobian REAL,\n"
    "  depth INTEGER NOT NULL,\n"
    "  ring_level INTEGER NOT NULL,\n"
    "  centre_corner_folds INTEGER NOT NULL,\n"
    "  injectivity TEXT NOT NULL,\n"
    "  injectivity_reason TEXT NOT NULL,\n"
    "  degree INTEGER NOT NULL,\n"
    "  injectivity_certified INTEGER NOT NULL,\n"
    "  improper_pairs INTEGER,\n"
    "  adjacent_pairs INTEGER,\n"
    "  seconds REAL NOT NULL,\n"
    "  PRIMARY KEY (scheme_id, kind, k, link)) WITHOUT ROWID;\n"
    "CREATE VIEW cases AS SELECT s.name AS scheme, s.identity AS identity, r.*,\n"
    "  CASE WHEN 'fail' IN (r.eigen_condition, r.regularity, r.injectivity) THEN 'fail'\n"
    "       WHEN r.eigen_condition = 'pass' AND r.regularity = 'pass' AND\n"
    "            r.injectivity = 'pass' THEN 'pass'\n"
    "       ELSE 'undecided' END AS verdict\n"
    "  FROM result r JOIN scheme s ON s.id = r.scheme_id;\n";

static ss_status db_error(ss_store *st, ss_error *err, const char *what) {
  return ss_error_set(err, SS_EIO, "%s: %s: %s", st->path, what, sqlite3_errmsg(st->db));
}

static int exec(ss_store *st, const char *sql) {
  return sqlite3_exec(st->db, sql, NULL, NULL, NULL);
}

/* One integer from a one-row query; -1 on error. */
static int64_t query_int(ss_store *st, const char *sql, int *rc) {
  sqlite3_stmt *q = NULL;
  int64_t v = -1;
  *rc = sqlite3_prepare_v2(st->db, sql, -1, &q, NULL);
  if (*rc == SQLITE_OK) {
    *rc = sqlite3_step(q);
    if (*rc == SQLITE_ROW) {
      v = sqlite3_column_int64(q, 0);
      *rc = SQLITE_OK;
    }
  }
  sqlite3_finalize(q);
  return v;
}

/* Is the open file a healthy store of our schema?  An empty database (a new
 * or zero-length file) reports *empty = 1. */
static ss_status validate(ss_store *st, int *empty, ss_error *err) {
  int rc;
  const int64_t ntables = query_int(st, "SELECT count(*) FROM sqlite_schema", &rc);
  if (rc != SQLITE_OK)
    return ss_error_set(err, SS_EINPUT, "%s: not a subspectra results store (%s)",
                        st->path, sqlite3_errmsg(st->db));
  const int64_t app = query_int(st, "PRAGMA application_id", &rc);
  const int64_t ver = query_int(st, "PRAGMA user_version", &rc);
  *empty = ntables == 0 && app == 0;
  if (*empty) return SS_OK;
  if (app != SS_STORE_APP_ID)
    return ss_error_set(err, SS_EINPUT,
                        "%s: a foreign SQLite database, not a subspectra results "
                        "store (application_id %" PRId64 ")",
                        st->path, app);
  if (ver != SS_STORE_SCHEMA)
    return ss_error_set(err, SS_EINPUT,
                        "%s: results store of schema version %" PRId64
                        ", this program reads version %d",
                        st->path, ver, SS_STORE_SCHEMA);
  sqlite3_stmt *q = NULL;
  rc = sqlite3_prepare_v2(st->db, "PRAGMA quick_check", -1, &q, NULL);
  if (rc == SQLITE_OK) rc = sqlite3_step(q);
  if (rc != SQLITE_ROW || strcmp((const char *)sqlite3_column_text(q, 0), "ok")) {
    char what[200];
    snprintf(what, sizeof what, "%s",
             rc == SQLITE_ROW ? (const char *)sqlite3_column_text(q, 0)
                              : sqlite3_errmsg(st->db));
    sqlite3_finalize(q);
    return ss_error_set(err, SS_EINPUT, "%s: corrupt results store (%s)", st->path, what);
  }
  sqlite3_finalize(q);
  return SS_OK;
}

static ss_status create(ss_store *st, ss_error *err) {
  char sql[4096];
  char when[32];
  time_t t = time(NULL);
  struct tm tm;
  strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", gmtime_r(&t, &tm));
  snprintf(sql, sizeof sql,
           "BEGIN IMMEDIATE;\n%s"
           "INSERT INTO meta VALUES('program','subspectra'),('schema','%d'),"
           "('created','%s');\n"
           "PRAGMA application_id = %d;\nPRAGMA user_version = %d;\nCOMMIT;",
           schema_sql, SS_STORE_SCHEMA, when, SS_STORE_APP_ID, SS_STORE_SCHEMA);
  if (exec(st, sql) != SQLITE_OK) {
    ss_status s = db_error(st, err, "cannot create the schema");
    exec(st, "ROLLBACK");
    return s;
  }
  return SS_OK;
}

static ss_status prepare(ss_store *st, ss_error *err) {
  if (sqlite3_prepare_v2(st->db,
                         "SELECT eigen_condition, regularity, injectivity FROM result "
                         "WHERE "
                         "scheme_id=?1 AND (kind=?2 OR (?2='vertex' AND "
                         "kind='edge-point')) AND k=?3 AND link=?4",
                         -1, &st->has, NULL) != SQLITE_OK)
    return db_error(st, err, "prepare");
  if (st->readonly) return SS_OK;
  if (sqlite3_prepare_v2(st->db,
                         "INSERT OR IGNORE INTO result(scheme_id,kind,k,link,cells,"
                         "two_ring,one_ring,lambda1,lambda2,lambda3,lambda4,eigenvalues,"
                         "eigen_condition,eigen_reason,tolerance,regularity,"
                         "regularity_reason,min_scaled_jacobian,depth,improper_pairs,"
                         "adjacent_pairs,seconds,eigen_certified,regularity_certified,"
                         "ring_level,centre_corner_folds,injectivity,injectivity_reason,"
                         "degree,injectivity_certified) VALUES(?1,?2,?3,?4,?5,?6,?7,?8,"
                         "?9,?10,?11,?12,?13,?14,?15,?16,?17,?18,?19,?20,?21,?22,?23,?24,"
                         "?25,?26,?27,?28,?29,?30)",
                         -1, &st->put, NULL) != SQLITE_OK)
    return db_error(st, err, "prepare");
  return SS_OK;
}

/* Reading a WAL database needs its -shm file, which cannot be created beside
 * a store in a directory the user may not write (a shared results folder, a
 * read-only medium).  Such a store is reopened as immutable: nothing is
 * written, and no other process may be writing it meanwhile.  1 if reopened. */
static int retry_immutable(ss_store *st, const char *path) {
  const int code = sqlite3_errcode(st->db);
  if (code != SQLITE_READONLY && code != SQLITE_CANTOPEN) return 0;
  /* a file: URI, percent-encoding what the URI syntax reserves */
  const size_t n = strlen(path);
  char *uri = malloc(3 * n + 32);
  if (!uri) return 0;
  size_t k = (size_t)sprintf(uri, "file:");
  for (size_t i = 0; i < n; i++) {
    const unsigned char ch = (unsigned char)path[i];
    if (ch == '%' || ch == '?' || ch == '#' || ch <= ' ')
      k += (size_t)sprintf(uri + k, "%%%02X", ch);
    else
      uri[k++] = (char)ch;
  }
  strcpy(uri + k, "?immutable=1");
  sqlite3_close(st->db);
  st->db = NULL;
  const int rc = sqlite3_open_v2(
      uri, &st->db, SQLITE_OPEN_READONLY | SQLITE_OPEN_URI | SQLITE_OPEN_NOMUTEX, NULL);
  free(uri);
  return rc == SQLITE_OK;
}

ss_status ss_store_open(const char *path, ss_store_mode mode, ss_store **out,
                        ss_error *err) {
  *out = NULL;
  ss_store *st = calloc(1, sizeof *st);
  if (!st || !(st->path = strdup(path))) {
    free(st);
    return ss_error_nomem(err, "results store");
  }
  st->readonly = mode == SS_STORE_READ;
  struct stat sb;
  if (st->readonly && stat(path, &sb) != 0) {
    free(st->path);
    free(st);
    return ss_error_set(err, SS_EIO, "%s: no such results store", path);
  }
  const int flags =
      st->readonly ? SQLITE_OPEN_READONLY : SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE;
  ss_status s = SS_OK;
  int empty = 0;
  if (sqlite3_open_v2(path, &st->db, flags | SQLITE_OPEN_NOMUTEX, NULL) != SQLITE_OK) {
    s = ss_error_set(err, SS_EIO, "%s: cannot open: %s", path,
                     st->db ? sqlite3_errmsg(st->db) : "out of memory");
    goto fail;
  }
  sqlite3_busy_timeout(st->db, 30000);
  s = validate(st, &empty, err);
  if (s && st->readonly && retry_immutable(st, path)) s = validate(st, &empty, err);
  if (s) goto fail;
  if (empty && st->readonly) {
    s = ss_error_set(err, SS_EINPUT, "%s: an empty file, not a subspectra results store",
                     path);
    goto fail;
  }
  if (!st->readonly) {
    /* WAL: readers never block the writer, and a killed writer leaves a log
     * that the next open replays; NORMAL syncs at checkpoints, enough
     * against a process being killed (not against power loss). */
    if (exec(st, "PRAGMA journal_mode=WAL") != SQLITE_OK ||
        exec(st, "PRAGMA synchronous=NORMAL") != SQLITE_OK) {
      s = db_error(st, err, "cannot set the journal mode");
      goto fail;
    }
    if (empty && (s = create(st, err))) goto fail;
  }
  if ((s = prepare(st, err))) goto fail;
  *out = st;
  return SS_OK;
fail:
  ss_store_close(st);
  return s;
}

void ss_store_close(ss_store *st) {
  if (!st) return;
  sqlite3_finalize(st->has);
  sqlite3_finalize(st->put);
  sqlite3_close(st->db);
  free(st->path);
  free(st);
}

void ss_store_identity(const ss_store_scheme *sc, char *buf, size_t n) {
  char diag[40] = "";
  if (sc->reads_diagonals)
    snprintf(diag, sizeof diag, " diagonals=%s", ss_diag_name(sc->diag));
  if (sc->stencil)
    snprintf(buf, n, "stencil:%016" PRIx64 " tol=%g depth=%d rings=%d%s%s",
             sc->stencil_hash, sc->opts.tol, sc->opts.depth, sc->opts.ring_levels,
             sc->opts.certify ? " certified" : "", diag);
  else
    snprintf(buf, n, "%s tol=%g depth=%d rings=%d%s%s", sc->name, sc->opts.tol,
             sc->opts.depth, sc->opts.ring_levels, sc->opts.certify ? " certified" : "",
             diag);
}

ss_status ss_store_scheme_id(ss_store *st, const ss_store_scheme *sc, int64_t *id,
                             ss_error *err) {
  char ident[256], hash[17];
  ss_store_identity(sc, ident, sizeof ident);
  snprintf(hash, sizeof hash, "%016" PRIx64, sc->stencil_hash);
  sqlite3_stmt *q = NULL;
  int rc =
      sqlite3_prepare_v2(st->db, "SELECT id FROM scheme WHERE identity=?1", -1, &q, NULL);
  if (rc == SQLITE_OK) {
    sqlite3_bind_text(q, 1, ident, -1, SQLITE_TRANSIENT);
    rc = sqlite3_step(q);
  }
  if (rc == SQLITE_ROW) {
    *id = sqlite3_column_int64(q, 0);
    sqlite3_finalize(q);
    return SS_OK;
  }
  sqlite3_finalize(q);
  if (rc != SQLITE_DONE) return db_error(st, err, "scheme lookup");
  if (st->readonly)
    return ss_error_set(err, SS_EINPUT, "%s: no results for scheme '%s'", st->path,
                        ident);
  rc = sqlite3_prepare_v2(st->db,
                          "INSERT OR IGNORE INTO scheme(identity,name,stencil,"
                          "stencil_hash,tol,depth,diagonals,ring_levels,certify) "
                          "VALUES(?1,?2,?3,?4,?5,?6,?7,?8,?9)",
                          -1, &q, NULL);
  if (rc == SQLITE_OK) {
    sqlite3_bind_text(q, 1, ident, -1, SQLITE_TRANSIENT);
    sqlite3_bind_text(q, 2, sc->name, -1, SQLITE_TRANSIENT);
    if (sc->stencil) {
      sqlite3_bind_text(q, 3, sc->stencil, -1, SQLITE_TRANSIENT);
      sqlite3_bind_text(q, 4, hash, -1, SQLITE_TRANSIENT);
    }
    sqlite3_bind_double(q, 5, sc->opts.tol);
    sqlite3_bind_int(q, 6, sc->opts.depth);
    if (sc->reads_diagonals)
      sqlite3_bind_text(q, 7, ss_diag_name(sc->diag), -1, SQLITE_STATIC);
    sqlite3_bind_int(q, 8, sc->opts.ring_levels);
    sqlite3_bind_int(q, 9, sc->opts.certify);
    rc = sqlite3_step(q);
  }
  sqlite3_finalize(q);
  if (rc != SQLITE_DONE) return db_error(st, err, "scheme insert");
  /* another process may have inserted it first: look it up again */
  return ss_store_scheme_id(st, sc, id, err);
}

static ss_verdict_kind verdict_of(const char *name);

ss_status ss_store_has(ss_store *st, int64_t id, ss_case_kind kind, int k,
                       const char *link, int *found, ss_verdict_kind *verdict,
                       ss_error *err) {
  sqlite3_reset(st->has);
  sqlite3_bind_int64(st->has, 1, id);
  sqlite3_bind_text(st->has, 2, ss_case_name(kind), -1, SQLITE_STATIC);
  sqlite3_bind_int(st->has, 3, k);
  sqlite3_bind_text(st->has, 4, link ? link : "", -1, SQLITE_TRANSIENT);
  const int rc = sqlite3_step(st->has);
  *found = rc == SQLITE_ROW;
  if (*found && verdict) {
    ss_result r;
    r.cond.verdict = verdict_of((const char *)sqlite3_column_text(st->has, 0));
    r.reg.verdict = verdict_of((const char *)sqlite3_column_text(st->has, 1));
    r.inj.verdict = verdict_of((const char *)sqlite3_column_text(st->has, 2));
    *verdict = ss_result_verdict(&r);
  }
  sqlite3_reset(st->has);
  if (rc != SQLITE_ROW && rc != SQLITE_DONE) return db_error(st, err, "lookup");
  return SS_OK;
}

/* The kept eigenvalues as JSON [[re, im, multiplicity], ...], 17 digits so
 * that they read back bit for bit. */
static char *eig_json(const ss_result *r) {
  size_t cap = 64 + (size_t)r->neig * 64, len = 0;
  char *s = malloc(cap);
  if (!s) return NULL;
  len += (size_t)snprintf(s, cap, "[");
  for (int i = 0; i < r->neig; i++)
    len += (size_t)snprintf(s + len, cap - len, "%s[%.17g,%.17g,%d]", i ? "," : "",
                            r->eig[i].re, r->eig[i].im, r->eig[i].mult);
  snprintf(s + len, cap - len, "]");
  return s;
}

static void bind_real(sqlite3_stmt *q, int i, double v) {
  if (isfinite(v))
    sqlite3_bind_double(q, i, v);
  else
    sqlite3_bind_null(q, i);
}

ss_status ss_store_put(ss_store *st, int64_t id, const ss_result *r, int *added,
                       ss_error *err) {
  if (st->readonly) return ss_error_set(err, SS_EINPUT, "%s: opened read-only", st->path);
  char *ev = eig_json(r);
  if (!ev) return ss_error_nomem(err, "eigenvalue list");
  sqlite3_stmt *q = st->put;
  sqlite3_reset(q);
  sqlite3_clear_bindings(q);
  sqlite3_bind_int64(q, 1, id);
  sqlite3_bind_text(q, 2, ss_case_name(r->kind), -1, SQLITE_STATIC);
  sqlite3_bind_int(q, 3, r->k);
  sqlite3_bind_text(q, 4, r->link ? r->link : "", -1, SQLITE_STATIC);
  sqlite3_bind_int64(q, 5, (int64_t)r->cells);
  sqlite3_bind_int64(q, 6, (int64_t)r->two_ring);
  sqlite3_bind_int64(q, 7, (int64_t)r->one_ring);
  for (int i = 1; i <= 4; i++)
    if (i < r->neig) bind_real(q, 7 + i, hypot(r->eig[i].re, r->eig[i].im));
  sqlite3_bind_text(q, 12, ev, -1, SQLITE_STATIC);
  sqlite3_bind_text(q, 13, ss_verdict_name(r->cond.verdict), -1, SQLITE_STATIC);
  sqlite3_bind_text(q, 14, r->cond.reason, -1, SQLITE_STATIC);
  sqlite3_bind_double(q, 15, r->tol);
  sqlite3_bind_text(q, 16, ss_verdict_name(r->reg.verdict), -1, SQLITE_STATIC);
  sqlite3_bind_text(q, 17, r->reg.reason, -1, SQLITE_STATIC);
  bind_real(q, 18, r->min_sj);
  sqlite3_bind_int(q, 19, r->depth);
  if (r->has_diag) {
    sqlite3_bind_int64(q, 20, (int64_t)r->improper);
    sqlite3_bind_int64(q, 21, (int64_t)r->pairs);
  }
  sqlite3_bind_double(q, 22, r->seconds);
  sqlite3_bind_int(q, 23, r->cond_certified);
  sqlite3_bind_int(q, 24, r->reg_certified);
  sqlite3_bind_int(q, 25, r->ring_level);
  sqlite3_bind_int64(q, 26, (int64_t)r->centre_corner_folds);
  sqlite3_bind_text(q, 27, ss_verdict_name(r->inj.verdict), -1, SQLITE_STATIC);
  sqlite3_bind_text(q, 28, r->inj.reason, -1, SQLITE_STATIC);
  sqlite3_bind_int(q, 29, r->inj_degree);
  sqlite3_bind_int(q, 30, r->inj_certified);
  const int rc = sqlite3_step(q);
  sqlite3_reset(q);
  free(ev);
  if (rc != SQLITE_DONE) return db_error(st, err, "insert");
  if (added) *added = sqlite3_changes(st->db) > 0;
  return SS_OK;
}

ss_status ss_store_count(ss_store *st, int64_t id, size_t nk[SS_NCASEKINDS],
                         ss_error *err) {
  for (int i = 0; i < SS_NCASEKINDS; i++)
    nk[i] = 0;
  sqlite3_stmt *q = NULL;
  int rc = sqlite3_prepare_v2(st->db,
                              "SELECT kind, count(*) FROM result WHERE ?1 < 0 OR "
                              "scheme_id = ?1 GROUP BY kind",
                              -1, &q, NULL);
  if (rc == SQLITE_OK) sqlite3_bind_int64(q, 1, id);
  while (rc == SQLITE_OK && (rc = sqlite3_step(q)) == SQLITE_ROW) {
    const char *kind = (const char *)sqlite3_column_text(q, 0);
    for (int i = 0; i < SS_NCASEKINDS; i++)
      if (!strcmp(kind, ss_case_name((ss_case_kind)i)))
        nk[i] = (size_t)sqlite3_column_int64(q, 1);
    rc = SQLITE_OK;
  }
  sqlite3_finalize(q);
  if (rc != SQLITE_DONE) return db_error(st, err, "count");
  return SS_OK;
}

static int kind_of(const char *name) {
  for (int i = 0; i < SS_NCASEKINDS; i++)
    if (!strcmp(name, ss_case_name((ss_case_kind)i))) return i;
  return -1;
}

static ss_verdict_kind verdict_of(const char *name) {
  return !strcmp(name, "pass") ? SS_PASS : !strcmp(name, "fail") ? SS_FAIL : SS_UNDECIDED;
}

static void copy_text(char *dst, size_t n, const unsigned char *src) {
  snprintf(dst, n, "%s", src ? (const char *)src : "");
}

/* Read the eigenvalue list back; SS_EINPUT when it is not what eig_json
 * writes. */
static ss_status parse_eig(const char *text, ss_result *r) {
  json_object *a = json_tokener_parse(text);
  ss_status s = SS_OK;
  if (!a || !json_object_is_type(a, json_type_array) ||
      json_object_array_length(a) > SS_RESULT_NEIG) {
    s = SS_EINPUT;
    goto done;
  }
  r->neig = (int)json_object_array_length(a);
  for (int i = 0; i < r->neig; i++) {
    json_object *v = json_object_array_get_idx(a, (size_t)i);
    if (!json_object_is_type(v, json_type_array) || json_object_array_length(v) != 3) {
      s = SS_EINPUT;
      goto done;
    }
    r->eig[i].re = json_object_get_double(json_object_array_get_idx(v, 0));
    r->eig[i].im = json_object_get_double(json_object_array_get_idx(v, 1));
    r->eig[i].mult = json_object_get_int(json_object_array_get_idx(v, 2));
  }
done:
  json_object_put(a);
  return s;
}

ss_status ss_store_each(ss_store *st, const char *where, ss_store_visit visit, void *ctx,
                        ss_error *err) {
  static const char *const cols =
      "SELECT scheme, identity, kind, k, link, cells, two_ring, one_ring, eigenvalues, "
      "eigen_condition, eigen_reason, tolerance, regularity, regularity_reason, "
      "min_scaled_jacobian, depth, improper_pairs, adjacent_pairs, seconds, "
      "eigen_certified, regularity_certified, ring_level, centre_corner_folds, "
      "injectivity, injectivity_reason, degree, injectivity_certified FROM cases";
  size_t n = strlen(cols) + (where ? strlen(where) : 0) + 64;
  char *sql = malloc(n);
  if (!sql) return ss_error_nomem(err, "query");
  snprintf(sql, n, "%s%s%s%s ORDER BY identity, kind, k, link", cols,
           where ? " WHERE (" : "", where ? where : "", where ? ")" : "");
  sqlite3_stmt *q = NULL;
  const char *tail = NULL;
  int rc = sqlite3_prepare_v2(st->db, sql, -1, &q, &tail);
  if (rc != SQLITE_OK || (tail && *tail)) {
    ss_status s = ss_error_set(err, SS_EINPUT, "--where '%s': %s", where ? where : "",
                               rc != SQLITE_OK ? sqlite3_errmsg(st->db)
                                               : "more than one statement");
    sqlite3_finalize(q);
    free(sql);
    return s;
  }
  free(sql);
  ss_status s = SS_OK;
  while ((rc = sqlite3_step(q)) == SQLITE_ROW) {
    ss_store_row row;
    memset(&row, 0, sizeof row);
    row.scheme = (const char *)sqlite3_column_text(q, 0);
    row.identity = (const char *)sqlite3_column_text(q, 1);
    ss_result *r = &row.r;
    const int kind = kind_of((const char *)sqlite3_column_text(q, 2));
    if (kind < 0 || parse_eig((const char *)sqlite3_column_text(q, 8), r)) {
      s = ss_error_set(err, SS_EINPUT, "%s: malformed result row", st->path);
      break;
    }
    r->kind = (ss_case_kind)kind;
    r->k = sqlite3_column_int(q, 3);
    r->valence = kind == SS_CASE_EDGE || kind == SS_CASE_SURFACE_VERTEX ? r->k
                 : kind == SS_CASE_EDGE_POINT                           ? r->k - 2
                                                                        : 0;
    r->link = (char *)sqlite3_column_text(q, 4);
    r->cells = (size_t)sqlite3_column_int64(q, 5);
    r->two_ring = (size_t)sqlite3_column_int64(q, 6);
    r->one_ring = (size_t)sqlite3_column_int64(q, 7);
    r->cond.verdict = verdict_of((const char *)sqlite3_column_text(q, 9));
    copy_text(r->cond.reason, sizeof r->cond.reason, sqlite3_column_text(q, 10));
    r->tol = sqlite3_column_double(q, 11);
    r->reg.verdict = verdict_of((const char *)sqlite3_column_text(q, 12));
    copy_text(r->reg.reason, sizeof r->reg.reason, sqlite3_column_text(q, 13));
    r->min_sj = sqlite3_column_type(q, 14) == SQLITE_NULL ? (double)NAN
                                                          : sqlite3_column_double(q, 14);
    r->depth = sqlite3_column_int(q, 15);
    r->has_diag = sqlite3_column_type(q, 16) != SQLITE_NULL;
    r->improper = (size_t)sqlite3_column_int64(q, 16);
    r->pairs = (size_t)sqlite3_column_int64(q, 17);
    r->seconds = sqlite3_column_double(q, 18);
    r->cond_certified = sqlite3_column_int(q, 19);
    r->reg_certified = sqlite3_column_int(q, 20);
    r->ring_level = sqlite3_column_int(q, 21);
    r->centre_corner_folds = (size_t)sqlite3_column_int64(q, 22);
    r->inj.verdict = verdict_of((const char *)sqlite3_column_text(q, 23));
    copy_text(r->inj.reason, sizeof r->inj.reason, sqlite3_column_text(q, 24));
    r->inj_degree = sqlite3_column_int(q, 25);
    r->inj_certified = sqlite3_column_int(q, 26);
    if (visit(&row, ctx)) break;
  }
  if (!s && rc != SQLITE_ROW && rc != SQLITE_DONE) s = db_error(st, err, "query");
  sqlite3_finalize(q);
  return s;
}

ss_status ss_store_merge(ss_store *st, const char *src, size_t *added, size_t *present,
                         ss_error *err) {
  ss_store *in = NULL;
  ss_status s = ss_store_open(src, SS_STORE_READ, &in, err);
  if (s) return s;
  size_t nin[SS_NCASEKINDS], before[SS_NCASEKINDS], after[SS_NCASEKINDS];
  s = ss_store_count(in, -1, nin, err);
  ss_store_close(in);
  if (s) return s;
  if ((s = ss_store_count(st, -1, before, err))) return s;
  sqlite3_stmt *q = NULL;
  int rc = sqlite3_prepare_v2(st->db, "ATTACH DATABASE ?1 AS src", -1, &q, NULL);
  if (rc == SQLITE_OK) {
    sqlite3_bind_text(q, 1, src, -1, SQLITE_TRANSIENT);
    rc = sqlite3_step(q);
  }
  sqlite3_finalize(q);
  if (rc != SQLITE_DONE) return db_error(st, err, "cannot attach the input store");
  /* schemes are matched by identity, so ids may differ between stores */
  rc = exec(st, "BEGIN IMMEDIATE;"
                "INSERT OR IGNORE INTO main.scheme(identity,name,stencil,stencil_hash,"
                "tol,depth,ring_levels,certify,diagonals) SELECT identity,name,stencil,"
                "stencil_hash,tol,depth,ring_levels,certify,diagonals FROM src.scheme;"
                "INSERT OR IGNORE INTO main.result SELECT m.id, r.kind, r.k, r.link, "
                "r.cells, r.two_ring, r.one_ring, r.lambda1, r.lambda2, r.lambda3, "
                "r.lambda4, r.eigenvalues, r.eigen_condition, r.eigen_reason, "
                "r.eigen_certified, r.tolerance, r.regularity, r.regularity_reason, "
                "r.regularity_certified, r.min_scaled_jacobian, r.depth, r.ring_level, "
                "r.centre_corner_folds, r.injectivity, r.injectivity_reason, r.degree, "
                "r.injectivity_certified, r.improper_pairs, r.adjacent_pairs, "
                "r.seconds FROM src.result r JOIN src.scheme s ON s.id = r.scheme_id "
                "JOIN main.scheme m ON m.identity = s.identity;"
                "COMMIT;");
  if (rc != SQLITE_OK) {
    s = db_error(st, err, "merge");
    exec(st, "ROLLBACK");
  }
  exec(st, "DETACH DATABASE src");
  if (s || (s = ss_store_count(st, -1, after, err))) return s;
  size_t a = 0, t = 0;
  for (int i = 0; i < SS_NCASEKINDS; i++) {
    a += after[i] - before[i];
    t += nin[i];
  }
  if (added) *added = a;
  if (present) *present = t - a;
  return SS_OK;
}
