/* ss_psi_tet.c — the spokes of a tet/oct vertex case from the edge case's
 * local matrix (method and classes: ss_psi_tet.h). */
#include "ss_psi_tet.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_clock.h"
#include "ss_cx.h"
#include "ss_dense.h"
#include "ss_eigvec.h"
#include "ss_jac.h"

#define TET_TOL 1e-6 /* eigenvalues equal within this (relative) */

void ss_psi_tet_edge_free(ss_psi_tet_edge *m) {
  if (!m) return;
  ss_local_free(m->E);
  free(m->l);
  free(m->r);
  free(m);
}

/* Push a net (3 coordinates per point) through ring level R. */
static void push3(const ss_local_ring *R, const double *prev, double *out) {
  for (size_t i = 0; i < R->nv; i++) {
    double v[3] = {0.0, 0.0, 0.0};
    for (size_t q = R->ptr[i]; q < R->ptr[i + 1]; q++)
      for (int d = 0; d < 3; d++)
        v[d] += R->w[q] * prev[R->col[q] * 3 + (size_t)d];
    memcpy(out + 3 * i, v, sizeof v);
  }
}

/* x (M->n2 x 3) pushed to ring levels 0..upto of M: net[r] (each malloc'd,
 * the caller frees).  0, or -1 out of memory. */
static int push_levels(const ss_local *M, const double *x, int upto, double **net) {
  const double *prev = x;
  for (int r = 0; r <= upto; r++) {
    net[r] = malloc((3 * M->ring[r].nv + 1) * sizeof *net[r]);
    if (!net[r]) return -1;
    push3(M->ring + r, prev, net[r]);
    prev = net[r];
  }
  return 0;
}

/* Corners of cell c of ring level R from net into y (nv x 3). */
static int cell_corners(const ss_local_ring *R, size_t c, const double *net, double *y) {
  const int nv = ss_cell_nverts(R->ctype[c]);
  for (int j = 0; j < nv; j++)
    memcpy(y + 3 * j, net + 3 * R->corner[c * SS_MAXCELLVERTS + (size_t)j],
           3 * sizeof *y);
  return nv;
}

/* The sign of the edge's map (r_h, r_1, r_2) on E's last ring level: +1 or
 * -1 when every cell is of that strict sign, else 0.  -2 out of memory. */
static int edge_sigma(const ss_psi_tet_edge *m) {
  const ss_local *E = m->E;
  const size_t n2 = E->n2;
  double *x = malloc((3 * n2 + 1) * sizeof *x), *net[SS_LOCAL_MAXRING] = {NULL};
  int sign = -2;
  if (!x) return -2;
  for (size_t i = 0; i < n2; i++)
    for (int d = 0; d < 3; d++)
      x[3 * i + (size_t)d] = m->r[(size_t)d * n2 + i];
  const int last = E->nring - 1;
  if (last >= 0 && !push_levels(E, x, last, net)) {
    const ss_local_ring *R = E->ring + last;
    size_t pos = 0, neg = 0;
    for (size_t c = 0; c < R->ncells; c++) {
      double y[3 * SS_MAXCELLVERTS];
      cell_corners(R, c, net[last], y);
      ss_jac_result j;
      ss_jac_cell(R->ctype[c], y, 3, SS_JAC_DEPTH, &j);
      pos += j.sign == SS_JAC_POSITIVE;
      neg += j.sign == SS_JAC_NEGATIVE;
    }
    sign = R->ncells && pos == R->ncells ? 1 : R->ncells && neg == R->ncells ? -1 : 0;
  }
  for (int r = 0; r < SS_LOCAL_MAXRING; r++)
    free(net[r]);
  free(x);
  return sign;
}

/* Pick 1/2 and the real double pair among v's four leading eigenvalues into
 * col[0..2]; next = the largest modulus after them.  0, or -1. */
