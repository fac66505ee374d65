/* ss_jsr.c — bounds on the joint spectral radius: the norm profile rho_k by
 * brute force, the lower bound from spectral radii of products, and the
 * branch and bound (Gripenberg 1996) for the upper bound.  Method and
 * certification: ss_jsr.h. */
#include "ss_jsr.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <lapacke.h>

#include "ss_jsr_cert.h"

ss_jsr_opts ss_jsr_defaults(void) {
  ss_jsr_opts o = {8, 1e-3, SS_JSR_NORM_INF, 10000000, 0.0, 0};
  return o;
}

void ss_jsr_result_clear(ss_jsr_result *r) {
  if (!r) return;
  free(r->rho_inf);
  free(r->rho_2);
  free(r->lower_word);
  memset(r, 0, sizeof *r);
}

/* The depth-first walk over words.  Level k (0-based) of the stacks holds the
 * word's product of length k + 1, Y_{w_{k+1}} ... Y_{w_1}, formed as
 * Y_{w_{k+1}} times level k - 1: one n x n product per node.  All buffers are
 * allocated once (grown by ws_reserve when the branch and bound deepens). */
typedef struct {
  size_t m, n;            /* number and order of the matrices */
  const double *const *Y; /* the input matrices (not owned) */
  int cap;                /* levels the stacks hold */
  int *word;              /* cap: the current word, word[k] in 0..m-1 */
  double *prod;           /* cap * n * n: the computed products, row-major */
  double *err_inf;        /* cap: rigorous bound on ||exact - computed||_inf */
  double *nhat_inf;       /* cap: ||computed product||_inf (floating point) */
  double *bnd;            /* cap: the branch and bound's value of the prefix */
  double *a;              /* n * n: scratch copy for LAPACK (destroyed) */
  double *wr, *wi, *sv;   /* n each: eigenvalues and singular values */
  double *sb;             /* n: dgesvd's superdiagonal scratch */
  double *ynorm;          /* m: rigorous upper bounds of ||Y_i||_inf */
  double gam;             /* gamma_n = n u / (1 - n u), u the unit roundoff */
  double lower;           /* best rho(Y_w)^{1/|w|} found so far (floating point) */
  int lower_len;          /* its word's length */
  int *lower_word;        /* cap: its word */
  size_t nodes;           /* products formed */
  ss_status st;           /* first LAPACK failure, SS_OK if none */
} jsr_ws;

static const double U = DBL_EPSILON / 2;

/* x rounded away from 0 by a few units: covers the rounding of the handful of
 * floating-point operations on nonnegative numbers that produced x. */
static double up(double x) {
  return x * (1 + 8 * U);
}

/* A rigorous upper bound of x^{1/k} for x >= 0 from pow: glibc's pow is
 * within one ulp, and 1/k rounded perturbs the exponent by at most u/k, which
 * moves the result by the factor exp(u |ln x| / k). */
static double root_up(double x, int k) {
  if (x <= 0) return 0;
  double r = pow(x, 1.0 / k);
  return r * (1 + (8 + fabs(log(x))) * 2 * U);
}

