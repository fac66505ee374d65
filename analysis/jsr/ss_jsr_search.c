/* ss_jsr_search.c — the JSR's walks over words: the brute force to a fixed
 * length (one length at a time, within a deadline), the branch and bound pass (Gripenberg
 * 1996), the lower bound from the spectral radii of Lyndon words, and the choice of the
 * norm the branch and bound runs in: the diagonal weighting from Perron vectors, the
 * ellipsoidal copies (ss_jsr_ws.h). */
#include <lapacke.h>
#include <stdlib.h>
#include <string.h>

#include "ss_clock.h"
#include "ss_jsr_ellipsoid.h"
#include "ss_jsr_ws.h"

/* Step the depth-first walk to the next sibling at level *k, backtracking
 * to lower levels when a level's m letters are used up; 0 when the walk is
 * over.  A caller descends by `w->word[++k] = -1`. */
static int ws_next(ss_jsr_ws *w, int *k) {
  while (*k >= 0 && ++w->word[*k] >= (int)w->m)
    (*k)--;
  return *k >= 0;
}

/* 1 if the word w[0..len-1] is a Lyndon word (strictly smaller than all its
 * proper rotations; Duval's test).  Every word is a rotation of a power of a
 * Lyndon word, and rho(Y_w)^{1/|w|} is the same for rotations and powers,
 * so the lower bound needs the eigenvalues of Lyndon words only: about
 * 1/len of all words. */
static int is_lyndon(const int *w, int len) {
  int i = 0, j = 1;
  while (j < len && w[i] <= w[j]) {
    i = w[i] < w[j] ? 0 : i + 1;
    j++;
  }
  return i == 0 && j == len;
}

/* 1 if the word a (length la) comes before b (length lb) in the depth-first
 * order of the walks: lexicographic, a prefix before its extensions. */
static int word_before(const int *a, int la, const int *b, int lb) {
  for (int j = 0; j < la && j < lb; j++)
    if (a[j] != b[j]) return a[j] < b[j];
  return la < lb;
}

/* Offer the word at levels 0..k to the lower bound.  rho(P) <= ||P||_inf, so
 * the eigenvalue computation is skipped when the norm cannot beat the bound,
 * and for words that are not Lyndon words (is_lyndon).  With ties, a word
 * whose value equals the bound (often: products with the same spectral
 * radius up to rounding) replaces the bound's word if it comes first in the
 * depth-first order (word_before): the brute force, which walks the lengths
 * one at a time, then keeps the word a single depth-first walk would keep
 * (the weighting and so the branch and bound depend on it). */
static void ws_offer_lower(ss_jsr_ws *w, int k, int ties) {
  const double lim = pow(w->lower, (double)(k + 1));
  if (fmin(w->nhat_inf[k], w->cap2[k]) * (1 + 1e-12) <= lim || !isfinite(w->nhat_inf[k]))
    return;
  if (!is_lyndon(w->word, k + 1)) return;
  const double r = ss_jsr_ws_specrad(w, k);
  if (r <= lim && !ties) return;
  const double v = pow(r, 1.0 / (k + 1));
  if (v > w->lower || (ties && v == w->lower &&
                       word_before(w->word, k + 1, w->lower_word, w->lower_len))) {
    w->lower = v;
    w->lower_len = k + 1;
    memcpy(w->lower_word, w->word, (size_t)(k + 1) * sizeof *w->word);
  }
}

/* The words of length t + 1 (level t), each formed from its prefix (the
 * prefixes' products re-formed, not judged): their largest norms into
 * rho_inf[t], rho_2[t], rho_cert[t] (not yet rooted), and the lower bound.
 * With t > 0 and deadline > 0 the wall clock is read before every product;
 * returns 1 if the length is complete, 0 if the deadline stopped it (then
 * *words of its words were judged). */
static int brute_length(ss_jsr_ws *w, int t, double deadline, double *rho_inf,
                        double *rho_2, double *rho_cert, size_t *words) {
  const double p = 1.0 / (t + 1);
  int k = 0;
  *words = 0;
  w->word[0] = -1;
  while (ws_next(w, &k)) {
    if (t > 0 && deadline > 0 && ss_clock_wall() > deadline) return 0;
    ss_jsr_ws_push(w, k, (size_t)w->word[k]);
    if (k < t) {
      w->word[++k] = -1;
      continue;
    }
    ++*words;
    rho_inf[t] = fmax(rho_inf[t], pow(w->nhat_inf[k], p));
    rho_cert[t] = fmax(rho_cert[t], ss_jsr_ws_norm_inf_up(w, k));
    /* ||P||_2 <= min(sqrt(||P||_1 ||P||_inf), ||P||_F) skips the SVD when
     * it cannot raise the maximum */
    if (w->cap2[k] * (1 + 1e-12) > pow(rho_2[t], (double)(k + 1)))
      rho_2[t] = fmax(rho_2[t], pow(ss_jsr_ws_norm_2(w, k), p));
    ws_offer_lower(w, k, 1);
  }
  return 1;
}

