/* ss_scheme_ccsolid.c — Catmull-Clark solids: the refinement rules of Joy and
 * MacCracken (K. I. Joy, R. MacCracken, "The refinement rules for
 * Catmull-Clark solids", UC Davis tech. rep. CSE-96-1, 1996; R. MacCracken,
 * K. I. Joy, "Free-form deformations with lattices of arbitrary topology",
 * SIGGRAPH 96), the scheme whose limit the direct-evaluation paper
 * (altenhofen2018direct in docs/references.bib) evaluates.
 *
 * On the multilinear split of a hex mesh, with every average taken over the
 * coarse complex and every count read from it (never typed per topology):
 *   cell point    the centroid of the hex's 8 vertices;
 *   face point    (C0 + 2 A + C1) / 4 for a face in two hexes, A the face
 *                 centroid, C0, C1 the new cell points of the two hexes;
 *   edge point    (C + 2 A + (n - 3) M) / n for an edge in n faces (= n hexes
 *                 around an interior edge), C the mean of the new cell points
 *                 of the hexes at the edge, A the mean of the centroids of the
 *                 faces at it, M its midpoint;
 *   vertex point  (C + 3 A + 3 E + (n - 7) P) / n for a vertex in n hexes, C
 *                 the mean of the new cell points of the hexes at P, A the
 *                 mean of the centroids of the faces at P, E the mean of the
 *                 midpoints of the edges at P.
 * On a regular grid these are the tricubic B-spline rules (vertex 27/64 on P,
 * edge 9/32 on M, face 3/16 on A).  Along an extraordinary edge they are not
 * a tensor product of the Catmull-Clark surface rule and the cubic curve
 * rule (docs/schemes.md, "Catmull-Clark solids").
 *
 * ccsolid-tensor: the same rules but at a vertex P on an extraordinary edge —
 * interior, with n = 2m hexes, m + 2 edges: two of valence m != 4 that share
 * no hex ("along", the extraordinary edge through P) and m of valence 4
 * ("across"), i.e. the link bipyramid:m —
 *   vertex point  (m - 3)/(2m) (P + E_along) + (1/m) E_across + C / n + 3 A / n,
 * E_along, E_across the means of the midpoints of the edges along and across.
 * This is the tensor product of the cubic curve rule (1/8, 3/4, 1/8) along
 * the edge and Catmull-Clark's valence-m surface vertex rule across it: its
 * weights on six classes of points (P, its m neighbours across, its m
 * diagonals across; each in P's layer and in the two next) against the six
 * averages' (P, E_along, E_across, the faces across, the faces along, C)
 * make a triangular system (docs/schemes.md); the cell and face weights come
 * out as Joy and MacCracken's, so only the edges' and P's change.  Every
 * other point keeps the rules above (on a regular grid there is no such
 * vertex: the tricubic B-spline still).
 *
 * Boundaries and creases.  The "surface" of the mesh is its boundary faces
 * (quads of exactly one hex) together with the quad cells given explicitly
 * in the mesh.  Every vertex on the surface, on a segment cell or a vertex
 * cell is refined by the Catmull-Clark surface rule on the surface quads
 * (ss_scheme_catmull_clark_emit), with creases after Hoppe et al.
 * (ss_crease.h): segment cells and surface edges in other than two surface
 * quads are cubic B-spline crease curves, vertex cells and vertices with
 * three or more crease edges are interpolated.  This is the boundary rule of
 * Joy and MacCracken (the boundary of a Catmull-Clark solid is a
 * Catmull-Clark surface).  Explicit interior quads are our choice for
 * lower-dimensional cells, as MLCA treats them: a crease surface inside the
 * volume, refined like a boundary (its edges where it meets the boundary are
 * in three surface quads, hence crease curves).  Segment cells off the
 * surface are crease curves too; the vertex where such a curve ends inside
 * the volume is interpolated (it has one crease edge in no surface quad).
 *
 * Input must be manifold where the volume rules act: a quad face in more
 * than two hexes, an edge whose hexes do not form one fan (a cycle, or a path
 * ending on the boundary), or a vertex whose hexes do not form a ball or a
 * half-ball (hexes not connected through faces at the vertex, or a link of
 * Euler characteristic other than 2, closed, or 1, with boundary) is refused
 * (SS_EINPUT, naming the vertices).  All of this is read from the cells
 * holding a fine vertex, so the rule reaches one ring (ss_scheme_reach 1);
 * so is ccsolid-tensor's test of a vertex on an extraordinary edge (an edge
 * at P lies only in hexes holding P). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_scheme_impl.h"

#define NLAT 27 /* lattice points {0,1,2}^3 of a split hex */

