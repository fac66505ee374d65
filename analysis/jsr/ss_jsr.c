/* ss_jsr.c — bounds on the joint spectral radius: validates the inputs,
 * scales them by a power of two, and runs the stages — brute force, weighting,
 * ellipsoid, invariant polytope, branch and bound (Gripenberg 1996),
 * certification of the lower bound — over the walks of ss_jsr_search.c.
 * Method and certification: ss_jsr.h. */
#include "ss_jsr.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ss_clock.h"
#include "ss_jsr_cert.h"
#include "ss_jsr_polytope.h"
#include "ss_jsr_ws.h"

/* AUTO tries the ellipsoidal norm up to this order (the tet/oct face is 30,
 * its edges 3..10 up to 50; the fit costs O(m n^3) per L-BFGS step). */
enum { ELL_AUTO_MAX_N = 64 };

/* The invariant polytope's vertex cap inside ss_jsr_compute (memory about
 * (12 m + 8 n) bytes per vertex plus GLPK's 2 n nonzeros per vertex). */
enum { POLY_CAP = 20000 };

ss_jsr_opts ss_jsr_defaults(void) {
  ss_jsr_opts o = {8, 1e-3, SS_JSR_NORM_AUTO, 10000000, 0.0, 0, 1, 1, {NULL, NULL}};
  return o;
}

void ss_jsr_result_clear(ss_jsr_result *r) {
  if (!r) return;
  free(r->rho_inf);
  free(r->rho_2);
  free(r->lower_word);
  memset(r, 0, sizeof *r);
}

/* The invariant polytope (ss_jsr_polytope.h) from the current lower bound's
 * word, eps = gap / 2 (so that a closed polytope meets the gap), until the
 * wall-clock time `until` (0: no limit but the vertex cap).  Fills
 * out->polytope, poly_vertices, poly_upper.  Only running out of memory is
 * an error; anything else the method cannot do leaves the gap to the branch
 * and bound. */
static ss_status try_polytope(ss_jsr_ws *w, const double *const *Y, double gap,
                              double until, ss_jsr_result *out, ss_error *err) {
  out->polytope = SS_POLY_LP;
  out->poly_upper = INFINITY;
  if (w->lower_len < 1 || w->n > 4096) return SS_OK;
  ss_jsr_polytope_opts po = ss_jsr_polytope_defaults();
  po.eps = gap > 0 ? fmin(gap / 2, 0.25) : 1e-9;
  po.max_vertices = POLY_CAP;
  po.max_seconds = until > 0 ? fmax(until - ss_clock_wall(), 1e-3) : 0;
  ss_jsr_polytope_result pr;
  ss_error e2 = {0};
  const ss_status st =
      ss_jsr_polytope(w->m, w->n, Y, w->lower_word, w->lower_len, &po, &pr, &e2);
  if (st == SS_ENOMEM) return ss_error_nomem(err, "jsr invariant polytope");
  if (st != SS_OK) return SS_OK;
  out->polytope = (int)pr.stop;
  out->poly_vertices = pr.vertices;
  if (pr.stop == SS_POLY_CLOSED) out->poly_upper = pr.upper;
  return SS_OK;
}

/* The candidate norms of the branch and bound: the plain inf-norm, the
 * weighted inf-norm, the 2-norm and the ellipsoidal norm (the 2-norm of the
 * similar copies); ss_jsr_ws_select takes the same numbers. */
enum { C_INF, C_WINF, C_2, C_ELL, NCAND };
static const ss_jsr_norm cand_norm[NCAND] = {SS_JSR_NORM_INF, SS_JSR_NORM_INF,
                                             SS_JSR_NORM_2, SS_JSR_NORM_2};

/* One run of ss_jsr_compute: the options, the inputs in use, the workspace
 * and what each stage hands to the next. */
