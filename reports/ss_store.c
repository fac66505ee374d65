/* ss_store.c — the SQLite results store (ss_store.h). */
#include "ss_store.h"

#include <errno.h>
#include <inttypes.h>
#include <libgen.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include <json-c/json.h>
#include <sqlite3.h>

#include "ss_store_impl.h"

enum { SS_STORE_OPEN_WAIT_MS = 5000 }; /* how long open waits for a lock */

ss_status ss_store_db_error(ss_store *st, ss_error *err, const char *what) {
  const int code = sqlite3_errcode(st->db);
  return ss_error_set(err, SS_EIO, "%s: %s: %s%s", st->path, what, sqlite3_errmsg(st->db),
                      code == SQLITE_BUSY || code == SQLITE_LOCKED
                          ? " (another process holds the results store)"
                          : "");
}

int ss_store_exec(ss_store *st, const char *sql) {
  return sqlite3_exec(st->db, sql, NULL, NULL, NULL);
}

/* exec, retried while the database is busy, up to about ms milliseconds.
 * Switching to WAL needs an exclusive lock, and where two connections would
 * deadlock on a lock upgrade SQLite returns SQLITE_BUSY at once without
 * calling the busy handler (seen when several sweeps create one store at
 * once on a loaded machine): so wait here, 10 ms at a time. */
static int exec_retry(ss_store *st, const char *sql, int ms) {
  int rc;
  const struct timespec pause = {0, 10 * 1000 * 1000};
  for (int waited = 0;; waited += 10) {
    rc = ss_store_exec(st, sql);
    if ((rc != SQLITE_BUSY && rc != SQLITE_LOCKED) || waited >= ms) return rc;
    nanosleep(&pause, NULL);
  }
}