/* Lattice index of the point with digits t[0..3). */
static int lat_index(const int *t) {
  return t[0] + 3 * t[1] + 9 * t[2];
}

static void lat_digits(int p, int *t) {
  t[0] = p % 3;
  t[1] = (p / 3) % 3;
  t[2] = p / 9;
}

/* Number of digits equal to 1: 0 corner, 1 edge, 2 face, 3 cell centre. */
static int lat_kind(int p) {
  int t[3];
  lat_digits(p, t);
  return (t[0] == 1) + (t[1] == 1) + (t[2] == 1);
}

/* Workspace of one refinement. */
typedef struct {
  size_t nhex;         /* coarse hexes */
  ss_idx *lat;         /* nhex * NLAT fine vertices: the split lattice of each */
  uint32_t *nhexat;    /* per fine vertex: coarse hexes holding it */
  uint32_t *uf;        /* union-find over (hex, lattice point) nodes */
  uint32_t *pair;      /* per fine vertex: first node seen (faces), or root */
  uint32_t *nfaceat;   /* per coarse vertex: faces in a hex at it */
  uint32_t *nedgeat;   /* per coarse vertex: edges in a hex at it */
  unsigned char *bnd;  /* per coarse vertex: on a face of one hex */
  unsigned char *on;   /* per fine vertex: refined by the surface rule */
  unsigned char *expl; /* per fine vertex: centre of an explicit quad */
  ss_idx *quads;       /* fine surface quads, 4 each */
  size_t nquads;       /* surface quads held */
  size_t *lptr;        /* restricted split: parent offsets */
  uint32_t *axis;      /* ccsolid-tensor, per coarse vertex: m if it lies on an
                          extraordinary edge of valence m (header), else 0 */
} cs_work;

static uint32_t uf_find(uint32_t *uf, uint32_t a) {
  while (uf[a] != a) {
    uf[a] = uf[uf[a]];
    a = uf[a];
  }
  return a;
}

static void uf_union(uint32_t *uf, uint32_t a, uint32_t b) {
  a = uf_find(uf, a);
  b = uf_find(uf, b);
  if (a != b) uf[a < b ? b : a] = a < b ? a : b;
}

/* "a, b, c and d": the parents of fine vertex x, 1-based. */
static void name_parents(const ss_split *L, size_t x, char *buf, size_t cap) {
  ss_scheme_list_vertices(L->parent + L->ptr[x], ss_split_npar(L, x), buf, cap);
}

/* The lattices of the coarse hexes: child kc of hex h (fine hex 8h + kc,
 * octant bits(kc)) holds at its corner k the lattice point bits(kc) +
 * bits(k) (ss_split.h). */
static void build_lattices(const ss_cx *fine, cs_work *w) {
  for (size_t h = 0; h < w->nhex; h++)
    for (int kc = 0; kc < 8; kc++) {
      const ss_idx *v = ss_cx_cell(fine, SS_HEX, 8 * h + (size_t)kc);
      const unsigned o = ss_cube_corner_bits(3, kc);
      for (int k = 0; k < 8; k++) {
        const unsigned b = ss_cube_corner_bits(3, k);
        int t[3];
        for (int i = 0; i < 3; i++)
          t[i] = (int)((o >> i & 1u) + (b >> i & 1u));
        w->lat[h * NLAT + (size_t)lat_index(t)] = v[k];
      }
    }
}

