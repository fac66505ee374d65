/* ss_store_schema.c — the results store's schema: created in an empty file,
 * upgraded from version 2, or read in version 2 without changing the file
 * (ss_store_impl.h). */
#include <stdio.h>
#include <time.h>

#include "ss_store_impl.h"

/* The tables.  Column comments are repeated in docs/sweep.md.  The columns after
 * `seconds` came with version 3 (see added_cols). */
static const char *const tables_sql =
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
    "  diagonals TEXT,\n"
    "  psi_depth INTEGER NOT NULL DEFAULT 0);\n"
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
    "  eigen_on TEXT,\n"
    "  regularity_on TEXT,\n"
    "  injectivity_on TEXT,\n"
    "  psi_verdict TEXT,\n"
    "  psi_covered REAL,\n"
    "  psi_uncovered REAL,\n"
    "  psi_pieces INTEGER,\n"
    "  PRIMARY KEY (scheme_id, kind, k, link)) WITHOUT ROWID;\n";

/* The view `cases`, over the tables of one schema (printf: "" three times for
 * the file's own; "TEMP ", "temp.", "temp." for the views of a version-2
 * store read as it is). */
#define CASES_VIEW_SQL                                                                   \
  "CREATE %sVIEW cases AS SELECT s.name AS scheme, s.identity AS identity, r.*,\n"       \
  "  CASE WHEN 'fail' IN (r.eigen_condition, r.regularity, r.injectivity) THEN 'fail'\n" \
  "       WHEN r.eigen_condition = 'pass' AND r.regularity = 'pass' AND\n"               \
  "            r.injectivity = 'pass' THEN 'pass'\n"                                     \
  "       ELSE 'undecided' END AS verdict\n"                                             \
  "  FROM %sresult r JOIN %sscheme s ON s.id = r.scheme_id;\n"

/* What version 3 added to version 2: ADD COLUMN clauses of result (they are
 * the last columns of tables_sql, in this order), then of scheme. */
static const char *const added_result[] = {
    "eigen_on TEXT",    "regularity_on TEXT", "injectivity_on TEXT", "psi_verdict TEXT",
    "psi_covered REAL", "psi_uncovered REAL", "psi_pieces INTEGER"};
enum { NADDED = sizeof added_result / sizeof added_result[0] };
static const char *const added_scheme = "psi_depth INTEGER NOT NULL DEFAULT 0";

/* The columns of version 2, for the views that read such a store as it is. */
static const char *const v2_result_cols =
    "scheme_id, kind, k, link, cells, two_ring, one_ring, lambda1, lambda2, lambda3, "
    "lambda4, eigenvalues, eigen_condition, eigen_reason, eigen_certified, tolerance, "
    "regularity, regularity_reason, regularity_certified, min_scaled_jacobian, depth, "
    "ring_level, centre_corner_folds, injectivity, injectivity_reason, degree, "
    "injectivity_certified, improper_pairs, adjacent_pairs, seconds";
static const char *const v2_scheme_cols =
    "id, identity, name, stencil, stencil_hash, tol, depth, ring_levels, certify, "
    "diagonals";

