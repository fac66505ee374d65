/* ss_psi_mask.c — det Dψ at the ring's regular vertices from tangent masks
 * (ss_psi_mask.h). */
#include "ss_psi_mask.h"
#include "ss_psi_mask_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <lapacke.h>

#include "ss_dense.h"
#include "ss_jac.h"

/* The support of c as a cone (size must be dim, values positive): 0, else -1 */
int ss_psi_mask_cone_of(const ss_star_coord *c, int dim, ss_psi_mask_cpt *p) {
  if (c->n != dim) return -1;
  for (int i = 0; i < 3; i++) {
    p->cone[i] = i < dim ? c->idx[i] : -1;
    p->v[i] = i < dim ? c->val[i] : 0;
    if (i < dim && p->v[i] <= 0) return -1;
  }
  return 0;
}

static int cmp_keyed(const void *a, const void *b) {
  return ss_star_coord_cmp(&((const keyed *)a)->c, &((const keyed *)b)->c);
}

/* The point of level ix with coordinates c, or SIZE_MAX. */
static size_t find(const level_ix *ix, const ss_star_coord *c) {
  size_t lo = 0, hi = ix->R->nv;
  while (lo < hi) {
    const size_t mid = lo + (hi - lo) / 2;
    const int s = ss_star_coord_cmp(&ix->ord[mid].c, c);
    if (s == 0) return ix->ord[mid].i;
    if (s < 0)
      lo = mid + 1;
    else
      hi = mid;
  }
  return SIZE_MAX;
}

/* The coordinate vector on cone with values v (all positive: else returns
 * an empty vector, n = 0, which names no interior point). */
static ss_star_coord coord_on(const int *cone, int dim, const int *v) {
  int32_t idx[3], val[3];
  for (int i = 0; i < dim; i++) {
    if (v[i] <= 0) return ss_star_coord_make(0, idx, val);
    idx[i] = cone[i];
    val[i] = v[i];
  }
  return ss_star_coord_make(dim, idx, val);
}

static int off_cmp(const void *a, const void *b) {
  const int *x = a, *y = b;
  for (int i = 0; i < 3; i++)
    if (x[i] != y[i]) return x[i] < y[i] ? -1 : 1;
  return 0;
}

static long off_find(int (*o)[3], size_t n, const int *x) {
  const int(*h)[3] = bsearch(x, o, n, sizeof *o, off_cmp);
  return h ? (long)(h - (const int(*)[3])o) : -1;
}

/* The one-ring O(q) of point qi (coordinates q) of ring level r, its
 * matrix A (rows of level r + 1) and the level-r points of q + O (idx, in
 * O's sorted order), into nb (o, A allocated here) and *pidx.  Returns 0,
 * 1 if O is not whole inside q's cone on these levels (or too large), -1
 * out of memory. */