int64_t ss_store_query_int(ss_store *st, const char *sql, int *rc) {
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

/* The first read of a file failed: say why.  Only a file that SQLite cannot
 * parse is "not a store"; a lock, a permission or the medium is not the
 * file's fault. */
static ss_status first_read_error(ss_store *st, ss_error *err) {
  const char *msg = sqlite3_errmsg(st->db);
  switch (sqlite3_errcode(st->db)) {
  case SQLITE_BUSY:
  case SQLITE_LOCKED:
    return ss_error_set(err, SS_EIO,
                        "%s: the results store is locked by another process (%s); "
                        "try again when it has finished",
                        st->path, msg);
  case SQLITE_CORRUPT:
    return ss_error_set(err, SS_EINPUT, "%s: corrupt results store (%s)", st->path, msg);
  case SQLITE_READONLY:
  case SQLITE_CANTOPEN:
  case SQLITE_PERM:
  case SQLITE_IOERR:
  case SQLITE_AUTH:
    return ss_error_set(err, SS_EIO, "%s: cannot read the results store (%s)%s", st->path,
                        msg,
                        st->readonly ? ""
                                     : ": is its directory writable? (a store needs "
                                       "its -wal and -shm files beside it)");
  default: /* SQLITE_NOTADB and the like */
    return ss_error_set(err, SS_EINPUT, "%s: not a subspectra results store (%s)",
                        st->path, msg);
  }
}

/* Before opening path to write: can this process write the file, or create
 * it, and create its -wal and -shm files beside it?  SS_EIO naming what
 * stops it (a read-only file system, the file's or the directory's
 * permissions), for the user who would otherwise read SQLite's "attempt to
 * write a readonly database" or worse. */
static ss_status check_writable(const char *path, ss_error *err) {
  const int exists = access(path, F_OK) == 0;
  if (exists && access(path, W_OK) != 0)
    return ss_error_set(err, SS_EIO, "%s: cannot write the results store: %s", path,
                        errno == EROFS ? "a read-only file system"
                        : errno == EACCES
                            ? "no write permission on the file (open it with `report`, "
                              "or `merge` it into a store of yours)"
                            : strerror(errno));
  /* the directory, needed to create the store, or its -wal and -shm files */
  char *wal = malloc(strlen(path) + 8), *dir = strdup(path);
  ss_status s = SS_OK;
  if (!wal || !dir) {
    s = ss_error_nomem(err, "results store");
    goto done;
  }
  int need_dir = !exists;
  sprintf(wal, "%s-wal", path);
  need_dir |= access(wal, F_OK) != 0;
  sprintf(wal, "%s-shm", path);
  need_dir |= access(wal, F_OK) != 0;
  const char *d = dirname(dir);
  if (need_dir && access(d, W_OK | X_OK) != 0)
    s = ss_error_set(err, SS_EIO, "%s: cannot %s the results store: directory %s: %s",
                     path, exists ? "write" : "create", d,
                     errno == EROFS    ? "a read-only file system"
                     : errno == EACCES ? "no write permission (a store needs its -wal "
                                         "and -shm files beside it)"
                                       : strerror(errno));
done:
  free(wal);
  free(dir);
  return s;
}

/* Is the open file a healthy store of our schema, or of version 2 (which
 * ss_store_schema_upgrade reads: *old = 1)?  An empty database (a new or
 * zero-length file) reports *empty = 1. */
static ss_status validate(ss_store *st, int *empty, int *old, ss_error *err) {
  int rc;
  const int64_t ntables =
      ss_store_query_int(st, "SELECT count(*) FROM sqlite_schema", &rc);
  if (rc != SQLITE_OK) return first_read_error(st, err);
  const int64_t app = ss_store_query_int(st, "PRAGMA application_id", &rc);
  const int64_t ver = ss_store_query_int(st, "PRAGMA user_version", &rc);
  *empty = ntables == 0 && app == 0;
  *old = ver == 2;
  if (*empty) return SS_OK;
  if (app != SS_STORE_APP_ID)
    return ss_error_set(err, SS_EINPUT,
                        "%s: a foreign SQLite database, not a subspectra results "
                        "store (application_id %" PRId64 ")",
                        st->path, app);
  if (ver != SS_STORE_SCHEMA && ver != 2)
    return ss_error_set(err, SS_EINPUT,
                        "%s: results store of schema version %" PRId64
                        ", this program reads version %d (and upgrades version 2)",
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
    /* a row against a constraint (a hand edit with ignore_check_constraints):
     * name it as ss_store_check_rows does */
    ss_status s;
    if (ver == SS_STORE_SCHEMA &&
        (!strncmp(what, "CHECK constraint", 16) || !strncmp(what, "NULL value in", 13)) &&
        (s = ss_store_check_rows(st, err)))
      return s;
    return ss_error_set(err, SS_EINPUT, "%s: corrupt results store (%s)", st->path, what);
  }
  sqlite3_finalize(q);
  return SS_OK;
}

static ss_status prepare(ss_store *st, ss_error *err) {
  if (sqlite3_prepare_v2(st->db,
                         "SELECT eigen_condition, regularity, injectivity FROM result "
                         "WHERE "
                         "scheme_id=?1 AND (kind=?2 OR (?2='vertex' AND "
                         "kind='edge-point')) AND k=?3 AND link=?4",
                         -1, &st->has, NULL) != SQLITE_OK)
    return ss_store_db_error(st, err, "prepare");
  if (st->readonly) return SS_OK;
  if (sqlite3_prepare_v2(
          st->db,
          "INSERT OR IGNORE INTO result(scheme_id,kind,k,link,cells,"
          "two_ring,one_ring,lambda1,lambda2,lambda3,lambda4,eigenvalues,"
          "eigen_condition,eigen_reason,tolerance,regularity,"
          "regularity_reason,min_scaled_jacobian,depth,improper_pairs,"
          "adjacent_pairs,seconds,eigen_certified,regularity_certified,"
          "ring_level,centre_corner_folds,injectivity,injectivity_reason,"
          "degree,injectivity_certified,eigen_on,regularity_on,"
          "injectivity_on,psi_verdict,psi_covered,psi_uncovered,psi_pieces) "
          "VALUES(?1,?2,?3,?4,?5,?6,?7,?8,?9,?10,?11,?12,?13,?14,?15,?16,"
          "?17,?18,?19,?20,?21,?22,?23,?24,?25,?26,?27,?28,?29,?30,?31,?32,"
          "?33,?34,?35,?36,?37)",
          -1, &st->put, NULL) != SQLITE_OK)
    return ss_store_db_error(st, err, "prepare");
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
  ss_status s = st->readonly ? SS_OK : check_writable(path, err);
  if (s) goto fail;
  int empty = 0, old = 0;
  if (sqlite3_open_v2(path, &st->db, flags | SQLITE_OPEN_NOMUTEX, NULL) != SQLITE_OK) {
    s = ss_error_set(err, SS_EIO, "%s: cannot open: %s", path,
                     st->db ? sqlite3_errmsg(st->db) : "out of memory");
    goto fail;
  }
  /* Readers of a WAL database never wait for its writers: a first read that
   * stays locked for seconds means another program holds the store
   * exclusively, not a sweep adding rows; say so soon.  Writers then wait
   * their turn (another process committing a row, a merge) much longer. */
  sqlite3_busy_timeout(st->db, SS_STORE_OPEN_WAIT_MS);
  s = validate(st, &empty, &old, err);
  if (s && st->readonly && retry_immutable(st, path)) s = validate(st, &empty, &old, err);
  if (s) goto fail;
  sqlite3_busy_timeout(st->db, 30000);
  if (empty && st->readonly) {
    s = ss_error_set(err, SS_EINPUT, "%s: an empty file, not a subspectra results store",
                     path);
    goto fail;
  }
  if (!st->readonly) {
    /* WAL: readers never block the writer, and a killed writer leaves a log
     * that the next open replays; NORMAL syncs at checkpoints, enough
     * against a process being killed (not against power loss). */
    if (exec_retry(st, "PRAGMA journal_mode=WAL", 30000) != SQLITE_OK ||
        ss_store_exec(st, "PRAGMA synchronous=NORMAL") != SQLITE_OK) {
      s = ss_store_db_error(st, err, "cannot set the journal mode");
      goto fail;
    }
    int raced = 0;
    if (empty && (s = ss_store_schema_create(st, &raced, err))) goto fail;
    if (raced && ((s = validate(st, &empty, &old, err)) || empty)) {
      if (!s) s = ss_error_set(err, SS_EIO, "%s: cannot create the schema", path);
      goto fail;
    }
  }
  if (old && (s = ss_store_schema_upgrade(st, err))) goto fail;
  if ((s = ss_store_check_rows(st, err))) goto fail;
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

/* The shortest "%.Ng" text of x that reads back as x (N = 6..17): 1e-06 stays
 * "1e-06" (so the identities of stores written before tolerances were exact
 * keep matching), 1.0000006e-06 is no longer "1e-06". */
static void exact_real(double x, char *buf, size_t n) {
  for (int p = 6; p <= 17; p++) {
    snprintf(buf, n, "%.*g", p, x);
    if (strtod(buf, NULL) == x) return;
  }
}

void ss_store_identity(const ss_store_scheme *sc, char *buf, size_t n) {
  char tail[64] = "", tol[32];
  int len = 0;
  if (sc->reads_diagonals)
    len = snprintf(tail, sizeof tail, " diagonals=%s", ss_diag_name(sc->diag));
  if (sc->opts.psi_depth) /* (appended: identities without psi are as before) */
    len += snprintf(tail + len, sizeof tail - (size_t)len, " psi-depth=%d",
                    sc->opts.psi_depth);
  if (sc->opts.psi_tubes) /* (the identity alone records it: no column) */
    snprintf(tail + len, sizeof tail - (size_t)len, " psi-tubes");
  exact_real(sc->opts.tol, tol, sizeof tol);
  if (sc->stencil)
    snprintf(buf, n, "stencil:%016" PRIx64 " tol=%s depth=%d rings=%d%s%s",
             sc->stencil_hash, tol, sc->opts.depth, sc->opts.ring_levels,
             sc->opts.certify ? " certified" : "", tail);
  else
    snprintf(buf, n, "%s tol=%s depth=%d rings=%d%s%s", sc->name, tol, sc->opts.depth,
             sc->opts.ring_levels, sc->opts.certify ? " certified" : "", tail);
}

ss_status ss_store_scheme_id(ss_store *st, const ss_store_scheme *sc, int64_t *id,
                             ss_error *err) {
  char ident[256], hash[17];
  ss_store_identity(sc, ident, sizeof ident);
  snprintf(hash, sizeof hash, "%016" PRIx64, sc->stencil_hash);
  sqlite3_stmt *q = NULL;
  int rc = sqlite3_prepare_v2(st->db, "SELECT id, tol FROM scheme WHERE identity=?1", -1,
                              &q, NULL);
  if (rc == SQLITE_OK) {
    sqlite3_bind_text(q, 1, ident, -1, SQLITE_TRANSIENT);
    rc = sqlite3_step(q);
  }
  if (rc == SQLITE_ROW) {
    *id = sqlite3_column_int64(q, 0);
    const double tol = sqlite3_column_double(q, 1);
    sqlite3_finalize(q);
    /* a program before exact identities wrote tolerances to 6 digits: its
     * rows under this identity may have been computed with another one */
    if (tol != sc->opts.tol)
      return ss_error_set(err, SS_EINPUT,
                          "%s: scheme '%s' was stored by an older subspectra for the "
                          "tolerance %.17g, which it did not tell apart from %.17g: "
                          "its rows may hold either; use another store",
                          st->path, ident, tol, sc->opts.tol);
    return SS_OK;
  }
  sqlite3_finalize(q);
  if (rc != SQLITE_DONE) return ss_store_db_error(st, err, "scheme lookup");
  if (st->readonly)
    return ss_error_set(err, SS_EINPUT, "%s: no results for scheme '%s'", st->path,
                        ident);
  rc = sqlite3_prepare_v2(
      st->db,
      "INSERT OR IGNORE INTO scheme(identity,name,stencil,"
      "stencil_hash,tol,depth,diagonals,ring_levels,certify,psi_depth) "
      "VALUES(?1,?2,?3,?4,?5,?6,?7,?8,?9,?10)",
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
    sqlite3_bind_int(q, 10, sc->opts.psi_depth);
    rc = sqlite3_step(q);
  }
  sqlite3_finalize(q);
  if (rc != SQLITE_DONE) return ss_store_db_error(st, err, "scheme insert");
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
    r.v.cond.verdict = verdict_of((const char *)sqlite3_column_text(st->has, 0));
    r.v.reg.verdict = verdict_of((const char *)sqlite3_column_text(st->has, 1));
    r.v.inj.verdict = verdict_of((const char *)sqlite3_column_text(st->has, 2));
    *verdict = ss_result_verdict(&r);
  }
  sqlite3_reset(st->has);
  if (rc != SQLITE_ROW && rc != SQLITE_DONE) return ss_store_db_error(st, err, "lookup");
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
  sqlite3_bind_text(q, 13, ss_verdict_name(r->v.cond.verdict), -1, SQLITE_STATIC);
  sqlite3_bind_text(q, 14, r->v.cond.reason, -1, SQLITE_STATIC);
  sqlite3_bind_double(q, 15, r->tol);
  sqlite3_bind_text(q, 16, ss_verdict_name(r->v.reg.verdict), -1, SQLITE_STATIC);
  sqlite3_bind_text(q, 17, r->v.reg.reason, -1, SQLITE_STATIC);
  bind_real(q, 18, r->min_sj);
  sqlite3_bind_int(q, 19, r->depth);
  if (r->has_diag) {
    sqlite3_bind_int64(q, 20, (int64_t)r->improper);
    sqlite3_bind_int64(q, 21, (int64_t)r->pairs);
  }
  sqlite3_bind_double(q, 22, r->seconds);
  sqlite3_bind_int(q, 23, r->v.cond.certified);
  sqlite3_bind_int(q, 24, r->v.reg.certified);
  sqlite3_bind_int(q, 25, r->ring_level);
  sqlite3_bind_int64(q, 26, (int64_t)r->centre_corner_folds);
  sqlite3_bind_text(q, 27, ss_verdict_name(r->v.inj.verdict), -1, SQLITE_STATIC);
  sqlite3_bind_text(q, 28, r->v.inj.reason, -1, SQLITE_STATIC);
  sqlite3_bind_int(q, 29, r->inj_degree);
  sqlite3_bind_int(q, 30, r->v.inj.certified);
  const ss_verdict *v[3] = {&r->v.cond, &r->v.reg, &r->v.inj};
  for (int i = 0; i < 3; i++) /* NULL: not judged */
    if (v[i]->on != SS_ON_NOTHING)
      sqlite3_bind_text(q, 31 + i, ss_judged_on_name(v[i]->on), -1, SQLITE_STATIC);
  if (r->psi.ran) { /* NULL: psi not judged */
    sqlite3_bind_text(q, 34, ss_verdict_name(r->psi.verdict), -1, SQLITE_STATIC);
    bind_real(q, 35, r->psi.covered);
    bind_real(q, 36, r->psi.uncovered);
    sqlite3_bind_int64(q, 37, (int64_t)r->psi.pieces);
  }
  const int rc = sqlite3_step(q);
  sqlite3_reset(q);
  free(ev);
  if (rc != SQLITE_DONE) return ss_store_db_error(st, err, "insert");
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
    ss_case_kind k;
    if (!ss_case_kind_parse((const char *)sqlite3_column_text(q, 0), &k))
      nk[k] = (size_t)sqlite3_column_int64(q, 1);
    rc = SQLITE_OK;
  }
  sqlite3_finalize(q);
  if (rc != SQLITE_DONE) return ss_store_db_error(st, err, "count");
  return SS_OK;
}

