/* test_psi_spoke_tet.c — the spokes of tet/oct vertex cases from the edge
 * case's local matrix (ss_psi_tet.h):
 *   - the label map on the ring: round every spoke point of even t, every
 *     edge-case label y_i that lands names a ring point whose row (the
 *     global rule, read from the ring level) is S's row i of the edge case,
 *     entry for entry, with S's columns y_j mapped round the coarse spoke
 *     point t/2 e_a of the previous level (the two-ring for ring level 0):
 *     octahedron (valence 4), icosahedron (5), a k = 9 link (3..6);
 *   - the sign: on the icosahedron, whose net passes, every spoke has the
 *     ring's sign, and on the k = 9 link every spoke of valences 3, 4, 5, 6
 *     (sigma differs between them: -1, +1, -1, -1);
 *   - a second path to the sign: the matched neighbourhood X of each usable
 *     spoke point refined 10 times by the edge's S alone (no eigenvectors),
 *     the tets of the edge case's cells at its centre are all of the sign
 *     of s (det Dpsi in the tube);
 *   - basis covariance: the net x G + b gives s det G at every spoke;
 *   - a reflection of the link fixing spokes (the MLCA test's k = 9 link,
 *     det R = +1, derived in test_psi_spoke.c): those spokes are degenerate
 *     (relative |s| at rounding), the others not, and psi fails;
 *   - relabelling: the same link with its vertices renamed gives the same
 *     class per spoke (mapped) and one common sign factor. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ss_dense.h"
#include "ss_eigvec.h"
#include "ss_link.h"
#include "ss_local.h"
#include "ss_pipeline.h"
#include "ss_psi_tet.h"
#include "ss_scheme.h"
#include "ss_test.h"

/* k = 9, undecided by the net (4 inverted cells along spokes on ring level
 * 2, shrinking): spokes of valences 3, 4, 5, 6. */
static const char *const K9 = "9 bcdefg,agc,abgd,acghe,adhif,aeihg,afhdcb,dgfie,ehf";
/* k = 9 with reflections fixing spokes (tests/psi/test_psi_spoke.c). */
static const char *const KR = "9 bcdefghi,aic,abied,ace,adcigf,aeg,afeih,agi,ahgecb";

static ss_link *parse(const char *text) {
  ss_link *l = NULL;
  ss_error err = {0};
  if (ss_link_named(text, &l, &err) && ss_link_parse(text, &l, &err)) {
    fprintf(stderr, "%s: %s\n", text, err.msg);
    return NULL;
  }
  return l;
}

/* The tet/oct vertex case of l with every ring level, whole (as
 * ss_psi_tet_judge reads it). */
static ss_local *deep_case(const ss_scheme *s, const ss_link *l) {
  const ss_case c = {SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0};
  ss_local *M = NULL;
  ss_error err = {0};
  ss_local_opts o = ss_local_defaults();
  o.nring = SS_LOCAL_MAXRING;
  o.whole = 1;
  if (ss_local_new_opts(s, &c, &o, &M, &err)) {
    fprintf(stderr, "local: %s\n", err.msg);
    return NULL;
  }
  return M;
}

/* The point of ring level r (r = -1: the two-ring) with coordinates c. */
static size_t find(const ss_local *M, int r, const ss_star_coord *c) {
  if (r < 0) return ss_local_label_index(M, c);
  const ss_local_ring *R = M->ring + r;
  for (size_t i = 0; i < R->nv; i++)
    if (!ss_star_coord_cmp(R->coord + i, c)) return i;
  return SIZE_MAX;
}

/* Row i of S of edge model m against the ring's row round spoke point
 * t e_a of level r (t even): 1 equal, 0 different, -1 not comparable. */