int ss_psi_mask_closure(const ss_psi_mask_ctx *t, int r, const ss_psi_mask_cpt *q,
                        ss_psi_mask_nbhd *nb, size_t **pidx) {
  const level_ix *C = t->lev + r, *F = t->lev + r + 1;
  const int dim = t->dim;
  int(*o)[3] = malloc(SS_PSI_MASK_MAXO * sizeof *o);
  size_t *child = malloc(SS_PSI_MASK_MAXO * sizeof *child);
  size_t n = 1, rc = 1;
  memset(nb, 0, sizeof *nb);
  *pidx = NULL;
  if (!o || !child) goto fail_nomem;
  memset(o[0], 0, sizeof o[0]);
  for (size_t i = 0; i < n; i++) {
    int v[3] = {0, 0, 0};
    for (int d = 0; d < dim; d++)
      v[d] = 2 * q->v[d] + o[i][d];
    const ss_star_coord cc = coord_on(q->cone, dim, v);
    if (cc.n == 0 || (child[i] = find(F, &cc)) == SIZE_MAX) goto fail;
    const ss_local_ring *R = F->R;
    for (size_t e = R->ptr[child[i]]; e < R->ptr[child[i] + 1]; e++) {
      ss_psi_mask_cpt p;
      if (ss_psi_mask_cone_of(C->R->coord + R->col[e], dim, &p) ||
          memcmp(p.cone, q->cone, sizeof p.cone))
        goto fail;
      int off[3] = {0, 0, 0};
      for (int d = 0; d < dim; d++)
        off[d] = p.v[d] - q->v[d];
      size_t k = 0;
      while (k < n && off_cmp(o[k], off))
        k++;
      if (k < n) continue;
      if (n == SS_PSI_MASK_MAXO) goto fail;
      memcpy(o[n++], off, sizeof off);
    }
  }
  qsort(o, n, sizeof *o, off_cmp);
  nb->n = n;
  nb->o = o;
  nb->A = calloc(n * n + 1, sizeof *nb->A);
  *pidx = malloc((n + 1) * sizeof **pidx);
  if (!nb->A || !*pidx) goto fail_nomem;
  for (size_t i = 0; i < n; i++) {
    int v[3] = {0, 0, 0};
    for (int d = 0; d < dim; d++)
      v[d] = q->v[d] + o[i][d];
    const ss_star_coord pc = coord_on(q->cone, dim, v);
    (*pidx)[i] = find(C, &pc);
    for (int d = 0; d < dim; d++)
      v[d] = 2 * q->v[d] + o[i][d];
    const ss_star_coord cc = coord_on(q->cone, dim, v);
    const size_t ci = find(F, &cc);
    const ss_local_ring *R = F->R;
    for (size_t e = R->ptr[ci]; e < R->ptr[ci + 1]; e++) {
      ss_psi_mask_cpt p;
      ss_psi_mask_cone_of(C->R->coord + R->col[e], dim, &p);
      int off[3] = {0, 0, 0};
      for (int d = 0; d < dim; d++)
        off[d] = p.v[d] - q->v[d];
      nb->A[i * n + (size_t)off_find(o, n, off)] += R->w[e];
    }
  }
  free(child);
  return 0;
fail_nomem:
  rc = (size_t)-1;
fail:
  free(o);
  free(child);
  free(nb->A);
  free(*pidx);
  nb->o = NULL;
  nb->A = NULL;
  *pidx = NULL;
  return rc == 1 ? 1 : -1;
}

/* Same offsets, and weights equal to SS_PSI_MASK_SAME (the rule's weights
 * are rationals computed in doubles: one weight summed in another order
 * differs in its last bits) */
static int nbhd_equal(const ss_psi_mask_nbhd *a, const ss_psi_mask_nbhd *b) {
  if (a->n != b->n || memcmp(a->o, b->o, a->n * sizeof *a->o)) return 0;
  for (size_t k = 0; k < a->n * a->n; k++)
    if (!(fabs(a->A[k] - b->A[k]) <= SS_PSI_MASK_SAME)) return 0;
  return 1;
}

static int by_modulus_desc(const void *a, const void *b) {
  const double x = *(const double *)a, y = *(const double *)b;
  return x > y ? -1 : x < y ? 1 : 0;
}

/* Whether A's spectrum is a smooth regular vertex's: 1 simple, then 1/2
 * dim times, every other eigenvalue of modulus below 1/2 (to
 * SS_PSI_MASK_TOL).  0 also when LAPACK fails or memory runs out. */
static int spectrum_ok(int dim, const ss_psi_mask_nbhd *nb) {
  const size_t n = nb->n;
  double *a = malloc((n * n + 1) * sizeof *a), *wr = malloc((n + 1) * sizeof *wr);
  double *wi = malloc((n + 1) * sizeof *wi);
  int ok = a && wr && wi;
  if (ok) {
    memcpy(a, nb->A, n * n * sizeof *a);
    ok = LAPACKE_dgeev(LAPACK_ROW_MAJOR, 'N', 'N', (lapack_int)n, a, (lapack_int)n, wr,
                       wi, NULL, 1, NULL, 1) == 0;
  }
  if (ok) {
    for (size_t i = 0; i < n; i++)
      wr[i] = hypot(wr[i], wi[i]);
    qsort(wr, n, sizeof *wr, by_modulus_desc);
    const double e = SS_PSI_MASK_TOL;
    ok = n > (size_t)dim + 1 && fabs(wr[0] - 1.0) <= e && wr[1] < 1.0 - e;
    for (int d = 1; ok && d <= dim; d++)
      ok = fabs(wr[d] - 0.5) <= e;
    ok = ok && wr[dim + 1] < 0.5 - e;
  }
  free(a);
  free(wr);
  free(wi);
  return ok;
}

/* The tangent masks of nb (ss_psi_mask.h) into nb->L, or nb->L = NULL when
 * A does not reproduce linear functions or the system is singular or not
 * solved to SS_PSI_MASK_TOL.  Returns -1 out of memory, else 0. */