static int kind_of(const char *name) {
  ss_case_kind k;
  return ss_case_kind_parse(name, &k) ? -1 : (int)k;
}

static ss_verdict_kind verdict_of(const char *name) {
  return !strcmp(name, "pass") ? SS_PASS : !strcmp(name, "fail") ? SS_FAIL : SS_UNDECIDED;
}

/* What a verdict was judged on, from its name (ss_judged_on_name); NULL (not
 * judged, or a row of schema 2) and unknown names: SS_ON_NOTHING. */
static ss_judged_on judged_on_of(const unsigned char *name) {
  static const ss_judged_on all[] = {SS_ON_SPECTRUM, SS_ON_NET, SS_ON_PSI, SS_ON_JSR};
  for (size_t i = 0; name && i < sizeof all / sizeof all[0]; i++)
    if (!strcmp((const char *)name, ss_judged_on_name(all[i]))) return all[i];
  return SS_ON_NOTHING;
}

/* A REAL column, NaN for NULL (bind_real's inverse). */
static double column_real(sqlite3_stmt *q, int i) {
  return sqlite3_column_type(q, i) == SQLITE_NULL ? (double)NAN
                                                  : sqlite3_column_double(q, i);
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
      "injectivity, injectivity_reason, degree, injectivity_certified, eigen_on, "
      "regularity_on, injectivity_on, psi_verdict, psi_covered, psi_uncovered, "
      "psi_pieces FROM cases";
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
      s = ss_error_set(
          err, SS_EINPUT,
          "%s: invalid row (hand-edited?): table result, row (%s, kind '%s', "
          "k %d, link '%.200s'): eigenvalues = '%.60s' is not a JSON list of "
          "at most %d [re, im, multiplicity]",
          st->path, row.identity, sqlite3_column_text(q, 2), sqlite3_column_int(q, 3),
          sqlite3_column_text(q, 4), sqlite3_column_text(q, 8), SS_RESULT_NEIG);
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
    r->v.cond.verdict = verdict_of((const char *)sqlite3_column_text(q, 9));
    copy_text(r->v.cond.reason, sizeof r->v.cond.reason, sqlite3_column_text(q, 10));
    r->tol = sqlite3_column_double(q, 11);
    r->v.reg.verdict = verdict_of((const char *)sqlite3_column_text(q, 12));
    copy_text(r->v.reg.reason, sizeof r->v.reg.reason, sqlite3_column_text(q, 13));
    r->min_sj = column_real(q, 14);
    r->depth = sqlite3_column_int(q, 15);
    r->has_diag = sqlite3_column_type(q, 16) != SQLITE_NULL;
    r->improper = (size_t)sqlite3_column_int64(q, 16);
    r->pairs = (size_t)sqlite3_column_int64(q, 17);
    r->seconds = sqlite3_column_double(q, 18);
    r->v.cond.certified = sqlite3_column_int(q, 19);
    r->v.reg.certified = sqlite3_column_int(q, 20);
    r->ring_level = sqlite3_column_int(q, 21);
    r->centre_corner_folds = (size_t)sqlite3_column_int64(q, 22);
    r->v.inj.verdict = verdict_of((const char *)sqlite3_column_text(q, 23));
    copy_text(r->v.inj.reason, sizeof r->v.inj.reason, sqlite3_column_text(q, 24));
    r->inj_degree = sqlite3_column_int(q, 25);
    r->v.inj.certified = sqlite3_column_int(q, 26);
    r->v.cond.on = judged_on_of(sqlite3_column_text(q, 27));
    r->v.reg.on = judged_on_of(sqlite3_column_text(q, 28));
    r->v.inj.on = judged_on_of(sqlite3_column_text(q, 29));
    if (sqlite3_column_type(q, 30) != SQLITE_NULL) /* psi judged */
      r->psi = (ss_result_psi){1, verdict_of((const char *)sqlite3_column_text(q, 30)),
                               column_real(q, 31), column_real(q, 32),
                               (size_t)sqlite3_column_int64(q, 33)};
    if (visit(&row, ctx)) break;
  }
  if (!s && rc != SQLITE_ROW && rc != SQLITE_DONE)
    s = ss_store_db_error(st, err, "query");
  sqlite3_finalize(q);
  return s;
}