/* Brute force over the words of length 1..K, one length at a time (so that
 * a time limit leaves complete lengths): rho_inf, rho_2 (floating point), the
 * rigorous inf-norm profile rho_cert, and the lower bound.  Returns the
 * number of complete lengths; *cut_words: words of the next length judged
 * before the deadline (0 if all K are complete). */
int ss_jsr_brute_force(ss_jsr_ws *w, int K, double deadline, double *rho_inf,
                       double *rho_2, double *rho_cert, size_t *cut_words) {
  for (int k = 0; k < K; k++)
    rho_inf[k] = rho_2[k] = rho_cert[k] = 0;
  *cut_words = 0;
  int done = 0;
  while (done < K &&
         brute_length(w, done, deadline, rho_inf, rho_2, rho_cert, cut_words)) {
    rho_cert[done] = ss_jsr_root_up(rho_cert[done], done + 1);
    *cut_words = 0;
    done++;
  }
  return done;
}

/* min over k <= s of the rigorous max_{|w| = k} ||Y_w||_inf^{1/k} for the
 * current (scaled) matrices: an upper bound on rho(Y), used to rank the
 * scalings. */
static double scaling_score(ss_jsr_ws *w, int s) {
  double best = INFINITY, mx[64] = {0};
  int k = 0;
  w->word[0] = -1;
  while (ws_next(w, &k)) {
    ss_jsr_ws_push(w, k, (size_t)w->word[k]);
    mx[k] = fmax(mx[k], ss_jsr_ws_norm_inf_up(w, k));
    if (k + 1 < s) w->word[++k] = -1;
  }
  for (k = 0; k < s; k++)
    best = fmin(best, ss_jsr_root_up(mx[k], k + 1));
  return best;
}

/* d = |v| for v the eigenvector of the largest eigenvalue (in modulus) of the
 * product of the lower bound's word rotated to start at letter r, floored at
 * 1e-6 of its maximum; the inputs must be active (ss_jsr_ws_scale(w, Y, NULL)).
 * Returns 0 if LAPACK fails.  The eigenvectors of P^T that dgeev returns as
 * left vectors for the row-major buffer are conjugates of P's right ones. */
static int perron_vector(ss_jsr_ws *w, int r, double *d) {
  const int len = w->lower_len;
  const size_t n = w->n, nn = n * n;
  int *rot = w->word + len; /* scratch: the stack has room for 2 len */
  for (int k = 0; k < len; k++)
    rot[k] = w->lower_word[(r + k) % len];
  for (int k = 0; k < len; k++)
    ss_jsr_ws_push(w, k, (size_t)rot[k]);
  memcpy(w->a, w->prod + (size_t)(len - 1) * nn, nn * sizeof *w->a);
  if (LAPACKE_dgeev(LAPACK_COL_MAJOR, 'V', 'N', (lapack_int)n, w->a, (lapack_int)n, w->wr,
                    w->wi, w->vl, (lapack_int)n, NULL, 1) != 0)
    return 0;
  size_t j = 0;
  for (size_t t = 1; t < n; t++)
    if (hypot(w->wr[t], w->wi[t]) > hypot(w->wr[j], w->wi[j])) j = t;
  if (w->wi[j] < 0) j--; /* the pair's second: its vector is re - i im */
  double mx = 0;
  for (size_t t = 0; t < n; t++) {
    const double re = w->vl[j * n + t], im = w->wi[j] != 0 ? w->vl[(j + 1) * n + t] : 0;
    d[t] = hypot(re, im);
    mx = fmax(mx, d[t]);
  }
  if (!(mx > 0) || !isfinite(mx)) return 0;
  for (size_t t = 0; t < n; t++)
    d[t] = fmax(d[t] / mx, 1e-6);
  return 1;
}

/* Choose the diagonal scaling of the inf-norm for the branch and bound: the
 * identity, or |eigenvector| of the products of the lower bound's word and
 * its rotations (for a nonnegative product P with Perron vector v,
 * ||D^{-1} P D||_inf = rho(P) with D = diag(v)), or their sum; the one with
 * the smallest scaling_score wins and stays active (ss_jsr_ws_scale).  Any choice
 * is an exact similarity, so every choice gives valid bounds. */