static int same_row(const ss_local *M, const ss_psi_tet_edge *m, int a, const int *nb,
                    int r, int t, size_t i) {
  const ss_local *E = m->E;
  ss_star_coord f, q;
  if (ss_psi_tet_map_label(a, nb, m->n, t, E->label + i, &f)) return -1;
  const size_t fi = find(M, r, &f);
  if (fi == SIZE_MAX) return -1;
  const ss_local_ring *R = M->ring + r;
  size_t nnz = 0;
  for (size_t j = 0; j < E->n2; j++) {
    const double w = E->S[i * E->n2 + j];
    if (w == 0.0) continue;
    nnz++;
    if (ss_psi_tet_map_label(a, nb, m->n, t / 2, E->label + j, &q)) return 0;
    const size_t qi = find(M, r - 1, &q);
    int hit = 0;
    for (size_t e = R->ptr[fi]; e < R->ptr[fi + 1]; e++)
      if (R->col[e] == qi) hit = fabs(R->w[e] - w) <= 1e-13;
    if (!hit) return 0;
  }
  size_t nz = 0;
  for (size_t e = R->ptr[fi]; e < R->ptr[fi + 1]; e++)
    nz += R->w[e] != 0.0;
  return nz == nnz;
}

static void rows(const ss_scheme *s, const char *text) {
  ss_link *l = parse(text);
  ss_local *M = l ? deep_case(s, l) : NULL;
  if (!M) {
    CHECK(0, "%s: case", text);
    ss_link_free(l);
    return;
  }
  for (int a = 0; a < l->k; a++) {
    const int n = ss_link_deg(l, a);
    ss_psi_tet_edge *m = NULL;
    ss_error err = {0};
    if (ss_psi_tet_edge_new(s, n, &m, &err)) {
      CHECK(0, "edge %d: %s", n, err.msg);
      continue;
    }
    size_t equal = 0, differ = 0, centre = 0;
    for (int r = 0; r < M->nring; r++)
      for (size_t v = 0; v < M->ring[r].nv; v++) {
        const ss_star_coord *c = M->ring[r].coord + v;
        /* the claim: round a point whose labels all keep e_a >= 1 */
        if (c->n != 1 || c->idx[0] != a || c->val[0] % 2 ||
            c->val[0] / 2 <= (int)m->emaxneg)
          continue;
        for (size_t i = 0; i < m->E->n2; i++) {
          const int k = same_row(M, m, a, l->nbr + l->off[a], r, c->val[0], i);
          equal += k == 1;
          differ += k == 0;
          centre += k == 1 && i == 0;
        }
      }
    CHECK(differ == 0 && centre >= 2 && equal >= m->E->n2,
          "%s spoke %c (valence %d): %zu rows equal to S's, %zu differ, %zu at the "
          "spoke point itself",
          text, 'a' + a, n, equal, differ, centre);
    ss_psi_tet_edge_free(m);
  }
  ss_local_free(M);
  ss_link_free(l);
}

/* The subdominant right eigenvectors of M's S as a net (n2 x 3). */
static double *eig_net(const ss_local *M) {
  ss_eigvec *v = NULL;
  ss_error err = {0};
  if (ss_eigvec_new(M->S, M->n2, 4, 1e-6, &v, &err)) return NULL;
  double *x = malloc(3 * M->n2 * sizeof *x);
  for (size_t i = 0; x && i < M->n2; i++)
    for (int d = 0; d < 3; d++)
      x[3 * i + (size_t)d] = v->right_re[(size_t)(d + 1) * M->n2 + i];
  ss_eigvec_free(v);
  return x;
}

/* The pipeline's verdicts on link text (psi judged: the spokes). */
static ss_pipeline *run(const ss_scheme *s, const ss_link *l) {
  ss_pipeline_opts o = ss_pipeline_defaults();
  o.psi_depth = 4;
  const ss_case c = {SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0};
  ss_pipeline *p = NULL;
  ss_error err = {0};
  if (ss_pipeline_compute(s, &c, &o, SS_PIPE_VERDICTS, NULL, &p, &err) || !p->cm) {
    fprintf(stderr, "pipeline: %s\n", err.msg);
    ss_pipeline_free(p);
    return NULL;
  }
  return p;
}