static int pick_modes(const ss_eigvec *v, int col[3], double *lambda, double *next) {
  int h = -1, p[2] = {-1, -1}, np = 0;
  if (v->k < 5) return -1;
  for (int j = 1; j < 4; j++) {
    if (fabs(v->im[j]) > TET_TOL || !v->biorth[j]) return -1;
    if (fabs(v->re[j] - 0.5) <= TET_TOL * 0.5 && h < 0)
      h = j;
    else if (np < 2)
      p[np++] = j;
  }
  if (h < 0 || np != 2 || v->group[p[0]] != v->group[p[1]] ||
      v->group[h] == v->group[p[0]])
    return -1;
  for (int j = 4; j < v->k; j++)
    if (v->group[j] == v->group[p[0]] || v->group[j] == v->group[h]) return -1;
  col[0] = h;
  col[1] = p[0];
  col[2] = p[1];
  *lambda = v->re[p[0]];
  *next = hypot(v->re[4], v->im[4]);
  return 0;
}

/* The largest -dx_a over E's labels (for a spoke point at t = 0). */
static size_t most_behind(const ss_local *E, int n) {
  long worst = 0;
  for (size_t j = 0; j < E->n2; j++) {
    const ss_star_coord *y = E->label + j;
    long yn = 0, sum = 0;
    for (int q = 0; q < y->n; q++)
      if (y->idx[q] == n)
        yn = y->val[q];
      else
        sum += y->val[q];
    const long behind = -(yn - sum) / 2;
    if (behind > worst) worst = behind;
  }
  return (size_t)worst;
}

ss_status ss_psi_tet_edge_new(const ss_scheme *s, int n, ss_psi_tet_edge **out,
                              ss_error *err) {
  *out = NULL;
  if (n < 3) return ss_error_set(err, SS_EINPUT, "tet spokes: valence %d < 3", n);
  if (ss_scheme_reads_diagonals(s))
    return ss_error_set(err, SS_EINPUT,
                        "tet spokes: %s reads major diagonals (the vertex star's round a "
                        "spoke need not be the edge case's)",
                        ss_scheme_name(s));
  ss_psi_tet_edge *m = calloc(1, sizeof *m);
  if (!m) return ss_error_nomem(err, "tet spokes: edge");
  m->n = n;
  const ss_case c = {SS_CASE_EDGE, NULL, n, SS_DIAG_BFS, 0};
  ss_eigvec *v = NULL;
  ss_status st = ss_local_new(s, &c, &m->E, err);
  if (!st && m->E->cell != SS_TET)
    st = ss_error_set(err, SS_EINPUT, "tet spokes: %s splits no tets", ss_scheme_name(s));
  if (!st) st = ss_eigvec_new(m->E->S, m->E->n2, 5, TET_TOL, &v, err);
  if (st) goto done;
  const size_t n2 = m->E->n2;
  int col[3];
  if (pick_modes(v, col, &m->lambda, &m->next)) {
    st = ss_error_set(err, SS_ENUMERIC,
                      "tet spokes: the edge of valence %d has no spectrum 1, 1/2, "
                      "lambda, lambda (real, biorthonormal) among its leading four",
                      n);
    goto done;
  }
  m->l = malloc((3 * n2 + 1) * sizeof *m->l);
  m->r = malloc((3 * n2 + 1) * sizeof *m->r);
  if (!m->l || !m->r) {
    st = ss_error_nomem(err, "tet spokes: edge modes");
    goto done;
  }
  for (int j = 0; j < 3; j++) {
    memcpy(m->l + (size_t)j * n2, v->left_re + (size_t)col[j] * n2, n2 * sizeof *m->l);
    memcpy(m->r + (size_t)j * n2, v->right_re + (size_t)col[j] * n2, n2 * sizeof *m->r);
  }
  m->emaxneg = most_behind(m->E, n);
  m->sigma = edge_sigma(m);
  if (m->sigma == -2)
    st = ss_error_nomem(err, "tet spokes: edge map");
  else if (m->sigma == 0)
    st = ss_error_set(err, SS_ENUMERIC,
                      "tet spokes: the edge map of valence %d is not of one strict sign "
                      "on its ring",
                      n);
done:
  ss_eigvec_free(v);
  if (st)
    ss_psi_tet_edge_free(m);
  else
    *out = m;
  return st;
}

