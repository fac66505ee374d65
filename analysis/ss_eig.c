/* ss_eig.c — eigenvalues by blocks (one-ring block, strongly connected outer
 * blocks), multiplicities, the eigenvalue condition and the subdominant basis.
 * Method: ss_eig.h. */
#include "ss_eig.h"

#include <complex.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <lapacke.h>

ss_eig_opts ss_eig_defaults(int dim) {
  ss_eig_opts o = {1e-6, 1e-2, dim, 1};
  return o;
}

const char *ss_verdict_name(ss_verdict_kind v) {
  return v == SS_PASS ? "pass" : v == SS_FAIL ? "fail" : "undecided";
}

void ss_eig_free(ss_eig *e) {
  if (!e) return;
  free(e->val);
  free(e->basis);
  free(e);
}

/* The leading m x m block of the row-major n x n matrix S, column-major into
 * a (LAPACK's layout). */
static void colmajor(const double *S, size_t n, size_t m, double *a) {
  for (size_t i = 0; i < m; i++)
    for (size_t j = 0; j < m; j++)
      a[j * m + i] = S[i * n + j];
}

/* ---- strongly connected components of the outer block (Tarjan, iterative) ---- */

/* Components of the graph on nodes 0..nc-1 with an edge i -> j when
 * S[n1+i][n1+j] != 0 (row i reads column j).  comp[] receives the nodes
 * component by component, start[0..ncomp] the offsets.  Tarjan emits a
 * component after every component it reaches, so this is an order in which
 * block forward substitution works.  Returns the number of components, or -1
 * when out of memory. */
static long tarjan(const double *S, size_t n, size_t n1, size_t *comp, size_t *start) {
  const size_t nc = n - n1;
  size_t *index = malloc((nc + 1) * sizeof *index), *low = malloc((nc + 1) * sizeof *low),
         *stack = malloc((nc + 1) * sizeof *stack),
         *call = malloc((nc + 1) * sizeof *call), *next = malloc((nc + 1) * sizeof *next);
  unsigned char *on = calloc(nc + 1, 1);
  long ncomp = -1;
  if (!index || !low || !stack || !call || !next || !on) goto done;
  for (size_t i = 0; i < nc; i++)
    index[i] = SIZE_MAX;
  size_t counter = 0, sp = 0, emitted = 0;
  ncomp = 0;
  start[0] = 0;
  for (size_t root = 0; root < nc; root++) {
    if (index[root] != SIZE_MAX) continue;
    size_t depth = 0;
    call[depth++] = root;
    index[root] = low[root] = counter++;
    next[root] = 0;
    stack[sp++] = root;
    on[root] = 1;
    while (depth) {
      size_t v = call[depth - 1];
      const double *row = S + (n1 + v) * n + n1;
      int descended = 0;
      while (next[v] < nc) {
        size_t w = next[v]++;
        if (w == v || row[w] == 0.0) continue;
        if (index[w] == SIZE_MAX) {
          index[w] = low[w] = counter++;
          next[w] = 0;
          stack[sp++] = w;
          on[w] = 1;
          call[depth++] = w;
          descended = 1;
          break;
        }
        if (on[w] && index[w] < low[v]) low[v] = index[w];
      }
      if (descended) continue;
      if (low[v] == index[v]) {
        size_t w;
        do {
          w = stack[--sp];
          on[w] = 0;
          comp[emitted++] = w;
        } while (w != v);
        start[++ncomp] = emitted;
      }
      depth--;
      if (depth) {
        size_t u = call[depth - 1];
        if (low[v] < low[u]) low[u] = low[v];
      }
    }
  }
done:
  free(index);
  free(low);
  free(stack);
  free(call);
  free(next);
  free(on);
  return ncomp;
}

/* ---- dense eigenvalues of a block ---- */

/* Eigenvalues (and, if vr != NULL, right eigenvectors, column-major n x n) of
 * the m x m column-major matrix a (overwritten), with reciprocal condition
 * numbers in rc. */
static ss_status block_eig(double *a, size_t m, double *wr, double *wi, double *rc,
                           double *vr, ss_error *err) {
  const lapack_int n = (lapack_int)m;
  double *vl = malloc(m * m * sizeof *vl), *own = vr ? NULL : malloc(m * m * sizeof *own),
         *scale = malloc(m * sizeof *scale), *rcv = malloc(m * sizeof *rcv);
  ss_status st = SS_OK;
  if (!vl || (!vr && !own) || !scale || !rcv) {
    st = ss_error_nomem(err, "eigenvalues");
    goto done;
  }
  lapack_int ilo, ihi;
  double abnrm;
  lapack_int info =
      LAPACKE_dgeevx(LAPACK_COL_MAJOR, 'B', 'V', 'V', 'E', n, a, n, wr, wi, vl, n,
                     vr ? vr : own, n, &ilo, &ihi, scale, &abnrm, rc, rcv);
  if (info != 0)
    st = ss_error_set(err, SS_ENUMERIC,
                      "LAPACK dgeevx failed on a %zu x %zu block (info %d)", m, m,
                      (int)info);
done:
  free(vl);
  free(own);
  free(scale);
  free(rcv);
  return st;
}