static int masks(int dim, ss_psi_mask_nbhd *nb) {
  const size_t n = nb->n, m = n + (size_t)dim;
  nb->L = NULL;
  double omax = 1.0;
  for (size_t i = 0; i < n; i++)
    for (int d = 0; d < dim; d++)
      omax = fmax(omax, fabs((double)nb->o[i][d]));
  for (size_t i = 0; i < n; i++) /* A X = X / 2 */
    for (int d = 0; d < dim; d++) {
      double s = -0.5 * nb->o[i][d];
      for (size_t j = 0; j < n; j++)
        s += nb->A[i * n + j] * nb->o[j][d];
      if (!(fabs(s) <= SS_PSI_MASK_TOL * omax)) return 0;
    }
  if (!spectrum_ok(dim, nb)) return 0;
  /* B^T Y = E^T: B = [A - I/2 | X] (n x m), Y = L^T (n x dim) */
  double *Bt = calloc(m * n + 1, sizeof *Bt), *Y = calloc(m * (size_t)dim + 1, sizeof *Y);
  double *sv = malloc((n + 1) * sizeof *sv), *B0 = malloc((m * n + 1) * sizeof *B0);
  if (!Bt || !Y || !sv || !B0) {
    free(Bt), free(Y), free(sv), free(B0);
    return -1;
  }
  for (size_t i = 0; i < n; i++)
    for (size_t j = 0; j < n; j++)
      Bt[j * n + i] = nb->A[i * n + j] - (i == j ? 0.5 : 0.0);
  for (int d = 0; d < dim; d++) {
    for (size_t i = 0; i < n; i++)
      Bt[(n + (size_t)d) * n + i] = nb->o[i][d];
    Y[(n + (size_t)d) * (size_t)dim + (size_t)d] = 1.0;
  }
  memcpy(B0, Bt, m * n * sizeof *B0);
  lapack_int rank = 0;
  const lapack_int info =
      LAPACKE_dgelsd(LAPACK_ROW_MAJOR, (lapack_int)m, (lapack_int)n, dim, Bt,
                     (lapack_int)n, Y, dim, sv, 1e-12, &rank);
  int ok = info == 0 && rank == (lapack_int)n;
  for (size_t i = 0; ok && i < m; i++) /* the residual of B^T L^T = E^T */
    for (int d = 0; d < dim; d++) {
      double s = (i == n + (size_t)d) ? -1.0 : 0.0, mag = fabs(s);
      for (size_t j = 0; j < n; j++) {
        s += B0[i * n + j] * Y[j * (size_t)dim + (size_t)d];
        mag += fabs(B0[i * n + j] * Y[j * (size_t)dim + (size_t)d]);
      }
      if (!(fabs(s) <= SS_PSI_MASK_TOL * fmax(1.0, mag))) ok = 0;
    }
  if (ok) {
    nb->L = malloc((size_t)dim * n * sizeof *nb->L);
    if (!nb->L)
      ok = -1;
    else
      for (int d = 0; d < dim; d++)
        for (size_t j = 0; j < n; j++)
          nb->L[(size_t)d * n + j] = Y[j * (size_t)dim + (size_t)d];
  }
  free(Bt), free(Y), free(sv), free(B0);
  return ok < 0 ? -1 : 0;
}

/* The orientation (+-1) of the chart on the cone of each ring cell of the
 * cell types with a determinant (tets, hexes; triangles, quads), recorded
 * in t->orient.  Returns 0, 1 if two cells of one cone disagree, -1 out of
 * memory. */