/* The 9 lattice points of the face with lattice point f (two digits 1). */
static void face_points(int f, int *pts) {
  int t[3], fixed = 0;
  lat_digits(f, t);
  while (t[fixed] == 1)
    fixed++;
  const int i = (fixed + 1) % 3, j = (fixed + 2) % 3;
  int n = 0;
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) {
      int u[3];
      u[fixed] = t[fixed];
      u[i] = a;
      u[j] = b;
      pts[n++] = lat_index(u);
    }
}

/* The manifold checks of the header, SS_EINPUT on the first failure. */
static ss_status check_manifold(const ss_cx *fine, const ss_split *L, cs_work *w,
                                ss_error *err) {
  const size_t nf = fine->nv, nc = L->ncoarse;
  char names[160];
  for (size_t x = nc; x < nf; x++)
    if (ss_split_npar(L, x) == 4 && w->nhexat[x] > 2) {
      name_parents(L, x, names, sizeof names);
      return ss_error_set(err, SS_EINPUT,
                          "scheme ccsolid: the quadrilateral face with vertices %s lies "
                          "in %u hexahedra; a Catmull-Clark solid takes at most 2 "
                          "(non-manifold mesh)",
                          names, (unsigned)w->nhexat[x]);
    }
  /* join the lattice points of two hexes across every face they share */
  const size_t nnode = w->nhex * NLAT;
  for (size_t q = 0; q < nnode; q++)
    w->uf[q] = (uint32_t)q;
  for (size_t x = 0; x < nf; x++)
    w->pair[x] = UINT32_MAX;
  for (size_t h = 0; h < w->nhex; h++)
    for (int p = 0; p < NLAT; p++) {
      if (lat_kind(p) != 2) continue;
      const ss_idx f = w->lat[h * NLAT + (size_t)p];
      if (w->pair[f] == UINT32_MAX) {
        w->pair[f] = (uint32_t)(h * NLAT + (size_t)p);
        continue;
      }
      const size_t g = w->pair[f] / NLAT;
      int mine[9], theirs[9];
      face_points(p, mine);
      face_points((int)(w->pair[f] % NLAT), theirs);
      for (int a = 0; a < 9; a++)
        for (int b = 0; b < 9; b++)
          if (w->lat[h * NLAT + (size_t)mine[a]] == w->lat[g * NLAT + (size_t)theirs[b]])
            uf_union(w->uf, (uint32_t)(h * NLAT + (size_t)mine[a]),
                     (uint32_t)(g * NLAT + (size_t)theirs[b]));
    }
  /* every vertex and edge: one class of hexes joined through faces at it */
  for (size_t x = 0; x < nf; x++)
    w->pair[x] = UINT32_MAX;
  for (size_t h = 0; h < w->nhex; h++)
    for (int p = 0; p < NLAT; p++) {
      if (lat_kind(p) > 1) continue;
      const ss_idx x = w->lat[h * NLAT + (size_t)p];
      const uint32_t r = uf_find(w->uf, (uint32_t)(h * NLAT + (size_t)p));
      if (w->pair[x] == UINT32_MAX) {
        w->pair[x] = r;
      } else if (w->pair[x] != r) {
        name_parents(L, x, names, sizeof names);
        return ss_error_set(err, SS_EINPUT,
                            "scheme ccsolid: the hexahedra at %s %s do not form one %s "
                            "through faces at it (non-manifold mesh)",
                            lat_kind(p) ? "the edge between vertices" : "vertex", names,
                            lat_kind(p) ? "fan" : "ball or half-ball");
      }
    }
  /* Euler characteristic of each vertex's link: 2 (sphere) or 1 (disk) */
  for (size_t x = nc; x < nf; x++) {
    const size_t np = ss_split_npar(L, x);
    if (w->nhexat[x] == 0 || (np != 2 && np != 4)) continue;
    for (size_t q = L->ptr[x]; q < L->ptr[x + 1]; q++) {
      const ss_idx a = L->parent[q];
      if (np == 2) w->nedgeat[a]++;
      if (np == 4) w->nfaceat[a]++;
      if (np == 4 && w->nhexat[x] == 1) w->bnd[a] = 1;
    }
  }
  for (size_t v = 0; v < nc; v++) {
    if (!w->nhexat[v]) continue;
    const long chi = (long)w->nedgeat[v] - (long)w->nfaceat[v] + (long)w->nhexat[v];
    if (chi != (w->bnd[v] ? 1 : 2))
      return ss_error_set(err, SS_EINPUT,
                          "scheme ccsolid: the hexahedra at vertex %zu do not form a "
                          "%s (their link has Euler characteristic %ld; non-manifold "
                          "mesh)",
                          v + 1, w->bnd[v] ? "half-ball" : "ball", chi);
  }
  return SS_OK;
}