ss_status ss_eig_dense(const double *S, size_t n, double *re, double *im, ss_error *err) {
  double *a = malloc((n * n + 1) * sizeof *a), *vr = malloc((n * n + 1) * sizeof *vr);
  if (!a || !vr) {
    free(a);
    free(vr);
    return ss_error_nomem(err, "eigenvalues");
  }
  colmajor(S, n, n, a);
  lapack_int info = LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'V', (lapack_int)n, a,
                                  (lapack_int)n, re, im, NULL, 1, vr, (lapack_int)n);
  free(a);
  free(vr);
  if (info != 0)
    return ss_error_set(err, SS_ENUMERIC, "LAPACK dgeev failed (info %d)", (int)info);
  return SS_OK;
}

/* ---- ordering and groups ---- */

static double modulus(const ss_eigval *v) {
  return hypot(v->re, v->im);
}

static int by_modulus(const void *pa, const void *pb) {
  const ss_eigval *a = pa, *b = pb;
  /* moduli equal to 12 digits are ties (a conjugate pair, +-x), settled below;
   * rounding to a grid keeps the comparison transitive */
  double ma = nearbyint(modulus(a) * 1e12), mb = nearbyint(modulus(b) * 1e12);
  if (ma != mb) return ma > mb ? -1 : 1;
  int ca = a->im != 0.0, cb = b->im != 0.0;
  if (ca != cb) return ca - cb;
  if (a->re != b->re) return a->re > b->re ? -1 : 1;
  if (a->im != b->im) return a->im > b->im ? -1 : 1;
  return 0;
}

static int close_to(const ss_eigval *a, const ss_eigval *b, double tol) {
  double d = hypot(a->re - b->re, a->im - b->im);
  return d <= tol * fmax(modulus(a), modulus(b));
}

/* Group equal eigenvalues (within tol, relative) and set their
 * multiplicities.  SS_ENOMEM. */
static ss_status make_groups(ss_eig *e, double tol, ss_error *err) {
  int ng = 0;
  size_t *rep = malloc((e->n + 1) * sizeof *rep); /* first member of a group */
  size_t *size = calloc(e->n + 1, sizeof *size);  /* members of a group */
  if (!rep || !size) {
    free(rep);
    free(size);
    return ss_error_nomem(err, "eigenvalue groups");
  }
  for (size_t i = 0; i < e->n; i++) {
    int g = -1;
    /* groups are contiguous in practice; look back over the recent ones */
    for (int k = ng - 1; k >= 0 && k >= ng - 8 && g < 0; k--)
      if (close_to(e->val + rep[k], e->val + i, tol)) g = k;
    if (g < 0) {
      g = ng++;
      rep[g] = i;
    }
    e->val[i].group = g;
    size[g]++;
  }
  for (size_t i = 0; i < e->n; i++)
    e->val[i].mult = (int)size[e->val[i].group];
  e->ngroups = ng;
  free(rep);
  free(size);
  return SS_OK;
}

/* ---- the eigenvalue condition ---- */

static void condition(ss_eig *e, int m, double tol) {
  ss_verdict *v = &e->cond;
  v->verdict = SS_PASS;
  v->reason[0] = '\0';
  if (e->n < (size_t)m + 2) {
    v->verdict = SS_UNDECIDED;
    snprintf(v->reason, sizeof v->reason, "only %zu eigenvalues", e->n);
    return;
  }
  const ss_eigval *l = e->val;
  if (!(fabs(l[0].re - 1.0) <= tol && l[0].im == 0.0)) {
    v->verdict = SS_FAIL;
    snprintf(v->reason, sizeof v->reason, "lambda0 = %.10g%+.3gi is not 1", l[0].re,
             l[0].im);
    return;
  }
  if (l[0].mult > 1) {
    v->verdict = SS_FAIL;
    snprintf(v->reason, sizeof v->reason, "eigenvalue 1 is not simple (multiplicity %d)",
             l[0].mult);
    return;
  }
  for (int i = 1; i <= m; i++) {
    if (fabs(l[i].im) > tol * modulus(l + i)) {
      v->verdict = SS_FAIL;
      snprintf(v->reason, sizeof v->reason, "lambda%d = %.10g%+.10gi is complex", i,
               l[i].re, l[i].im);
      return;
    }
    if (!(l[i].re > 0.0)) {
      v->verdict = SS_FAIL;
      snprintf(v->reason, sizeof v->reason, "lambda%d = %.10g is not positive", i,
               l[i].re);
      return;
    }
  }
  const double lm = l[m].re, next = modulus(l + m + 1);
  if (!(lm - next > tol * lm)) {
    v->verdict = SS_FAIL;
    snprintf(v->reason, sizeof v->reason,
             "lambda%d = %.10g is not larger than |lambda%d| = %.10g (relative tolerance "
             "%.1e)",
             m, lm, m + 1, next, tol);
  }
}

