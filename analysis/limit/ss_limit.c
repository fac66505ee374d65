/* ss_limit.c — limit evaluation on hex meshes: the cached walk with
 * eigen-jumps over stationary runs, the reference by repeated local
 * subdivision, and the tricubic B-spline (method in ss_limit.h). */
#include "ss_limit.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "ss_limit_impl.h"

/* Runs shorter than this are walked step by step: a jump costs about two
 * plain steps (V^-1 P and V y, complex), so it pays from three steps on. */
#define JUMP_MIN 3

#define LIM_RECENT 64 /* coarse-only states whose transitions are kept */

/* A cached (key, child) transition. */
typedef struct {
  size_t next;     /* state of the child patch */
  ss_lim_frame g;  /* the child's canonical frame relative to the inherited one */
  double *W;       /* rows: child patch points from parent patch points */
  ss_lim_eig *eig; /* for a stationary run (next == self, g = id): lazily */
} ss_lim_trans;

/* The layered structure of a patch around an extraordinary edge (the
 * paper's eq. (1)): the patch points in 4 layers along the edge, columns
 * across them, and whether both stationary halves W_b factor as A_b (x) T,
 * A_b the cubic B-spline's 4 x 4 left/right matrices. */
typedef struct {
  int status;         /* 1 factors, -1 does not (or no edge here) */
  int axis;           /* the edge's axis in the patch's frame */
  int *layer;         /* K: 0..3, the B-spline index along the axis */
  size_t *col;        /* K: the column of each point */
  size_t ncol;        /* columns */
  size_t (*colpt)[4]; /* ncol x 4: the point of each column in each layer */
} ss_lim_tensor;

static void tensor_free(ss_lim_tensor *t) {
  if (!t) return;
  free(t->layer);
  free(t->col);
  free(t->colpt);
  free(t);
}

/* A patch topology met so far. */
typedef struct {
  ss_lim_patch patch;  /* key, regularity and net (src: of the instance below) */
  ss_cx *cx;           /* an instance of the patch as a complex (for refining) */
  uint64_t hash;       /* ss_lim_patch_hash */
  ss_lim_trans *tr[8]; /* per child, NULL until computed */
  int coarse_only;     /* 1 while only coarse cells have this patch (no transition
                          leads to it): its transitions may be evicted */
  int held;            /* 1 while its transitions are in the ring of recent ones */
  ss_lim_tensor *ten;  /* the layered structure, computed on first need */
  size_t src_cell;     /* coarse-only: a mesh cell with this patch, to rebuild the
                          instance cx from (it is dropped with the transitions) */
} ss_lim_state;

/* Per coarse cell: its patch's state and where its points come from. */
typedef struct {
  size_t state;   /* SIZE_MAX until first used */
  ss_idx *src;    /* the patch's mesh vertices, in the patch's numbering */
  ss_lim_frame g; /* the patch's canonical frame relative to the cell's stored
                  vertex order (isomorphic cells share their transitions) */
} ss_lim_cell;

struct ss_limit {
  const ss_scheme *s; /* borrowed */
  ss_cx *mesh;        /* owned copy */
  ss_lim_adj adj;     /* hex adjacency of the mesh */
  int64_t *loc;       /* scratch, mesh->nv entries, all -1 between calls */
  ss_lim_cell *cell;  /* per hex */
  ss_lim_state **st;  /* states */
  size_t nst, capst;  /* their number and room */
  size_t *tab;        /* hash table of states: index + 1, 0 empty */
  size_t captab;      /* its size, a power of 2 */
  /* Coarse-only states' transitions are kept for the LIM_RECENT most recent
   * ones only: on an unstructured mesh nearly every irregular coarse cell has
   * a patch of its own, and keeping all their W (~80 KB each) would grow
   * with the mesh; points are usually asked cell by cell. */
  size_t recent[LIM_RECENT]; /* ring of coarse-only states holding transitions */
  size_t nrecent;            /* entries ever pushed (the ring's head) */
  int tensor;                /* use eq. (1) where an edge's runs factor (default
                                1; ss_limit_set_tensor) */
  ss_limit_stats stats;
};

size_t ss_limit_ncells(const ss_limit *L) {
  return L->mesh->nc[SS_HEX];
}

ss_limit_stats ss_limit_get_stats(const ss_limit *L) {
  return L->stats;
}

void ss_limit_set_tensor(ss_limit *L, int on) {
  L->tensor = on != 0;
}

static void drop_transitions(ss_lim_state *s) {
  for (int k = 0; k < 8; k++)
    if (s->tr[k]) {
      free(s->tr[k]->W);
      ss_lim_eig_free(s->tr[k]->eig);
      free(s->tr[k]);
      s->tr[k] = NULL;
    }
}

static void state_free(ss_lim_state *s) {
  if (!s) return;
  ss_lim_patch_free(&s->patch);
  ss_cx_free(s->cx);
  drop_transitions(s);
  tensor_free(s->ten);
  free(s);
}

void ss_limit_free(ss_limit *L) {
  if (!L) return;
  for (size_t i = 0; i < L->nst; i++)
    state_free(L->st[i]);
  free(L->st);
  free(L->tab);
  if (L->cell)
    for (size_t c = 0; c < L->mesh->nc[SS_HEX]; c++)
      free(L->cell[c].src);
  free(L->cell);
  free(L->loc);
  ss_lim_adj_free(&L->adj);
  ss_cx_free(L->mesh);
  free(L);
}

/* Cubic B-spline rows of the left (b = 0) and right (b = 1) halves: child
 * points at positions -1..2 of the half from the parent's at -1..2. */
static const double bspline_half[2][4][4] = {{{0.5, 0.5, 0, 0},
                                              {0.125, 0.75, 0.125, 0},
                                              {0, 0.5, 0.5, 0},
                                              {0, 0.125, 0.75, 0.125}},
                                             {{0.125, 0.75, 0.125, 0},
                                              {0, 0.5, 0.5, 0},
                                              {0, 0.125, 0.75, 0.125},
                                              {0, 0, 0.5, 0.5}}};