/* The value columns of result: every column but the key (scheme_id, kind, k,
 * link) and the timing (seconds), which two runs of one case do not share.
 * Two rows of one key conflict when any of these differs (but see
 * NRECORDED). */
#define VALUE_COLS                                                                       \
  "cells, two_ring, one_ring, lambda1, lambda2, lambda3, lambda4, eigenvalues, "         \
  "eigen_condition, eigen_reason, eigen_certified, tolerance, regularity, "              \
  "regularity_reason, regularity_certified, min_scaled_jacobian, depth, ring_level, "    \
  "centre_corner_folds, injectivity, injectivity_reason, degree, "                       \
  "injectivity_certified, improper_pairs, adjacent_pairs, eigen_on, regularity_on, "     \
  "injectivity_on, psi_verdict, psi_covered, psi_uncovered, psi_pieces"
/* NVALUE values, of which the last NRECORDED came with schema 3: a store
 * upgraded from schema 2 holds NULL there (not recorded), which is no
 * conflict with a value */
enum { NVALUE = 32, NRECORDED = 7 };

/* Exactly equal stored values (storage class and value; reals compared as
 * doubles, so bit for bit but for the sign of zero). */
static int same_value(sqlite3_value *a, sqlite3_value *b) {
  const int t = sqlite3_value_type(a);
  if (t != sqlite3_value_type(b)) return 0;
  switch (t) {
  case SQLITE_NULL:
    return 1;
  case SQLITE_INTEGER:
    return sqlite3_value_int64(a) == sqlite3_value_int64(b);
  case SQLITE_FLOAT:
    return sqlite3_value_double(a) == sqlite3_value_double(b);
  default: {
    const void *pa =
        t == SQLITE_TEXT ? (const void *)sqlite3_value_text(a) : sqlite3_value_blob(a);
    const void *pb =
        t == SQLITE_TEXT ? (const void *)sqlite3_value_text(b) : sqlite3_value_blob(b);
    const int na = sqlite3_value_bytes(a), nb = sqlite3_value_bytes(b);
    return na == nb && (na == 0 || memcmp(pa, pb, (size_t)na) == 0);
  }
  }
}

