/* ss_enum.c — the link generator (see ss_enum.h for the method). */
#include "ss_enum.h"

#include <stdlib.h>
#include <string.h>

#include "ss_canon.h"

#define MAXN (SS_ENUM_MAXK + 1)

/* A rotation system being grown: nb[v][0..deg[v]) in cyclic order. */
typedef struct {
  int n;
  int deg[MAXN];
  int nb[MAXN][MAXN];
} graph;

typedef struct {
  int v, deg;
  int row[MAXN];
} saved_row;

typedef struct {
  int nsaved;
  saved_row s[6];
} undo_log;

/* Per-depth workspace: the parent's automorphisms. */
typedef struct {
  int naut;
  int aut[4 * 3 * MAXN][MAXN];
} level_ws;

typedef struct {
  const ss_enum_opts *o;
  ss_enum_visit visit;
  void *ctx;
  uint64_t count[SS_ENUM_MAXK + 1]; /* visited, by k */
  uint64_t index[SS_ENUM_MAXK + 1]; /* nodes generated so far, by level */
  int split;                        /* level where parts are cut */
  int stop;                         /* the visitor asked to stop */
  graph g;
  ss_canon_ws *cw;
  int starts[3 * 2 * MAXN * MAXN]; /* canon(): (vertex, position, direction) */
  int skey[2 * MAXN * MAXN];       /* canon(): the starts' sort keys */
  int off[MAXN];
  level_ws *lev; /* one per level */
  /* output view */
  int loff[MAXN + 1], lnbr[6 * MAXN];
} gen;

/* ---- rotation edits ---- */

static int pos(const graph *g, int v, int w) {
  for (int i = 0; i < g->deg[v]; i++)
    if (g->nb[v][i] == w) return i;
  return -1;
}

static void save(const graph *g, undo_log *u, int v) {
  saved_row *s = &u->s[u->nsaved++];
  s->v = v;
  s->deg = g->deg[v];
  /* the whole row: a copy of constant size is a few inline moves, not a call */
  memcpy(s->row, g->nb[v], sizeof s->row);
}

static void undo(graph *g, undo_log *u) {
  for (int i = u->nsaved - 1; i >= 0; i--) {
    saved_row *s = &u->s[i];
    g->deg[s->v] = s->deg;
    memcpy(g->nb[s->v], s->row, sizeof s->row);
  }
  u->nsaved = 0;
  g->n--;
}

/* Insert w into v's list at position p. */
static void ins_at(graph *g, int v, int p, int w) {
  int *row = g->nb[v];
  for (int t = g->deg[v]; t > p; t--) /* a few entries: no library call */
    row[t] = row[t - 1];
  row[p] = w;
  g->deg[v]++;
}

static void ins_after(graph *g, int v, int a, int w) {
  ins_at(g, v, pos(g, v, a) + 1, w);
}

static void replace(graph *g, int v, int old, int w) {
  g->nb[v][pos(g, v, old)] = w;
}

static void remove_nb(graph *g, int v, int w) {
  int p = pos(g, v, w), d = g->deg[v];
  memmove(&g->nb[v][p], &g->nb[v][p + 1], (size_t)(d - p - 1) * sizeof(int));
  g->deg[v] = d - 1;
}

static int next_of(const graph *g, int v, int w) {
  int p = pos(g, v, w) + 1;
  return g->nb[v][p == g->deg[v] ? 0 : p];
}

static int prev_of(const graph *g, int v, int w) {
  int p = pos(g, v, w) - 1;
  return g->nb[v][p < 0 ? g->deg[v] - 1 : p];
}

static int adjacent(const graph *g, int a, int b) {
  return pos(g, a, b) >= 0;
}

/* E3 into the face (x, y, z), y at position i around x and z following it. */
static void expand3(graph *g, undo_log *u, int x, int i, int y, int z) {
  int v = g->n++;
  save(g, u, x), save(g, u, y), save(g, u, z);
  ins_at(g, x, i + 1, v);
  ins_after(g, y, z, v);
  ins_after(g, z, x, v);
  g->deg[v] = 3;
  g->nb[v][0] = x, g->nb[v][1] = y, g->nb[v][2] = z;
}