/* Regular patches are evaluated by the tricubic B-spline, which is right only
 * if the scheme's rule on a regular grid is the tricubic B-spline's: check it
 * on the 3x3x3 block, child by child (the 1D rows are the cubic B-spline's
 * midpoint 1/2 1/2 and vertex 1/8 3/4 1/8 rules; the 3D rows their tensor
 * product).  A stencil file with other hex weights is refused here instead
 * of evaluated wrongly. */
static ss_status check_bspline(const ss_scheme *s, ss_error *err) {
  const double(*A)[4][4] = bspline_half;
  ss_status st;
  ss_cx *g = NULL, *pcx = NULL, *ccx = NULL;
  ss_lim_adj adj = {0};
  ss_lim_patch p = {0}, c = {0};
  double *W = NULL;
  int64_t loc[64];
  if ((st = ss_cx_new(3, &g, err))) return st;
  for (int k = 0; k < 4 && !st; k++)
    for (int j = 0; j < 4 && !st; j++)
      for (int i = 0; i < 4 && !st; i++) {
        double x[3] = {i, j, k};
        st = ss_cx_add_vertex(g, x, 0, err);
      }
  /* the centre cell first, so that it is hex 0 */
  for (int q = 0; q < 27 && !st; q++) {
    int r = (q + 13) % 27, i = r % 3, j = (r / 3) % 3, k = r / 9;
    ss_idx v[8];
    for (int b = 0; b < 8; b++) {
      unsigned bits = ss_cube_corner_bits(3, b);
      v[b] = (ss_idx)((i + (int)(bits & 1u)) + 4 * ((j + (int)((bits >> 1) & 1u)) +
                                                    4 * (k + (int)((bits >> 2) & 1u))));
    }
    st = ss_cx_add_cell(g, SS_HEX, v, 0, err);
  }
  for (int v = 0; v < 64; v++)
    loc[v] = -1;
  ss_lim_frame id = ss_lim_frame_id(), gk;
  if (st || (st = ss_lim_adj_build(g, &adj, err)) ||
      (st = ss_lim_patch_build(&adj, 0, &id, loc, &p, err)) ||
      (st = ss_lim_patch_complex(g, &p, &pcx, err)))
    goto done;
  double worst = 0.0;
  for (int k = 0; k < 8 && p.regular; k++) {
    if ((st = ss_lim_step(s, pcx, k, 0, &c, &gk, &ccx, &W, err))) goto done;
    unsigned b = ss_cube_corner_bits(3, k);
    for (int q = 0; q < 64 && c.regular; q++)
      for (int r = 0; r < 64; r++) {
        double want = A[b & 1u][q % 4][r % 4] *
                      A[(b >> 1) & 1u][(q / 4) % 4][(r / 4) % 4] *
                      A[(b >> 2) & 1u][q / 16][r / 16];
        double e = fabs(W[(size_t)c.net[q] * 64 + p.net[r]] - want);
        if (e > worst) worst = e;
      }
    if (!c.regular) worst = 1.0;
    ss_lim_patch_free(&c);
    ss_cx_free(ccx);
    ccx = NULL;
    free(W);
    W = NULL;
  }
  if (!p.regular || worst > 1e-12)
    st = ss_error_set(err, SS_EINPUT,
                      "scheme %s does not refine a regular hex grid by the tricubic "
                      "B-spline rules (a weight is off by %.3g), which limit evaluation "
                      "assumes on regular cells",
                      ss_scheme_name(s), worst);
done:
  free(W);
  ss_lim_patch_free(&c);
  ss_lim_patch_free(&p);
  ss_cx_free(ccx);
  ss_cx_free(pcx);
  ss_lim_adj_free(&adj);
  ss_cx_free(g);
  return st;
}

ss_status ss_limit_new(const ss_scheme *s, const ss_cx *mesh, ss_limit **out,
                       ss_error *err) {
  ss_status st;
  *out = NULL;
  if (ss_scheme_split_kind(s) != SS_SPLIT_MULTILINEAR || !ss_scheme_accepts(s, SS_HEX) ||
      ss_scheme_reach(s) != 1)
    return ss_error_set(
        err, SS_EINPUT,
        "limit evaluation needs a scheme that splits hexahedra "
        "multilinearly with a one-ring rule (mlca, ccsolid); %s is not one",
        ss_scheme_name(s));
  if (mesh->dim != 3)
    return ss_error_set(err, SS_EINPUT,
                        "limit evaluation needs a mesh with 3 coordinates, not %d",
                        mesh->dim);
  for (int t = 0; t < SS_NCELLTYPES; t++)
    if (t != SS_HEX && mesh->nc[t])
      return ss_error_set(err, SS_EINPUT,
                          "limit evaluation takes meshes of hexahedra only; this one has "
                          "%zu %s (creases and boundary cells of lower dimension are not "
                          "supported yet)",
                          mesh->nc[t], ss_cell_plural((ss_cell_type)t));
  if (!mesh->nc[SS_HEX])
    return ss_error_set(err, SS_EINPUT, "limit evaluation: the mesh has no hexahedra");
  if ((st = ss_cx_validate(mesh, err))) return st;
  ss_limit *L = calloc(1, sizeof *L);
  if (!L) return ss_error_nomem(err, "limit evaluator");
  L->s = s;
  L->tensor = 1;
  if ((st = ss_cx_copy(mesh, &L->mesh, err))) goto done;
  if ((st = ss_lim_adj_build(L->mesh, &L->adj, err))) goto done;
  L->loc = malloc((mesh->nv + 1) * sizeof *L->loc);
  L->cell = calloc(mesh->nc[SS_HEX], sizeof *L->cell);
  L->captab = 64;
  L->tab = calloc(L->captab, sizeof *L->tab);
  if (!L->loc || !L->cell || !L->tab) {
    st = ss_error_nomem(err, "limit evaluator");
    goto done;
  }
  for (size_t v = 0; v < mesh->nv; v++)
    L->loc[v] = -1;
  for (size_t c = 0; c < mesh->nc[SS_HEX]; c++)
    L->cell[c].state = SIZE_MAX;
  st = check_bspline(s, err);
done:
  if (st)
    ss_limit_free(L);
  else
    *out = L;
  return st;
}