static int orientations(ss_psi_mask_ctx *t) {
  static const int corners[SS_NCELLTYPES][4] = {[SS_TET] = {0, 1, 2, 3},
                                                [SS_HEX] = {0, 1, 3, 4},
                                                [SS_TRIANGLE] = {0, 1, 2, -1},
                                                [SS_QUAD] = {0, 1, 3, -1}};
  const int dim = t->dim;
  for (int r = 0; r < t->M->nring; r++) {
    const ss_local_ring *R = t->M->ring + r;
    for (size_t c = 0; c < R->ncells; c++) {
      const ss_cell_type ty = R->ctype[c];
      if (ss_cell_dim(ty) != dim ||
          (ty != SS_TET && ty != SS_HEX && ty != SS_TRIANGLE && ty != SS_QUAD))
        continue;
      int cone[3] = {-1, -1, -1}, nc = 0, ok = 1;
      double x[4][3] = {{0}};
      for (int k = 0; k <= dim && ok; k++) {
        const ss_star_coord *p =
            R->coord + R->corner[c * SS_MAXCELLVERTS + (size_t)corners[ty][k]];
        for (int e = 0; e < p->n && ok; e++) {
          int a = 0;
          while (a < nc && cone[a] != p->idx[e])
            a++;
          if (a == nc) {
            if (nc == dim)
              ok = 0;
            else
              cone[nc++] = p->idx[e];
          }
          if (ok) x[k][a] = p->val[e];
        }
      }
      if (!ok || nc != dim) continue;
      /* the cone ascending, the coordinates permuted alike */
      int perm[3] = {0, 1, 2};
      for (int i = 0; i < nc; i++)
        for (int j = i + 1; j < nc; j++)
          if (cone[perm[j]] < cone[perm[i]]) {
            const int s = perm[i];
            perm[i] = perm[j];
            perm[j] = s;
          }
      double e[3][3] = {{0}};
      for (int k = 1; k <= dim; k++)
        for (int i = 0; i < dim; i++)
          e[k - 1][i] = x[k][perm[i]] - x[0][perm[i]];
      const double det = dim == 3 ? ss_dense_det3(e[0], e[1], e[2])
                                  : e[0][0] * e[1][1] - e[0][1] * e[1][0];
      if (det == 0.0) continue;
      const int sign = det > 0 ? 1 : -1;
      int key[3] = {cone[perm[0]], cone[perm[1]], dim == 3 ? cone[perm[2]] : -1};
      size_t k = 0;
      while (k < t->norient && memcmp(t->orient[k], key, sizeof key))
        k++;
      if (k < t->norient) {
        if (t->orient[k][3] != sign) return 1;
        continue;
      }
      if (t->norient == t->capo) {
        const size_t cap = 2 * t->capo + 8;
        int(*no)[4] = realloc(t->orient, cap * sizeof *no);
        if (!no) return -1;
        t->orient = no;
        t->capo = cap;
      }
      memcpy(t->orient[t->norient], key, sizeof key);
      t->orient[t->norient++][3] = sign;
    }
  }
  return 0;
}

int ss_psi_mask_orient_of(const ss_psi_mask_ctx *t, const int *cone) {
  for (size_t k = 0; k < t->norient; k++)
    if (!memcmp(t->orient[k], cone, 3 * sizeof *cone)) return t->orient[k][3];
  return 0;
}

/* The neighbourhood equal to nb among t's, else nb itself added (moved). */
static ss_psi_mask_nbhd *intern(ss_psi_mask_ctx *t, ss_psi_mask_nbhd *nb, int *added) {
  *added = 0;
  for (size_t k = 0; k < t->nnb; k++)
    if (nbhd_equal(t->nb + k, nb)) return t->nb + k;
  if (t->nnb == t->cap) {
    const size_t cap = 2 * t->cap + 4;
    ss_psi_mask_nbhd *m = realloc(t->nb, cap * sizeof *m);
    if (!m) return NULL;
    t->nb = m;
    t->cap = cap;
  }
  t->nb[t->nnb] = *nb;
  t->nb[t->nnb].L = NULL;
  t->nb[t->nnb].stationary = 0;
  t->nb[t->nnb].tried = 0;
  *added = 1;
  return t->nb + t->nnb++;
}

void ss_psi_mask_nbhd_free(ss_psi_mask_nbhd *nb) {
  free(nb->o);
  free(nb->A);
  free(nb->L);
}

/* det Dψ at point qi of ring level r (coordinates q) into *pt, with *sign
 * its sign (0 flat) — or *sign = 2 when q is not a regular vertex here —
 * and *checked whether its neighbourhood was seen stationary.  Returns 0,
 * -1 out of memory. */