/* E4 on the edge a-c. */
static void expand4(graph *g, undo_log *u, int a, int c) {
  int b = prev_of(g, a, c), d = next_of(g, a, c), v = g->n++;
  save(g, u, a), save(g, u, b), save(g, u, c), save(g, u, d);
  replace(g, a, c, v);
  replace(g, c, a, v);
  ins_after(g, b, c, v);
  ins_after(g, d, a, v);
  g->deg[v] = 4;
  g->nb[v][0] = a, g->nb[v][1] = b, g->nb[v][2] = c, g->nb[v][3] = d;
}

/* E5 at the corner of a between c and d (d following c around a). */
static void expand5(graph *g, undo_log *u, int a, int c) {
  int d = next_of(g, a, c), b = prev_of(g, a, c), e = next_of(g, a, d), v = g->n++;
  save(g, u, a), save(g, u, b), save(g, u, c), save(g, u, d), save(g, u, e);
  replace(g, a, c, v);
  remove_nb(g, a, d);
  replace(g, c, a, v);
  replace(g, d, a, v);
  ins_after(g, b, c, v);
  ins_after(g, e, a, v);
  g->deg[v] = 5;
  g->nb[v][0] = a, g->nb[v][1] = b, g->nb[v][2] = c, g->nb[v][3] = d, g->nb[v][4] = e;
}

/* ---- canonical codes of the current graph ---- */

/* -1, 0, +1 as the degrees of the neighbours of a turning from i in
 * direction da compare with those of b from j in direction db (lexicographic,
 * the shorter sequence first). */
static int degrees_cmp(const graph *g, int a, int i, int da, int b, int j, int db) {
  const int d = g->deg[a];
  if (d != g->deg[b]) return d < g->deg[b] ? -1 : 1;
  for (int t = 0; t < d; t++) {
    int x = g->deg[g->nb[a][(i + da * t + d * t) % d]];
    int y = g->deg[g->nb[b][(j + db * t + d * t) % d]];
    if (x != y) return x < y ? -1 : 1;
  }
  return 0;
}

/* The starts (vertex, position, direction) for a canonical code of the
 * current graph from the half-edges at verts[0..nverts), both directions,
 * into s->starts; returns their number.  Every vertex in verts has the same
 * degree d.  Only starts whose first neighbour has the least degree are kept:
 * a code opens with the start's list (1..d, closed by k), then its first
 * neighbour's, which is 0, d, one new label per further neighbour, 2, k, so a
 * lower degree puts the 2 earlier and gives a lower code; the least code and
 * the starts reaching it are unchanged.  With `group` (only the automorphisms
 * are wanted, not the least code), only starts whose whole sequence of
 * neighbour degrees is the least are kept: an automorphism maps a start to
 * one with the same sequence, so the set stays invariant.  The starts are
 * sorted by the degrees of their first three neighbours, for the same reason:
 * likely winners first, so the others are abandoned early (ss_canon.h: the
 * order changes only the work). */