typedef struct {
  const ss_jsr_opts *o;   /* the options (not owned) */
  int K;                  /* the brute force's depth, o->depth */
  int auto_;              /* AUTO or POLYTOPE: every candidate norm may serve
                             (POLYTOPE runs the polytope first, then the branch
                             and bound as AUTO) */
  double t0;              /* the start (ss_clock_wall) */
  double deadline;        /* t0 + o->max_seconds, 0 for no time limit: every
                             stage's */
  const double *const *Y; /* the inputs in use: the caller's or yn */
  int ex;                 /* the inputs in use are the caller's times 2^ex */
  double *ybuf;           /* m * n * n: the scaled inputs, NULL if ex == 0 */
  const double **yn;      /* m: pointers into ybuf */
  double *rho_cert;       /* K: the rigorous inf-norm profile */
  double *best_d;         /* n: the weights of the weighted inf-norm */
  double upper;           /* the best rigorous upper bound so far */
  size_t brute_nodes;     /* products the brute force formed */
  size_t max_nodes;       /* the branch and bound's node limit, 0: none */
  int use[NCAND];         /* 1 for the candidate norms o->norm allows */
  int ncand;              /* how many */
  int active;             /* the candidate in use */
  ss_jsr_ws w;            /* the walks' workspace */
} jsr_run;

/* The inputs and options of ss_jsr_compute checked; SS_EINPUT with the reason
 * if anything is out of range. */
static ss_status validate(size_t m, size_t n, const double *const *Y,
                          const ss_jsr_opts *o, ss_error *err) {
  if (m < 1) return ss_error_set(err, SS_EINPUT, "jsr: no matrices (m = 0)");
  if (n < 1) return ss_error_set(err, SS_EINPUT, "jsr: matrices of order n = 0");
  if (!Y) return ss_error_set(err, SS_EINPUT, "jsr: no matrices given");
  if (n > 100000 || m > 1000000)
    return ss_error_set(err, SS_EINPUT, "jsr: %zu matrices of order %zu: too large", m,
                        n);
  if (o->depth < 1 || o->depth > 64)
    return ss_error_set(err, SS_EINPUT, "jsr: depth %d not in 1..64", o->depth);
  {
    /* brute force forms every word of length <= depth: refuse what could
     * not finish rather than run for years */
    double words = 0, p = 1;
    for (int k = 1; k <= o->depth && words <= 1e10; k++)
      words += (p *= (double)m);
    if (words > 1e10)
      return ss_error_set(err, SS_EINPUT,
                          "jsr: depth %d with %zu matrices means more than 10^10 "
                          "products of brute force; lower the depth",
                          o->depth, m);
  }
  if (!(o->gap >= 0) || !isfinite(o->gap))
    return ss_error_set(err, SS_EINPUT, "jsr: gap %g is not a finite number >= 0",
                        o->gap);
  if (o->norm != SS_JSR_NORM_INF && o->norm != SS_JSR_NORM_2 &&
      o->norm != SS_JSR_NORM_AUTO && o->norm != SS_JSR_NORM_ELLIPSOID &&
      o->norm != SS_JSR_NORM_POLYTOPE)
    return ss_error_set(err, SS_EINPUT, "jsr: unknown norm %d", (int)o->norm);
  if (isnan(o->max_seconds))
    return ss_error_set(err, SS_EINPUT, "jsr: max_seconds is NaN");
  if (o->max_depth < 0)
    return ss_error_set(err, SS_EINPUT, "jsr: max_depth %d < 0", o->max_depth);
  if (o->fit_words < 1 || o->fit_words > 5)
    return ss_error_set(err, SS_EINPUT, "jsr: fit_words %d not in 1..5", o->fit_words);
  {
    double prods = 1; /* the ellipsoid's fit holds all m^K products */
    for (int k = 0; k < o->fit_words; k++)
      prods *= (double)m;
    if (prods > 4096)
      return ss_error_set(err, SS_EINPUT,
                          "jsr: fit_words %d with %zu matrices means %.0f products "
                          "(at most 4096); lower fit_words",
                          o->fit_words, m, prods);
  }
  for (size_t i = 0; i < m; i++) {
    if (!Y[i]) return ss_error_set(err, SS_EINPUT, "jsr: matrix %zu is missing", i + 1);
    for (size_t e = 0; e < n * n; e++)
      if (!isfinite(Y[i][e]))
        return ss_error_set(err, SS_EINPUT,
                            "jsr: matrix %zu, entry (%zu, %zu) is not finite (%g)", i + 1,
                            e / n + 1, e % n + 1, Y[i][e]);
  }
  if (n * U * 4 >= 1) return ss_error_set(err, SS_EINPUT, "jsr: order %zu too large", n);
  return SS_OK;
}

