/* ss_store_check.c — every row of a results store checked against what
 * ss_store_put and ss_store_scheme_id write (ss_store_impl.h): the type,
 * range or allowed names of each column, and each result's scheme row.
 * SQLite keeps a column's type only as an affinity, and a store can be edited
 * by hand: k = 'x' would read as 0, cells = -1 as 2^64 - 1, a verdict 'maybe'
 * as undecided, and results whose scheme row is gone would vanish from the
 * view `cases`.  One scan per table, in SQL. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_store_impl.h"

/* What one column may hold. */
typedef struct {
  const char *col;   /* the column */
  char type;         /* 'i' integer in lo..hi, 'r' a finite number (lo: 0 any, 1
                        >= 0, 2 > 0), 't' text, 'n' one of names, 'f' the id of
                        a scheme row */
  int nullable;      /* 1: NULL is allowed */
  long long lo, hi;  /* 'i': the range; 'r': see type */
  const char *names; /* 'n': the names, "'a','b'" */
} rule;

#define INTMAX    2147483647LL
#define SIZEMAX   9223372036854775807LL
#define VERDICTS  "'pass','fail','undecided'"
#define JUDGED_ON "'nothing','spectrum','control-net','psi','jsr'"

static const rule result_rules[] = {
    {"scheme_id", 'f', 0, 0, 0, NULL},
    {"kind", 'n', 0, 0, 0, "'vertex','edge','face','surface-vertex','edge-point'"},
    {"k", 'i', 0, 0, INTMAX, NULL},
    {"link", 't', 0, 0, 0, NULL},
    {"cells", 'i', 0, 0, SIZEMAX, NULL},
    {"two_ring", 'i', 0, 0, SIZEMAX, NULL},
    {"one_ring", 'i', 0, 0, SIZEMAX, NULL},
    {"lambda1", 'r', 1, 0, 0, NULL},
    {"lambda2", 'r', 1, 0, 0, NULL},
    {"lambda3", 'r', 1, 0, 0, NULL},
    {"lambda4", 'r', 1, 0, 0, NULL},
    {"eigenvalues", 't', 0, 0, 0, NULL},
    {"eigen_condition", 'n', 0, 0, 0, VERDICTS},
    {"eigen_reason", 't', 0, 0, 0, NULL},
    {"eigen_certified", 'i', 0, 0, 1, NULL},
    {"tolerance", 'r', 0, 2, 0, NULL},
    {"regularity", 'n', 0, 0, 0, VERDICTS},
    {"regularity_reason", 't', 0, 0, 0, NULL},
    {"regularity_certified", 'i', 0, 0, 1, NULL},
    {"min_scaled_jacobian", 'r', 1, 0, 0, NULL},
    {"depth", 'i', 0, 0, INTMAX, NULL},
    {"ring_level", 'i', 0, -1, INTMAX, NULL}, /* -1: no map */
    {"centre_corner_folds", 'i', 0, 0, SIZEMAX, NULL},
    {"injectivity", 'n', 0, 0, 0, VERDICTS},
    {"injectivity_reason", 't', 0, 0, 0, NULL},
    {"degree", 'i', 0, -INTMAX - 1, INTMAX, NULL},
    {"injectivity_certified", 'i', 0, 0, 1, NULL},
    {"improper_pairs", 'i', 1, 0, SIZEMAX, NULL},
    {"adjacent_pairs", 'i', 1, 0, SIZEMAX, NULL},
    {"seconds", 'r', 0, 1, 0, NULL},
    {"eigen_on", 'n', 1, 0, 0, JUDGED_ON},
    {"regularity_on", 'n', 1, 0, 0, JUDGED_ON},
    {"injectivity_on", 'n', 1, 0, 0, JUDGED_ON},
    {"psi_verdict", 'n', 1, 0, 0, VERDICTS},
    {"psi_covered", 'r', 1, 0, 0, NULL},
    {"psi_uncovered", 'r', 1, 0, 0, NULL},
    {"psi_pieces", 'i', 1, 0, SIZEMAX, NULL},
};

static const rule scheme_rules[] = {
    {"id", 'i', 0, -SIZEMAX - 1, SIZEMAX, NULL},
    {"identity", 't', 0, 0, 0, NULL},
    {"name", 't', 0, 0, 0, NULL},
    {"stencil", 't', 1, 0, 0, NULL},
    {"stencil_hash", 't', 1, 0, 0, NULL},
    {"tol", 'r', 0, 2, 0, NULL},
    {"depth", 'i', 0, 0, INTMAX, NULL},
    {"ring_levels", 'i', 0, 0, INTMAX, NULL},
    {"certify", 'i', 0, 0, 1, NULL},
    {"diagonals", 'n', 1, 0, 0, "'bfs','skew','center','proper'"},
    {"psi_depth", 'i', 0, 0, INTMAX, NULL},
};