static int collect_starts(gen *s, const int *verts, int nverts, int group, int first,
                          int *nfirst) {
  const graph *g = &s->g;
  int mind = MAXN;
  *nfirst = 0;
  for (int t = 0; t < nverts; t++)
    for (int i = 0; i < g->deg[verts[t]]; i++)
      if (g->deg[g->nb[verts[t]][i]] < mind) mind = g->deg[g->nb[verts[t]][i]];
  int n = 0;
  for (int t = 0; t < nverts; t++) {
    const int v = verts[t], d = g->deg[v], *q = g->nb[v];
    for (int i = 0; i < d; i++)
      for (int dir = 1; dir >= -1; dir -= 2) {
        if (g->deg[q[i]] != mind) continue;
        const int i1 = (i + dir + d) % d, i2 = (i + 2 * dir + 2 * d) % d;
        const int key = (v != first) << 20 | /* first's starts first */
                        ((g->deg[q[i]] * 32 + g->deg[q[i1]]) * 32 + g->deg[q[i2]]);
        *nfirst += v == first;
        int j = n++;
        for (; j > 0 && s->skey[j - 1] > key; j--) {
          s->skey[j] = s->skey[j - 1];
          memcpy(&s->starts[3 * j], &s->starts[3 * (j - 1)], 3 * sizeof *s->starts);
        }
        s->skey[j] = key;
        s->starts[3 * j] = v, s->starts[3 * j + 1] = i, s->starts[3 * j + 2] = dir;
      }
  }
  if (group) {
    int least = 0, m = 0;
    const int *st = s->starts;
    for (int j = 1; j < n; j++)
      if (degrees_cmp(g, st[3 * j], st[3 * j + 1], st[3 * j + 2], st[3 * least],
                      st[3 * least + 1], st[3 * least + 2]) < 0)
        least = j;
    const int lv = st[3 * least], lp = st[3 * least + 1], ld = st[3 * least + 2];
    for (int j = 0; j < n; j++)
      if (!degrees_cmp(g, st[3 * j], st[3 * j + 1], st[3 * j + 2], lv, lp, ld)) {
        memmove(&s->starts[3 * m], &s->starts[3 * j], 3 * sizeof *s->starts);
        m++;
      }
    n = m;
  }
  return n;
}

/* Least code of the current graph over the starts s->starts[0..n), or 1 if a
 * start from nfirst on beats the first nfirst (ss_canon_run).  No inverse
 * table: most starts are abandoned before they reach most vertices. */
static int canon(gen *s, int n, int nfirst) {
  graph *g = &s->g;
  ss_cgraph cg = {g->n, s->off, g->deg, &g->nb[0][0], NULL};
  return ss_canon_run(&cg, s->starts, n, nfirst, s->cw);
}

/* The automorphisms found by the last canon() into lw.  Valid when that run's
 * starts were a set of half-edges mapped onto itself by every automorphism:
 * then the starts reaching the least code are in bijection with the
 * automorphisms, the first being the identity. */
static void group_from_canon(gen *s, level_ws *lw) {
  const graph *g = &s->g;
  const ss_canon_ws *w = s->cw;
  lw->naut = w->nbest;
  for (int j = 0; j < w->nbest; j++)
    for (int v = 0; v < g->n; v++)
      lw->aut[j][v] = w->best_order[w->labels[j * g->n + v]];
}

/* Automorphisms of the current graph into lw, from the half-edges at
 * verts[0..nverts), a set of vertices that every automorphism maps onto itself
 * (all of them, or one that every automorphism fixes). */
static void automorphisms(gen *s, level_ws *lw, const int *verts, int nverts) {
  int nfirst, n = collect_starts(s, verts, nverts, 1, -1, &nfirst);
  if (n == 1) { /* no other start looks alike: only the identity */
    lw->naut = 1;
    for (int v = 0; v < s->g.n; v++)
      lw->aut[0][v] = v;
    return;
  }
  canon(s, n, n);
  group_from_canon(s, lw);
}

/* ---- the canonical reduction ---- */

/* The degrees a, b, c, ... read as a base-32 number (degrees are below 32):
 * comparing two such numbers compares the sequences lexicographically. */
static long digits4(int a, int b, int c, int d) {
  return (((long)a * 32 + b) * 32 + c) * 32 + d;
}

static long max2(long a, long b) {
  return a > b ? a : b;
}

/* Invariant of the reduction at u with choice i (degree 3: none; 4: the
 * diagonal at positions i, i+2; 5: the apex at position i), or -1 if that
 * reduction is not valid: the greatest sequence of the degrees of u's
 * neighbours read around u from an end of the choice (degree 3: from any
 * neighbour), in either direction, so that mirror images agree. */
