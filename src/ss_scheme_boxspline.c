/* ss_scheme_boxspline.c — box-spline solid subdivision (Chang, McDonnell, Qin:
 * "A new solid subdivision scheme based on box splines", sections 3.3–3.6).
 *
 * Over the tet/oct split (tets and octahedra only), every fine vertex is a
 * combination of coarse vertices:
 *   old vertex x, k = |rho(x)|:      9/16 x + 7/(16k) sum rho(x)          (3.7)
 *     (at k = 14 this is the regular rule (3.3): 18/32 x + 1/32 each)
 *   edge point of e = (a, b), k = |rho(e)|:
 *     k = 4:  8/32 (a + b) + 4/32 each                                   (3.5)
 *     else:   5/16 (a + b) + 3/(8k) each                                 (3.8)
 *     (at k = 6 this is the regular rule (3.4): 10/32 and 2/32)
 *   octahedron centre: 4/32 each corner + 4/32 more on each end of the
 *     octahedron's major diagonal                                        (3.6)
 * with rho (Definition 3.3) the neighbours by an edge or by a major diagonal of
 * an octahedron, and rho(e) = rho(a) ∩ rho(b).  Major diagonals live in the
 * vertex order (ss_split.h): an octahedron's is its pair (0, 3), and the split
 * hands every child the diagonal parallel to its parent's (Algorithm 1).
 *
 * Boundary (section 3.6, figure 14): vertices and edges on the boundary
 * surface (triangular faces held by one cell) follow Loop's rules on that
 * surface: a vertex with n boundary neighbours (1 - n beta) x + beta each,
 * beta = (5/8 - (3/8 + cos(2 pi / n) / 4)^2) / n; an edge 3/8 (a + b) + 1/8
 * of the vertex opposite it in each of its two boundary triangles (split
 * evenly when the boundary is not a manifold there). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ss_scheme_impl.h"

/* Sorted adjacency lists of the coarse vertices. */
typedef struct {
  size_t *ptr; /* nv + 1 */
  ss_idx *nb;  /* neighbours, sorted, distinct within a list */
} adjacency;

static void adj_free(adjacency *A) {
  free(A->ptr);
  free(A->nb);
}

static int cmp_idx(const void *a, const void *b) {
  const ss_idx x = *(const ss_idx *)a, y = *(const ss_idx *)b;
  return (x > y) - (x < y);
}

/* Build lists from the pairs (a[i], b[i]), i < n, both directions; duplicates
 * dropped.  0 or -1 without memory. */
static int adj_make(size_t nv, size_t n, const ss_idx *pairs, adjacency *A) {
  A->ptr = calloc(nv + 2, sizeof *A->ptr);
  A->nb = malloc((2 * n + 1) * sizeof *A->nb);
  if (!A->ptr || !A->nb) return -1;
  for (size_t i = 0; i < 2 * n; i++)
    A->ptr[pairs[i] + 2]++;
  for (size_t v = 0; v < nv; v++)
    A->ptr[v + 2] += A->ptr[v + 1];
  for (size_t i = 0; i < n; i++) {
    const ss_idx a = pairs[2 * i], b = pairs[2 * i + 1];
    A->nb[A->ptr[a + 1]++] = b;
    A->nb[A->ptr[b + 1]++] = a;
  }
  /* sort each list and squeeze out repeats, compacting in place */
  size_t out = 0;
  for (size_t v = 0; v < nv; v++) {
    const size_t b = A->ptr[v], e = A->ptr[v + 1];
    qsort(A->nb + b, e - b, sizeof *A->nb, cmp_idx);
    const size_t start = out;
    for (size_t q = b; q < e; q++)
      if (q == b || A->nb[q] != A->nb[q - 1]) A->nb[out++] = A->nb[q];
    A->ptr[v] = start;
  }
  A->ptr[nv] = out;
  return 0;
}

/* Triangular faces of the coarse cells, as sorted triples with the opposite
 * vertex of their cell. */
typedef struct {
  ss_idx v[3]; /* sorted corners */
  ss_idx opp;  /* unused: keeps the struct a multiple of 4 words */
} face;

static int face_cmp(const void *a, const void *b) {
  return memcmp(a, b, 3 * sizeof(ss_idx));
}

static face make_face(ss_idx a, ss_idx b, ss_idx c) {
  face f = {{a, b, c}, 0};
  for (int i = 1; i < 3; i++)
    for (int j = i; j > 0 && f.v[j - 1] > f.v[j]; j--) {
      ss_idx t = f.v[j];
      f.v[j] = f.v[j - 1];
      f.v[j - 1] = t;
    }
  return f;
}

static double loop_beta(double n) {
  const double t = 3.0 / 8.0 + cos(2.0 * M_PI / n) / 4.0;
  return (5.0 / 8.0 - t * t) / n;
}