int ss_psi_tet_map_label(int a, const int *nb, int n, int t, const ss_star_coord *y,
                         ss_star_coord *out) {
  long yn = 0, sum = 0;
  int32_t idx[SS_STAR_MAXSUPP], val[SS_STAR_MAXSUPP];
  int m = 0, f[2], nf = 0;
  for (int q = 0; q < y->n; q++) {
    if (y->idx[q] == n) {
      yn = y->val[q];
    } else if (y->idx[q] >= 0 && y->idx[q] < n && nf < 2 && y->val[q] > 0) {
      f[nf++] = y->idx[q];
      sum += y->val[q];
      idx[m] = nb[y->idx[q]];
      val[m++] = y->val[q];
    } else {
      return -1;
    }
  }
  if (nf == 2 && (f[1] - f[0] + n) % n != 1 && (f[0] - f[1] + n) % n != 1) return -1;
  if ((yn - sum) % 2 != 0) return -1;
  const long ta = (long)t + (yn - sum) / 2;
  if (ta < 0) return -1;
  if (ta > 0) {
    idx[m] = a;
    val[m++] = (int32_t)ta;
  }
  *out = ss_star_coord_make(m, idx, val);
  return 0;
}

/* A ring level's points sorted by coordinates, for lookup. */
typedef struct {
  ss_star_coord c; /* the coordinates */
  size_t i;        /* the point */
} keyed;

static int cmp_keyed(const void *x, const void *y) {
  return ss_star_coord_cmp(&((const keyed *)x)->c, &((const keyed *)y)->c);
}

/* The point of the sorted list k (n entries) with coordinates c, or
 * SIZE_MAX. */
static size_t lookup(const keyed *k, size_t n, const ss_star_coord *c) {
  size_t lo = 0, hi = n;
  while (lo < hi) {
    const size_t mid = lo + (hi - lo) / 2;
    const int d = ss_star_coord_cmp(&k[mid].c, c);
    if (d == 0) return k[mid].i;
    if (d < 0)
      lo = mid + 1;
    else
      hi = mid;
  }
  return SIZE_MAX;
}

/* What one classification works with. */
typedef struct {
  const ss_local *M;             /* the vertex case */
  const ss_link *link;           /* its link */
  double *net[SS_LOCAL_MAXRING]; /* psi's points on each ring level */
  keyed *key[SS_LOCAL_MAXRING];  /* each level's points by coordinates */
  ss_psi_tet_edge **edge;        /* edge models by valence (lazily built) */
  int maxn;                      /* entries of edge: valences 0..maxn */
  size_t *at;                    /* scratch: the matched points, E->n2 */
  size_t skipped;                /* spoke points not usable */
} tet_ctx;

/* A two-ring cell round p holding the spoke to link vertex a, and the
 * parameters of the point x0 e_a in it; SIZE_MAX when there is none. */
static size_t spoke_cell(const ss_local *M, int a, double x0, double at[3]) {
  const int32_t one = 1, ia = a;
  const ss_star_coord ea = ss_star_coord_make(1, &ia, &one);
  const size_t qa = ss_local_label_index(M, &ea);
  for (size_t c = 0; c < M->ncells && qa != SIZE_MAX; c++) {
    const size_t *v = M->corner + c * SS_MAXCELLVERTS;
    if (M->ctype[c] != SS_TET) continue;
    int jp = -1, ja = -1;
    for (int j = 0; j < 4; j++) {
      if (v[j] == 0) jp = j;
      if (v[j] == qa) ja = j;
    }
    if (jp < 0 || ja < 0) continue;
    double bary[4] = {0, 0, 0, 0};
    bary[jp] = 1.0 - x0;
    bary[ja] = x0;
    for (int d = 0; d < 3; d++)
      at[d] = bary[d + 1];
    return c;
  }
  return SIZE_MAX;
}