static long reduction_invariant(const graph *g, int u, int i) {
  const int d = g->deg[u];
  const int *q = g->nb[u];
  if (d == 3) {
    /* from each neighbour both ways: every order of the three degrees, the
     * greatest of which is the decreasing one (min/max: no branch to miss) */
    const int a = g->deg[q[0]], b = g->deg[q[1]], c = g->deg[q[2]];
    const int ab = a > b ? a : b, hi = ab > c ? ab : c;
    const int ba = a < b ? a : b, lo = ba < c ? ba : c;
    return ((long)hi * 32 + (a + b + c - hi - lo)) * 32 + lo;
  }
  if (d == 4) {
    if (adjacent(g, q[i], q[i + 2])) return -1;
    const int t0 = g->deg[q[i]], t1 = g->deg[q[i + 1]], t2 = g->deg[q[i + 2]],
              t3 = g->deg[q[(i + 3) % 4]];
    return max2(max2(digits4(t0, t1, t2, t3), digits4(t0, t3, t2, t1)),
                max2(digits4(t2, t3, t0, t1), digits4(t2, t1, t0, t3)));
  }
  if (adjacent(g, q[i], q[(i + 2) % 5]) || adjacent(g, q[i], q[(i + 3) % 5])) return -1;
  const int t0 = g->deg[q[i]], t1 = g->deg[q[(i + 1) % 5]], t2 = g->deg[q[(i + 2) % 5]],
            t3 = g->deg[q[(i + 3) % 5]], t4 = g->deg[q[(i + 4) % 5]];
  return max2(digits4(t0, t1, t2, t3) * 32 + t4, digits4(t0, t4, t3, t2) * 32 + t1);
}

/* Key of reduction (u, i) under labelling lab. */
static int reduction_key(const graph *g, const int *lab, int u, int i) {
  const int d = g->deg[u];
  int x = 0;
  if (d == 4) {
    int a = lab[g->nb[u][i]], c = lab[g->nb[u][i + 2]];
    x = a < c ? a : c;
  } else if (d == 5) {
    x = lab[g->nb[u][i]];
  }
  return lab[u] * MAXN + x;
}

/* Is the new vertex v = n-1 with choice 0 the canonical reduction of the
 * current graph, up to automorphism?  Its degree is the minimum degree.  If
 * so and lw is not NULL, the automorphism group goes into lw for the children
 * (ss_enum.h: a parent's expansions are tried once per orbit).  The group
 * comes from the half-edges at the vertices whose reductions tie with v's:
 * the reduction invariant is kept by every automorphism (mirror images
 * included), so that set is mapped onto itself; with no tie every
 * automorphism fixes v and the half-edges at v alone are enough. */
static int is_canonical(gen *s, level_ws *lw) {
  graph *g = &s->g;
  const int v = g->n - 1, d = g->deg[v];
  const int nchoice = d == 3 ? 1 : d == 4 ? 2 : 5;
  const long mine = reduction_invariant(g, v, 0);
  int ties = 0;
  int tie_u[MAXN * 5], tie_i[MAXN * 5];
  for (int u = 0; u < g->n; u++) {
    if (g->deg[u] != d) continue;
    for (int i = 0; i < nchoice; i++) {
      long f = reduction_invariant(g, u, i);
      if (f > mine) return 0;
      if (f == mine) tie_u[ties] = u, tie_i[ties] = i, ties++;
    }
  }
  if (ties == 1) {
    if (lw) automorphisms(s, lw, &tie_u[0], 1);
    return 1;
  }
  /* full canonical labelling from the tied vertices */
  int verts[MAXN * 5], nverts = 0;
  for (int t = 0; t < ties; t++)
    if (!nverts || verts[nverts - 1] != tie_u[t]) verts[nverts++] = tie_u[t];
  /* v = n - 1 with choice 0 wins only if a least start is at v (the least
   * labelling's vertex 0 is a least start's vertex, and the best key is the
   * one with label 0): so v must keep a start, and a start elsewhere that
   * beats all of v's settles it. */
  int nfirst, n = collect_starts(s, verts, nverts, 0, v, &nfirst);
  if (!nfirst || canon(s, n, nfirst)) return 0;
  ss_canon_ws *w = s->cw;
  int best = -1;
  for (int t = 0; t < ties; t++) {
    int key = reduction_key(g, w->labels, tie_u[t], tie_i[t]);
    if (best < 0 || key < best) best = key;
  }
  for (int j = 0; j < w->nbest; j++)
    if (reduction_key(g, w->labels + j * g->n, v, 0) == best) {
      if (lw) group_from_canon(s, lw);
      return 1;
    }
  return 0;
}