/* The error of a LAPACK failure recorded in the workspace. */
static ss_status lapack_failed(const ss_jsr_ws *w, ss_error *err) {
  return w->st == SS_ENOMEM ? ss_error_nomem(err, "jsr LAPACK scratch")
                            : ss_error_set(err, SS_ENUMERIC,
                                           "jsr: LAPACK eigenvalue or singular value "
                                           "computation did not converge");
}

/* The workspace and the result's profiles allocated. */
static ss_status run_alloc(jsr_run *r, size_t m, size_t n, ss_jsr_result *out,
                           ss_error *err) {
  ss_jsr_ws *w = &r->w;
  const int K = r->K;
  w->m = m, w->n = n, w->Y = r->Y;
  w->gam = (double)n * U / (1 - (double)n * U);
  w->tiny = (double)n * (double)n * DBL_TRUE_MIN;
  w->a = malloc(n * n * sizeof *w->a);
  w->wr = malloc(n * sizeof *w->wr);
  w->wi = malloc(n * sizeof *w->wi);
  w->sv = malloc(n * sizeof *w->sv);
  w->sb = malloc(n * sizeof *w->sb);
  w->ynorm = malloc(m * sizeof *w->ynorm);
  w->delta = malloc(m * sizeof *w->delta);
  w->zbuf = malloc(m * n * n * sizeof *w->zbuf);
  w->zptr = malloc(m * sizeof *w->zptr);
  w->d = malloc(2 * n * sizeof *w->d);
  w->vl = malloc(n * n * sizeof *w->vl);
  w->v = malloc(n * n * sizeof *w->v);
  w->t2 = malloc(n * n * sizeof *w->t2);
  w->y2 = malloc(m * sizeof *w->y2);
  w->yf = malloc(m * sizeof *w->yf);
  r->best_d = malloc(n * sizeof *r->best_d);
  out->rho_inf = calloc((size_t)K, sizeof *out->rho_inf);
  out->rho_2 = calloc((size_t)K, sizeof *out->rho_2);
  r->rho_cert = calloc((size_t)K, sizeof *r->rho_cert);
  if (!w->a || !w->wr || !w->wi || !w->sv || !w->sb || !w->ynorm || !w->delta ||
      !w->zbuf || !w->zptr || !w->d || !w->vl || !w->v || !w->t2 || !w->y2 || !w->yf ||
      !r->best_d || !out->rho_inf || !out->rho_2 || !r->rho_cert ||
      !ss_jsr_ws_reserve(w, K))
    return ss_error_nomem(err, "jsr workspace");
  return SS_OK;
}

/* JSR(2^e Y) = 2^e JSR(Y): the inputs are scaled by the power of two that
 * brings the largest norm near 1 (exactly, or not at all), so that long
 * products neither overflow nor underflow for inputs of any size; the
 * results are scaled back exactly at the end (finish).  Sets r->ex and
 * r->Y. */
static ss_status scale_inputs(jsr_run *r, ss_error *err) {
  const size_t m = r->w.m, n = r->w.n;
  const double *const *Y = r->Y;
  int ex = 0;
  double mx = 0;
  for (size_t i = 0; i < m; i++)
    mx = fmax(mx, ss_dense_max_row_sum(Y[i], n));
  if (mx > 0 && isfinite(mx)) ex = -ilogb(mx);
  if (ex != 0) {
    r->ybuf = malloc(m * n * n * sizeof *r->ybuf);
    r->yn = malloc(m * sizeof *r->yn);
    if (!r->ybuf || !r->yn) return ss_error_nomem(err, "jsr scaled inputs");
    for (size_t i = 0; i < m && ex != 0; i++) {
      for (size_t e = 0; e < n * n && ex != 0; e++) {
        const double z = ldexp(Y[i][e], ex);
        if (ldexp(z, -ex) != Y[i][e]) ex = 0; /* underflow: not exact */
        r->ybuf[i * n * n + e] = z;
      }
      r->yn[i] = r->ybuf + i * n * n;
    }
  }
  if (ex != 0) r->Y = (const double *const *)r->yn;
  r->ex = ex;
  return SS_OK;
}