/* ---- the tricubic B-spline ---- */

/* Uniform cubic B-spline basis on [0,1] for the points at -1, 0, 1, 2, and
 * its derivative. */
static void basis(double t, double b[4], double d[4]) {
  const double s = 1.0 - t, t2 = t * t, t3 = t2 * t;
  b[0] = s * s * s / 6.0;
  b[1] = (3.0 * t3 - 6.0 * t2 + 4.0) / 6.0;
  b[2] = (-3.0 * t3 + 3.0 * t2 + 3.0 * t + 1.0) / 6.0;
  b[3] = t3 / 6.0;
  d[0] = -s * s / 2.0;
  d[1] = (9.0 * t2 - 12.0 * t) / 6.0;
  d[2] = (-9.0 * t2 + 6.0 * t + 3.0) / 6.0;
  d[3] = t2 / 2.0;
}

void ss_limit_bspline(const double (*net)[3], double u, double v, double w, double p[3],
                      double jac[3][3]) {
  double bu[4], du[4], bv[4], dv[4], bw[4], dw[4];
  basis(u, bu, du);
  basis(v, bv, dv);
  basis(w, bw, dw);
  double r[4][3] = {{0}};
  for (int k = 0; k < 4; k++)
    for (int j = 0; j < 4; j++)
      for (int i = 0; i < 4; i++) {
        const double *q = net[i + 4 * j + 16 * k];
        const double c[4] = {bu[i] * bv[j] * bw[k], du[i] * bv[j] * bw[k],
                             bu[i] * dv[j] * bw[k], bu[i] * bv[j] * dw[k]};
        for (int e = 0; e < 4; e++)
          for (int d = 0; d < 3; d++)
            r[e][d] += c[e] * q[d];
      }
  for (int d = 0; d < 3; d++)
    p[d] = r[0][d];
  if (jac)
    for (int e = 0; e < 3; e++)
      for (int d = 0; d < 3; d++)
        jac[e][d] = r[e + 1][d];
}

/* ---- states ---- */

static ss_status grow_table(ss_limit *L, ss_error *err) {
  size_t cap = L->captab * 2;
  size_t *t = calloc(cap, sizeof *t);
  if (!t) return ss_error_nomem(err, "state table");
  for (size_t i = 0; i < L->nst; i++) {
    size_t h = (size_t)L->st[i]->hash & (cap - 1);
    while (t[h])
      h = (h + 1) & (cap - 1);
    t[h] = i + 1;
  }
  free(L->tab);
  L->tab = t;
  L->captab = cap;
  return SS_OK;
}

/* The state of patch p (taken over: moved into a new state, or freed when its
 * key is known), with instance complex cx (likewise). */
static ss_status state_of(ss_limit *L, ss_lim_patch *p, ss_cx *cx, size_t *out,
                          ss_error *err) {
  ss_status st;
  uint64_t h = ss_lim_patch_hash(p);
  size_t i = (size_t)h & (L->captab - 1);
  while (L->tab[i]) {
    ss_lim_state *s = L->st[L->tab[i] - 1];
    if (s->hash == h && ss_lim_patch_same(&s->patch, p)) {
      *out = L->tab[i] - 1;
      ss_lim_patch_free(p);
      ss_cx_free(cx);
      return SS_OK;
    }
    i = (i + 1) & (L->captab - 1);
  }
  ss_lim_state *s = calloc(1, sizeof *s);
  if (!s) {
    st = ss_error_nomem(err, "state");
    goto fail;
  }
  if (L->nst == L->capst) {
    size_t cap = L->capst ? 2 * L->capst : 16;
    ss_lim_state **n = realloc(L->st, cap * sizeof *n);
    if (!n) {
      st = ss_error_nomem(err, "states");
      goto fail;
    }
    L->st = n;
    L->capst = cap;
  }
  s->patch = *p;
  s->cx = cx;
  s->hash = h;
  L->st[L->nst] = s;
  L->tab[i] = L->nst + 1;
  *out = L->nst++;
  L->stats.keys++;
  if (2 * L->nst > L->captab) return grow_table(L, err);
  return SS_OK;
fail:
  free(s);
  ss_lim_patch_free(p);
  ss_cx_free(cx);
  return st;
}

/* The state of coarse cell c (its patch in its canonical frame). */
static ss_status cell_state(ss_limit *L, size_t c, ss_error *err) {
  if (L->cell[c].state != SIZE_MAX) return SS_OK;
  ss_status st;
  ss_lim_patch p;
  ss_cx *cx = NULL;
  /* a regular patch needs no canonical frame (every frame gives the same
   * grid walk up to the B-spline's symmetry, and it has no transitions):
   * most cells of a mesh are, and the 48 walks would dominate a first pass */
  L->cell[c].g = ss_lim_frame_id();
  if ((st = ss_lim_patch_build(&L->adj, c, &L->cell[c].g, L->loc, &p, err))) return st;
  if (!p.regular) {
    ss_lim_patch_free(&p);
    if ((st = ss_lim_patch_canonical(&L->adj, c, L->loc, &p, &L->cell[c].g, err)))
      return st;
  }
  ss_idx *src = malloc((p.nv + 1) * sizeof *src);
  if (!src) {
    ss_lim_patch_free(&p);
    return ss_error_nomem(err, "cell patch");
  }
  memcpy(src, p.src, p.nv * sizeof *src);
  if ((st = ss_lim_patch_complex(L->mesh, &p, &cx, err))) {
    free(src);
    ss_lim_patch_free(&p);
    return st;
  }
  size_t s, before = L->nst;
  if ((st = state_of(L, &p, cx, &s, err))) {
    free(src);
    return st;
  }
  if (L->nst > before) {
    /* a coarse-only patch keeps no instance until its transitions are
     * needed: one per irregular cell would grow with the mesh */
    L->st[s]->coarse_only = 1;
    L->st[s]->src_cell = c;
    ss_cx_free(L->st[s]->cx);
    L->st[s]->cx = NULL;
  }
  L->cell[c].src = src;
  L->cell[c].state = s;
  return SS_OK;
}