/* s at spoke point i (coordinate t e_a) of ring level r of spoke sp, with
 * edge model m and a's neighbours nb: into smp.  0, or 1 when not usable. */
static int spoke_value(tet_ctx *T, const ss_psi_tet_edge *m, const int *nb, int a, int r,
                       size_t i, int t, ss_psi_spoke_sample *smp) {
  const ss_local *E = m->E;
  const ss_local_ring *R = T->M->ring + r;
  if (t <= (int)m->emaxneg) return 1;
  for (size_t j = 0; j < E->n2; j++) {
    ss_star_coord c;
    if (ss_psi_tet_map_label(a, nb, m->n, t, E->label + j, &c)) return 1;
    T->at[j] = lookup(T->key[r], R->nv, &c);
    if (T->at[j] == SIZE_MAX) return 1;
  }
  const double *X = T->net[r];
  double col[3][3] = {{0}}, d = 0.0;
  for (size_t j = 0; j < E->n2; j++) {
    const double *p = X + 3 * T->at[j];
    const double *q = X + 3 * i;
    const double dist = hypot(hypot(p[0] - q[0], p[1] - q[1]), p[2] - q[2]);
    if (dist > d) d = dist;
    for (int k = 0; k < 3; k++)
      for (int e = 0; e < 3; e++)
        col[k][e] += m->l[(size_t)k * E->n2 + j] * p[e];
  }
  smp->x0 = ldexp((double)t, -(r + 1));
  smp->cell = spoke_cell(T->M, a, smp->x0, smp->at);
  memcpy(smp->on, smp->at, sizeof smp->on);
  smp->axis = -1;
  smp->s = m->sigma * ss_dense_det3(col[0], col[1], col[2]);
  smp->rel = d > 0.0 ? fabs(smp->s) / (d * d * d) : 0.0;
  smp->det_eval = smp->s;
  return 0;
}

/* Count sample smp into spoke sp (ss_psi_spoke.c's rule: sign holds bits 1
 * positive, 2 negative until classified). */
static void add_sample(ss_psi_spoke *sp, const ss_psi_spoke_sample *smp) {
  if (sp->nsamples == 0 || fabs(smp->s) < sp->smin) {
    sp->smin = fabs(smp->s);
    sp->min = *smp;
  }
  if (fabs(smp->s) > sp->smax) sp->smax = fabs(smp->s);
  if (sp->nsamples == 0 || smp->rel < sp->relmin) sp->relmin = smp->rel;
  sp->nsamples++;
  if (smp->rel < SS_PSI_SPOKE_DEGENERATE) {
    sp->ndegenerate++;
    return;
  }
  const int k = smp->s > 0.0 ? 0 : 1;
  if (!(sp->sign & (1 << k))) sp->w[k] = *smp;
  sp->sign |= 1 << k;
}

/* The edge model of valence n, built on first use. */
static ss_status edge_of(const ss_scheme *s, tet_ctx *T, int n, ss_psi_tet_edge **m,
                         ss_error *err) {
  if (n > T->maxn) return ss_error_set(err, SS_EINPUT, "tet spokes: valence %d", n);
  ss_status st = SS_OK;
  if (!T->edge[n]) st = ss_psi_tet_edge_new(s, n, &T->edge[n], err);
  *m = T->edge[n];
  if (!st) {
    free(T->at);
    T->at = malloc((T->edge[n]->E->n2 + 1) * sizeof *T->at);
    if (!T->at) st = ss_error_nomem(err, "tet spokes: matches");
  }
  return st;
}