static ss_status boxspline_rule(const ss_scheme *s, const ss_cx *coarse,
                                const ss_cx *fine, const ss_split *L, ss_sink *k,
                                ss_error *err) {
  (void)s;
  (void)fine;
  const size_t nv = coarse->nv, nt = coarse->nc[SS_TET], no = coarse->nc[SS_OCT];
  ss_status st = SS_OK;
  adjacency rho = {NULL, NULL}, bnd = {NULL, NULL};
  ss_idx *pairs = NULL, *bpairs = NULL, *common = NULL;
  face *faces = NULL;
  unsigned char *onb = NULL;
  /* coarse edges: the fine vertices with two parents */
  size_t ne = 0;
  for (size_t f = nv; f < L->nfine; f++)
    ne += ss_split_npar(L, f) == 2;
  pairs = malloc((2 * (ne + no) + 1) * sizeof *pairs);
  const size_t nf = 4 * nt + 8 * no;
  faces = malloc((nf + 1) * sizeof *faces);
  bpairs = malloc((6 * nf + 1) * sizeof *bpairs);
  onb = calloc(nv + 1, 1);
  if (!pairs || !faces || !bpairs || !onb) {
    st = ss_error_nomem(err, "box-spline neighbours");
    goto done;
  }
  size_t np = 0;
  for (size_t f = nv; f < L->nfine; f++)
    if (ss_split_npar(L, f) == 2) {
      pairs[2 * np] = L->parent[L->ptr[f]];
      pairs[2 * np + 1] = L->parent[L->ptr[f] + 1];
      np++;
    }
  for (size_t o = 0; o < no; o++) { /* major diagonals: pair (0, 3) */
    const ss_idx *v = ss_cx_cell(coarse, SS_OCT, o);
    pairs[2 * np] = v[0];
    pairs[2 * np + 1] = v[3];
    np++;
  }
  if (adj_make(nv, np, pairs, &rho)) {
    st = ss_error_nomem(err, "box-spline neighbours");
    goto done;
  }
  /* boundary: faces held by one cell */
  size_t nfa = 0;
  for (size_t t = 0; t < nt; t++) {
    const ss_idx *v = ss_cx_cell(coarse, SS_TET, t);
    for (int i = 0; i < 4; i++)
      faces[nfa++] = make_face(v[(i + 1) % 4], v[(i + 2) % 4], v[(i + 3) % 4]);
  }
  for (size_t o = 0; o < no; o++) {
    const ss_idx *v = ss_cx_cell(coarse, SS_OCT, o);
    for (int f = 0; f < 8; f++)
      faces[nfa++] = make_face(v[f & 1 ? 3 : 0], v[f & 2 ? 4 : 1], v[f & 4 ? 5 : 2]);
  }
  qsort(faces, nfa, sizeof *faces, face_cmp);
  size_t nb = 0;
  for (size_t i = 0; i < nfa;) {
    size_t j = i + 1;
    while (j < nfa && face_cmp(faces + i, faces + j) == 0)
      j++;
    if (j - i == 1) {
      const ss_idx *v = faces[i].v;
      for (int e = 0; e < 3; e++) {
        bpairs[2 * nb] = v[e];
        bpairs[2 * nb + 1] = v[(e + 1) % 3];
        nb++;
        onb[v[e]] = 1;
      }
      faces[i].opp = 1; /* mark: a boundary face */
    } else {
      for (size_t q = i; q < j; q++)
        faces[q].opp = 0;
    }
    i = j;
  }
  if (adj_make(nv, nb, bpairs, &bnd)) {
    st = ss_error_nomem(err, "box-spline boundary");
    goto done;
  }
  size_t maxdeg = 0;
  for (size_t v = 0; v < nv; v++)
    maxdeg = rho.ptr[v + 1] - rho.ptr[v] > maxdeg ? rho.ptr[v + 1] - rho.ptr[v] : maxdeg;
  common = malloc((maxdeg + 1) * sizeof *common);
  if (!common) {
    st = ss_error_nomem(err, "box-spline neighbours");
    goto done;
  }
  /* old vertices */
  for (size_t x = 0; x < nv; x++) {
    if (onb[x]) {
      const size_t n = bnd.ptr[x + 1] - bnd.ptr[x];
      const double beta = n ? loop_beta((double)n) : 0.0;
      ss_sink_emit(k, x, x, 1.0 - (double)n * beta);
      for (size_t q = bnd.ptr[x]; q < bnd.ptr[x + 1]; q++)
        ss_sink_emit(k, x, bnd.nb[q], beta);
      continue;
    }
    const size_t n = rho.ptr[x + 1] - rho.ptr[x];
    if (n == 0) { /* a vertex in no cell keeps its place */
      ss_sink_emit(k, x, x, 1.0);
      continue;
    }
    ss_sink_emit(k, x, x, 9.0 / 16.0);
    for (size_t q = rho.ptr[x]; q < rho.ptr[x + 1]; q++)
      ss_sink_emit(k, x, rho.nb[q], 7.0 / (16.0 * (double)n));
  }
  /* edge points and octahedron centres */
  for (size_t f = nv; f < L->nfine; f++) {
    const size_t npar = ss_split_npar(L, f);
    const ss_idx *par = L->parent + L->ptr[f];
    if (npar == 2) {
      const ss_idx a = par[0], b = par[1];
      if (onb[a] && onb[b]) {
        /* a boundary edge: the vertices opposite it in boundary triangles */
        size_t m = 0;
        for (size_t q = bnd.ptr[a]; q < bnd.ptr[a + 1]; q++) {
          const ss_idx c = bnd.nb[q];
          if (c == b) continue;
          face t = make_face(a, b, c);
          const face *hit = bsearch(&t, faces, nfa, sizeof *faces, face_cmp);
          /* bsearch finds some copy; a boundary face occurs once */
          if (hit && hit->opp) common[m++] = c;
        }
        if (m > 0) {
          ss_sink_emit(k, f, a, 3.0 / 8.0);
          ss_sink_emit(k, f, b, 3.0 / 8.0);
          for (size_t i = 0; i < m; i++)
            ss_sink_emit(k, f, common[i], 0.25 / (double)m);
          continue;
        }
      }
      /* rho(e): the sorted intersection of rho(a) and rho(b) */
      size_t m = 0, p = rho.ptr[a], q = rho.ptr[b];
      while (p < rho.ptr[a + 1] && q < rho.ptr[b + 1]) {
        if (rho.nb[p] < rho.nb[q])
          p++;
        else if (rho.nb[p] > rho.nb[q])
          q++;
        else
          common[m++] = rho.nb[p], p++, q++;
      }
      if (m == 0) {
        ss_sink_emit(k, f, a, 0.5);
        ss_sink_emit(k, f, b, 0.5);
      } else if (m == 4) {
        ss_sink_emit(k, f, a, 8.0 / 32.0);
        ss_sink_emit(k, f, b, 8.0 / 32.0);
        for (size_t i = 0; i < m; i++)
          ss_sink_emit(k, f, common[i], 4.0 / 32.0);
      } else {
        ss_sink_emit(k, f, a, 5.0 / 16.0);
        ss_sink_emit(k, f, b, 5.0 / 16.0);
        for (size_t i = 0; i < m; i++)
          ss_sink_emit(k, f, common[i], 3.0 / (8.0 * (double)m));
      }
    } else if (npar != 1 && npar != 6) {
      st = ss_error_set(err, SS_EINTERNAL, "fine vertex %zu with %zu parents", f, npar);
      goto done;
    }
  }
  /* octahedron centres: the split adds one per coarse octahedron, in order,
   * after the edge midpoints it creates; find each by its six parents */
  {
    size_t oc = 0;
    for (size_t f = nv; f < L->nfine && oc < no; f++) {
      if (ss_split_npar(L, f) != 6) continue;
      const ss_idx *v = ss_cx_cell(coarse, SS_OCT, oc);
      ss_idx sorted[6];
      memcpy(sorted, v, sizeof sorted);
      qsort(sorted, 6, sizeof *sorted, cmp_idx);
      if (memcmp(sorted, L->parent + L->ptr[f], sizeof sorted) != 0) {
        st = ss_error_set(err, SS_EINTERNAL,
                          "octahedron %zu: its centre is not where "
                          "the split put it",
                          oc);
        goto done;
      }
      for (int i = 0; i < 6; i++)
        ss_sink_emit(k, f, v[i], (i == 0 || i == 3 ? 8.0 : 4.0) / 32.0);
      oc++;
    }
    if (oc != no) st = ss_error_set(err, SS_EINTERNAL, "octahedron centres missing");
  }
done:
  adj_free(&rho);
  adj_free(&bnd);
  free(pairs);
  free(bpairs);
  free(common);
  free(faces);
  free(onb);
  return st;
}

ss_status ss_scheme_boxspline_new(ss_scheme **out, ss_error *err) {
  const unsigned accepts = (1u << SS_TET) | (1u << SS_OCT);
  ss_status st =
      ss_scheme_alloc("boxspline", SS_SPLIT_TETOCT, accepts, boxspline_rule, out, err);
  if (!st) {
    (*out)->reach = 2; /* rho(e) reads both ends' neighbourhoods */
    (*out)->diagonals = 1;
  }
  return st;
}