/* ---- orbits of expansions under the parent's automorphisms ---- */

static void sort3(int *a) {
  int t;
  if (a[0] > a[1]) t = a[0], a[0] = a[1], a[1] = t;
  if (a[1] > a[2]) t = a[1], a[1] = a[2], a[2] = t;
  if (a[0] > a[1]) t = a[0], a[0] = a[1], a[1] = t;
}

/* 1 if the expansion with key (k0, k1, k2) is the least of its orbit.
 * kind 3: a face (sorted); 4: an edge (k0 < k1, k2 unused); 5: a vertex k0
 * and a pair k1 < k2. */
static int least_in_orbit(const level_ws *lw, int kind, int k0, int k1, int k2) {
  const int key[3] = {k0, k1, kind == 4 ? 0 : k2};
  for (int j = 1; j < lw->naut; j++) {
    const int *a = lw->aut[j];
    int im[3] = {a[k0], a[k1], kind == 4 ? 0 : a[k2]};
    if (kind == 3) {
      sort3(im);
    } else {
      int lo = kind == 4 ? 0 : 1; /* the unordered pair */
      if (im[lo] > im[lo + 1]) {
        int t = im[lo];
        im[lo] = im[lo + 1], im[lo + 1] = t;
      }
    }
    for (int c = 0; c < 3; c++)
      if (im[c] != key[c]) {
        if (im[c] < key[c]) return 0;
        break;
      }
  }
  return 1;
}

/* ---- the search ---- */

static void visit_node(gen *s);

static void output(gen *s) {
  graph *g = &s->g;
  const int k = g->n;
  s->count[k]++;
  if (!s->visit) return;
  int n = 0;
  for (int v = 0; v < k; v++) {
    s->loff[v] = n;
    for (int i = 0; i < g->deg[v]; i++)
      s->lnbr[n++] = g->nb[v][i];
  }
  s->loff[k] = n;
  ss_link l = {k, s->loff, s->lnbr};
  if (s->visit(&l, s->ctx)) s->stop = 1;
}

/* A node was generated: decide by its index whether this part owns it. */
static void accept(gen *s) {
  const int k = s->g.n;
  const ss_enum_opts *o = s->o;
  uint64_t idx = s->index[k]++;
  int mine =
      o->nparts == 1 || k > s->split || idx % (uint64_t)o->nparts == (uint64_t)o->part;
  if (k == s->split && !mine) return;
  if (mine && k >= o->kmin) output(s);
  if (k < o->kmax && !s->stop) visit_node(s);
}

static void visit_node(gen *s) {
  graph *g = &s->g;
  const int n = g->n;
  level_ws *lw = &s->lev[n];
  /* the children's groups, needed only if they are expanded in turn */
  level_ws *child_lw = n + 1 < s->o->kmax ? &s->lev[n + 1] : NULL;
  undo_log u = {0};
  int cnt3 = 0, cnt4 = 0;
  for (int v = 0; v < n; v++)
    cnt3 += g->deg[v] == 3, cnt4 += g->deg[v] == 4;

  /* E3: faces, each once as (x; y, z) with x the smallest */
  for (int x = 0; x < n && !s->stop; x++)
    for (int i = 0; i < g->deg[x]; i++) {
      int y = g->nb[x][i], z = g->nb[x][i + 1 == g->deg[x] ? 0 : i + 1];
      if (y < x || z < x) continue;
      int key[3] = {x, y, z};
      sort3(key);
      if (lw->naut > 1 && !least_in_orbit(lw, 3, key[0], key[1], key[2])) continue;
      expand3(g, &u, x, i, y, z);
      if (is_canonical(s, child_lw)) accept(s);
      undo(g, &u);
      if (s->stop) return;
    }
  /* E4: edges a < c whose quadrilateral apexes b, d hold every degree-3 vertex */
  if (cnt3 <= 2)
    for (int a = 0; a < n && !s->stop; a++)
      for (int i = 0; i < g->deg[a]; i++) {
        int c = g->nb[a][i];
        if (c < a) continue;
        int b = prev_of(g, a, c), d = next_of(g, a, c);
        if (cnt3 - (g->deg[b] == 3) - (g->deg[d] == 3) != 0) continue;
        if (lw->naut > 1 && !least_in_orbit(lw, 4, a, c, 0)) continue;
        expand4(g, &u, a, c);
        if (is_canonical(s, child_lw)) accept(s);
        undo(g, &u);
        if (s->stop) return;
      }
  /* E5: corners (a; c, d) with deg a >= 6, deg c, d >= 5, and every degree-4
   * vertex among the pentagon's b, e */
  if (cnt3 == 0 && cnt4 <= 2)
    for (int a = 0; a < n && !s->stop; a++) {
      if (g->deg[a] < 6) continue;
      for (int i = 0; i < g->deg[a]; i++) {
        int c = g->nb[a][i], d = next_of(g, a, c);
        if (g->deg[c] < 5 || g->deg[d] < 5) continue;
        int b = prev_of(g, a, c), e = next_of(g, a, d);
        if (cnt4 - (g->deg[b] == 4) - (g->deg[e] == 4) != 0) continue;
        int lo = c < d ? c : d, hi = c < d ? d : c;
        if (lw->naut > 1 && !least_in_orbit(lw, 5, a, lo, hi)) continue;
        expand5(g, &u, a, c);
        if (is_canonical(s, child_lw)) accept(s);
        undo(g, &u);
        if (s->stop) return;
      }
    }
}