/* Every spoke of one sign, the ring's (sign) when sign != 0. */
static void all_of_sign(const ss_psi_spokes *sk, int sign, const char *what) {
  for (size_t i = 0; i < sk->n; i++)
    CHECK(sk->spoke[i].cls == SS_SPOKE_ONE_SIGN && sk->spoke[i].sign == sign &&
              sk->spoke[i].nsamples == 18 && sk->spoke[i].relmin > 1e-3,
          "%s spoke %c (valence %d): class %d, sign %d (ring %d), %zu points, relative "
          "|s| >= %g",
          what, 'a' + sk->spoke[i].vertex, sk->spoke[i].valence, sk->spoke[i].cls,
          sk->spoke[i].sign, sign, sk->spoke[i].nsamples, sk->spoke[i].relmin);
}

/* x pushed to ring level r of M (malloc'd). */
static double *pushed(const ss_local *M, const double *x, int r) {
  double *prev = NULL;
  const double *in = x;
  for (int q = 0; q <= r; q++) {
    const ss_local_ring *R = M->ring + q;
    double *out = calloc(3 * R->nv + 1, sizeof *out);
    for (size_t i = 0; out && i < R->nv; i++)
      for (size_t e = R->ptr[i]; e < R->ptr[i + 1]; e++)
        for (int d = 0; d < 3; d++)
          out[3 * i + (size_t)d] += R->w[e] * in[3 * R->col[e] + (size_t)d];
    free(prev);
    prev = out;
    in = out;
  }
  return prev;
}

/* The second path round spoke point t e_a of level r: the matched points
 * refined 40 times by the edge's S (centred and rescaled each time), then
 * the sign of every tet of the edge case at its centre: +1 or -1 when all
 * agree, 0 when they do not, 2 when the point is not usable. */
static int refined_sign(const ss_local *M, const double *net, const ss_psi_tet_edge *m,
                        const ss_link *l, int a, int r, int t) {
  const ss_local *E = m->E;
  const size_t n2 = E->n2;
  double *X = malloc(3 * n2 * sizeof *X), *Y = malloc(3 * n2 * sizeof *Y);
  int sign = 2;
  for (size_t j = 0; j < n2; j++) {
    ss_star_coord c;
    size_t q = SIZE_MAX;
    if (!ss_psi_tet_map_label(a, l->nbr + l->off[a], m->n, t, E->label + j, &c))
      q = find(M, r, &c);
    if (q == SIZE_MAX || t <= (int)m->emaxneg) goto done;
    memcpy(X + 3 * j, net + 3 * q, 3 * sizeof *X);
  }
  for (int step = 0; step < 40; step++) {
    double big = 0.0;
    for (size_t i = 0; i < n2; i++)
      for (int d = 0; d < 3; d++) {
        double v = 0.0;
        for (size_t j = 0; j < n2; j++)
          v += E->S[i * n2 + j] * (X[3 * j + (size_t)d] - X[(size_t)d]);
        Y[3 * i + (size_t)d] = v;
        if (fabs(v) > big) big = fabs(v);
      }
    for (size_t i = 0; i < 3 * n2; i++)
      X[i] = Y[i] / big;
  }
  int pos = 0, neg = 0;
  for (size_t c = 0; c < E->ncells; c++) {
    const size_t *v = E->corner + c * SS_MAXCELLVERTS;
    if (E->ctype[c] != SS_TET || (v[0] && v[1] && v[2] && v[3])) continue;
    double e[3][3];
    for (int k = 0; k < 3; k++)
      for (int d = 0; d < 3; d++)
        e[k][d] = X[3 * v[k + 1] + (size_t)d] - X[3 * v[0] + (size_t)d];
    const double det = ss_dense_det3(e[0], e[1], e[2]);
    pos += det > 0.0;
    neg += det < 0.0;
  }
  sign = pos && !neg ? 1 : neg && !pos ? -1 : 0;
done:
  free(X);
  free(Y);
  return sign;
}