/* The statements of one merge (see ss_store_merge). */
typedef struct {
  sqlite3_stmt *schemes; /* src: the scheme rows */
  sqlite3_stmt *addsch;  /* st: insert a scheme row if its identity is new */
  sqlite3_stmt *rows;    /* src: identity, key, values, seconds of every result */
  sqlite3_stmt *id;      /* st: the id of an identity */
  sqlite3_stmt *ins;     /* st: insert a result unless its key is there */
  sqlite3_stmt *repl;    /* st: insert or replace a result */
  sqlite3_stmt *old;     /* st: the values stored under a key */
} merge_sql;

static void merge_sql_free(merge_sql *m) {
  sqlite3_finalize(m->schemes);
  sqlite3_finalize(m->addsch);
  sqlite3_finalize(m->rows);
  sqlite3_finalize(m->id);
  sqlite3_finalize(m->ins);
  sqlite3_finalize(m->repl);
  sqlite3_finalize(m->old);
}

/* Prepare m's statements; on failure *failed is the connection that refused. */
static int merge_sql_prepare(merge_sql *m, sqlite3 *src, sqlite3 *dst, sqlite3 **failed) {
  static const char *const params =
      "VALUES(?1,?2,?3,?4,?5,?6,?7,?8,?9,?10,?11,?12,?13,?14,?15,?16,?17,?18,?19,?20,"
      "?21,?22,?23,?24,?25,?26,?27,?28,?29,?30,?31,?32,?33,?34,?35,?36,?37)";
  static const char *const scheme_cols = "identity,name,stencil,stencil_hash,tol,depth,"
                                         "ring_levels,certify,diagonals,psi_depth";
  char sql[2048];
  *failed = src;
  snprintf(sql, sizeof sql, "SELECT %s FROM scheme", scheme_cols);
  int rc = sqlite3_prepare_v2(src, sql, -1, &m->schemes, NULL);
  /* (a subquery for the identity: scheme has a depth column too) */
  snprintf(sql, sizeof sql,
           "SELECT (SELECT identity FROM scheme WHERE id = scheme_id), kind, k, link, "
           "%s, seconds FROM result ORDER BY 1, 2, 3, 4",
           VALUE_COLS);
  if (rc == SQLITE_OK) rc = sqlite3_prepare_v2(src, sql, -1, &m->rows, NULL);
  if (rc != SQLITE_OK) return rc;
  *failed = dst;
  snprintf(sql, sizeof sql,
           "INSERT OR IGNORE INTO scheme(%s) VALUES(?1,?2,?3,?4,?5,?6,?7,?8,?9,?10)",
           scheme_cols);
  rc = sqlite3_prepare_v2(dst, sql, -1, &m->addsch, NULL);
  if (rc == SQLITE_OK)
    rc = sqlite3_prepare_v2(dst, "SELECT id FROM scheme WHERE identity = ?1", -1, &m->id,
                            NULL);
  snprintf(sql, sizeof sql,
           "INSERT OR IGNORE INTO result(scheme_id, kind, k, link, %s, seconds) %s",
           VALUE_COLS, params);
  if (rc == SQLITE_OK) rc = sqlite3_prepare_v2(dst, sql, -1, &m->ins, NULL);
  snprintf(sql, sizeof sql,
           "INSERT OR REPLACE INTO result(scheme_id, kind, k, link, %s, seconds) %s",
           VALUE_COLS, params);
  if (rc == SQLITE_OK) rc = sqlite3_prepare_v2(dst, sql, -1, &m->repl, NULL);
  snprintf(sql, sizeof sql,
           "SELECT %s FROM result WHERE scheme_id = ?1 AND kind = ?2 AND k = ?3 AND "
           "link = ?4",
           VALUE_COLS);
  if (rc == SQLITE_OK) rc = sqlite3_prepare_v2(dst, sql, -1, &m->old, NULL);
  return rc;
}