/* The brute force to depth K, within the deadline: the profiles, the lower
 * bound, and the first upper bound.  min_k rho_k over the complete lengths
 * bounds rho(Y); the rigorous inf-norm profile is used (the branch and
 * bound's first pass, at depth K, is at least as good in its own norm: max
 * over words of the min over prefixes <= min_k rho_k). */
static ss_status brute_stage(jsr_run *r, ss_jsr_result *out, ss_error *err) {
  ss_jsr_ws *w = &r->w;
  ss_progress_step(&r->o->progress, "products for rho_k", 0, (size_t)r->K);
  out->depth = ss_jsr_brute_force(w, r->K, r->deadline, out->rho_inf, out->rho_2,
                                  r->rho_cert, &out->cut_words);
  if (w->st != SS_OK) return lapack_failed(w, err);
  out->cut_len = out->depth < r->K ? out->depth + 1 : 0;
  ss_progress_step(&r->o->progress, "products for rho_k", (size_t)out->depth,
                   (size_t)r->K);
  r->upper = INFINITY;
  for (int k = 0; k < out->depth; k++)
    if (r->rho_cert[k] < r->upper) r->upper = r->rho_cert[k];
  r->brute_nodes = w->nodes;
  return SS_OK;
}

/* The norms the branch and bound may run in besides the plain ones: the
 * diagonally weighted inf-norm (an exact similarity; the profile rho_inf stays
 * the plain inf-norm) and the ellipsoidal norm (ss_jsr_ellipsoid.h), fitted,
 * then the similar copies enclosed; AUTO tries it for orders up to
 * ELL_AUTO_MAX_N (the fit costs O(m n^3) per step), with at most a quarter of
 * the time limit.  Then the candidates o->norm allows, the first active. */
static ss_status norms_stage(jsr_run *r, ss_error *err) {
  ss_jsr_ws *w = &r->w;
  const ss_jsr_opts *o = r->o;
  int have = 0;
  if (o->weighted && (o->norm == SS_JSR_NORM_INF || r->auto_) &&
      r->upper > w->lower * (1 + o->gap)) {
    if (!ss_jsr_ws_reserve(w, 2 * w->lower_len))
      return ss_error_nomem(err, "jsr scaling");
    ss_jsr_choose_scaling(w, r->Y, r->K, r->best_d, &have);
    if (w->st != SS_OK) return lapack_failed(w, err);
  }
  int have_ell = 0;
  if ((o->norm == SS_JSR_NORM_ELLIPSOID || (r->auto_ && w->n <= ELL_AUTO_MAX_N)) &&
      r->upper > w->lower * (1 + o->gap)) {
    ss_status st = SS_OK;
    have_ell = ss_jsr_ws_ellipsoid(w, r->Y, o->fit_words,
                                   r->deadline > 0 ? r->t0 + o->max_seconds / 4 : 0, &st);
    if (st == SS_ENOMEM) return ss_error_nomem(err, "jsr ellipsoidal norm");
    if (!have_ell && o->norm == SS_JSR_NORM_ELLIPSOID)
      return ss_error_set(err, SS_ENUMERIC,
                          "jsr: the ellipsoidal norm could not be fitted or its "
                          "similarity not enclosed (ill-conditioned)");
  }
  r->use[C_INF] = o->norm == SS_JSR_NORM_INF || r->auto_;
  r->use[C_WINF] = have;
  r->use[C_2] = o->norm == SS_JSR_NORM_2 || r->auto_;
  r->use[C_ELL] = have_ell;
  r->ncand = 0, r->active = C_INF;
  for (int c = NCAND - 1; c >= 0; c--)
    if (r->use[c]) r->ncand++, r->active = c;
  ss_jsr_ws_select(w, r->Y, r->active, r->best_d);
  r->max_nodes = o->max_nodes ? r->brute_nodes + o->max_nodes : 0;
  return SS_OK;
}

/* What one pass of the branch and bound came to (bnb_step). */
enum { PASS_DONE, PASS_LAST, PASS_NONE, PASS_FAILED };