/* Add the 4 fine quads of the boundary face f (lattice point) of hex h. */
static void add_face_children(cs_work *w, size_t h, int f) {
  int pts[9];
  face_points(f, pts); /* pts[3 a + b], a, b in 0..2 over two free digits */
  for (int a = 0; a < 2; a++)
    for (int b = 0; b < 2; b++) {
      ss_idx *q = w->quads + 4 * w->nquads++;
      q[0] = w->lat[h * NLAT + (size_t)pts[3 * a + b]];
      q[1] = w->lat[h * NLAT + (size_t)pts[3 * (a + 1) + b]];
      q[2] = w->lat[h * NLAT + (size_t)pts[3 * (a + 1) + b + 1]];
      q[3] = w->lat[h * NLAT + (size_t)pts[3 * a + b + 1]];
    }
}

/* The surface (header): its fine quads w->quads, the marks w->on, and the
 * split restricted to the marked vertices (w->lptr and *par, which the
 * caller frees). */
static ss_status build_surface(const ss_cx *fine, const ss_split *L, cs_work *w,
                               ss_idx **par, ss_error *err) {
  const size_t nf = fine->nv;
  for (size_t q = 0; q < fine->nc[SS_QUAD]; q++) {
    const ss_idx *v = ss_cx_cell(fine, SS_QUAD, q);
    for (int i = 0; i < 4; i++)
      if (ss_split_npar(L, v[i]) == 4) w->expl[v[i]] = 1;
  }
  for (size_t i = 0; i < fine->nc[SS_QUAD] * 4; i++)
    w->quads[i] = fine->cells[SS_QUAD][i];
  w->nquads = fine->nc[SS_QUAD];
  for (size_t h = 0; h < w->nhex; h++)
    for (int p = 0; p < NLAT; p++) {
      if (lat_kind(p) != 2) continue;
      const ss_idx f = w->lat[h * NLAT + (size_t)p];
      if (w->nhexat[f] == 1 && !w->expl[f]) add_face_children(w, h, p);
    }
  for (size_t i = 0; i < w->nquads * 4; i++)
    w->on[w->quads[i]] = 1;
  for (size_t i = 0; i < fine->nc[SS_SEGMENT] * 2; i++)
    w->on[fine->cells[SS_SEGMENT][i]] = 1;
  for (size_t i = 0; i < fine->nc[SS_VERTEX]; i++)
    w->on[fine->cells[SS_VERTEX][i]] = 1;
  /* a fine vertex off the surface is no edge or face of it: no parents */
  w->lptr[0] = 0;
  size_t m = 0;
  if (!(*par = malloc((L->ptr[nf] + 1) * sizeof **par)))
    return ss_error_nomem(err, "ccsolid surface");
  for (size_t x = 0; x < nf; x++) {
    if (w->on[x])
      for (size_t q = L->ptr[x]; q < L->ptr[x + 1]; q++)
        (*par)[m++] = L->parent[q];
    w->lptr[x + 1] = m;
  }
  return SS_OK;
}

