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
 * out->found and the fields that go with it. */
static void try_map(const ss_charmap *cm, const ss_local *M, const chart_map *g,
                    size_t *P, unsigned char *seen, const char *what, int reverses,
                    ss_charmap_sym *out) {
  const size_t n = M->n2;
  const int m = cm->dim;
  memset(seen, 0, n);
  size_t moved = 0;
  for (size_t i = 0; i < n; i++) {
    const ss_star_coord y = map_label(g, M->label + i);
    P[i] = ss_local_label_index(M, &y);
    if (P[i] == SIZE_MAX || seen[P[i]]) return; /* not a symmetry of the two-ring */
    seen[P[i]] = 1;
    moved += P[i] != i;
  }
  if (!moved) return;            /* the identity on the two-ring */
  for (size_t i = 0; i < n; i++) /* P S = S P, entry by entry */
    for (size_t j = 0; j < n; j++) {
      const double a = M->S[i * n + j];
      if (a != 0.0 && !(fabs(M->S[P[i] * n + P[j]] - a) <= 1e-12)) return;
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
    if (!(fabs(A[col][col]) > 0.0)) return;
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
  if (!(res <= 1e-12 * xn)) return;
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
  }
}

ss_status ss_charmap_symmetry(const ss_charmap *cm, const ss_local *M, const ss_case *c,
                              ss_charmap_sym *out, ss_error *err) {
  memset(out, 0, sizeof *out);
  const int nc = M->ncoord;
  if (cm->n != M->n2 || nc < 1 || (c->kind == SS_CASE_VERTEX && !c->link) ||
      (c->kind == SS_CASE_VERTEX && c->link->k != nc))
    return ss_error_set(err, SS_EINPUT, "symmetry test: the case does not match the map");
  size_t *P = malloc((M->n2 + 1) * sizeof *P);
  unsigned char *seen = malloc(M->n2 + 1);
  int *perm = malloc((size_t)nc * sizeof *perm);
  int *aut = NULL, naut = 0;
  ss_status st = SS_OK;
  if (!P || !seen || !perm) {
    st = ss_error_nomem(err, "symmetry test");
    goto done;
  }
  chart_map g = {nc, perm, -1};
  char what[160];
  if (c->kind == SS_CASE_VERTEX) {
    if ((st = ss_link_automorphisms(c->link, &aut, &naut, err))) goto done;
    /* an automorphism keeps the orientation iff it maps the link's first
     * oriented triangle (0, w, w'), w' after w around 0, to an oriented one */
    const ss_link *l = c->link;
    const int w0 = l->nbr[l->off[0]], w1 = l->nbr[l->off[0] + 1];
    for (int a = 1; a < naut && !(out->found && out->reverses); a++) { /* 0: identity */
      memcpy(perm, aut + (size_t)a * (size_t)nc, (size_t)nc * sizeof *perm);
      const int v = perm[0], d = ss_link_deg(l, v);
      int pos = 0;
      while (pos < d && l->nbr[l->off[v] + pos] != perm[w0])
        pos++;
      const int reverses = l->nbr[l->off[v] + (pos + 1) % d] != perm[w1];
      snprintf(what, sizeof what, "link automorphism %d of %d (%s)", a + 1, naut,
               reverses ? "a reflection" : "orientation-preserving");
      try_map(cm, M, &g, P, seen, what, reverses, out);
    }
  } else if (c->kind == SS_CASE_EDGE || c->kind == SS_CASE_SURFACE_VERTEX) {
    /* the faces (rays) around the edge (vertex), turned by s and reflected;
     * an edge may also be flipped end for end (its coordinate n negated) */
    const int n = c->n, flips = c->kind == SS_CASE_EDGE ? 2 : 1;
    for (int f = 0; f < flips && !(out->found && out->reverses); f++)
      for (int refl = 0; refl < 2 && !(out->found && out->reverses); refl++)
        for (int s = 0; s < n && !(out->found && out->reverses); s++) {
          if (!f && !refl && !s) continue;
          for (int i = 0; i < n; i++)
            perm[i] = refl ? ((s - i) % n + n) % n : (i + s) % n;
          if (flips == 2) perm[n] = n;
          g.flip = f ? n : -1;
          snprintf(what, sizeof what, "%s by %d%s%s", refl ? "reflection" : "rotation", s,
                   c->kind == SS_CASE_EDGE ? " around the edge" : "",
                   f ? ", with the edge flipped end for end" : "");
          try_map(cm, M, &g, P, seen, what, refl != f, out);
        }
  } else if (c->kind == SS_CASE_FACE) {
    /* the centre is (2, 1, 1) in the face (0, 1, 2): the swaps 1 <-> 2 and 3 <-> 4 */
    for (int q = 1; q < 4 && !(out->found && out->reverses); q++) {
      for (int i = 0; i < nc; i++)
        perm[i] = i;
      if (q & 1) perm[1] = 2, perm[2] = 1;
      if (q & 2) perm[3] = 4, perm[4] = 3;
      snprintf(what, sizeof what, "%s%s%s", q & 1 ? "the swap of face vertices 1, 2" : "",
               q == 3 ? " and " : "", q & 2 ? "the swap of the two tets" : "");
      try_map(cm, M, &g, P, seen, what, q != 3, out);
    }
  }
done:
  free(P);
  free(seen);
  free(perm);
  free(aut);
  return st;
}