/* Spoke a (its samples on every ring level) into sp. */
static ss_status one_spoke(const ss_scheme *s, tet_ctx *T, int a, ss_psi_spoke *sp,
                           ss_error *err) {
  const ss_link *l = T->link;
  const int n = ss_link_deg(l, a);
  const int *nb = l->nbr + l->off[a];
  ss_psi_tet_edge *m = NULL;
  ss_status st = edge_of(s, T, n, &m, err);
  if (st) return st;
  sp->vertex = a;
  sp->valence = n;
  sp->mu = m->lambda;
  sp->gap = m->next / (m->lambda < 0.5 ? m->lambda : 0.5);
  for (int r = 0; r < T->M->nring; r++) {
    const ss_local_ring *R = T->M->ring + r;
    for (size_t i = 0; i < R->nv; i++) {
      const ss_star_coord *c = R->coord + i;
      if (c->n != 1 || c->idx[0] != a || c->val[0] <= 0) continue;
      ss_psi_spoke_sample smp;
      if (spoke_value(T, m, nb, a, r, i, c->val[0], &smp))
        T->skipped++;
      else
        add_sample(sp, &smp);
    }
  }
  ss_psi_spoke_classify(sp);
  return SS_OK;
}

/* Build T's nets and lookups for M and x.  SS_ENOMEM. */
static ss_status ctx_open(tet_ctx *T, const ss_local *M, const ss_link *l,
                          const double *x, ss_error *err) {
  memset(T, 0, sizeof *T);
  T->M = M;
  T->link = l;
  T->maxn = l->k;
  T->edge = calloc((size_t)l->k + 1, sizeof *T->edge);
  if (!T->edge || push_levels(M, x, M->nring - 1, T->net))
    return ss_error_nomem(err, "tet spokes: ring nets");
  for (int r = 0; r < M->nring; r++) {
    const ss_local_ring *R = M->ring + r;
    T->key[r] = malloc((R->nv + 1) * sizeof *T->key[r]);
    if (!T->key[r]) return ss_error_nomem(err, "tet spokes: lookup");
    for (size_t i = 0; i < R->nv; i++)
      T->key[r][i] = (keyed){R->coord[i], i};
    qsort(T->key[r], R->nv, sizeof *T->key[r], cmp_keyed);
  }
  return SS_OK;
}

static void ctx_close(tet_ctx *T) {
  for (int r = 0; r < SS_LOCAL_MAXRING; r++) {
    free(T->net[r]);
    free(T->key[r]);
  }
  for (int n = 0; T->edge && n <= T->maxn; n++)
    ss_psi_tet_edge_free(T->edge[n]);
  free(T->edge);
  free(T->at);
}

ss_status ss_psi_tet_spokes_classify(const ss_scheme *s, const ss_local *M,
                                     const ss_link *l, const double *x,
                                     ss_psi_spokes *out, size_t *nskipped,
                                     ss_error *err) {
  memset(out, 0, sizeof *out);
  if (nskipped) *nskipped = 0;
  if (M->dim != 3 || M->cell != SS_TET || !l || M->ncoord != l->k || M->nring < 1)
    return ss_error_set(err, SS_EINPUT, "tet spokes: not a tet vertex case of this link");
  for (int r = 0; r < M->nring; r++)
    if (!M->ring[r].coord)
      return ss_error_set(err, SS_EINPUT, "tet spokes: ring level %d has no coordinates",
                          r);
  const double t0 = ss_clock_cpu();
  tet_ctx T;
  ss_status st = ctx_open(&T, M, l, x, err);
  if (!st) {
    out->spoke = calloc((size_t)l->k + 1, sizeof *out->spoke);
    if (!out->spoke) st = ss_error_nomem(err, "tet spokes");
  }
  for (int a = 0; a < l->k && !st; a++) {
    ss_psi_spoke *sp = &out->spoke[out->n++];
    st = one_spoke(s, &T, a, sp, err);
    out->none += sp->cls == SS_SPOKE_ONE_SIGN;
    out->nchange += sp->cls == SS_SPOKE_SIGN_CHANGE;
    out->ndegenerate += sp->cls == SS_SPOKE_DEGENERATE;
  }
  if (nskipped) *nskipped = T.skipped;
  ctx_close(&T);
  if (st) ss_psi_spokes_free(out);
  out->seconds = ss_clock_cpu() - t0;
  return st;
}