/* The transition of state i into child k, computed on first use. */
static ss_status transition(ss_limit *L, size_t i, int k, ss_lim_trans **out,
                            ss_error *err) {
  ss_status st;
  ss_lim_state *s = L->st[i];
  if (s->tr[k]) {
    *out = s->tr[k];
    return SS_OK;
  }
  if (!s->cx) {
    ss_lim_patch p;
    size_t c = s->src_cell;
    if ((st = ss_lim_patch_build(&L->adj, c, &L->cell[c].g, L->loc, &p, err))) return st;
    int same = ss_lim_patch_same(&p, &s->patch);
    st = same ? ss_lim_patch_complex(L->mesh, &p, &s->cx, err)
              : ss_error_set(err, SS_EINTERNAL, "limit: cell %zu's patch changed", c + 1);
    ss_lim_patch_free(&p);
    if (st) return st;
  }
  ss_lim_trans *t = calloc(1, sizeof *t);
  if (!t) return ss_error_nomem(err, "transition");
  ss_lim_patch child;
  ss_cx *ccx;
  if ((st = ss_lim_step(L->s, s->cx, k, 1, &child, &t->g, &ccx, &t->W, err))) {
    free(t);
    return st;
  }
  if ((st = state_of(L, &child, ccx, &t->next, err))) {
    free(t->W);
    free(t);
    return st;
  }
  L->st[i]->tr[k] = t; /* L->st may have moved, the state has not */
  L->stats.transitions++;
  L->st[t->next]->coarse_only = 0; /* a child's patch: keep its transitions */
  if (s->coarse_only && !s->held) {
    size_t slot = L->nrecent % LIM_RECENT;
    if (L->nrecent >= LIM_RECENT) {
      ss_lim_state *old = L->st[L->recent[slot]];
      if (old->coarse_only) {
        drop_transitions(old);
        ss_cx_free(old->cx);
        old->cx = NULL;
      }
      old->held = 0;
    }
    L->recent[slot] = i;
    L->nrecent++;
    s->held = 1;
  }
  *out = t;
  return SS_OK;
}

/* ---- the walk ---- */

static ss_status check_args(const ss_limit *L, size_t cell, const double x[3],
                            ss_error *err) {
  if (cell >= L->mesh->nc[SS_HEX])
    return ss_error_set(err, SS_EINPUT,
                        "cell %zu does not exist (the mesh has %zu cells)", cell + 1,
                        L->mesh->nc[SS_HEX]);
  static const char *const name[3] = {"u", "v", "w"};
  for (int a = 0; a < 3; a++)
    if (!(x[a] >= 0.0 && x[a] <= 1.0))
      return ss_error_set(err, SS_EINPUT, "parameter %s = %g is outside [0, 1]", name[a],
                          x[a]);
  return SS_OK;
}

/* A point in the current sub-cell, exactly: coordinate a is d[a] from the
 * corner side s[a] (x = s ? 1 - d : d), with d <= 1/2.  Doubling, picking a
 * child and turning the frame (a reflection only flips s) are then exact in
 * binary floating point, so a point 1e-300 from an extraordinary vertex stays
 * that far through any frame; x itself (with rounding) is formed only for the
 * B-spline of a regular sub-cell. */
typedef struct {
  int s[3];    /* the corner side each coordinate is measured from */
  double d[3]; /* the distance from it, in [0, 1/2] */
} ss_lim_pt;

static void pt_normalize(ss_lim_pt *p) {
  for (int a = 0; a < 3; a++)
    if (p->d[a] > 0.5) {
      p->s[a] ^= 1;
      p->d[a] = 1.0 - p->d[a]; /* exact: Sterbenz */
    }
}

static ss_lim_pt pt_make(const double x[3]) {
  ss_lim_pt p;
  for (int a = 0; a < 3; a++) {
    p.s[a] = 0;
    p.d[a] = x[a];
  }
  pt_normalize(&p);
  return p;
}

static void pt_x(const ss_lim_pt *p, double x[3]) {
  for (int a = 0; a < 3; a++)
    x[a] = p->s[a] ? 1.0 - p->d[a] : p->d[a];
}

/* The child holding the point: bit a set iff x_a >= 1/2. */
static int child_of(const ss_lim_pt *p) {
  unsigned b = 0;
  for (int a = 0; a < 3; a++)
    if (p->s[a] || p->d[a] == 0.5) b |= 1u << a;
  return ss_cube_corner_index(3, b);
}

/* How many consecutive steps from p go into child bits b (-1: for ever);
 * exact, from the binary exponents of the distances to that corner. */
static long run_length(const ss_lim_pt *p, unsigned b) {
  long m = -1;
  for (int a = 0; a < 3; a++) {
    int bit = (int)((b >> a) & 1u), e;
    double dist = p->s[a] == bit ? p->d[a] : 1.0 - p->d[a];
    if (dist == 0.0) continue;
    double f = frexp(dist, &e);
    long ma = bit && f == 0.5 ? 1L - e : -(long)e;
    if (m < 0 || ma < m) m = ma;
  }
  return m;
}

/* m steps into child bits b: the distance to that corner times 2^m. */
static void pt_jump(ss_lim_pt *p, unsigned b, long m) {
  for (int a = 0; a < 3; a++) {
    int bit = (int)((b >> a) & 1u);
    double dist = p->s[a] == bit ? p->d[a] : 1.0 - p->d[a];
    p->s[a] = bit;
    p->d[a] = ldexp(dist, (int)m);
  }
  pt_normalize(p);
}

/* One step into child k, then frame g; M <- G 2 M. */
static void advance(ss_lim_pt *p, int k, const ss_lim_frame *g, double M[3][3]) {
  pt_jump(p, ss_cube_corner_bits(3, k), 1);
  ss_lim_pt q;
  double G[3][3], N[3][3];
  for (int a = 0; a < 3; a++) {
    q.s[a] = p->s[g->perm[a]] ^ g->flip[a];
    q.d[a] = p->d[g->perm[a]];
  }
  *p = q;
  double zero[3] = {0, 0, 0}, unused[3];
  ss_lim_frame_apply(g, zero, unused, G);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      N[i][j] = 0.0;
      for (int r = 0; r < 3; r++)
        N[i][j] += 2.0 * G[i][r] * M[r][j];
    }
  memcpy(M, N, sizeof N);
}