/* The second path at every spoke point of every level: sign as expected
 * (the spoke's) wherever usable; returns the points compared. */
static size_t second_path(const ss_scheme *s, const ss_local *M, const double *x,
                          const ss_link *l, const ss_psi_spokes *sk, const char *what) {
  size_t compared = 0;
  for (int r = 0; r < M->nring; r++) {
    double *net = pushed(M, x, r);
    for (size_t i = 0; net && i < sk->n; i++) {
      const ss_psi_spoke *sp = &sk->spoke[i];
      ss_psi_tet_edge *m = NULL;
      ss_error err = {0};
      if (ss_psi_tet_edge_new(s, sp->valence, &m, &err)) continue;
      for (size_t v = 0; v < M->ring[r].nv; v++) {
        const ss_star_coord *c = M->ring[r].coord + v;
        if (c->n != 1 || c->idx[0] != sp->vertex) continue;
        const int g = refined_sign(M, net, m, l, sp->vertex, r, c->val[0]);
        if (g == 2) continue;
        compared++;
        CHECK(g == sp->sign,
              "%s spoke %c, level %d, t = %d: refined tets of sign %d, s %d", what,
              'a' + sp->vertex, r, c->val[0], g, sp->sign);
      }
      ss_psi_tet_edge_free(m);
    }
    free(net);
  }
  return compared;
}

/* G = a fixed matrix of negative determinant, b a shift. */
static void covariance(const ss_scheme *s, const ss_local *M, const double *x,
                       const ss_link *l, const ss_psi_spokes *sk) {
  const double G[3][3] = {{0.3, 1.1, -0.2}, {0.9, -0.4, 0.5}, {0.2, 0.7, 1.3}};
  const double b[3] = {5.0, -3.0, 2.0};
  const double dg = ss_dense_det3(G[0], G[1], G[2]);
  double *y = malloc(3 * M->n2 * sizeof *y);
  for (size_t i = 0; i < M->n2; i++)
    for (int e = 0; e < 3; e++) {
      double v = b[e];
      for (int d = 0; d < 3; d++)
        v += x[3 * i + (size_t)d] * G[d][e];
      y[3 * i + (size_t)e] = v;
    }
  ss_psi_spokes sy;
  ss_error err = {0};
  if (ss_psi_tet_spokes_classify(s, M, l, y, &sy, NULL, &err)) {
    CHECK(0, "classify x G + b: %s", err.msg);
    free(y);
    return;
  }
  CHECK(dg < 0.0 && sy.n == sk->n, "det G %g, %zu spokes", dg, sy.n);
  for (size_t i = 0; i < sy.n && i < sk->n; i++) {
    const ss_psi_spoke *p = &sk->spoke[i], *q = &sy.spoke[i];
    CHECK(q->cls == p->cls && q->sign == -p->sign && q->nsamples == p->nsamples &&
              fabs(q->smin - fabs(dg) * p->smin) <= 1e-9 * q->smin &&
              fabs(q->smax - fabs(dg) * p->smax) <= 1e-9 * q->smax,
          "spoke %c: x G + b gives s det G (|s| in [%g, %g] against [%g, %g] |det G|)",
          'a' + p->vertex, q->smin, q->smax, p->smin, p->smax);
  }
  ss_psi_spokes_free(&sy);
  free(y);
}

/* The k = 9 link: every spoke of the ring's sign, by both paths; the
 * pipeline passes it by evidence; covariance. */
