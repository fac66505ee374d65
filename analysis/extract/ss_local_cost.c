/* ss_local_cost.c — what a case will cost before it is built: rows of S,
 * memory and time (formulas in ss_local_cost.h), and the memory budget. */
#include "ss_local_cost.h"

#include <math.h>
#include <stdio.h>
#include <sys/resource.h>
#include <unistd.h>

#define BASE_BYTES 16e6 /* the program itself, measured */
#define FLOP_RATE  2e9  /* dense LAPACK on one core, flops per second */
#define PATCH_RATE 40e6 /* refined-patch bytes built per second */

/* Largest degree of a link vertex. */
static int max_degree(const ss_link *l) {
  int d = 0;
  for (int v = 0; v < l->k; v++)
    d = ss_link_deg(l, v) > d ? ss_link_deg(l, v) : d;
  return d;
}

ss_status ss_local_estimate(const ss_scheme *s, const ss_case *c, ss_local_cost *out,
                            ss_error *err) {
  *out = (ss_local_cost){0, 0, 0, 0, 0, 0.0, 0.0, 0.0, 0.0};
  const int ml = ss_scheme_split_kind(s) == SS_SPLIT_MULTILINEAR;
  const int box = ss_scheme_reads_diagonals(s);
  ss_cell_type t;
  ss_status st = ss_case_cell(s, c->kind, &t, err);
  if (st) return st;
  if (c->kind == SS_CASE_VERTEX && !c->link)
    return ss_error_set(err, SS_EINPUT, "the vertex case needs a link");
  /* the first level on which the centre is a vertex */
  const int lc = ss_case_centre_level(c->kind);
  if (c->kind != SS_CASE_VERTEX && c->kind != SS_CASE_FACE &&
      (c->n < 3 || c->n > SS_STAR_MAXN))
    return ss_error_set(err, SS_EINPUT, "valence %d is not in 3..%d", c->n, SS_STAR_MAXN);
  const double k = c->kind == SS_CASE_VERTEX ? (double)c->link->k : 0.0;
  const double n = (double)c->n;
  double n2 = 0, n1 = 0, sv = 0, sc = 0, b = 0;
  switch (c->kind) {
  case SS_CASE_VERTEX:
    sc = 2 * k - 4;
    sv = ml ? 6 * k - 9 : k + 1;
    n2 = ml ? 30 * k - 55 : 5 * k - 5;
    n1 = ml ? 6 * k - 9 : k + 1;
    b = ml ? 2.0 * max_degree(c->link) + 1 : 3 * k - 6;
    break;
  case SS_CASE_EDGE:
    sc = n;
    sv = ml ? 4 * n + 2 : n + 2;
    b = 2 * n + 1;
    if (ml) {
      n2 = 30 * n + 5;
      n1 = 6 * n + 3;
    } else if (box && c->diag == SS_DIAG_SKEW) {
      n2 = 14 * n + 5;
      n1 = 2 * n + 3;
    } else if (box && c->diag != SS_DIAG_CENTER) {
      n2 = ceil((29 * n + 9) / 2);
      n1 = ceil((5 * n + 5) / 2);
    } else {
      n2 = 15 * n + 5;
      n1 = 3 * n + 3;
    }
    break;
  case SS_CASE_FACE:
    sc = 2;
    sv = 5;
    n2 = box ? 81 : 85;
    n1 = box ? 15 : 19;
    b = 5;
    break;
  default: /* surface vertex */
    sc = n;
    sv = ml ? 2 * n + 1 : n + 1;
    n2 = ml ? 6 * n + 1 : 3 * n + 1;
    n1 = ml ? 2 * n + 1 : n + 1;
    b = 3;
    if (ss_scheme_split_kind(s) == SS_SPLIT_BISECT) {
      /* quasi48: the chart has r = n rays (class 4) or n / 2 (class 8) */
      const int cls = ss_case_class48(c->n, c->cls);
      if (cls != 4 && (cls != 8 || c->n < 6 || c->n % 2))
        return ss_error_set(err, SS_EINPUT,
                            cls == 8 ? "a class-8 vertex of a 4-8 mesh has an even "
                                       "valence of at least 6, not %d"
                                     : "4-8 vertex class must be 4 or 8 (valence %d)",
                            c->n);
      const double r = cls == 8 ? n / 2 : n;
      sv = n + 1; /* class 8: 2r + 1 */
      n2 = 19 * r + 1;
      n1 = 11 * r + 1;
    }
    break;
  }
  if (b > n2 - n1) b = n2 - n1;
  const double beta0 = t == SS_HEX    ? 0.3e6
                       : t == SS_TET  ? 0.125e6
                       : t == SS_QUAD ? 8e3
                                      : 4e3;
  const double patch = beta0 * pow(8.0, lc) * (ss_scheme_reach(s) > 1 ? 4.0 : 1.0) * sc;
  const double dense = 8.0 * n2 * n2, m = fmax(n1, b);
  const double eig = 8.0 * (2 * n1 * n1 + 3 * m * m + 6 * m + 2 * b * b + b * (n2 - n1));
  out->n2 = (size_t)n2;
  out->n1 = (size_t)n1;
  out->star_vertices = (size_t)sv;
  out->star_cells = (size_t)sc;
  out->block = (size_t)b;
  out->dense_bytes = dense;
  out->bytes = BASE_BYTES + patch + fmax(2 * dense, dense + eig);
  out->flops = 25.0 * (n1 * n1 * n1 + (n2 - n1) * b * b) + 4.0 * n2 * n2;
  out->seconds = out->flops / FLOP_RATE + patch / PATCH_RATE;
  return SS_OK;
}

double ss_local_memory_budget(void) {
  const long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGESIZE);
  double b = pages > 0 && size > 0 ? 0.5 * (double)pages * (double)size : 0.0;
  const int res[2] = {RLIMIT_AS, RLIMIT_DATA};
  for (int i = 0; i < 2; i++) {
    struct rlimit r;
    if (getrlimit(res[i], &r) || r.rlim_cur == RLIM_INFINITY) continue;
    const double lim = 0.75 * (double)r.rlim_cur;
    if (b <= 0.0 || lim < b) b = lim;
  }
  return b;
}

const char *ss_local_bytes_text(double bytes, char *buf, size_t n) {
  if (bytes >= 1e9)
    snprintf(buf, n, "%.1f GB", bytes / 1e9);
  else if (bytes >= 1e6)
    snprintf(buf, n, "%.1f MB", bytes / 1e6);
  else
    snprintf(buf, n, "%.0f KB", bytes / 1e3);
  return buf;
}

ss_status ss_local_check_budget(const ss_local_cost *k, double budget, ss_error *err) {
  if (budget <= 0.0 || k->bytes <= budget) return SS_OK;
  char need[32], have[32];
  return ss_error_set(err, SS_ENOMEM,
                      "needs about %zu rows of S and ~%s of memory (more than the "
                      "budget of %s)",
                      k->n2, ss_local_bytes_text(k->bytes, need, sizeof need),
                      ss_local_bytes_text(budget, have, sizeof have));
}