/* Bind the key and values of the current row of m->rows to q (as ?2.., after
 * the scheme id ?1). */
static void bind_row(sqlite3_stmt *q, sqlite3_stmt *row, int64_t id, int n) {
  sqlite3_reset(q);
  sqlite3_clear_bindings(q);
  sqlite3_bind_int64(q, 1, id);
  for (int i = 1; i < n; i++)
    sqlite3_bind_value(q, i + 1, sqlite3_column_value(row, i));
}

/* The text of the current row's key: "(IDENTITY) KIND K[ LINK]". */
static void row_key(sqlite3_stmt *row, char *buf, size_t n) {
  const char *link = (const char *)sqlite3_column_text(row, 3);
  snprintf(buf, n, "(%s) %s %d%s%s", (const char *)sqlite3_column_text(row, 0),
           (const char *)sqlite3_column_text(row, 1), sqlite3_column_int(row, 2),
           link && *link ? " " : "", link ? link : "");
}

/* Copy src's schemes and results into st (the transaction is the caller's).
 * An SQLite status; *failed is the connection whose error it is. */
static int merge_rows(ss_store *st, ss_store *in, ss_store_prefer prefer,
                      ss_store_merge_stats *ms, sqlite3 **failed) {
  merge_sql m = {0};
  char *ident = NULL; /* the identity whose id in st is id */
  int64_t id = -1;
  int rc = merge_sql_prepare(&m, in->db, st->db, failed);
  if (rc != SQLITE_OK) goto done;
  while ((rc = sqlite3_step(m.schemes)) == SQLITE_ROW) {
    sqlite3_reset(m.addsch);
    for (int i = 0; i < 10; i++)
      sqlite3_bind_value(m.addsch, i + 1, sqlite3_column_value(m.schemes, i));
    if ((rc = sqlite3_step(m.addsch)) != SQLITE_DONE) {
      *failed = st->db;
      goto done;
    }
  }
  if (rc != SQLITE_DONE) {
    *failed = in->db;
    goto done;
  }
  const int ncols = 4 + NVALUE + 1; /* identity, key, values, seconds */
  while ((rc = sqlite3_step(m.rows)) == SQLITE_ROW) {
    *failed = st->db;
    const char *s = (const char *)sqlite3_column_text(m.rows, 0);
    if (!s) continue; /* (a result of no scheme: nothing to match it by) */
    if (!ident || strcmp(ident, s)) {
      free(ident);
      if (!(ident = strdup(s))) {
        rc = SQLITE_NOMEM;
        goto done;
      }
      sqlite3_reset(m.id);
      sqlite3_bind_text(m.id, 1, s, -1, SQLITE_TRANSIENT);
      if ((rc = sqlite3_step(m.id)) != SQLITE_ROW) goto missing;
      id = sqlite3_column_int64(m.id, 0);
      sqlite3_reset(m.id);
    }
    bind_row(m.ins, m.rows, id, ncols);
    if ((rc = sqlite3_step(m.ins)) != SQLITE_DONE) goto done;
    if (sqlite3_changes(st->db) > 0) {
      ms->added++;
      continue;
    }
    /* the key is there: equal values, or a conflict */
    bind_row(m.old, m.rows, id, 4);
    if ((rc = sqlite3_step(m.old)) != SQLITE_ROW) goto missing;
    int same = 1;
    for (int i = 0; i < NVALUE && same; i++) {
      sqlite3_value *a = sqlite3_column_value(m.old, i),
                    *b = sqlite3_column_value(m.rows, 4 + i);
      same = same_value(a, b) ||
             (i >= NVALUE - NRECORDED && (sqlite3_value_type(a) == SQLITE_NULL ||
                                          sqlite3_value_type(b) == SQLITE_NULL));
    }
    sqlite3_reset(m.old);
    if (same) {
      ms->present++;
      continue;
    }
    if (ms->conflicts < SS_STORE_NKEYS)
      row_key(m.rows, ms->first[ms->conflicts], sizeof ms->first[0]);
    ms->conflicts++;
    if (prefer == SS_STORE_PREFER_NEW) {
      bind_row(m.repl, m.rows, id, ncols);
      if ((rc = sqlite3_step(m.repl)) != SQLITE_DONE) goto done;
      ms->replaced++;
    }
  }
  if (rc != SQLITE_DONE) *failed = in->db;
  goto done;
missing: /* a row just written or read is not there: only an error explains it */
  if (rc == SQLITE_DONE) rc = SQLITE_INTERNAL;
done:
  free(ident);
  merge_sql_free(&m);
  return rc == SQLITE_DONE ? SQLITE_OK : rc;
}

