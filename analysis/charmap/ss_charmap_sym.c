/* ss_charmap_sym.c — symmetries of a case that the characteristic map does not
 * see (psi o sigma = psi): a certain failure of injectivity.  Method:
 * ss_charmap.h. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_charmap.h"
#include "ss_link.h"

/* One candidate symmetry: chart index i goes to perm[i]; the entry of index
 * `flip` (or none, -1) changes sign. */
typedef struct {
  int ncoord; /* chart dimension */
  int *perm;  /* ncoord images */
  int flip;   /* signed index negated, or -1 */
} chart_map;

/* The label of sigma(x). */
static ss_star_coord map_label(const chart_map *g, const ss_star_coord *x) {
  int32_t idx[SS_STAR_MAXSUPP], val[SS_STAR_MAXSUPP];
  for (int e = 0; e < x->n; e++) {
    idx[e] = g->perm[x->idx[e]];
    val[e] = x->idx[e] == g->flip ? -x->val[e] : x->val[e];
  }
  return ss_star_coord_make(x->n, idx, val);
}

static size_t gcd(size_t a, size_t b) {
  while (b) {
    const size_t t = a % b;
    a = b;
    b = t;
  }
  return a;
}

/* Test one candidate; P (n2 entries) and seen (n2 bytes) are scratch.  Sets
 * out->found and the fields that go with it, and returns 1, when it is kept. */
static int try_map(const ss_charmap *cm, const ss_local *M, const chart_map *g, size_t *P,
                   unsigned char *seen, const char *what, int reverses,
                   ss_charmap_sym *out) {
  const size_t n = M->n2;
  const int m = cm->dim;
  memset(seen, 0, n);
  size_t moved = 0;
  for (size_t i = 0; i < n; i++) {
    const ss_star_coord y = map_label(g, M->label + i);
    P[i] = ss_local_label_index(M, &y);
    if (P[i] == SIZE_MAX || seen[P[i]]) return 0; /* not a symmetry of the two-ring */
    seen[P[i]] = 1;
    moved += P[i] != i;
  }
  if (!moved) return 0;          /* the identity on the two-ring */
  for (size_t i = 0; i < n; i++) /* P S = S P, entry by entry */
    for (size_t j = 0; j < n; j++) {
      const double a = M->S[i * n + j];
      if (a != 0.0 && !(fabs(M->S[P[i] * n + P[j]] - a) <= 1e-12)) return 0;
    }
  out->tested++;
  /* M_sigma from P X = X M_sigma: normal equations (X is normalised, so
   * X^T X is well conditioned) */
  double G[9] = {0}, R[9] = {0}, Ms[9], xn = 0.0, res = 0.0;
  for (size_t i = 0; i < n; i++)
    for (int a = 0; a < m; a++) {
      const double xa = cm->x[i * (size_t)m + (size_t)a];
      xn += xa * xa;
      for (int b = 0; b < m; b++) {
        G[a * m + b] += xa * cm->x[i * (size_t)m + (size_t)b];
        R[a * m + b] += xa * cm->x[P[i] * (size_t)m + (size_t)b];
      }
    }
  /* Ms = G^-1 R by Gaussian elimination with partial pivoting (m <= 3) */
  double A[3][6];
  for (int a = 0; a < m; a++)
    for (int b = 0; b < m; b++)
      A[a][b] = G[a * m + b], A[a][m + b] = R[a * m + b];
  for (int col = 0; col < m; col++) {
    int piv = col;
    for (int r = col + 1; r < m; r++)
      if (fabs(A[r][col]) > fabs(A[piv][col])) piv = r;
    for (int q = 0; q < 2 * m; q++) {
      const double t = A[col][q];
      A[col][q] = A[piv][q];
      A[piv][q] = t;
    }
    if (!(fabs(A[col][col]) > 0.0)) return 0;
    for (int r = 0; r < m; r++) {
      if (r == col) continue;
      const double f = A[r][col] / A[col][col];
      for (int q = 0; q < 2 * m; q++)
        A[r][q] -= f * A[col][q];
    }
  }
  for (int a = 0; a < m; a++)
    for (int b = 0; b < m; b++)
      Ms[a * m + b] = A[a][m + b] / A[a][a];
  for (size_t i = 0; i < n; i++) /* the subspace must be invariant */
    for (int b = 0; b < m; b++) {
      double v = cm->x[P[i] * (size_t)m + (size_t)b];
      for (int a = 0; a < m; a++)
        v -= cm->x[i * (size_t)m + (size_t)a] * Ms[a * m + b];
      res += v * v;
    }
  if (!(res <= 1e-12 * xn)) return 0;
  /* the order of sigma on the two-ring: the lcm of P's cycle lengths */
  size_t order = 1;
  memset(seen, 0, n);
  for (size_t i = 0; i < n; i++) {
    if (seen[i]) continue;
    size_t len = 0;
    for (size_t j = i; !seen[j]; j = P[j], len++)
      seen[j] = 1;
    order = order / gcd(order, len) * len;
  }
  double dist = 0.0;
  for (int a = 0; a < m; a++)
    for (int b = 0; b < m; b++) {
      const double d = Ms[a * m + b] - (a == b ? 1.0 : 0.0);
      dist += d * d;
    }
  dist = sqrt(dist);
  const double gap = 2.0 * sin(M_PI / (double)order);
  if (dist < 0.5 * gap && (!out->found || (reverses && !out->reverses))) {
    out->found = 1;
    out->reverses = reverses;
    out->order = (int)order;
    out->moved = moved;
    out->distance = dist;
    out->gap = gap;
    snprintf(out->what, sizeof out->what, "%s", what);
    return 1;
  }
  return 0;
}