static int judge_point(ss_psi_mask_ctx *t, int r, size_t qi, const ss_psi_mask_cpt *q,
                       ss_psi_mask_point *pt, int *sign, int *checked) {
  const int dim = t->dim;
  ss_psi_mask_nbhd nb, nb2;
  size_t *idx = NULL, *idx2 = NULL;
  *sign = 2;
  int rc = ss_psi_mask_closure(t, r, q, &nb, &idx);
  if (rc) return rc < 0 ? -1 : 0;
  int added = 0;
  ss_psi_mask_nbhd *h = intern(t, &nb, &added);
  if (!h) {
    ss_psi_mask_nbhd_free(&nb);
    free(idx);
    return -1;
  }
  if (!added) ss_psi_mask_nbhd_free(&nb);
  if (!h->stationary && r + 2 < t->M->nring) { /* read again one level down */
    ss_psi_mask_cpt q2 = *q;
    for (int d = 0; d < dim; d++)
      q2.v[d] = 2 * q->v[d];
    rc = ss_psi_mask_closure(t, r + 1, &q2, &nb2, &idx2);
    if (rc < 0) {
      free(idx);
      return -1;
    }
    if (rc == 0) {
      h->stationary = nbhd_equal(h, &nb2) ? 1 : -1;
      ss_psi_mask_nbhd_free(&nb2);
      free(idx2);
    }
  }
  if (!h->tried && masks(dim, h)) {
    free(idx);
    return -1;
  }
  h->tried = 1;
  if (h->stationary < 0 || !h->L) {
    free(idx);
    return 0;
  }
  *checked = h->stationary > 0;
  /* D[d] = sum_i L[d][i] psi(q + o_i), derivatives along level-w axes */
  double D[3][3] = {{0}};
  const double *P = t->net[r];
  const double scale = ldexp(1.0, r + 1);
  for (int d = 0; d < dim; d++) {
    for (size_t i = 0; i < h->n; i++)
      for (int c = 0; c < dim; c++)
        D[d][c] += h->L[(size_t)d * h->n + i] * P[idx[i] * (size_t)dim + (size_t)c];
    for (int c = 0; c < dim; c++)
      D[d][c] *= scale;
  }
  free(idx);
  const double det =
      dim == 3 ? ss_dense_det3(D[0], D[1], D[2]) : D[0][0] * D[1][1] - D[0][1] * D[1][0];
  double norms = 1.0;
  for (int d = 0; d < dim; d++)
    norms *= sqrt(D[d][0] * D[d][0] + D[d][1] * D[d][1] + D[d][2] * D[d][2]);
  const int o = ss_psi_mask_orient_of(t, q->cone);
  pt->level = r;
  pt->point = qi;
  for (int d = 0; d < 3; d++) {
    pt->cone[d] = d < dim ? q->cone[d] : -1;
    pt->x[d] = d < dim ? ldexp((double)q->v[d], -(r + 1)) : 0.0;
  }
  pt->det = det * o;
  pt->lo = pt->hi = pt->det;
  *sign = (o == 0 || !(fabs(det) > SS_JAC_FLAT * norms)) ? 0 : pt->det > 0 ? 1 : -1;
  return 0;
}

void ss_psi_mask_ctx_free(ss_psi_mask_ctx *t) {
  for (int r = 0; r < t->M->nring; r++) {
    if (t->lev) free(t->lev[r].ord);
    if (t->net) free(t->net[r]);
  }
  free(t->lev);
  free(t->net);
  for (size_t k = 0; k < t->nnb; k++)
    ss_psi_mask_nbhd_free(t->nb + k);
  free(t->nb);
  free(t->orient);
}

/* The levels' lookups and the nets pushed from x.  Returns 0 or -1. */
int ss_psi_mask_ctx_build(ss_psi_mask_ctx *t, const double *x) {
  const ss_local *M = t->M;
  const int nr = M->nring;
  t->lev = calloc((size_t)nr + 1, sizeof *t->lev);
  t->net = calloc((size_t)nr + 1, sizeof *t->net);
  if (!t->lev || !t->net) return -1;
  const double *prev = x;
  for (int r = 0; r < nr; r++) {
    const ss_local_ring *R = M->ring + r;
    level_ix *L = t->lev + r;
    L->R = R;
    L->ord = malloc((R->nv + 1) * sizeof *L->ord);
    t->net[r] = malloc((R->nv * (size_t)t->dim + 1) * sizeof *t->net[r]);
    if (!L->ord || !t->net[r]) return -1;
    for (size_t i = 0; i < R->nv; i++) {
      L->ord[i].c = R->coord[i];
      L->ord[i].i = i;
    }
    qsort(L->ord, R->nv, sizeof *L->ord, cmp_keyed);
    ss_local_ring_push(R, prev, t->dim, t->net[r]);
    prev = t->net[r];
  }
  return orientations(t);
}

ss_status ss_psi_mask_judge(const ss_local *M, const double *x, size_t n,
                            ss_psi_mask_result *out, ss_error *err) {
  return ss_psi_mask_each(M, x, n, NULL, NULL, out, err);
}