/* The surface complex of w over fine's vertices (arrays borrowed). */
static ss_cx surface_cx(const ss_cx *fine, const cs_work *w) {
  ss_cx surf = {0};
  surf.dim = fine->dim;
  surf.nv = fine->nv;
  surf.nc[SS_QUAD] = w->nquads;
  surf.cells[SS_QUAD] = w->quads;
  surf.nc[SS_SEGMENT] = fine->nc[SS_SEGMENT];
  surf.cells[SS_SEGMENT] = fine->cells[SS_SEGMENT];
  surf.nc[SS_VERTEX] = fine->nc[SS_VERTEX];
  surf.cells[SS_VERTEX] = fine->cells[SS_VERTEX];
  return surf;
}

/* w->axis (header, ccsolid-tensor): the coarse vertices off the surface
 * whose edges of valence other than 4 are exactly two, m each, in no common
 * hex, with 2m hexes and m + 2 edges at the vertex.  ends: 2 per coarse
 * vertex, scratch. */
static void find_axes(size_t nc, cs_work *w, ss_idx *ends) {
  const ss_idx none = (ss_idx)-1;
  for (size_t v = 0; v < nc; v++) {
    w->axis[v] = 1; /* a candidate until refuted */
    ends[2 * v] = ends[2 * v + 1] = none;
  }
  for (size_t h = 0; h < w->nhex; h++)
    for (int p = 0; p < NLAT; p++) {
      const ss_idx x = w->lat[h * NLAT + (size_t)p];
      if (lat_kind(p) != 0 || !w->axis[x]) continue;
      int t[3], odd = 0;
      lat_digits(p, t);
      for (int i = 0; i < 3 && !w->on[x]; i++) {
        int u[3] = {t[0], t[1], t[2]};
        u[i] = 1;
        const ss_idx e = w->lat[h * NLAT + (size_t)lat_index(u)];
        if (w->nhexat[e] == 4) continue;
        odd++;
        if (ends[2 * x] == none || ends[2 * x] == e)
          ends[2 * x] = e;
        else if (ends[2 * x + 1] == none || ends[2 * x + 1] == e)
          ends[2 * x + 1] = e;
        else
          odd = 9; /* a third */
      }
      if (w->on[x] || odd > 1) w->axis[x] = 0;
    }
  for (size_t v = 0; v < nc; v++) {
    if (!w->axis[v] || ends[2 * v + 1] == none) {
      w->axis[v] = 0;
      continue;
    }
    const uint32_t m = w->nhexat[ends[2 * v]];
    const int ok = m >= 3 && w->nhexat[ends[2 * v + 1]] == m && w->nhexat[v] == 2 * m &&
                   w->nedgeat[v] == m + 2;
    w->axis[v] = ok ? m : 0;
  }
}

/* The vertex rule at fine vertex x from hex lat (its corner t): Joy and
 * MacCracken's, or the tensor product's where w->axis[x] (header). */
static void vertex_rule(const cs_work *w, const ss_idx *lat, const int *t, ss_idx x,
                        ss_sink *k) {
  const double n = (double)w->nhexat[x];
  const double m = w->axis ? (double)w->axis[x] : 0.0;
  ss_sink_emit(k, x, lat[13], 1.0 / (n * n));
  const double nfa = (double)w->nfaceat[x], ned = (double)w->nedgeat[x];
  for (int i = 0; i < 3; i++) {
    int u[3] = {t[0], t[1], t[2]};
    u[i] = 1;
    const ss_idx e = lat[lat_index(u)];
    const double ne = (double)w->nhexat[e]; /* each edge seen from its ne hexes */
    if (m > 0.0) /* along: (m - 3)/(4m) each of 2; across: 1/m each of m */
      ss_sink_emit(k, x, e, (ne == m ? (m - 3.0) / (4.0 * m) : 1.0 / (m * m)) / ne);
    else /* 3 E / n over ned edges (as before the variant, bit for bit) */
      ss_sink_emit(k, x, e, 3.0 / (n * ned * ne));
    u[(i + 1) % 3] = 1; /* the face spanned by directions i, i + 1 */
    ss_sink_emit(k, x, lat[lat_index(u)], 3.0 / (n * nfa * 2.0));
  }
}