/* The SQL condition "t.col is valid" (never NULL) into buf. */
static void rule_sql(const rule *r, char *buf, size_t n) {
  char c[64], e[512];
  snprintf(c, sizeof c, "t.%s", r->col);
  switch (r->type) {
  case 'i':
    snprintf(e, sizeof e, "typeof(%s) = 'integer' AND %s BETWEEN %lld AND %lld", c, c,
             r->lo, r->hi);
    break;
  case 'r':
    snprintf(e, sizeof e,
             "typeof(%s) IN ('integer', 'real') AND %s > -9e999 AND %s < 9e999 AND %s %s",
             c, c, c, c,
             r->lo == 1   ? ">= 0"
             : r->lo == 2 ? "> 0"
                          : "IS NOT NULL");
    break;
  case 't':
    snprintf(e, sizeof e, "typeof(%s) = 'text'", c);
    break;
  case 'n':
    snprintf(e, sizeof e, "typeof(%s) = 'text' AND %s IN (%s)", c, c, r->names);
    break;
  default: /* 'f' */
    snprintf(e, sizeof e,
             "typeof(%s) = 'integer' AND EXISTS (SELECT 1 FROM scheme s WHERE s.id = %s)",
             c, c);
  }
  if (r->nullable)
    snprintf(buf, n, "(%s IS NULL OR (%s))", c, e);
  else
    snprintf(buf, n, "(%s)", e);
}

/* What a valid value of r is, for the message. */
static void rule_text(const rule *r, char *buf, size_t n) {
  switch (r->type) {
  case 'i':
    snprintf(buf, n, "%s an integer in %lld..%lld", r->nullable ? "NULL or" : "", r->lo,
             r->hi);
    break;
  case 'r':
    snprintf(buf, n, "%s a finite number%s", r->nullable ? "NULL or" : "",
             r->lo == 1   ? " >= 0"
             : r->lo == 2 ? " > 0"
                          : "");
    break;
  case 't':
    snprintf(buf, n, "%s text", r->nullable ? "NULL or" : "");
    break;
  case 'n':
    snprintf(buf, n, "%s one of %s", r->nullable ? "NULL or" : "", r->names);
    break;
  default:
    snprintf(buf, n, "the id of a row of table scheme");
  }
  if (buf[0] == ' ') memmove(buf, buf + 1, strlen(buf));
}

enum { NSHOWN = 3 }; /* invalid rows named in the message */

/* Check one table (n rules); the invalid rows are counted into *bad and the
 * first ones described into msg (its length *len, room m).  key: the SQL text
 * naming a row. */
static int check_table(ss_store *st, const char *table, const char *key,
                       const rule *rules, int n, size_t *bad, char *msg, size_t *len,
                       size_t m) {
  size_t cap = 4096 + (size_t)n * 1700;
  char *sql = malloc(cap);
  if (!sql) return SQLITE_NOMEM;
  size_t k = (size_t)snprintf(sql, cap, "SELECT %s, CASE", key);
  for (int i = 0; i < n; i++) {
    char e[800];
    rule_sql(&rules[i], e, sizeof e);
    k += (size_t)snprintf(sql + k, cap - k, " WHEN NOT %s THEN %d", e, i);
  }
  k += (size_t)snprintf(sql + k, cap - k, " END AS bad, CASE");
  for (int i = 0; i < n; i++) {
    char e[800];
    rule_sql(&rules[i], e, sizeof e);
    k += (size_t)snprintf(sql + k, cap - k, " WHEN NOT %s THEN quote(t.%s)", e,
                          rules[i].col);
  }
  snprintf(sql + k, cap - k, " END AS value FROM %s AS t WHERE bad IS NOT NULL", table);
  sqlite3_stmt *q = NULL;
  int rc = sqlite3_prepare_v2(st->db, sql, -1, &q, NULL);
  free(sql);
  if (rc != SQLITE_OK) return rc;
  while ((rc = sqlite3_step(q)) == SQLITE_ROW) {
    if (++*bad > NSHOWN) continue;
    const rule *r = &rules[sqlite3_column_int(q, 1)];
    char want[300];
    rule_text(r, want, sizeof want);
    *len += (size_t)snprintf(msg + *len, *len < m ? m - *len : 0,
                             "%s table %s, row %.200s: %s = %.60s is not %s",
                             *bad > 1 ? ";" : "", table, sqlite3_column_text(q, 0),
                             r->col, sqlite3_column_text(q, 2), want);
  }
  sqlite3_finalize(q);
  return rc == SQLITE_DONE ? SQLITE_OK : rc;
}

ss_status ss_store_check_rows(ss_store *st, ss_error *err) {
  char msg[1800] = "";
  size_t len = 0, bad = 0;
  int rc = check_table(st, "scheme", "'id ' || quote(t.id)", scheme_rules,
                       (int)(sizeof scheme_rules / sizeof scheme_rules[0]), &bad, msg,
                       &len, sizeof msg);
  if (rc == SQLITE_OK)
    rc = check_table(
        st, "result",
        "'(scheme_id ' || quote(t.scheme_id) || ', kind ' || quote(t.kind) || "
        "', k ' || quote(t.k) || ', link ' || quote(t.link) || ')'",
        result_rules, (int)(sizeof result_rules / sizeof result_rules[0]), &bad, msg,
        &len, sizeof msg);
  if (rc == SQLITE_NOMEM) return ss_error_nomem(err, "results store check");
  if (rc != SQLITE_OK) return ss_store_db_error(st, err, "cannot check its rows");
  if (!bad) return SS_OK;
  return ss_error_set(err, SS_EINPUT, "%s: %zu invalid row%s (hand-edited?):%s%s",
                      st->path, bad, bad > 1 ? "s" : "", msg,
                      bad > NSHOWN ? "; and more" : "");
}