/* One pass of the branch and bound at depth L, *u its bound.  The first pass,
 * with more than one candidate, runs each and keeps the one with the lowest
 * bound active (every candidate's bound is valid).  PASS_DONE: *u is a bound;
 * PASS_LAST: *u is a bound but a limit stopped the candidates, go no deeper;
 * PASS_NONE: a limit stopped the pass, no bound; PASS_FAILED: LAPACK failed
 * (w->st). */
static int bnb_step(jsr_run *r, int L, double *u) {
  ss_jsr_ws *w = &r->w;
  const ss_jsr_opts *o = r->o;
  if (!(L == r->K && r->ncand > 1)) {
    if (!ss_jsr_bnb_pass(w, L, cand_norm[r->active], o->gap, r->max_nodes, r->deadline,
                         u))
      return PASS_NONE;
    return w->st != SS_OK ? PASS_FAILED : PASS_DONE;
  }
  int best = -1, stop = 0;
  *u = INFINITY;
  /* the ellipsoid first: usually the best, and a limit that stops the
   * pass early should not cut it off */
  static const int order[NCAND] = {C_ELL, C_WINF, C_INF, C_2};
  for (int oc = 0; oc < NCAND && !stop; oc++) {
    const int c = order[oc];
    if (!r->use[c]) continue;
    double uc;
    ss_jsr_ws_select(w, r->Y, c, r->best_d);
    if (!ss_jsr_bnb_pass(w, L, cand_norm[c], o->gap, r->max_nodes, r->deadline, &uc)) {
      stop = 1;
      break;
    }
    if (w->st != SS_OK) return PASS_FAILED;
    if (uc < *u) *u = uc, best = c;
  }
  if (best < 0) return PASS_NONE;
  r->active = best;
  ss_jsr_ws_select(w, r->Y, r->active, r->best_d);
  if (w->st != SS_OK) return PASS_FAILED;
  return stop ? PASS_LAST : PASS_DONE;
}

/* The invariant polytope first if o->norm asks for it, then the branch and
 * bound by iterative deepening: each pass's leaves give a valid bound, deeper
 * passes refine it; recomputing the shallow levels costs a factor of about
 * m / (m - 1) at most.  AUTO does not try the invariant polytope: on the
 * cases it exists for (tet/oct face and edges) the polytope does not close
 * within thousands of vertices (docs/methods.md, "Joint spectral radius"), so its time
 * would be taken from the branch and bound; --norm polytope asks for it. */
static ss_status bound_stage(jsr_run *r, ss_jsr_result *out, ss_error *err) {
  ss_jsr_ws *w = &r->w;
  const ss_jsr_opts *o = r->o;
  if (o->norm == SS_JSR_NORM_POLYTOPE && r->upper > w->lower * (1 + o->gap)) {
    const double now = ss_clock_wall();
    const double dl = r->deadline;
    const ss_status st =
        try_polytope(w, r->Y, o->gap, dl > 0 ? now + (dl - now) / 2 : 0, out, err);
    if (st != SS_OK) return st;
    if (out->poly_upper < r->upper) r->upper = out->poly_upper;
  }
  for (int L = r->K; r->upper > w->lower * (1 + o->gap); L++) {
    if (o->max_depth && L > o->max_depth) break;
    if (!ss_jsr_ws_reserve(w, L))
      return ss_error_nomem(err, "jsr branch and bound stack");
    ss_progress_step(&o->progress, "branch and bound, word length", (size_t)L, 0);
    double u;
    const int pass = bnb_step(r, L, &u);
    if (pass == PASS_FAILED) return lapack_failed(w, err);
    if (pass == PASS_NONE) break;
    out->bnb_depth = L;
    if (u < r->upper) r->upper = u;
    if (pass == PASS_LAST) break;
  }
  out->weighted = r->active == C_WINF;
  out->norm = r->upper >= out->poly_upper ? SS_JSR_NORM_POLYTOPE
              : r->active == C_ELL        ? SS_JSR_NORM_ELLIPSOID
                                          : cand_norm[r->active];
  if (w->st != SS_OK) return lapack_failed(w, err);
  out->nodes = w->nodes - r->brute_nodes;
  return SS_OK;
}