/* Point and Jacobian from a regular patch's points P (patch numbering). */
static void finish_regular(const ss_lim_patch *p, const double *P, const ss_lim_pt *pt,
                           double M[3][3], int derivatives, ss_limit_point *out) {
  double net[64][3], J[3][3], x[3];
  pt_x(pt, x);
  for (int i = 0; i < 64; i++)
    memcpy(net[i], P + (size_t)p->net[i] * 3, sizeof net[i]);
  ss_limit_bspline((const double(*)[3])net, x[0], x[1], x[2], out->p, J);
  if (derivatives)
    for (int i = 0; i < 3; i++)
      for (int d = 0; d < 3; d++) {
        out->jac[i][d] = 0.0;
        for (int a = 0; a < 3; a++)
          out->jac[i][d] += J[a][d] * M[a][i];
      }
}

/* P <- W P (Kc x K times K x 3) into a new buffer. */
static ss_status apply(const double *W, size_t Kc, size_t K, double **P, ss_error *err) {
  double *Q = calloc(Kc * 3 + 1, sizeof *Q);
  if (!Q) return ss_error_nomem(err, "patch points");
  for (size_t i = 0; i < Kc; i++)
    for (size_t j = 0; j < K; j++) {
      double w = W[i * K + j];
      if (w == 0.0) continue;
      for (int d = 0; d < 3; d++)
        Q[i * 3 + (size_t)d] += w * (*P)[j * 3 + (size_t)d];
    }
  free(*P);
  *P = Q;
  return SS_OK;
}

static ss_status not_reached(const ss_limit *L, size_t cell, int steps, ss_error *err) {
  return ss_error_set(
      err, SS_EINPUT,
      "cell %zu: no regular sub-cell after %d subdivision steps: the point "
      "lies on (or within about 2^-%d of) the mesh boundary, and limit "
      "points of the boundary surface are not supported yet",
      cell + 1, steps, steps);
  (void)L;
}

static ss_status walk(ss_limit *L, size_t s, double *P, double o[3], ss_lim_pt pt,
                      double M[3][3], int derivatives, int no_tensor, size_t cell,
                      ss_limit_point *out, ss_error *err);

/* The Jacobian at a fixed point: corner b (bits) of state s, whose run
 * matrix has eigen-decomposition e, patch points P.  With P = sum_i v_i c_i^T
 * and phi_i the limit of the net v_i, phi_i(b + (y - b)/2) = lambda_i
 * phi_i(y): a component with |lambda| < 1/2 has derivative 0 at b, one with
 * lambda = 1/2 (real, not defective) is homogeneous of degree 1 along rays,
 * so its derivative along axis a is 2 phi_i(b moved 1/2 along a), signed;
 * any other component with |lambda| >= 1/2 makes the Jacobian unbounded or
 * direction-dependent, and is refused.  J receives rows d/dx_a in the
 * current frame. */