/* Known counts (DESIGN section 6), used only to choose where to cut parts. */
static double width(int k) {
  static const double t[] = {0,  0,   0,    0,    1,     1,      2,       5,       14,
                             50, 233, 1249, 7595, 49566, 339722, 2406841, 17490241};
  return k <= 16 ? t[k] : 1e9;
}

int ss_enum_split_level(const ss_enum_opts *o) {
  if (o->nparts <= 1) return o->kmax;
  int B = o->kmax;
  for (int s = 5; s < B - 1; s++)
    if (width(s) >= 64.0 * o->nparts) return s;
  return B - 1 > 4 ? B - 1 : B;
}

ss_status ss_enum_links(const ss_enum_opts *o, ss_enum_visit visit, void *ctx,
                        uint64_t *counts, ss_error *err) {
  if (o->kmin < 4 || o->kmax > SS_ENUM_MAXK || o->kmin > o->kmax)
    return ss_error_set(err, SS_EINPUT, "vertex counts %d..%d: need 4 <= A <= B <= %d",
                        o->kmin, o->kmax, SS_ENUM_MAXK);
  if (o->nparts < 1 || o->part < 0 || o->part >= o->nparts)
    return ss_error_set(err, SS_EINPUT, "part %d/%d: need 0 <= I < N", o->part,
                        o->nparts);
  gen *s = calloc(1, sizeof *s);
  if (!s) return ss_error_nomem(err, "link generator");
  s->lev = malloc((size_t)(MAXN + 1) * sizeof *s->lev);
  s->cw = ss_canon_ws_new(MAXN, 8 * MAXN, 4 * 3 * MAXN);
  if (!s->lev || !s->cw) {
    free(s->lev);
    ss_canon_ws_free(s->cw);
    free(s);
    return ss_error_nomem(err, "link generator");
  }
  s->o = o;
  s->visit = visit;
  s->ctx = ctx;
  s->split = ss_enum_split_level(o);
  for (int v = 0; v < MAXN; v++)
    s->off[v] = v * MAXN;
  /* the tetrahedron */
  static const int k4[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  s->g.n = 4;
  for (int v = 0; v < 4; v++) {
    s->g.deg[v] = 3;
    memcpy(s->g.nb[v], k4[v], sizeof k4[v]);
  }
  static const int all4[4] = {0, 1, 2, 3};
  automorphisms(s, &s->lev[4], all4, 4);
  accept(s);
  if (counts)
    for (int k = 0; k <= SS_ENUM_MAXK; k++)
      counts[k] = s->count[k];
  free(s->lev);
  ss_canon_ws_free(s->cw);
  free(s);
  return SS_OK;
}