ss_status ss_store_merge(ss_store *st, const char *src, ss_store_prefer prefer,
                         ss_store_merge_stats *stats, ss_error *err) {
  ss_store_merge_stats ms;
  memset(&ms, 0, sizeof ms);
  if (stats) *stats = ms;
  if (st->readonly) return ss_error_set(err, SS_EINPUT, "%s: opened read-only", st->path);
  /* the same file by another name (a symbolic or hard link, ./x.db): SQLite
   * would wait for its own write lock */
  struct stat a, b;
  if (stat(st->path, &a) == 0 && stat(src, &b) == 0 && a.st_dev == b.st_dev &&
      a.st_ino == b.st_ino)
    return ss_error_set(err, SS_EINPUT,
                        "%s is the output store %s itself (the same file): nothing to "
                        "merge",
                        src, st->path);
  ss_store *in = NULL;
  ss_status s = ss_store_open(src, SS_STORE_READ, &in, err);
  if (s) return s;
  sqlite3 *failed = st->db;
  int rc = ss_store_exec(st, "BEGIN IMMEDIATE");
  if (rc == SQLITE_OK) rc = merge_rows(st, in, prefer, &ms, &failed);
  if (rc == SQLITE_OK) rc = ss_store_exec(st, "COMMIT");
  if (rc != SQLITE_OK) {
    if (rc == SQLITE_NOMEM)
      s = ss_error_nomem(err, "merge");
    else
      s = ss_error_set(err, SS_EIO, "%s: %s %s: %s", failed == in->db ? src : st->path,
                       failed == in->db ? "cannot read it to merge into" : "merging",
                       failed == in->db ? st->path : src,
                       sqlite3_errcode(failed) != SQLITE_OK ? sqlite3_errmsg(failed)
                                                            : sqlite3_errstr(rc));
    ss_store_exec(st, "ROLLBACK");
    memset(&ms, 0, sizeof ms);
  }
  ss_store_close(in);
  if (stats) *stats = ms;
  return s;
}
