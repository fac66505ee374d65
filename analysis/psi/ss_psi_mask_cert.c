/* ss_psi_mask_cert.c — the tangent masks' witnesses proven: exact masks
 * over Q, interval nets, an enclosure of det Dψ (ss_psi_mask.h, "Proof"). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <arb.h>
#include <flint/fmpq.h>
#include <flint/fmpq_mat.h>
#include <flint/fmpz_mat.h>

#include "double_interval.h"
#include "ss_charmap.h"
#include "ss_exact.h"
#include "ss_psi.h"
#include "ss_psi_mask_impl.h"

/* A exactly (each weight the rational it stands for) into Aq; 0, or -1 when a
 * weight is not such a rational. */
static int exact_matrix(const ss_psi_mask_nbhd *nb, long maxden, fmpq_mat_t Aq) {
  for (size_t i = 0; i < nb->n; i++)
    for (size_t j = 0; j < nb->n; j++) {
      long long p = 0, q = 1;
      const double a = nb->A[i * nb->n + j];
      if (a != 0.0 && !ss_exact_rational(a, maxden, &p, &q)) return -1;
      fmpq_set_si(fmpq_mat_entry(Aq, (slong)i, (slong)j), (slong)p, (ulong)q);
    }
  return 0;
}

/* Whether A's eigenvalue condition is proven (ss_exact: 1 simple, then
 * dim eigenvalues real, non-defective and separated from the rest) with
 * 1/2 the second distinct root, of multiplicity dim: with A X = X / 2
 * (checked exactly by the caller) this makes 1/2 the subdominant
 * eigenvalue, semisimple, its eigenspace spanned by X. */
static int spectrum_proven(const ss_psi_mask_nbhd *nb, int dim, long maxden) {
  ss_exact_opts o = ss_exact_defaults(dim);
  o.maxden = maxden;
  ss_exact *x = NULL;
  ss_error err = {0};
  if (ss_exact_new(nb->A, nb->n, nb->n, &o, &x, &err)) return 0;
  ss_verdict v;
  int cert = 0;
  ss_exact_condition(x, &v, &cert);
  size_t nr = 0;
  const ss_exact_root *r = ss_exact_roots(x, &nr);
  const int ok = v.verdict == SS_PASS && cert && nr >= 2 && r[1].degree == 1 &&
                 r[1].mult == dim && fabs(r[1].re - 0.5) <= r[1].rad && r[1].real;
  ss_exact_free(x);
  return ok;
}

/* The exact masks L (dim x n, L (A - I/2) = 0, L X = I) enclosed in lo, hi
 * (dim x n, row-major): 0, 1 not proven (A not rational, A X != X / 2, the
 * left nullspace of A - I/2 not of dimension dim, N^T X singular, or the
 * spectrum not proven), -1 out of memory. */