ss_status ss_store_schema_create(ss_store *st, int *raced, ss_error *err) {
  char sql[8192];
  char when[32];
  time_t t = time(NULL);
  struct tm tm;
  *raced = 0;
  if (ss_store_exec(st, "BEGIN IMMEDIATE") != SQLITE_OK)
    return ss_store_db_error(st, err, "cannot create the schema");
  int rc;
  const int64_t ntables =
      ss_store_query_int(st, "SELECT count(*) FROM sqlite_schema", &rc);
  if (rc != SQLITE_OK || ntables != 0) {
    ss_status s =
        rc != SQLITE_OK ? ss_store_db_error(st, err, "cannot create the schema") : SS_OK;
    ss_store_exec(st, "ROLLBACK");
    *raced = rc == SQLITE_OK;
    return s;
  }
  strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", gmtime_r(&t, &tm));
  int len = snprintf(sql, sizeof sql, "%s", tables_sql);
  len += snprintf(sql + len, sizeof sql - (size_t)len, CASES_VIEW_SQL, "", "", "");
  snprintf(sql + len, sizeof sql - (size_t)len,
           "INSERT INTO meta VALUES('program','subspectra'),('schema','%d'),"
           "('created','%s');\n"
           "PRAGMA application_id = %d;\nPRAGMA user_version = %d;\nCOMMIT;",
           SS_STORE_SCHEMA, when, SS_STORE_APP_ID, SS_STORE_SCHEMA);
  if (ss_store_exec(st, sql) != SQLITE_OK) {
    ss_status s = ss_store_db_error(st, err, "cannot create the schema");
    ss_store_exec(st, "ROLLBACK");
    return s;
  }
  return SS_OK;
}

/* Read-only: temporary views result, scheme and cases of version 3 over the
 * version-2 tables (nothing is written to the file: the temp schema is the
 * connection's own). */
static ss_status read_as_is(ss_store *st, ss_error *err) {
  char sql[4096];
  int len =
      snprintf(sql, sizeof sql, "CREATE TEMP VIEW result AS SELECT %s", v2_result_cols);
  for (int i = 0; i < NADDED; i++) {
    char name[32];
    sscanf(added_result[i], "%31s", name);
    len += snprintf(sql + len, sizeof sql - (size_t)len, ", NULL AS %s", name);
  }
  len += snprintf(sql + len, sizeof sql - (size_t)len,
                  " FROM main.result;\n"
                  "CREATE TEMP VIEW scheme AS SELECT %s, 0 AS psi_depth FROM "
                  "main.scheme;\n",
                  v2_scheme_cols);
  snprintf(sql + len, sizeof sql - (size_t)len, CASES_VIEW_SQL, "TEMP ", "temp.",
           "temp.");
  if (ss_store_exec(st, sql) != SQLITE_OK)
    return ss_store_db_error(st, err,
                             "cannot read the results store of schema version 2");
  return SS_OK;
}

ss_status ss_store_schema_upgrade(ss_store *st, ss_error *err) {
  if (st->readonly) return read_as_is(st, err);
  if (ss_store_exec(st, "BEGIN IMMEDIATE") != SQLITE_OK)
    return ss_store_db_error(st, err, "cannot upgrade the results store to schema 3");
  int rc;
  const int64_t ver = ss_store_query_int(st, "PRAGMA user_version", &rc);
  if (rc == SQLITE_OK && ver == SS_STORE_SCHEMA) { /* another process did it */
    ss_store_exec(st, "ROLLBACK");
    return SS_OK;
  }
  char sql[4096];
  int len = 0;
  for (int i = 0; i < NADDED; i++)
    len += snprintf(sql + len, sizeof sql - (size_t)len,
                    "ALTER TABLE result ADD COLUMN %s;\n", added_result[i]);
  len += snprintf(sql + len, sizeof sql - (size_t)len,
                  "ALTER TABLE scheme ADD COLUMN %s;\nDROP VIEW cases;\n", added_scheme);
  len += snprintf(sql + len, sizeof sql - (size_t)len, CASES_VIEW_SQL, "", "", "");
  snprintf(sql + len, sizeof sql - (size_t)len,
           "UPDATE meta SET value = '%d' WHERE key = 'schema';\n"
           "PRAGMA user_version = %d;\nCOMMIT;",
           SS_STORE_SCHEMA, SS_STORE_SCHEMA);
  if (rc != SQLITE_OK || ver != 2 || ss_store_exec(st, sql) != SQLITE_OK) {
    ss_status s =
        ss_store_db_error(st, err, "cannot upgrade the results store to schema 3");
    ss_store_exec(st, "ROLLBACK");
    return s;
  }
  return SS_OK;
}