/* The symmetries of a case, numbered 0 .. count - 1 (the identity left out). */
typedef struct {
  const ss_case *c; /* the case */
  int nc;           /* chart dimension */
  int *aut, naut;   /* vertex case: the link's automorphisms (aut[0] = id) */
} candidates;

static int cand_count(const candidates *C) {
  switch (C->c->kind) {
  case SS_CASE_VERTEX:
    return C->naut - 1;
  case SS_CASE_EDGE:
    return 4 * C->c->n - 1;
  case SS_CASE_SURFACE_VERTEX: /* the chart's rays: n, or n / 2 for a class-8
                                 vertex of quasi48 (ss_star_tri48_vertex) */
    return 2 * C->nc - 1;
  case SS_CASE_FACE:
    return 3;
  default:
    return 0;
  }
}

/* Candidate i as a chart map (perm must hold nc entries), whether it reverses
 * orientation, and in words. */
static void cand_make(const candidates *C, int i, chart_map *g, int *reverses, char *what,
                      size_t nwhat) {
  const ss_case *c = C->c;
  int *perm = g->perm;
  g->flip = -1;
  if (c->kind == SS_CASE_VERTEX) {
    /* an automorphism keeps the orientation iff it maps the link's first
     * oriented triangle (0, w, w'), w' after w around 0, to an oriented one */
    const int a = i + 1;
    memcpy(perm, C->aut + (size_t)a * (size_t)C->nc, (size_t)C->nc * sizeof *perm);
    const ss_link *l = c->link;
    const int w0 = l->nbr[l->off[0]], w1 = l->nbr[l->off[0] + 1];
    const int v = perm[0], d = ss_link_deg(l, v);
    int pos = 0;
    while (pos < d && l->nbr[l->off[v] + pos] != perm[w0])
      pos++;
    *reverses = l->nbr[l->off[v] + (pos + 1) % d] != perm[w1];
    snprintf(what, nwhat, "link automorphism %d of %d (%s)", a + 1, C->naut,
             *reverses ? "a reflection" : "orientation-preserving");
  } else if (c->kind == SS_CASE_EDGE || c->kind == SS_CASE_SURFACE_VERTEX) {
    /* the faces (rays) around the edge (vertex), turned by s and reflected;
     * an edge may also be flipped end for end (its coordinate n negated) */
    const int n = c->kind == SS_CASE_EDGE ? c->n : C->nc, q = i + 1, s = q % n,
              refl = (q / n) & 1, f = q / (2 * n);
    for (int j = 0; j < n; j++)
      perm[j] = refl ? ((s - j) % n + n) % n : (j + s) % n;
    if (c->kind == SS_CASE_EDGE) {
      perm[n] = n;
      g->flip = f ? n : -1;
    }
    *reverses = refl != f;
    snprintf(what, nwhat, "%s by %d%s%s", refl ? "reflection" : "rotation", s,
             c->kind == SS_CASE_EDGE ? " around the edge" : "",
             f ? ", with the edge flipped end for end" : "");
  } else {
    /* the face: the centre is (2, 1, 1) in the face (0, 1, 2), fixed by the
     * swaps 1 <-> 2 and 3 <-> 4 */
    const int q = i + 1;
    for (int j = 0; j < C->nc; j++)
      perm[j] = j;
    if (q & 1) perm[1] = 2, perm[2] = 1;
    if (q & 2) perm[3] = 4, perm[4] = 3;
    *reverses = q != 3;
    snprintf(what, nwhat, "%s%s%s", q & 1 ? "the swap of face vertices 1, 2" : "",
             q == 3 ? " and " : "", q & 2 ? "the swap of the two tets" : "");
  }
}