static void undecided_k9(const ss_scheme *s) {
  ss_link *l = parse(K9);
  ss_pipeline *p = l ? run(s, l) : NULL;
  ss_local *M = p ? deep_case(s, p->c.judged.link) : NULL;
  ss_psi_spokes sk;
  ss_error err = {0};
  if (!M ||
      ss_psi_tet_spokes_classify(s, M, p->c.judged.link, p->cm->x, &sk, NULL, &err)) {
    CHECK(0, "k = 9: spokes classified: %s", err.msg);
    goto done;
  }
  CHECK(p->reg.verdict.verdict == SS_UNDECIDED && p->reg.sign != 0,
        "k = 9: the net leaves regularity undecided");
  all_of_sign(&sk, p->reg.sign, "k = 9");
  const size_t n = second_path(s, M, p->cm->x, p->c.judged.link, &sk, "k = 9");
  CHECK(n == 18 * sk.n, "k = 9: %zu points by the second path", n);
  CHECK(p->psi.ran && p->psi.by_spokes && p->v.reg.verdict == SS_PASS &&
            p->v.reg.on == SS_ON_PSI && !p->v.reg.certified,
        "k = 9: passes on psi by evidence: %s", p->v.reg.reason);
  covariance(s, M, p->cm->x, p->c.judged.link, &sk);
  ss_psi_spokes_free(&sk);
done:
  ss_local_free(M);
  ss_pipeline_free(p);
  ss_link_free(l);
}

/* The icosahedron, whose net passes: every spoke (valence 5) of the ring's
 * sign, by both paths. */
static void icosahedron(const ss_scheme *s) {
  ss_link *l = parse("icosahedron");
  ss_pipeline *p = l ? run(s, l) : NULL;
  ss_local *M = p ? deep_case(s, p->c.judged.link) : NULL;
  ss_psi_spokes sk;
  ss_error err = {0};
  if (!M ||
      ss_psi_tet_spokes_classify(s, M, p->c.judged.link, p->cm->x, &sk, NULL, &err)) {
    CHECK(0, "icosahedron: spokes classified: %s", err.msg);
    goto done;
  }
  CHECK(p->reg.verdict.verdict == SS_PASS && sk.n == 12, "icosahedron: the net passes");
  all_of_sign(&sk, p->reg.sign, "icosahedron");
  CHECK(second_path(s, M, p->cm->x, p->c.judged.link, &sk, "icosahedron") == 18 * sk.n,
        "icosahedron: 18 points per spoke by the second path");
  CHECK(!p->psi.ran, "icosahedron: the net decides, the spokes are not consulted");
  ss_psi_spokes_free(&sk);
done:
  ss_local_free(M);
  ss_pipeline_free(p);
  ss_link_free(l);
}

/* Whether automorphism g of l reverses orientation (v's rotation maps to
 * g(v)'s read backwards). */
static int reverses(const ss_link *l, const int *g) {
  const int *nb = l->nbr + l->off[0], *ng = l->nbr + l->off[g[0]];
  const int n = ss_link_deg(l, 0);
  int at = 0;
  while (at < n && ng[at] != g[nb[0]])
    at++;
  return at < n && ng[(at + 1) % n] != g[nb[1]];
}

/* The classification of l's spokes with the net of l's own eigenvectors
 * (l's labelling kept). */
static int classify_link(const ss_scheme *s, const ss_link *l, ss_psi_spokes *sk) {
  ss_local *M = deep_case(s, l);
  double *x = M ? eig_net(M) : NULL;
  ss_error err = {0};
  int rc = !x || ss_psi_tet_spokes_classify(s, M, l, x, sk, NULL, &err);
  if (rc) fprintf(stderr, "classify: %s\n", err.msg);
  free(x);
  ss_local_free(M);
  return rc;
}

/* KR: a spoke fixed by a reflection of the link is degenerate exactly when
 * ... the others are of one sign, of both signs between them; the same
 * classes after renaming the vertices. */