void ss_jsr_choose_scaling(ss_jsr_ws *w, const double *const *Y, int K, double *best_d,
                           int *have) {
  int s = 1;
  double cnt = (double)w->m;
  while (s < K && s < 3 && cnt * (double)w->m <= 4096)
    s++, cnt *= (double)w->m;
  ss_jsr_ws_scale(w, Y, NULL);
  double best = scaling_score(w, s);
  *have = 0;
  const int len = w->lower_len, nrot = len < 8 ? len : 8;
  double *sum = w->d + w->n;
  for (size_t t = 0; t < w->n; t++)
    sum[t] = 0;
  for (int r = 0; r <= nrot && len > 0; r++) {
    ss_jsr_ws_scale(w, Y, NULL);
    if (r < nrot) {
      if (!perron_vector(w, r, w->d)) continue;
      for (size_t t = 0; t < w->n; t++)
        sum[t] += w->d[t];
    } else {
      memcpy(w->d, sum, w->n * sizeof *w->d);
    }
    ss_jsr_ws_scale(w, Y, w->d);
    const double sc = scaling_score(w, s);
    if (sc < best) {
      best = sc;
      memcpy(best_d, w->d, w->n * sizeof *best_d);
      *have = 1;
    }
  }
  ss_jsr_ws_scale(w, Y, *have ? best_d : NULL);
}

/* Make candidate c of the branch and bound active (ss_jsr_compute: 0 the
 * inputs, 1 the weighted copies, 2 the inputs for the 2-norm, 3 the
 * ellipsoidal copies). */
void ss_jsr_ws_select(ss_jsr_ws *w, const double *const *Y, int c, const double *best_d) {
  if (c == 3)
    ss_jsr_ws_scale(w, (const double *const *)w->eptr, NULL);
  else
    ss_jsr_ws_scale(w, Y, c == 1 ? best_d : NULL);
}

/* Fit the ellipsoidal norm to the inputs Y and enclose the similar copies
 * into w->ebuf (ss_jsr_ellipsoid.h).  Returns 1 if they are ready; 0 if the
 * fit or the enclosure failed (*st = SS_ENOMEM if memory ran out). */
int ss_jsr_ws_ellipsoid(ss_jsr_ws *w, const double *const *Y, int words, double deadline,
                        ss_status *st) {
  const size_t m = w->m, n = w->n;
  double *L = malloc(n * n * sizeof *L);
  w->ebuf = malloc(m * n * n * sizeof *w->ebuf);
  w->eptr = malloc(m * sizeof *w->eptr);
  w->edelta = malloc(m * sizeof *w->edelta);
  int ok = 0;
  *st = SS_OK;
  if (!L || !w->ebuf || !w->eptr || !w->edelta) {
    *st = SS_ENOMEM;
    goto done;
  }
  *st = ss_jsr_ellipsoid_fit_words(m, n, Y, words, deadline, L);
  if (*st != SS_OK) goto done;
  ok = ss_jsr_ellipsoid_similar(m, n, Y, L, w->ebuf, w->edelta, &w->ecw);
  for (size_t i = 0; i < m; i++)
    w->eptr[i] = w->ebuf + i * n * n;
done:
  free(L);
  if (!ok) { /* not usable: ss_jsr_ws_scale must not take it for the copies */
    free(w->eptr);
    w->eptr = NULL;
  }
  return ok;
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
int ss_jsr_bnb_pass(ss_jsr_ws *w, int L, ss_jsr_norm norm, double gap, size_t max_nodes,
                    double deadline, double *upper) {
  double mx = 0;
  int k = 0;
  w->word[0] = -1;
  while (ws_next(w, &k)) {
    if ((max_nodes && w->nodes >= max_nodes) ||
        (deadline > 0 && ss_clock_wall() > deadline))
      return 0;
    ss_jsr_ws_push(w, k, (size_t)w->word[k]);
    ws_offer_lower(w, k, 0);
    double b;
    if (norm == SS_JSR_NORM_INF) {
      b = ss_jsr_root_up(ss_jsr_ws_norm_inf_up(w, k), k + 1);
      if (k > 0) b = fmin(b, w->bnd[k - 1]);
    } else {
      /* the certified 2-norm costs an SVD with vectors and three products:
       * formed only where the floating-point value would lower the bound */
      b = k > 0 ? w->bnd[k - 1] : (double)INFINITY;
      if (pow(ss_jsr_ws_norm_2(w, k), 1.0 / (k + 1)) * (1 - 1e-12) < b)
        b = fmin(b, ss_jsr_root_up(ss_jsr_ws_norm_2_up(w, k), k + 1));
    }
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