static ss_status cand_new(const ss_local *M, const ss_case *c, candidates *C,
                          ss_error *err) {
  memset(C, 0, sizeof *C);
  C->c = c;
  C->nc = M->ncoord;
  if (M->nring < 0 || C->nc < 1 || (c->kind == SS_CASE_VERTEX && !c->link) ||
      (c->kind == SS_CASE_VERTEX && c->link->k != C->nc) ||
      (c->kind == SS_CASE_EDGE && C->nc != c->n + 1) ||
      (c->kind == SS_CASE_SURFACE_VERTEX && C->nc != c->n && 2 * C->nc != c->n) ||
      (c->kind == SS_CASE_FACE && C->nc != 5) || c->kind == SS_CASE_EDGE_POINT)
    return ss_error_set(err, SS_EINPUT, "symmetry test: the case does not match the map");
  if (c->kind == SS_CASE_VERTEX)
    return ss_link_automorphisms(c->link, &C->aut, &C->naut, err);
  return SS_OK;
}

ss_status ss_charmap_symmetry(const ss_charmap *cm, const ss_local *M, const ss_case *c,
                              ss_charmap_sym *out, ss_error *err) {
  memset(out, 0, sizeof *out);
  if (cm->n != M->n2)
    return ss_error_set(err, SS_EINPUT, "symmetry test: the case does not match the map");
  candidates C;
  ss_status st = cand_new(M, c, &C, err);
  if (st) return st;
  size_t *P = malloc((M->n2 + 1) * sizeof *P);
  unsigned char *seen = malloc(M->n2 + 1);
  int *perm = malloc((size_t)C.nc * sizeof *perm);
  if (!P || !seen || !perm) {
    st = ss_error_nomem(err, "symmetry test");
    goto done;
  }
  chart_map g = {C.nc, perm, -1};
  char what[160];
  const int n = cand_count(&C);
  for (int i = 0; i < n && !(out->found && out->reverses); i++) {
    int reverses = 0;
    cand_make(&C, i, &g, &reverses, what, sizeof what);
    if (try_map(cm, M, &g, P, seen, what, reverses, out)) out->index = i;
  }
done:
  free(P);
  free(seen);
  free(perm);
  free(C.aut);
  return st;
}

ss_status ss_charmap_sym_perm(const ss_local *M, const ss_case *c,
                              const ss_charmap_sym *y, size_t *P, ss_error *err) {
  if (!y->found) return ss_error_set(err, SS_EINPUT, "no symmetry was found");
  candidates C;
  ss_status st = cand_new(M, c, &C, err);
  if (st) return st;
  int *perm = malloc((size_t)C.nc * sizeof *perm);
  if (!perm) {
    free(C.aut);
    return ss_error_nomem(err, "symmetry");
  }
  chart_map g = {C.nc, perm, -1};
  int reverses = 0;
  char what[160];
  if (y->index < 0 || y->index >= cand_count(&C)) {
    st = ss_error_set(err, SS_EINPUT, "symmetry %d is not one of the case's", y->index);
  } else {
    cand_make(&C, y->index, &g, &reverses, what, sizeof what);
    for (size_t i = 0; i < M->n2 && !st; i++) {
      const ss_star_coord x = map_label(&g, M->label + i);
      P[i] = ss_local_label_index(M, &x);
      if (P[i] == SIZE_MAX)
        st = ss_error_set(err, SS_EINPUT, "symmetry %d does not map the two-ring",
                          y->index);
    }
  }
  free(perm);
  free(C.aut);
  return st;
}

ss_status ss_charmap_sym_group(const ss_local *M, const ss_case *c, size_t **perms,
                               size_t *ng, ss_error *err) {
  *perms = NULL;
  *ng = 0;
  candidates C;
  ss_status st = cand_new(M, c, &C, err);
  if (st) return st;
  const size_t n = M->n2;
  const int count = cand_count(&C);
  size_t *G = malloc(((size_t)count + 1) * n * sizeof *G + 1);
  int *perm = malloc((size_t)C.nc * sizeof *perm);
  if (!G || !perm) {
    st = ss_error_nomem(err, "symmetry group");
    goto done;
  }
  for (size_t i = 0; i < n; i++) /* the identity first */
    G[i] = i;
  size_t k = 1;
  chart_map g = {C.nc, perm, -1};
  char what[160];
  for (int q = 0; q < count; q++) {
    int reverses = 0, maps = 1;
    cand_make(&C, q, &g, &reverses, what, sizeof what);
    for (size_t i = 0; i < n && maps; i++) {
      const ss_star_coord x = map_label(&g, M->label + i);
      G[k * n + i] = ss_local_label_index(M, &x);
      maps = G[k * n + i] != SIZE_MAX;
    }
    k += (size_t)maps; /* a candidate that does not map the two-ring is left out */
  }
  *perms = G;
  *ng = k;
  G = NULL;
done:
  free(G);
  free(perm);
  free(C.aut);
  return st;
}