static double now_seconds(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void ws_free(jsr_ws *w) {
  free(w->word);
  free(w->prod);
  free(w->err_inf);
  free(w->nhat_inf);
  free(w->bnd);
  free(w->a);
  free(w->wr);
  free(w->wi);
  free(w->sv);
  free(w->sb);
  free(w->ynorm);
  free(w->lower_word);
}

/* Make the stacks hold `levels` levels; keeps their contents. */
static int ws_reserve(jsr_ws *w, int levels) {
  if (levels <= w->cap) return 1;
  const size_t L = (size_t)levels, nn = w->n * w->n;
  int *wd = realloc(w->word, L * sizeof *wd);
  if (wd) w->word = wd;
  double *p = realloc(w->prod, L * nn * sizeof *p);
  if (p) w->prod = p;
  double *e = realloc(w->err_inf, L * sizeof *e);
  if (e) w->err_inf = e;
  double *h = realloc(w->nhat_inf, L * sizeof *h);
  if (h) w->nhat_inf = h;
  double *b = realloc(w->bnd, L * sizeof *b);
  if (b) w->bnd = b;
  int *lw = realloc(w->lower_word, L * sizeof *lw);
  if (lw) w->lower_word = lw;
  if (!wd || !p || !e || !h || !b || !lw) return 0;
  w->cap = levels;
  return 1;
}

/* Maximum absolute row sum of the n x n row-major matrix a (floating point). */
static double norm_inf(const double *a, size_t n) {
  double mx = 0;
  for (size_t r = 0; r < n; r++) {
    double s = 0;
    for (size_t c = 0; c < n; c++)
      s += fabs(a[r * n + c]);
    if (s > mx) mx = s;
  }
  return mx;
}

/* Form the product at level k: Y_i, or Y_i times level k - 1, with its
 * rigorous error bound.  fl(Y P^) = Y P^ + F, |F| <= gamma_n |Y| |P^|
 * (Higham, Accuracy and Stability, 3.5), so E_k = P_k - P^_k = Y E_{k-1} - F and
 * ||E_k||_inf <= ||Y||_inf (||E_{k-1}||_inf + gamma_n ||P^_{k-1}||_inf). */
static void ws_push(jsr_ws *w, int k, size_t i) {
  const size_t n = w->n, nn = n * n;
  double *p = w->prod + (size_t)k * nn;
  const double *y = w->Y[i];
  w->word[k] = (int)i;
  w->nodes++;
  if (k == 0) {
    memcpy(p, y, nn * sizeof *p);
    w->err_inf[0] = 0;
  } else {
    const double *q = p - nn;
    for (size_t r = 0; r < n; r++) {
      double *pr = p + r * n;
      for (size_t c = 0; c < n; c++)
        pr[c] = 0;
      for (size_t t = 0; t < n; t++) {
        const double yrt = y[r * n + t];
        if (yrt == 0) continue;
        const double *qt = q + t * n;
        for (size_t c = 0; c < n; c++)
          pr[c] += yrt * qt[c];
      }
    }
    w->err_inf[k] = up(w->ynorm[i] * up(w->err_inf[k - 1] + w->gam * w->nhat_inf[k - 1]));
  }
  w->nhat_inf[k] = norm_inf(p, n);
}

/* A rigorous upper bound of ||exact product at level k||_inf: the computed
 * norm (a sum of n nonnegative terms, relative error <= gamma_n) plus the
 * product's error bound. */
static double ws_norm_inf_up(const jsr_ws *w, int k) {
  return up(up(w->nhat_inf[k] * (1 + 2 * w->gam)) + w->err_inf[k]);
}

/* Largest singular value of the product at level k (LAPACK, floating point).
 * The row-major buffer read as column-major is the transpose, which has the
 * same singular values. */
static double ws_norm_2(jsr_ws *w, int k) {
  const size_t n = w->n, nn = n * n;
  memcpy(w->a, w->prod + (size_t)k * nn, nn * sizeof *w->a);
  if (n == 1) return fabs(w->a[0]);
  lapack_int info =
      LAPACKE_dgesvd(LAPACK_COL_MAJOR, 'N', 'N', (lapack_int)n, (lapack_int)n, w->a,
                     (lapack_int)n, w->sv, NULL, 1, NULL, 1, w->sb);
  if (info != 0) {
    if (w->st == SS_OK) w->st = SS_ENUMERIC;
    return INFINITY;
  }
  return w->sv[0];
}

/* Spectral radius of the product at level k (LAPACK dgeev, floating point;
 * the transpose has the same eigenvalues). */
static double ws_specrad(jsr_ws *w, int k) {
  const size_t n = w->n, nn = n * n;
  memcpy(w->a, w->prod + (size_t)k * nn, nn * sizeof *w->a);
  if (n == 1) return fabs(w->a[0]);
  lapack_int info = LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'N', (lapack_int)n, w->a,
                                  (lapack_int)n, w->wr, w->wi, NULL, 1, NULL, 1);
  if (info != 0) {
    if (w->st == SS_OK) w->st = SS_ENUMERIC;
    return 0;
  }
  double r = 0;
  for (size_t j = 0; j < n; j++)
    r = fmax(r, hypot(w->wr[j], w->wi[j]));
  return r;
}