static int exact_masks(const ss_psi_mask_nbhd *nb, int dim, long maxden, double *lo,
                       double *hi) {
  const slong n = (slong)nb->n;
  int rc = 1;
  fmpq_mat_t Aq, X, T, K, C, L;
  fmpz_mat_t Kz, N;
  fmpz_t den, one;
  fmpz_init_set_ui(one, 1);
  fmpq_mat_init(Aq, n, n);
  fmpq_mat_init(X, n, dim);
  fmpq_mat_init(T, n, dim);
  fmpq_mat_init(K, n, n);
  fmpq_mat_init(C, dim, dim);
  fmpq_mat_init(L, dim, n);
  fmpz_mat_init(Kz, n, n);
  fmpz_mat_init(N, n, n);
  fmpz_init(den);
  if (exact_matrix(nb, maxden, Aq)) goto done;
  for (slong i = 0; i < n; i++)
    for (int d = 0; d < dim; d++)
      fmpq_set_si(fmpq_mat_entry(X, i, d), nb->o[i][d], 1);
  fmpq_mat_mul(T, Aq, X); /* 2 A X = X */
  fmpz_add_ui(den, one, 1);
  fmpq_mat_scalar_mul_fmpz(T, T, den);
  if (!fmpq_mat_equal(T, X)) goto done;
  /* the left nullspace of A - I/2: the nullspace of its transpose, scaled
   * to integers */
  for (slong i = 0; i < n; i++)
    for (slong j = 0; j < n; j++) {
      fmpq_set(fmpq_mat_entry(K, j, i), fmpq_mat_entry(Aq, i, j));
    }
  for (slong i = 0; i < n; i++) {
    fmpq_t h;
    fmpq_init(h);
    fmpq_set_si(h, 1, 2);
    fmpq_sub(fmpq_mat_entry(K, i, i), fmpq_mat_entry(K, i, i), h);
    fmpq_clear(h);
  }
  fmpq_mat_get_fmpz_mat_matwise(Kz, den, K);
  if (fmpz_mat_nullspace(N, Kz) != dim) goto done;
  /* C = (N^T X)^-1 over the nullspace's first dim columns, L = C N^T */
  fmpq_mat_t NtX, Nt;
  fmpq_mat_init(NtX, dim, dim);
  fmpq_mat_init(Nt, dim, n);
  for (int a = 0; a < dim; a++)
    for (slong i = 0; i < n; i++)
      fmpq_set_fmpz_frac(fmpq_mat_entry(Nt, a, i), fmpz_mat_entry(N, i, a), one);
  fmpq_mat_mul(NtX, Nt, X);
  if (fmpq_mat_inv(C, NtX)) {
    fmpq_mat_mul(L, C, Nt);
    rc = spectrum_proven(nb, dim, maxden) ? 0 : 1;
  }
  if (!rc) {
    arb_t v;
    arf_t b;
    arb_init(v);
    arf_init(b);
    for (int a = 0; a < dim; a++)
      for (slong i = 0; i < n; i++) {
        arb_set_fmpq(v, fmpq_mat_entry(L, a, i), 128);
        arb_get_lbound_arf(b, v, 128);
        lo[(size_t)a * (size_t)n + (size_t)i] = arf_get_d(b, ARF_RND_FLOOR);
        arb_get_ubound_arf(b, v, 128);
        hi[(size_t)a * (size_t)n + (size_t)i] = arf_get_d(b, ARF_RND_CEIL);
      }
    arb_clear(v);
    arf_clear(b);
  }
  fmpq_mat_clear(NtX);
  fmpq_mat_clear(Nt);
done:
  fmpq_mat_clear(Aq);
  fmpq_mat_clear(X);
  fmpq_mat_clear(T);
  fmpq_mat_clear(K);
  fmpq_mat_clear(C);
  fmpq_mat_clear(L);
  fmpz_mat_clear(Kz);
  fmpz_mat_clear(N);
  fmpz_clear(den);
  fmpz_clear(one);
  return rc;
}

/* det of the interval matrix D (rows), dim 2 or 3 */
static di_t idet(di_t D[3][3], int dim) {
  if (dim == 2)
    return di_fast_sub(di_fast_mul(D[0][0], D[1][1]), di_fast_mul(D[0][1], D[1][0]));
  di_t s = di_interval(0.0, 0.0);
  for (int c = 0; c < 3; c++) {
    const int c1 = (c + 1) % 3, c2 = (c + 2) % 3;
    const di_t minor =
        di_fast_sub(di_fast_mul(D[1][c1], D[2][c2]), di_fast_mul(D[1][c2], D[2][c1]));
    s = di_fast_add(s, di_fast_mul(D[0][c], minor));
  }
  return s;
}

/* The interval net of ring level r, pushed from the enclosure through levels
 * 0..r, into *lo, *hi (allocated): 0; 1 for a weight that is not a rational
 * of bounded denominator, -1 out of memory (both NULL then). */
static int inets(const ss_local *M, const ss_psi_enclosure *e, int r, int dim,
                 double **lo, double **hi) {
  const double *plo = e->lo, *phi = e->hi;
  double *cl = NULL, *ch = NULL;
  int rc = 0;
  for (int l = 0; l <= r && !rc; l++) {
    const size_t nv = M->ring[l].nv;
    double *nl = malloc((nv * (size_t)dim + 1) * sizeof *nl);
    double *nh = malloc((nv * (size_t)dim + 1) * sizeof *nh);
    if (!nl || !nh)
      rc = -1;
    else if (ss_charmap_push_interval(M->ring + l, plo, phi, dim, e->maxden, nl, nh))
      rc = 1;
    free(cl);
    free(ch);
    cl = nl;
    ch = nh;
    plo = cl;
    phi = ch;
  }
  if (rc) {
    free(cl);
    free(ch);
    cl = ch = NULL;
  }
  *lo = cl;
  *hi = ch;
  return rc;
}