ss_status ss_psi_mask_each(const ss_local *M, const double *x, size_t n,
                           ss_psi_mask_fn fn, void *arg, ss_psi_mask_result *out,
                           ss_error *err) {
  memset(out, 0, sizeof *out);
  out->wpos.level = out->wneg.level = -1;
  if (!M || !x || n != M->n2 || (M->dim != 2 && M->dim != 3))
    return ss_error_set(err, SS_EINPUT,
                        "psi masks: a net of %zu points for a two-ring of %zu", n,
                        M ? M->n2 : 0);
  for (int r = 0; r < M->nring; r++)
    if (!M->ring[r].coord)
      return ss_error_set(err, SS_EINPUT, "psi masks: ring level %d has no coordinates",
                          r);
  ss_psi_mask_ctx t = {M, M->dim, NULL, NULL, NULL, 0, 0, NULL, 0, 0};
  int rc = ss_psi_mask_ctx_build(&t, x);
  if (rc) {
    ss_psi_mask_ctx_free(&t);
    return rc > 0 ? ss_error_set(err, SS_EINTERNAL,
                                 "psi masks: two ring cells of one cone disagree on "
                                 "its orientation")
                  : ss_error_nomem(err, "psi masks");
  }
  for (int r = 0; r + 1 < M->nring && !rc; r++) {
    const ss_local_ring *R = M->ring + r;
    for (size_t i = 0; i < R->nv && !rc; i++) {
      ss_psi_mask_cpt q;
      if (ss_psi_mask_cone_of(R->coord + i, t.dim, &q)) continue;
      out->interior++;
      ss_psi_mask_point pt;
      int sign, checked = 0;
      if ((rc = judge_point(&t, r, i, &q, &pt, &sign, &checked)) || sign == 2) continue;
      out->judged++;
      out->unchecked += !checked;
      if (fn) fn(&pt, sign, arg);
      if (sign == 0)
        out->flat++;
      else if (sign > 0) {
        out->positive++;
        if (out->wpos.level < 0 || pt.det > out->wpos.det) out->wpos = pt;
      } else {
        out->negative++;
        if (out->wneg.level < 0 || pt.det < out->wneg.det) out->wneg = pt;
      }
    }
  }
  for (size_t k = 0; k < t.nnb; k++) {
    out->nmasks += t.nb[k].L != NULL;
    if (t.nb[k].n > out->maxo) out->maxo = t.nb[k].n;
  }
  ss_psi_mask_ctx_free(&t);
  return rc ? ss_error_nomem(err, "psi masks") : SS_OK;
}

ss_psi_point ss_psi_mask_point_of(const ss_local *M, const ss_psi_mask_point *pt) {
  ss_psi_point out = {SIZE_MAX, {0, 0, 0}, {pt->lo, pt->hi}, 1, {-1, -1, -1}, {0, 0, 0}};
  for (int d = 0; d < 3; d++) {
    out.cone[d] = pt->cone[d];
    out.x[d] = pt->x[d];
  }
  if (M->dim != 3) return out;
  for (size_t c = 0; c < M->ncells; c++) {
    if (M->ctype[c] != SS_TET) continue;
    double v[4][3] = {{0}};
    int ok = 1;
    for (int k = 0; k < 4 && ok; k++) {
      const ss_star_coord *q = M->label + M->corner[c * SS_MAXCELLVERTS + (size_t)k];
      for (int e = 0; e < q->n && ok; e++) {
        int a = 0;
        while (a < 3 && pt->cone[a] != q->idx[e])
          a++;
        if (a == 3)
          ok = 0;
        else
          v[k][a] = q->val[e];
      }
    }
    if (!ok) continue;
    double E[3][3], y[3];
    for (int k = 0; k < 3; k++)
      for (int a = 0; a < 3; a++)
        E[k][a] = v[k + 1][a] - v[0][a];
    for (int a = 0; a < 3; a++)
      y[a] = pt->x[a] - v[0][a];
    /* x - v0 = sum_k b_k E[k]: Cramer's rule on the columns */
    const double det = ss_dense_det3(E[0], E[1], E[2]);
    if (det == 0.0) continue;
    double b[3], sum = 0.0;
    for (int k = 0; k < 3; k++) {
      double F[3][3];
      memcpy(F, E, sizeof F);
      memcpy(F[k], y, sizeof y);
      b[k] = ss_dense_det3(F[0], F[1], F[2]) / det;
      sum += b[k];
    }
    if (b[0] < -1e-12 || b[1] < -1e-12 || b[2] < -1e-12 || sum > 1.0 + 1e-12) continue;
    out.cell = c;
    for (int k = 0; k < 3; k++)
      out.at[k] = b[k];
    out.det[0] = pt->lo * fabs(det); /* along the tet's edges: det E times */
    out.det[1] = pt->hi * fabs(det);
    return out;
  }
  return out;
}