/* Offer the word at levels 0..k to the lower bound.  rho(P) <= ||P||_inf, so
 * the eigenvalue computation is skipped when the norm cannot beat the bound. */
static void ws_offer_lower(jsr_ws *w, int k) {
  const double lim = pow(w->lower, (double)(k + 1));
  if (w->nhat_inf[k] <= lim) return;
  const double r = ws_specrad(w, k);
  if (r <= lim) return;
  const double v = pow(r, 1.0 / (k + 1));
  if (v > w->lower) {
    w->lower = v;
    w->lower_len = k + 1;
    memcpy(w->lower_word, w->word, (size_t)(k + 1) * sizeof *w->word);
  }
}

/* Step the depth-first walk to the next sibling at level *k, backtracking
 * to lower levels when a level's m letters are used up; 0 when the walk is
 * over.  A caller descends by `w->word[++k] = -1`. */
static int ws_next(jsr_ws *w, int *k) {
  while (*k >= 0 && ++w->word[*k] >= (int)w->m)
    (*k)--;
  return *k >= 0;
}

/* Brute force over all m^K words of length <= K: rho_inf, rho_2 (floating
 * point), rigorous inf-norm profile rho_cert, and the lower bound. */
static void brute_force(jsr_ws *w, int K, double *rho_inf, double *rho_2,
                        double *rho_cert) {
  for (int k = 0; k < K; k++)
    rho_inf[k] = rho_2[k] = rho_cert[k] = 0;
  int k = 0;
  w->word[0] = -1;
  while (ws_next(w, &k)) {
    ws_push(w, k, (size_t)w->word[k]);
    const double p = 1.0 / (k + 1);
    rho_inf[k] = fmax(rho_inf[k], pow(w->nhat_inf[k], p));
    rho_cert[k] = fmax(rho_cert[k], ws_norm_inf_up(w, k));
    /* ||P||_2 <= ||P||_inf^{1/2} ||P||_1^{1/2} is not cheap; sqrt(n) ||P||_inf
     * bounds ||P||_2 and skips the SVD when it cannot raise the maximum */
    const double two_cap = sqrt((double)w->n) * w->nhat_inf[k];
    if (two_cap * (1 + 1e-12) > pow(rho_2[k], (double)(k + 1)))
      rho_2[k] = fmax(rho_2[k], pow(ws_norm_2(w, k), p));
    ws_offer_lower(w, k);
    if (k + 1 < K) w->word[++k] = -1;
  }
  for (k = 0; k < K; k++)
    rho_cert[k] = root_up(rho_cert[k], k + 1);
}

/* One pass of the branch and bound to depth L.  The bound of a word w is
 *   b(w) = min over the prefixes u of w of N(u)^{1/|u|}
 * with N(u) the norm of Y_u (rigorous for the inf-norm).  The words not
 * extended (pruned, or of length L) form a complete set: every infinite word
 * has a prefix among them, so every long product factors into products of
 * these words and a bounded remainder, and submultiplicativity gives
 *   rho(Y) <= max over the leaves w of N(u_w)^{1/|u_w|},
 * u_w the prefix of w attaining b(w); that is, rho(Y) <= max_leaves b(w).
 * A word with b(w) <= target is not extended: its subtree can only lower its
 * bound, and it already cannot lift the maximum above the target.
 * Returns 1 and *upper if the pass completed, 0 if a limit stopped it. */