/* The volume rules of the header for every fine vertex off the surface. */
static void volume_rule(const ss_cx *fine, const ss_split *L, const cs_work *w,
                        ss_sink *k) {
  const size_t nf = fine->nv;
  for (size_t x = 0; x < nf; x++) {
    if (w->on[x]) continue;
    const size_t np = ss_split_npar(L, x);
    const double n = (double)w->nhexat[x];
    if (np == 8 || w->nhexat[x] == 0)
      ss_sink_emit(k, x, x, 1.0); /* cell point, or a vertex in no cell */
    else if (np == 4)
      ss_sink_emit(k, x, x, 0.5);
    else if (np == 1 && w->axis && w->axis[x]) /* (m - 3)/(2m), n = 2m */
      ss_sink_emit(k, x, x, (n - 6.0) / (2.0 * n));
    else
      ss_sink_emit(k, x, x, (n - (np == 2 ? 3.0 : 7.0)) / n);
  }
  for (size_t h = 0; h < w->nhex; h++) {
    const ss_idx *lat = w->lat + h * NLAT;
    const ss_idx c = lat[13]; /* the cell point, lattice (1, 1, 1) */
    for (int p = 0; p < NLAT; p++) {
      const ss_idx x = lat[p];
      const int kind = lat_kind(p);
      if (kind == 3 || w->on[x]) continue;
      const double n = (double)w->nhexat[x];
      int t[3];
      lat_digits(p, t);
      if (kind == 2) { /* face: C0 / 4 + C1 / 4 */
        ss_sink_emit(k, x, c, 0.25);
      } else if (kind == 1) { /* edge: its n faces are this hex's 2, twice */
        ss_sink_emit(k, x, c, 1.0 / (n * n));
        for (int i = 0; i < 3; i++) {
          if (t[i] == 1) continue;
          int u[3] = {t[0], t[1], t[2]};
          u[i] = 1;
          /* 2 A / n over n faces, each seen from its 2 hexes */
          ss_sink_emit(k, x, lat[lat_index(u)], 1.0 / (n * n));
        }
      } else {
        vertex_rule(w, lat, t, x, k);
      }
    }
  }
}

/* The work of one refinement up to the rules: every array of w allocated,
 * the lattices, the manifold checks and the surface (*par: the restricted
 * split's parents, the caller frees it).  SS_EINPUT, SS_ENOMEM. */
static ss_status prepare(const ss_cx *fine, const ss_split *L, cs_work *w, ss_idx **par,
                         ss_error *err) {
  const size_t nf = fine->nv, nc = L->ncoarse;
  w->nhex = fine->nc[SS_HEX] / 8;
  w->lat = malloc((w->nhex * NLAT + 1) * sizeof *w->lat);
  w->uf = malloc((w->nhex * NLAT + 1) * sizeof *w->uf);
  w->nhexat = calloc(nf + 1, sizeof *w->nhexat);
  w->pair = malloc((nf + 1) * sizeof *w->pair);
  w->nfaceat = calloc(nc + 1, sizeof *w->nfaceat);
  w->nedgeat = calloc(nc + 1, sizeof *w->nedgeat);
  w->bnd = calloc(nc + 1, 1);
  w->on = calloc(nf + 1, 1);
  w->expl = calloc(nf + 1, 1);
  w->lptr = malloc((nf + 1) * sizeof *w->lptr);
  if (!w->lat || !w->uf || !w->nhexat || !w->pair || !w->nfaceat || !w->nedgeat ||
      !w->bnd || !w->on || !w->expl || !w->lptr)
    return ss_error_nomem(err, "ccsolid rule");
  build_lattices(fine, w);
  for (size_t i = 0; i < w->nhex * NLAT; i++)
    w->nhexat[w->lat[i]]++;
  /* surface quads: the explicit ones and 4 per boundary face */
  size_t nbface = 0;
  for (size_t i = 0; i < w->nhex * NLAT; i++)
    nbface += lat_kind((int)(i % NLAT)) == 2 && w->nhexat[w->lat[i]] == 1;
  w->quads = malloc((4 * (fine->nc[SS_QUAD] + 4 * nbface) + 1) * sizeof *w->quads);
  if (!w->quads) return ss_error_nomem(err, "ccsolid surface");
  ss_status st = check_manifold(fine, L, w, err);
  return st ? st : build_surface(fine, L, w, par, err);
}