/* The result completed: the lower bound's word, its certified value where
 * the ball-arithmetic enclosure succeeds (else the floating-point one), the
 * bounds scaled back by 2^-ex, the flags and the time taken. */
static ss_status finish(jsr_run *r, ss_jsr_result *out, ss_error *err) {
  const ss_jsr_ws *w = &r->w;
  const int ex = r->ex;
  out->lower_word = malloc((size_t)(w->lower_len > 0 ? w->lower_len : 1) * sizeof(int));
  if (!out->lower_word) return ss_error_nomem(err, "jsr lower word");
  out->lower_len = w->lower_len;
  memcpy(out->lower_word, w->lower_word, (size_t)w->lower_len * sizeof(int));
  double lower_cert = 0;
  int lower_rigorous = 0;
  if (w->lower_len == 0)
    lower_rigorous = 1; /* no product has a nonzero spectral radius: 0 */
  else
    lower_rigorous =
        ss_jsr_cert_lower(w->n, r->Y, w->lower_word, w->lower_len, &lower_cert);
  /* the bounds are of the scaled inputs; scaling back by 2^-ex is exact
   * unless the result is subnormal, where one rounding is undone by a step
   * outwards */
  out->lower = ldexp(lower_rigorous ? lower_cert : w->lower, -ex);
  out->upper = ldexp(r->upper, -ex);
  out->poly_upper = ldexp(out->poly_upper, -ex);
  if (out->poly_upper > 0 && out->poly_upper < DBL_MIN)
    out->poly_upper = nextafter(out->poly_upper, INFINITY);
  if (out->lower > 0 && out->lower < DBL_MIN) out->lower = nextafter(out->lower, 0.0);
  if (out->upper > 0 && out->upper < DBL_MIN)
    out->upper = nextafter(out->upper, INFINITY);
  for (int k = 0; k < out->depth; k++) {
    out->rho_inf[k] = ldexp(out->rho_inf[k], -ex);
    out->rho_2[k] = ldexp(out->rho_2[k], -ex);
  }
  /* every upper bound above is rigorous (rounding carried in both norms) */
  out->certified = lower_rigorous;
  out->converged = out->upper <= out->lower * (1 + r->o->gap);
  out->seconds = ss_clock_wall() - r->t0;
  return SS_OK;
}

ss_status ss_jsr_compute(size_t m, size_t n, const double *const *Y, const ss_jsr_opts *o,
                         ss_jsr_result *out, ss_error *err) {
  const double t0 = ss_clock_wall();
  ss_jsr_opts d = ss_jsr_defaults();
  if (!o) o = &d;
  if (!out) return ss_error_set(err, SS_EINPUT, "jsr: no result given");
  memset(out, 0, sizeof *out);
  out->polytope = -1;
  out->poly_upper = INFINITY;
  ss_status st = validate(m, n, Y, o, err);
  if (st != SS_OK) return st;

  jsr_run r;
  memset(&r, 0, sizeof r);
  r.o = o, r.K = o->depth, r.t0 = t0, r.Y = Y;
  r.deadline = o->max_seconds > 0 ? t0 + o->max_seconds : 0;
  r.auto_ = o->norm == SS_JSR_NORM_AUTO || o->norm == SS_JSR_NORM_POLYTOPE;
  st = run_alloc(&r, m, n, out, err);
  if (st == SS_OK) st = scale_inputs(&r, err);
  if (st == SS_OK) {
    r.w.Y = r.Y;
    ss_jsr_ws_scale(&r.w, r.Y, NULL);
    st = brute_stage(&r, out, err);
  }
  if (st == SS_OK) {
    ss_progress_step(&o->progress, "fitting the norms", 0, 0);
    st = norms_stage(&r, err);
  }
  if (st == SS_OK) st = bound_stage(&r, out, err);
  if (st == SS_OK) st = finish(&r, out, err);
  ss_jsr_ws_free(&r.w);
  free(r.rho_cert);
  free(r.best_d);
  free(r.ybuf);
  free(r.yn);
  if (st != SS_OK) ss_jsr_result_clear(out);
  return st;
}