/* Witness w's det Dψ enclosed into w->lo, w->hi: 0 (enclosed), 1 not
 * proven (no exact masks, a weight without enclosure), -1 out of memory. */
static int enclose(const ss_psi_mask_ctx *t, const ss_psi_enclosure *e,
                   ss_psi_mask_point *w) {
  const int dim = t->dim, r = w->level;
  ss_psi_mask_cpt q;
  for (int d = 0; d < 3; d++) {
    q.cone[d] = w->cone[d];
    q.v[d] = d < dim ? (int)lround(ldexp(w->x[d], r + 1)) : 0;
  }
  ss_psi_mask_nbhd nb;
  size_t *idx = NULL;
  int rc = ss_psi_mask_closure(t, r, &q, &nb, &idx);
  if (rc) return rc;
  double *llo = malloc((nb.n * (size_t)dim + 1) * sizeof *llo);
  double *lhi = malloc((nb.n * (size_t)dim + 1) * sizeof *lhi);
  double *plo = NULL, *phi = NULL;
  rc = !llo || !lhi ? -1 : exact_masks(&nb, dim, e->maxden, llo, lhi);
  if (!rc) rc = inets(t->M, e, r, dim, &plo, &phi);
  if (!rc) {
    di_t D[3][3];
    const double scale = ldexp(1.0, r + 1);
    for (int a = 0; a < dim; a++)
      for (int c = 0; c < dim; c++) {
        di_t s = di_interval(0.0, 0.0);
        for (size_t i = 0; i < nb.n; i++) {
          const size_t k = idx[i] * (size_t)dim + (size_t)c;
          s = di_fast_add(s, di_fast_mul(di_interval(llo[(size_t)a * nb.n + i],
                                                     lhi[(size_t)a * nb.n + i]),
                                         di_interval(plo[k], phi[k])));
        }
        D[a][c] = di_fast_mul_d(s, scale); /* a power of 2: exact */
      }
    di_t det = idet(D, dim);
    if (ss_psi_mask_orient_of(t, q.cone) < 0) det = di_neg(det);
    w->lo = det.a;
    w->hi = det.b;
  }
  free(llo);
  free(lhi);
  free(plo);
  free(phi);
  free(idx);
  ss_psi_mask_nbhd_free(&nb);
  return rc;
}

ss_status ss_psi_mask_certify(const ss_local *M, const ss_psi_enclosure *e,
                              ss_psi_mask_result *out, ss_error *err) {
  if (!e || !e->lo || !e->hi || !M)
    return ss_error_set(err, SS_EINPUT, "psi masks: no enclosure");
  const size_t n = M->n2 * (size_t)M->dim;
  for (size_t i = 0; i < n; i++)
    if (!(e->lo[i] <= e->hi[i]) || !isfinite(e->lo[i]) || !isfinite(e->hi[i]))
      return ss_error_set(err, SS_EINPUT,
                          "psi masks: point %zu's enclosure [%g, %g] is not an interval "
                          "of finite bounds",
                          i / (size_t)M->dim + 1, e->lo[i], e->hi[i]);
  double *mid = malloc((n + 1) * sizeof *mid);
  if (!mid) return ss_error_nomem(err, "psi masks");
  for (size_t i = 0; i < n; i++)
    mid[i] = 0.5 * (e->lo[i] + e->hi[i]);
  ss_status st = ss_psi_mask_judge(M, mid, M->n2, out, err);
  out->enclosed = 1;
  if (st || out->wpos.level < 0 || out->wneg.level < 0) {
    free(mid);
    return st;
  }
  ss_psi_mask_ctx t = {0};
  t.M = M;
  t.dim = M->dim;
  int rc = ss_psi_mask_ctx_build(&t, mid);
  int p1 = 1, p2 = 1;
  if (!rc) p1 = enclose(&t, e, &out->wpos);
  if (!rc && p1 >= 0) p2 = enclose(&t, e, &out->wneg);
  ss_psi_mask_ctx_free(&t);
  free(mid);
  if (rc < 0 || p1 < 0 || p2 < 0) return ss_error_nomem(err, "psi masks");
  if (rc > 0)
    return ss_error_set(
        err, SS_EINTERNAL,
        "psi masks: two ring cells of one cone disagree on its orientation");
  out->proven = !p1 && !p2 && out->wpos.lo > 0.0 && out->wneg.hi < 0.0;
  return SS_OK;
}