/* ---- the subdominant basis ---- */

/* Orthonormal basis (first m columns of q, n x n column-major) of the invariant
 * subspace of the n x n column-major a (overwritten by its Schur form T) for
 * the eigenvalues nearest to target[0..m).  Returns 0, or -1 on failure. */
static int schur_basis(double *a, size_t n, const ss_eigval *target, int m, double *q) {
  const lapack_int nn = (lapack_int)n;
  double *wr = malloc(n * sizeof *wr), *wi = malloc(n * sizeof *wi);
  lapack_logical *sel = calloc(n, sizeof *sel);
  int rc = -1;
  if (!wr || !wi || !sel) goto done;
  lapack_int sdim = 0;
  if (LAPACKE_dgees(LAPACK_COL_MAJOR, 'V', 'N', NULL, nn, a, nn, &sdim, wr, wi, q, nn))
    goto done;
  for (int k = 0; k < m; k++) {
    size_t best = SIZE_MAX;
    double bd = INFINITY;
    for (size_t i = 0; i < n; i++) {
      if (sel[i]) continue;
      double d = hypot(wr[i] - target[k].re, wi[i] - target[k].im);
      if (d < bd) bd = d, best = i;
    }
    if (best == SIZE_MAX) goto done;
    sel[best] = 1;
  }
  lapack_int mout = 0;
  double s = 0.0, sep = 0.0;
  if (LAPACKE_dtrsen(LAPACK_COL_MAJOR, 'B', 'V', sel, nn, a, nn, q, nn, wr, wi, &mout, &s,
                     &sep))
    goto done;
  rc = mout == m ? 0 : -1;
done:
  free(wr);
  free(wi);
  free(sel);
  return rc;
}

/* Solve (C - mu I) x = r for the outer block by forward substitution over the
 * components (comp/start from tarjan); x, r indexed by outer node.  Returns 0,
 * or -1 if a diagonal block is (numerically) singular.  Workspaces: work holds
 * (b+1)^2 doubles and piv b pivots, b the largest block. */
static int outer_solve(const double *S, size_t n, size_t n1, const size_t *comp,
                       const size_t *start, long ncomp, double mu, const double *r,
                       double *x, unsigned char *done_, double *work, lapack_int *piv) {
  const size_t nc = n - n1;
  memset(done_, 0, nc);
  for (long c = 0; c < ncomp; c++) {
    const size_t b = start[c], sz = start[c + 1] - b;
    for (size_t k = 0; k < sz; k++) {
      const size_t i = comp[b + k];
      const double *row = S + (n1 + i) * n + n1;
      double s = r[i];
      for (size_t j = 0; j < nc; j++)
        if (done_[j] && row[j] != 0.0) s -= row[j] * x[j];
      work[sz * sz + k] = s; /* rhs after the sub-matrix */
      for (size_t l = 0; l < sz; l++)
        work[l * sz + k] = row[comp[b + l]] - (comp[b + l] == i ? mu : 0.0);
    }
    double scale = 0.0;
    for (size_t k = 0; k < sz * sz; k++)
      scale = fmax(scale, fabs(work[k]));
    if (sz == 1) {
      if (!(fabs(work[0]) > 1e-12 * fmax(1.0, scale))) return -1;
      x[comp[b]] = work[1] / work[0];
    } else {
      lapack_int info =
          LAPACKE_dgesv(LAPACK_COL_MAJOR, (lapack_int)sz, 1, work, (lapack_int)sz, piv,
                        work + sz * sz, (lapack_int)sz);
      if (info != 0) return -1;
      for (size_t k = 0; k < sz; k++)
        x[comp[b + k]] = work[sz * sz + k];
    }
    for (size_t k = 0; k < sz; k++)
      done_[comp[b + k]] = 1;
  }
  return 0;
}