static void work_clear(cs_work *w) {
  free(w->axis);
  free(w->lat);
  free(w->uf);
  free(w->nhexat);
  free(w->pair);
  free(w->nfaceat);
  free(w->nedgeat);
  free(w->bnd);
  free(w->on);
  free(w->expl);
  free(w->quads);
  free(w->lptr);
}

static ss_status ccsolid_rule(const ss_scheme *s, const ss_cx *coarse, const ss_cx *fine,
                              const ss_split *L, ss_sink *k, ss_error *err) {
  (void)coarse; /* the split complex and L say all this rule needs */
  cs_work w = {0};
  ss_idx *par = NULL;
  ss_status st = prepare(fine, L, &w, &par, err);
  if (!st && s->tensor_axis) {
    ss_idx *ends = malloc((2 * L->ncoarse + 1) * sizeof *ends);
    if (!ends || !(w.axis = malloc((L->ncoarse + 1) * sizeof *w.axis)))
      st = ss_error_nomem(err, "ccsolid-tensor rule");
    else
      find_axes(L->ncoarse, &w, ends);
    free(ends);
  }
  if (!st) {
    ss_split Ls = {L->ncoarse, fine->nv, w.lptr, par};
    ss_cx surf = surface_cx(fine, &w);
    st = ss_scheme_catmull_clark_emit(&surf, &Ls, w.on, k, err);
  }
  if (!st) volume_rule(fine, L, &w, k);
  free(par);
  work_clear(&w);
  return st;
}

ss_status ss_hex_surface_build(const ss_cx *fine, const ss_split *L, ss_hex_surface *out,
                               ss_error *err) {
  memset(out, 0, sizeof *out);
  cs_work w = {0};
  ss_idx *par = NULL;
  ss_status st = prepare(fine, L, &w, &par, err);
  if (!st) {
    out->surf = surface_cx(fine, &w);
    out->Ls = (ss_split){L->ncoarse, fine->nv, w.lptr, par};
    out->on = w.on;
    w.quads = NULL, w.lptr = NULL, w.on = NULL; /* now out's */
  } else {
    free(par);
  }
  work_clear(&w);
  return st;
}

void ss_hex_surface_clear(ss_hex_surface *h) {
  free(h->surf.cells[SS_QUAD]);
  free(h->Ls.ptr);
  free(h->Ls.parent);
  free(h->on);
  memset(h, 0, sizeof *h);
}

ss_status ss_scheme_ccsolid_new(ss_scheme **out, ss_error *err) {
  unsigned accepts =
      (1u << SS_VERTEX) | (1u << SS_SEGMENT) | (1u << SS_QUAD) | (1u << SS_HEX);
  return ss_scheme_alloc("ccsolid", SS_SPLIT_MULTILINEAR, accepts, ccsolid_rule, out,
                         err);
}

ss_status ss_scheme_ccsolid_tensor_new(ss_scheme **out, ss_error *err) {
  unsigned accepts =
      (1u << SS_VERTEX) | (1u << SS_SEGMENT) | (1u << SS_QUAD) | (1u << SS_HEX);
  ss_status st = ss_scheme_alloc("ccsolid-tensor", SS_SPLIT_MULTILINEAR, accepts,
                                 ccsolid_rule, out, err);
  if (!st) (*out)->tensor_axis = 1;
  return st;
}