static void reflection(const ss_scheme *s) {
  ss_link *l = parse(KR), *q = NULL;
  ss_psi_spokes sk, sq;
  int *aut = NULL, naut = 0;
  ss_error err = {0};
  if (!l || classify_link(s, l, &sk) || ss_link_automorphisms(l, &aut, &naut, &err)) {
    CHECK(0, "KR: classified");
    ss_link_free(l);
    return;
  }
  int fixed[64] = {0}, pos = 0, neg = 0;
  for (int i = 0; i < naut; i++)
    if (reverses(l, aut + i * l->k))
      for (int v = 0; v < l->k; v++)
        fixed[v] |= aut[i * l->k + v] == v;
  for (size_t i = 0; i < sk.n; i++) {
    const ss_psi_spoke *sp = &sk.spoke[i];
    if (fixed[sp->vertex])
      CHECK(sp->cls == SS_SPOKE_DEGENERATE && sp->ndegenerate == sp->nsamples &&
                sp->relmin < 1e-12,
            "KR spoke %c, fixed by a reflection: degenerate (class %d, relative |s| %g)",
            'a' + sp->vertex, sp->cls, sp->relmin);
    else
      CHECK(sp->cls == SS_SPOKE_ONE_SIGN && sp->relmin > 1e-4,
            "KR spoke %c: of one sign (class %d, relative |s| %g)", 'a' + sp->vertex,
            sp->cls, sp->relmin);
    pos += sp->cls == SS_SPOKE_ONE_SIGN && sp->sign > 0;
    neg += sp->cls == SS_SPOKE_ONE_SIGN && sp->sign < 0;
  }
  CHECK(fixed[2] && fixed[4] && fixed[6] && fixed[8] && pos && neg,
        "KR: reflections fix c, e, g, i; spokes of both signs (%d, %d)", pos, neg);
  /* renamed: v -> (v * 4 + 3) mod 9, a bijection */
  int deg[64], nbr[512], m = 0, perm[64];
  for (int v = 0; v < l->k; v++)
    perm[v] = (v * 4 + 3) % l->k;
  for (int w = 0; w < l->k; w++)
    for (int v = 0; v < l->k; v++) {
      if (perm[v] != w) continue;
      deg[w] = ss_link_deg(l, v);
      for (int j = l->off[v]; j < l->off[v + 1]; j++)
        nbr[m++] = perm[l->nbr[j]];
    }
  if (ss_link_new(l->k, deg, nbr, &q, &err) || classify_link(s, q, &sq)) {
    CHECK(0, "KR renamed: %s", err.msg);
  } else {
    int factor = 0;
    for (size_t i = 0; i < sk.n; i++) {
      const ss_psi_spoke *a = &sk.spoke[i], *b = &sq.spoke[perm[a->vertex]];
      if (a->cls == SS_SPOKE_ONE_SIGN && !factor) factor = a->sign * b->sign;
      CHECK(b->cls == a->cls && b->valence == a->valence &&
                (a->cls != SS_SPOKE_ONE_SIGN || b->sign == factor * a->sign),
            "KR spoke %c renamed %c: class %d / %d, sign %d / %d", 'a' + a->vertex,
            'a' + b->vertex, a->cls, b->cls, a->sign, b->sign);
    }
    ss_psi_spokes_free(&sq);
  }
  ss_psi_spokes_free(&sk);
  free(aut);
  ss_link_free(q);
  ss_link_free(l);
}

int main(void) {
  ss_scheme *s = NULL;
  ss_error err = {0};
  if (ss_scheme_new("tetoct", &s, &err)) {
    CHECK(0, "tetoct: %s", err.msg);
    return ss_test_done("psi_spoke_tet");
  }
  rows(s, "octahedron");
  rows(s, "icosahedron");
  rows(s, K9);
  icosahedron(s);
  undecided_k9(s);
  reflection(s);
  ss_scheme_free(s);
  return ss_test_done("psi_spoke_tet");
}