static int bnb_pass(jsr_ws *w, int L, ss_jsr_norm norm, double gap, size_t max_nodes,
                    double deadline, double *upper) {
  double mx = 0;
  int k = 0;
  w->word[0] = -1;
  while (ws_next(w, &k)) {
    if ((max_nodes && w->nodes >= max_nodes) ||
        (deadline > 0 && now_seconds() > deadline))
      return 0;
    ws_push(w, k, (size_t)w->word[k]);
    ws_offer_lower(w, k);
    const double nv =
        norm == SS_JSR_NORM_2 ? ws_norm_2(w, k) * (1 + 1e-14) : ws_norm_inf_up(w, k);
    double b = root_up(nv, k + 1);
    if (k > 0) b = fmin(b, w->bnd[k - 1]);
    w->bnd[k] = b;
    const double target = w->lower * (1 + gap);
    if (b <= target || k + 1 == L) {
      mx = fmax(mx, b);
      continue;
    }
    w->word[++k] = -1;
  }
  *upper = mx;
  return 1;
}

ss_status ss_jsr_compute(size_t m, size_t n, const double *const *Y, const ss_jsr_opts *o,
                         ss_jsr_result *out, ss_error *err) {
  const double t0 = now_seconds();
  ss_jsr_opts d = ss_jsr_defaults();
  if (!o) o = &d;
  if (!out) return ss_error_set(err, SS_EINPUT, "jsr: no result given");
  memset(out, 0, sizeof *out);
  if (m < 1) return ss_error_set(err, SS_EINPUT, "jsr: no matrices (m = 0)");
  if (n < 1) return ss_error_set(err, SS_EINPUT, "jsr: matrices of order n = 0");
  if (!Y) return ss_error_set(err, SS_EINPUT, "jsr: no matrices given");
  if (n > 100000 || m > 1000000)
    return ss_error_set(err, SS_EINPUT, "jsr: %zu matrices of order %zu: too large", m,
                        n);
  if (o->depth < 1 || o->depth > 64)
    return ss_error_set(err, SS_EINPUT, "jsr: depth %d not in 1..64", o->depth);
  if (!(o->gap >= 0) || !isfinite(o->gap))
    return ss_error_set(err, SS_EINPUT, "jsr: gap %g is not a finite number >= 0",
                        o->gap);
  if (o->norm != SS_JSR_NORM_INF && o->norm != SS_JSR_NORM_2)
    return ss_error_set(err, SS_EINPUT, "jsr: unknown norm %d", (int)o->norm);
  if (isnan(o->max_seconds))
    return ss_error_set(err, SS_EINPUT, "jsr: max_seconds is NaN");
  if (o->max_depth < 0)
    return ss_error_set(err, SS_EINPUT, "jsr: max_depth %d < 0", o->max_depth);
  for (size_t i = 0; i < m; i++) {
    if (!Y[i]) return ss_error_set(err, SS_EINPUT, "jsr: matrix %zu is missing", i + 1);
    for (size_t e = 0; e < n * n; e++)
      if (!isfinite(Y[i][e]))
        return ss_error_set(err, SS_EINPUT,
                            "jsr: matrix %zu, entry (%zu, %zu) is not finite (%g)", i + 1,
                            e / n + 1, e % n + 1, Y[i][e]);
  }
  if (n * U * 4 >= 1) return ss_error_set(err, SS_EINPUT, "jsr: order %zu too large", n);

  ss_status st = SS_OK;
  const int K = o->depth;
  double *rho_cert = NULL;
  jsr_ws w;
  memset(&w, 0, sizeof w);
  w.m = m, w.n = n, w.Y = Y;
  w.gam = (double)n * U / (1 - (double)n * U);
  w.a = malloc(n * n * sizeof *w.a);
  w.wr = malloc(n * sizeof *w.wr);
  w.wi = malloc(n * sizeof *w.wi);
  w.sv = malloc(n * sizeof *w.sv);
  w.sb = malloc(n * sizeof *w.sb);
  w.ynorm = malloc(m * sizeof *w.ynorm);
  out->rho_inf = calloc((size_t)K, sizeof *out->rho_inf);
  out->rho_2 = calloc((size_t)K, sizeof *out->rho_2);
  rho_cert = calloc((size_t)K, sizeof *rho_cert);
  if (!w.a || !w.wr || !w.wi || !w.sv || !w.sb || !w.ynorm || !out->rho_inf ||
      !out->rho_2 || !rho_cert || !ws_reserve(&w, K)) {
    st = ss_error_nomem(err, "jsr workspace");
    goto done;
  }
  for (size_t i = 0; i < m; i++)
    w.ynorm[i] = up(norm_inf(Y[i], n) * (1 + 2 * w.gam));
  out->depth = K;

  brute_force(&w, K, out->rho_inf, out->rho_2, rho_cert);
  if (w.st != SS_OK) goto lapack_failed;
  /* min_k rho_k bounds rho(Y) in every norm; the rigorous inf-norm profile
   * is the certified part */
  double upper = INFINITY;
  int upper_rigorous = 0;
  for (int k = 0; k < K; k++)
    if (rho_cert[k] < upper) upper = rho_cert[k], upper_rigorous = 1;
  if (o->norm == SS_JSR_NORM_2)
    for (int k = 0; k < K; k++)
      if (out->rho_2[k] * (1 + 1e-14) < upper)
        upper = out->rho_2[k] * (1 + 1e-14), upper_rigorous = 0;
  const size_t brute_nodes = w.nodes;

  /* branch and bound by iterative deepening: each pass's leaves give a valid
   * bound, deeper passes refine it; recomputing the shallow levels costs a
   * factor of about m / (m - 1) at most */
  const double deadline = o->max_seconds > 0 ? t0 + o->max_seconds : 0;
  const size_t max_nodes = o->max_nodes ? brute_nodes + o->max_nodes : 0;
  for (int L = K; upper > w.lower * (1 + o->gap); L++) {
    if (o->max_depth && L > o->max_depth) break;
    if (!ws_reserve(&w, L)) {
      st = ss_error_nomem(err, "jsr branch and bound stack");
      goto done;
    }
    double u;
    if (!bnb_pass(&w, L, o->norm, o->gap, max_nodes, deadline, &u)) break;
    if (w.st != SS_OK) goto lapack_failed;
    out->bnb_depth = L;
    if (u < upper) upper = u, upper_rigorous = o->norm == SS_JSR_NORM_INF;
  }
  if (w.st != SS_OK) goto lapack_failed;
  out->nodes = w.nodes - brute_nodes;

  out->lower_word = malloc((size_t)(w.lower_len > 0 ? w.lower_len : 1) * sizeof(int));
  if (!out->lower_word) {
    st = ss_error_nomem(err, "jsr lower word");
    goto done;
  }
  out->lower_len = w.lower_len;
  memcpy(out->lower_word, w.lower_word, (size_t)w.lower_len * sizeof(int));
  /* the floating-point lower bound is replaced by a certified one for the
   * same word when the ball-arithmetic enclosure succeeds */
  double lower_cert = 0;
  int lower_rigorous = 0;
  if (w.lower_len == 0)
    lower_rigorous = 1; /* no product has a nonzero spectral radius: 0 */
  else
    lower_rigorous = ss_jsr_cert_lower(n, Y, w.lower_word, w.lower_len, &lower_cert);
  out->lower = lower_rigorous ? lower_cert : w.lower;
  out->upper = upper;
  out->certified = lower_rigorous && upper_rigorous;
  out->converged = out->upper <= out->lower * (1 + o->gap);
  out->seconds = now_seconds() - t0;
  goto done;

lapack_failed:
  st = w.st == SS_ENOMEM ? ss_error_nomem(err, "jsr LAPACK scratch")
                         : ss_error_set(err, SS_ENUMERIC,
                                        "jsr: LAPACK eigenvalue or singular value "
                                        "computation did not converge");
done:
  ws_free(&w);
  free(rho_cert);
  if (st != SS_OK) ss_jsr_result_clear(out);
  return st;
}