/* ---- the driver ---- */

ss_status ss_eig_new(const double *S, size_t n, size_t n1, const ss_eig_opts *opts,
                     ss_eig **out, ss_error *err) {
  *out = NULL;
  if (n1 == 0 || n1 > n)
    return ss_error_set(err, SS_EINPUT,
                        "one-ring block of %zu rows in a %zu x %zu matrix", n1, n, n);
  if (!(opts->tol > 0.0 && opts->tol < 0.1) || !(opts->cluster >= 0.0) ||
      (opts->dim != 2 && opts->dim != 3))
    return ss_error_set(err, SS_EINPUT,
                        "eigenvalue tolerance must be in (0, 0.1), not %g", opts->tol);
  for (size_t i = 0; i < n1; i++)
    for (size_t j = n1; j < n; j++)
      if (S[i * n + j] != 0.0)
        return ss_error_set(err, SS_EINPUT,
                            "the one-ring block is not invariant: S[%zu][%zu] = %g", i, j,
                            S[i * n + j]);
  ss_status st = SS_OK;
  const size_t nc = n - n1;
  ss_eig *e = calloc(1, sizeof *e);
  double *a = malloc((n1 * n1 + 1) * sizeof *a), *vr = malloc((n1 * n1 + 1) * sizeof *vr),
         *wr = malloc((n + 1) * sizeof *wr), *wi = malloc((n + 1) * sizeof *wi),
         *rc = malloc((n + 1) * sizeof *rc), *awr = malloc((n1 + 1) * sizeof *awr),
         *awi = malloc((n1 + 1) * sizeof *awi);
  size_t *comp = malloc((nc + 1) * sizeof *comp),
         *start = malloc((nc + 2) * sizeof *start);
  double *blk = NULL, *bw = NULL;
  lapack_int *piv = NULL;
  if (!e || !a || !vr || !wr || !wi || !rc || !awr || !awi || !comp || !start) {
    st = ss_error_nomem(err, "eigenvalues");
    goto done;
  }
  e->n = n;
  e->tol = opts->tol;
  e->m = opts->dim;
  e->basis_kind = "";
  e->val = calloc(n + 1, sizeof *e->val);
  if (!e->val) {
    st = ss_error_nomem(err, "eigenvalues");
    goto done;
  }
  /* the one-ring block */
  colmajor(S, n, n1, a);
  if ((st = block_eig(a, n1, wr, wi, rc, vr, err))) goto done;
  for (size_t i = 0; i < n1; i++) {
    e->val[i] = (ss_eigval){wr[i], wi[i], rc[i], 0, 0, 0};
    awr[i] = wr[i];
    awi[i] = wi[i];
  }
  /* the outer blocks */
  long ncomp = tarjan(S, n, n1, comp, start);
  if (ncomp < 0) {
    st = ss_error_nomem(err, "outer blocks");
    goto done;
  }
  e->nblocks = (size_t)ncomp;
  size_t k = n1, big = 0;
  for (long c = 0; c < ncomp; c++)
    big = start[c + 1] - start[c] > big ? start[c + 1] - start[c] : big;
  e->largest_block = big;
  blk = malloc((big * big + 1) * sizeof *blk);
  bw = malloc(((big + 1) * (big + 1) + nc + 1) * sizeof *bw);
  piv = malloc((big + 1) * sizeof *piv);
  if (!blk || !bw || !piv) {
    st = ss_error_nomem(err, "outer blocks");
    goto done;
  }
  for (long c = 0; c < ncomp; c++) {
    const size_t b = start[c], sz = start[c + 1] - b;
    if (sz == 1) {
      const size_t i = n1 + comp[b];
      e->val[k++] = (ss_eigval){S[i * n + i], 0.0, 1.0, (int)c + 1, 0, 0};
      continue;
    }
    for (size_t r = 0; r < sz; r++)
      for (size_t q = 0; q < sz; q++)
        blk[q * sz + r] = S[(n1 + comp[b + r]) * n + n1 + comp[b + q]];
    if ((st = block_eig(blk, sz, wr, wi, rc, NULL, err))) goto done;
    for (size_t r = 0; r < sz; r++)
      e->val[k++] = (ss_eigval){wr[r], wi[r], rc[r], (int)c + 1, 0, 0};
  }
  qsort(e->val, n, sizeof *e->val, by_modulus);
  if ((st = make_groups(e, opts->tol, err))) goto done;
  condition(e, e->m, opts->tol);

  /* the subdominant basis: only when the leading m are real and positive */
  if (!opts->basis || e->cond.verdict != SS_PASS) goto done;
  const int m = e->m;
  int outer = 0, clustered = 0;
  for (int i = 1; i <= m; i++) {
    outer |= e->val[i].block != 0;
    for (int j = i + 1; j <= m; j++)
      clustered |= fabs(e->val[i].re - e->val[j].re) <= opts->cluster * e->val[i].re;
  }
  e->basis = calloc(n * (size_t)m + 1, sizeof *e->basis);
  double *t = calloc((size_t)(m * m), sizeof *t);
  double *x1 = calloc(n1 * (size_t)m + 1, sizeof *x1);
  double *full = NULL, *q = NULL;
  if (!e->basis || !t || !x1) {
    free(t);
    free(x1);
    st = ss_error_nomem(err, "subdominant basis");
    goto done;
  }
  int ok = 0;
  if (!outer && !clustered) {
    /* right eigenvectors of A: the columns of the leading real eigenvalues */
    unsigned char *used = calloc(n1 + 1, 1);
    ok = used != NULL;
    for (int i = 1; ok && i <= m; i++) {
      size_t best = SIZE_MAX;
      double bd = INFINITY;
      for (size_t c = 0; c < n1; c++) {
        if (used[c] || awi[c] != 0.0) continue;
        double d = fabs(awr[c] - e->val[i].re);
        if (d < bd) bd = d, best = c;
      }
      if (best == SIZE_MAX) {
        ok = 0;
        break;
      }
      used[best] = 1;
      memcpy(x1 + (size_t)(i - 1) * n1, vr + best * n1, n1 * sizeof *x1);
      t[(i - 1) * m + (i - 1)] = e->val[i].re;
    }
    free(used);
    if (ok) e->basis_kind = "eigenvectors";
  } else if (!outer) {
    q = malloc((n1 * n1 + 1) * sizeof *q);
    if (q) colmajor(S, n, n1, a); /* dgeevx overwrote the first copy */
    ok = q && schur_basis(a, n1, e->val + 1, m, q) == 0;
    if (ok) {
      memcpy(x1, q, n1 * (size_t)m * sizeof *x1);
      for (int i = 0; i < m; i++)
        for (int j = 0; j < m; j++)
          t[j * m + i] = a[(size_t)j * n1 + (size_t)i]; /* T11, column-major */
      e->basis_kind = "schur";
    }
  }
  if (ok) {
    /* extend: (C - T_jj) x2_j = sum_{i<j} T_ij x2_i - B x1_j */
    double *r = malloc((nc + 1) * sizeof *r);
    unsigned char *dn = malloc(nc + 1);
    for (int j = 0; ok && r && dn && j < m; j++) {
      for (size_t i = 0; i < nc; i++) {
        double s = 0.0;
        for (size_t c = 0; c < n1; c++)
          s -= S[(n1 + i) * n + c] * x1[(size_t)j * n1 + c];
        for (int l = 0; l < j; l++)
          s += t[j * m + l] * e->basis[(size_t)l * n + n1 + i];
        r[i] = s;
      }
      for (size_t i = 0; i < n1; i++)
        e->basis[(size_t)j * n + i] = x1[(size_t)j * n1 + i];
      ok = outer_solve(S, n, n1, comp, start, ncomp, t[j * m + j], r,
                       e->basis + (size_t)j * n + n1, dn, bw, piv) == 0;
    }
    if (!r || !dn) ok = 0;
    free(r);
    free(dn);
  }
  if (!ok) {
    /* a leading eigenvalue in the outer block, or extension impossible: Schur
     * form of the whole matrix */
    full = malloc((n * n + 1) * sizeof *full);
    free(q);
    q = malloc((n * n + 1) * sizeof *q);
    if (full && q) {
      colmajor(S, n, n, full);
      ok = schur_basis(full, n, e->val + 1, m, q) == 0;
      if (ok) {
        memcpy(e->basis, q, n * (size_t)m * sizeof *e->basis);
        e->basis_kind = "schur";
      }
    }
  }
  free(full);
  free(q);
  free(t);
  free(x1);
  if (!ok) {
    free(e->basis);
    e->basis = NULL;
    e->basis_kind = "";
    st = ss_error_set(err, SS_ENUMERIC, "no basis of the subdominant invariant subspace");
  }
done:
  free(a);
  free(vr);
  free(wr);
  free(wi);
  free(rc);
  free(awr);
  free(awi);
  free(comp);
  free(start);
  free(blk);
  free(bw);
  free(piv);
  if (st) {
    ss_eig_free(e);
    return st;
  }
  *out = e;
  return SS_OK;
}