static ss_status fixed_jacobian(ss_limit *L, size_t s, const ss_lim_eig *e, unsigned b,
                                const double *P, size_t cell, double J[3][3],
                                ss_error *err) {
  ss_status st = SS_OK;
  const size_t K = e->K;
  double *Q = NULL;
  if (e->pw)
    return ss_error_set(
        err, SS_ENUMERIC,
        "cell %zu: the Jacobian at this point (an extraordinary vertex or "
        "edge, or the boundary) needs the eigenvectors of a defective "
        "matrix: %s",
        cell + 1, e->why);
  Q = calloc(K * 3 + 1, sizeof *Q);
  if (!Q) return ss_error_nomem(err, "fixed-point Jacobian");
  double scale = 0.0;
  for (size_t j = 0; j < K * 3; j++)
    if (fabs(P[j] - P[j % 3]) > scale) scale = fabs(P[j] - P[j % 3]);
  double *C = malloc((K * 3 + 1) * sizeof *C);
  if (!C) {
    free(Q);
    return ss_error_nomem(err, "fixed-point Jacobian");
  }
  ss_lim_eig_coef(e, P, C);
  for (size_t i = 0; i < K; i++) {
    const double *c = C + i * 3;
    double cn = fabs(c[0]) + fabs(c[1]) + fabs(c[2]), al = cabs(e->lam[i]);
    if (e->pair[i] == 1) cn += fabs(c[3]) + fabs(c[4]) + fabs(c[5]);
    if (i == e->one || cn <= 1e-9 * scale || al < 0.5 - 1e-8) {
      if (e->pair[i] == 1) i++;
      continue;
    }
    if (fabs(al - 0.5) <= 1e-8 && e->pair[i] == 0) {
      for (size_t r = 0; r < K; r++)
        for (int d = 0; d < 3; d++)
          Q[r * 3 + (size_t)d] += e->V[i * K + r] * c[d];
      continue;
    }
    st =
        ss_error_set(err, SS_ENUMERIC,
                     "cell %zu: the parametric Jacobian is not defined at this point (an "
                     "extraordinary vertex or edge, or the boundary): the eigenvalue "
                     "%.6g%+.6gi of its run has modulus >= 1/2 and is not 1/2",
                     cell + 1, creal(e->lam[i]), cimag(e->lam[i]));
    free(C);
    goto done;
  }
  free(C);
  for (int a = 0; a < 3; a++) {
    ss_lim_pt y;
    for (int d = 0; d < 3; d++) {
      y.s[d] = (int)((b >> d) & 1u);
      y.d[d] = d == a ? 0.5 : 0.0;
    }
    double *Qa = malloc((K * 3 + 1) * sizeof *Qa),
           I3[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    if (!Qa) {
      st = ss_error_nomem(err, "fixed-point Jacobian");
      goto done;
    }
    memcpy(Qa, Q, K * 3 * sizeof *Qa);
    ss_limit_point phi;
    double oq[3] = {0, 0, 0};
    memset(&phi, 0, sizeof phi);
    if ((st = walk(L, s, Qa, oq, y, I3, 0, 1, cell, &phi, err))) goto done;
    const double sign = (b >> a) & 1u ? -2.0 : 2.0;
    for (int d = 0; d < 3; d++)
      J[a][d] = sign * phi.p[d];
  }
done:
  free(Q);
  return st;
}

/* Move the origin o to the first of K points P (3 coordinates each) and make
 * P relative to it.  The rows of W sum to 1, so W (P - o) = W P - o: a shift
 * commutes with every step, and keeping the points relative to a point of
 * the current sub-cell keeps their differences -- of the order of the
 * sub-cell's size, 2^-m after m steps -- to full relative precision, which
 * absolute coordinates would lose (an error of eps |P| 2^m in the Jacobian). */
static void recentre(double *P, size_t K, double o[3]) {
  double c[3] = {P[0], P[1], P[2]};
  for (size_t i = 0; i < K; i++)
    for (int d = 0; d < 3; d++)
      P[i * 3 + (size_t)d] -= c[d];
  for (int d = 0; d < 3; d++)
    o[d] += c[d];
}

static size_t uf_find(size_t *p, size_t i) {
  while (p[i] != i)
    i = p[i] = p[p[i]];
  return i;
}

/* Whether W (Kc child points x T's K parent points, row-major) is A_b (x) F
 * for some F: child point u in layer lc[u] of column cc[u] (ncc columns,
 * cpt[c][l] the point of column c in layer l), parent points as T says;
 * F (ncc x T->ncol) is scratch.  To 1e-12. */
static int factors(const double *W, size_t Kc, const int *lc, const size_t *cc,
                   size_t ncc, const size_t (*cpt)[4], const ss_lim_tensor *T, int b,
                   double *F) {
  const size_t K = T->ncol * 4, n = T->ncol;
  for (size_t p = 0; p < ncc; p++)
    for (size_t q = 0; q < n; q++)
      F[p * n + q] = W[cpt[p][1] * K + T->colpt[q][1]] / bspline_half[b][1][1];
  for (size_t u = 0; u < Kc; u++)
    for (size_t w = 0; w < K; w++) {
      double want = bspline_half[b][lc[u]][T->layer[w]] * F[cc[u] * n + T->col[w]];
      if (!(fabs(W[u * K + w] - want) <= 1e-12)) return 0;
    }
  return 1;
}

/* The layered structure of state i, whose child k is a stationary run: it
 * is an extraordinary edge's when exactly one neighbour k ^ (1 << a) of k is
 * a stationary run too (a vertex has none, a boundary face two), the
 * positions along a are consistent, the points form columns of 4 layers
 * across a, both runs' W factor as A_b (x) T to 1e-12, and every other child
 * is regular with its net factoring likewise -- then every basis function on
 * the cell is a product N_l(x_a) phi_c(y), which eq. (1) needs. */
static ss_status tensor_of(ss_limit *L, size_t i, int k, ss_lim_tensor **out,
                           ss_error *err) {
  ss_status st = SS_OK;
  ss_lim_state *S = L->st[i];
  if (S->ten) {
    *out = S->ten;
    return SS_OK;
  }
  ss_lim_tensor *T = calloc(1, sizeof *T);
  size_t *uf = NULL;
  double *F = NULL;
  if (!T) return ss_error_nomem(err, "layers");
  T->status = -1;
  const size_t K = S->patch.nv;
  unsigned bk = ss_cube_corner_bits(3, k);
  int axis = -1, runs = 0;
  ss_lim_trans *tr[2] = {NULL, NULL};
  for (int a = 0; a < 3; a++) {
    ss_lim_trans *t;
    if ((st = transition(L, i, ss_cube_corner_index(3, bk ^ (1u << a)), &t, err)))
      goto done;
    if (t->next == i && ss_lim_frame_is_id(&t->g)) {
      runs++;
      axis = a;
      tr[(bk >> a) & 1u ? 0 : 1] = t;
    }
  }
  S = L->st[i];
  if (runs != 1 || (S->patch.posbad >> axis) & 1u) goto done;
  tr[(bk >> axis) & 1u] = S->tr[k];
  T->axis = axis;
  T->layer = malloc((K + 1) * sizeof *T->layer);
  T->col = malloc((K + 1) * sizeof *T->col);
  T->colpt = malloc((K + 1) * sizeof *T->colpt);
  uf = malloc((K + 1) * sizeof *uf);
  if (!T->layer || !T->col || !T->colpt || !uf) {
    st = ss_error_nomem(err, "layers");
    goto done;
  }
  for (size_t v = 0; v < K; v++) {
    int l = S->patch.pos[v][axis] + 1;
    if (l < 0 || l > 3) goto done;
    T->layer[v] = l;
    uf[v] = v;
  }
  /* columns: the ends of every cell edge along the axis */
  for (size_t c = 0; c < S->patch.ncells; c++)
    for (unsigned b = 0; b < 8; b++)
      if (!((b >> axis) & 1u)) {
        size_t u = S->patch.key[c * 8 + (size_t)ss_cube_corner_index(3, b)];
        size_t w =
            S->patch.key[c * 8 + (size_t)ss_cube_corner_index(3, b | (1u << axis))];
        uf[uf_find(uf, u)] = uf_find(uf, w);
      }
  for (size_t v = 0; v < K; v++)
    T->col[v] = SIZE_MAX;
  for (size_t v = 0; v < K; v++) {
    size_t r = uf_find(uf, v);
    if (T->col[r] == SIZE_MAX) {
      T->col[r] = T->ncol;
      for (int l = 0; l < 4; l++)
        T->colpt[T->ncol][l] = SIZE_MAX;
      T->ncol++;
    }
    T->col[v] = T->col[r];
  }
  for (size_t v = 0; v < K; v++) {
    size_t *slot = &T->colpt[T->col[v]][T->layer[v]];
    if (*slot != SIZE_MAX) goto done; /* two points of a column in one layer */
    *slot = v;
  }
  for (size_t c = 0; c < T->ncol; c++)
    for (int l = 0; l < 4; l++)
      if (T->colpt[c][l] == SIZE_MAX) goto done;
  /* both halves: W[u][w] = A_b[layer u][layer w] F[col u][col w] */
  F = malloc((T->ncol * T->ncol + 64 * T->ncol + 1) * sizeof *F);
  if (!F) {
    st = ss_error_nomem(err, "layers");
    goto done;
  }
  for (int b = 0; b < 2; b++)
    if (!factors(tr[b]->W, K, T->layer, T->col, T->ncol, (const size_t(*)[4])T->colpt, T,
                 b, F))
      goto done;
  /* every other child: regular (a tricubic B-spline, a tensor product) with
   * its net factoring the same way, its layers along the edge's axis */
  for (int kk = 0; kk < 8; kk++) {
    unsigned bb = ss_cube_corner_bits(3, kk);
    if (((bb ^ bk) & ~(1u << axis)) == 0) continue; /* the two runs */
    ss_lim_trans *t;
    if ((st = transition(L, i, kk, &t, err))) goto done;
    const ss_lim_patch *cp = &L->st[t->next]->patch;
    if (!cp->regular) goto done;
    int ca = 0; /* the child's framed axis along the edge */
    while (t->g.perm[ca] != axis)
      ca++;
    int lay[64];
    size_t col[64], colpt[16][4];
    for (int g = 0; g < 64; g++) {
      int ix[3] = {g % 4, (g / 4) % 4, g / 16};
      int o1 = (ca + 1) % 3, o2 = (ca + 2) % 3;
      int l = t->g.flip[ca] ? 3 - ix[ca] : ix[ca];
      size_t v = cp->net[g];
      lay[v] = l;
      col[v] = (size_t)(4 * ix[o1] + ix[o2]);
      colpt[col[v]][l] = v;
    }
    if (!factors(t->W, 64, lay, col, 16, (const size_t(*)[4])colpt, T,
                 (int)((bb >> axis) & 1u), F))
      goto done;
  }
  T->status = 1;
  L->stats.tensor++;
done:
  free(uf);
  free(F);
  if (st) {
    tensor_free(T);
    return st;
  }
  L->st[i]->ten = T;
  *out = T;
  return SS_OK;
}

/* The point and Jacobian at pt of state s (whose child k is a stationary
 * run along a factoring edge, T) by the paper's eq. (1): the limit is
 * sum_(l,c) P[l,c] N_l(x_a) phi_c(y), so the net Q_c = sum_l N_l(x_a) P[l,c],
 * put in every layer, has the same limit at (0, y) -- a corner along the
 * edge, reached by one jump whatever x_a's digits; and the derivative along
 * the edge is the limit at (0, y) of the net with N_l'. */
static ss_status tensor_eval(ss_limit *L, size_t s, const ss_lim_tensor *T,
                             const double *P, const double o[3], ss_lim_pt pt,
                             double M[3][3], int derivatives, size_t cell,
                             ss_limit_point *out, ss_error *err) {
  ss_status st;
  const size_t K = L->st[s]->patch.nv;
  const int a = T->axis;
  double x[3], bw[2][4];
  pt_x(&pt, x);
  basis(x[a], bw[0], bw[1]);
  ss_lim_pt p0 = pt;
  p0.s[a] = 0;
  p0.d[a] = 0.0;
  for (int pass = 0; pass < (derivatives ? 2 : 1); pass++) {
    double *Q = malloc((K * 3 + 1) * sizeof *Q), oq[3] = {0, 0, 0}, M2[3][3];
    if (!Q) return ss_error_nomem(err, "layered net");
    for (size_t v = 0; v < K; v++)
      for (int d = 0; d < 3; d++) {
        double acc = 0.0;
        for (int l = 0; l < 4; l++)
          acc += bw[pass][l] * P[T->colpt[T->col[v]][l] * 3 + (size_t)d];
        Q[v * 3 + (size_t)d] = acc;
      }
    if (pass == 0)
      for (int d = 0; d < 3; d++)
        oq[d] = o[d];
    memcpy(M2, M, sizeof M2);
    ss_limit_point r;
    memset(&r, 0, sizeof r);
    if ((st = walk(L, s, Q, oq, p0, M2, pass == 0 ? derivatives : 0, 1, cell, &r, err)))
      return st;
    if (pass == 0) {
      *out = r;
      out->products++;
    } else {
      out->products += r.products + 1;
      /* d/dx_a in the current frame, then through M like the other rows */
      for (int i = 0; i < 3; i++)
        for (int d = 0; d < 3; d++)
          out->jac[i][d] += r.p[d] * M[a][i];
    }
  }
  return SS_OK;
}

/* The walk from state s with patch points P (taken over and freed), relative
 * to the origin o (recentred on the way; out->p is absolute). */
static ss_status walk(ss_limit *L, size_t s, double *P, double o[3], ss_lim_pt pt,
                      double M[3][3], int derivatives, int no_tensor, size_t cell,
                      ss_limit_point *out, ss_error *err) {
  ss_status st = SS_OK;
  double *P0 = NULL;
  int plain = 0;
  recentre(P, L->st[s]->patch.nv, o);
  for (;;) {
    ss_lim_state *S = L->st[s];
    if (S->patch.regular) {
      finish_regular(&S->patch, P, &pt, M, derivatives, out);
      for (int d = 0; d < 3; d++)
        out->p[d] += o[d];
      break;
    }
    int k = child_of(&pt);
    ss_lim_trans *t = NULL;
    if ((st = transition(L, s, k, &t, err))) goto done;
    S = L->st[s];
    if (t->next == s && ss_lim_frame_is_id(&t->g)) {
      if (!no_tensor && L->tensor) {
        ss_lim_tensor *T = NULL;
        if ((st = tensor_of(L, s, k, &T, err))) goto done;
        if (T->status == 1) {
          int steps = out->steps, products = out->products;
          st = tensor_eval(L, s, T, P, o, pt, M, derivatives, cell, out, err);
          out->steps += steps;
          out->products += products;
          goto done;
        }
      }
      long m = run_length(&pt, ss_cube_corner_bits(3, k));
      if (m < 0 || m >= JUMP_MIN) {
        if (!t->eig) {
          if ((st = ss_lim_eig_new(t->W, S->patch.nv, &t->eig, err))) goto done;
          L->stats.eigs++;
        }
        if (m < 0 && derivatives) {
          P0 = malloc((S->patch.nv * 3 + 1) * sizeof *P0);
          if (!P0) {
            st = ss_error_nomem(err, "patch points");
            goto done;
          }
          memcpy(P0, P, S->patch.nv * 3 * sizeof *P0);
        }
        double shift[3];
        if ((st = ss_lim_eig_power(t->eig, m, P, shift, err))) goto done;
        for (int d = 0; d < 3; d++)
          o[d] += shift[d];
        out->products++;
        if (m < 0) {
          /* a fixed point: every patch point is its limit */
          for (int d = 0; d < 3; d++)
            out->p[d] = o[d] + P[d];
          if (derivatives) {
            double J[3][3];
            if ((st = fixed_jacobian(L, s, t->eig, ss_cube_corner_bits(3, k), P0, cell, J,
                                     err)))
              goto done;
            for (int i = 0; i < 3; i++)
              for (int d = 0; d < 3; d++) {
                out->jac[i][d] = 0.0;
                for (int a = 0; a < 3; a++)
                  out->jac[i][d] += J[a][d] * M[a][i];
              }
          }
          goto done;
        }
        pt_jump(&pt, ss_cube_corner_bits(3, k), m);
        for (int a = 0; a < 3; a++)
          for (int j = 0; j < 3; j++)
            M[a][j] = ldexp(M[a][j], (int)m);
        out->steps += (int)m;
        recentre(P, S->patch.nv, o);
        continue;
      }
    }
    if ((st = apply(t->W, L->st[t->next]->patch.nv, S->patch.nv, &P, err))) goto done;
    advance(&pt, k, &t->g, M);
    out->steps++;
    out->products++;
    s = t->next;
    recentre(P, L->st[s]->patch.nv, o);
    if (++plain > SS_LIMIT_MAXSTEPS) {
      st = not_reached(L, cell, plain, err);
      goto done;
    }
  }
done:
  free(P0);
  free(P);
  return st;
}

ss_status ss_limit_eval(ss_limit *L, size_t cell, double u, double v, double w,
                        int derivatives, ss_limit_point *out, ss_error *err) {
  ss_status st;
  double x[3] = {u, v, w}, M[3][3];
  memset(out, 0, sizeof *out);
  if ((st = check_args(L, cell, x, err)) || (st = cell_state(L, cell, err))) return st;
  /* the cell's canonical frame: turned, not recomputed (exact) */
  const ss_lim_frame *g0 = &L->cell[cell].g;
  ss_lim_pt pt = pt_make(x), q;
  for (int a = 0; a < 3; a++) {
    q.s[a] = pt.s[g0->perm[a]] ^ g0->flip[a];
    q.d[a] = pt.d[g0->perm[a]];
  }
  ss_lim_frame_apply(g0, x, x, M);
  size_t s = L->cell[cell].state;
  const size_t K0 = L->st[s]->patch.nv;
  double *P = malloc((K0 * 3 + 1) * sizeof *P);
  if (!P) return ss_error_nomem(err, "patch points");
  for (size_t i = 0; i < K0; i++)
    memcpy(P + i * 3, L->mesh->x + (size_t)L->cell[cell].src[i] * 3, 3 * sizeof *P);
  double o[3] = {0, 0, 0};
  return walk(L, s, P, o, q, M, derivatives, 0, cell, out, err);
}

ss_status ss_limit_eval_reference(ss_limit *L, size_t cell, double u, double v, double w,
                                  int derivatives, int max_depth, ss_limit_point *out,
                                  ss_error *err) {
  ss_status st;
  double x[3] = {u, v, w}, M[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  ss_lim_pt pt = pt_make(x);
  ss_lim_patch p;
  ss_cx *pcx = NULL;
  double *P = NULL;
  memset(out, 0, sizeof *out);
  if ((st = check_args(L, cell, x, err))) return st;
  ss_lim_frame g = ss_lim_frame_id();
  if ((st = ss_lim_patch_build(&L->adj, cell, &g, L->loc, &p, err))) return st;
  if ((st = ss_lim_patch_complex(L->mesh, &p, &pcx, err))) goto done;
  double o[3] = {0, 0, 0}; /* the patch is kept relative to o (recentre) */
  for (int depth = 0;; depth++) {
    recentre(pcx->x, pcx->nv, o);
    if (p.regular) {
      P = malloc((p.nv * 3 + 1) * sizeof *P);
      if (!P) {
        st = ss_error_nomem(err, "patch points");
        goto done;
      }
      memcpy(P, pcx->x, p.nv * 3 * sizeof *P);
      finish_regular(&p, P, &pt, M, derivatives, out);
      for (int d = 0; d < 3; d++)
        out->p[d] += o[d];
      break;
    }
    if (depth >= max_depth) {
      st = ss_error_set(
          err, SS_ENUMERIC,
          "cell %zu: the reference evaluator found no regular sub-cell in %d "
          "steps (the point lies on or within 2^-%d of an extraordinary "
          "vertex or edge, or the boundary)",
          cell + 1, max_depth, max_depth);
      goto done;
    }
    int k = child_of(&pt);
    ss_lim_patch child;
    ss_cx *ccx;
    if ((st = ss_lim_step(L->s, pcx, k, 0, &child, &g, &ccx, NULL, err))) goto done;
    ss_lim_patch_free(&p);
    ss_cx_free(pcx);
    p = child;
    pcx = ccx;
    advance(&pt, k, &g, M);
    out->steps++;
    out->products++;
  }
done:
  free(P);
  ss_lim_patch_free(&p);
  ss_cx_free(pcx);
  return st;
}
