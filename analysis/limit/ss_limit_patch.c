/* ss_limit_patch.c — patches of hex cells: adjacency, the framed walk that
 * numbers them canonically, and one step of local refinement. */
#include <stdlib.h>
#include <string.h>

#include "ss_hash.h"
#include "ss_limit_impl.h"

/* ss_cube_corner_bits(3, .) and ss_cube_corner_index(3, .), one table (the
 * map is its own inverse: corners 2 and 3 swap, and 6 and 7), here because
 * the framed walk asks for them in its innermost loops. */
static const unsigned char corner3[8] = {0, 1, 3, 2, 4, 5, 7, 6};

/* Stored corner index of the corner with binary coordinates b. */
static int cidx(unsigned b) {
  return corner3[b & 7u];
}
static unsigned cbits(int k) {
  return corner3[k & 7];
}

void ss_lim_adj_free(ss_lim_adj *a) {
  if (!a) return;
  free(a->vptr);
  free(a->vcell);
  free(a->nb);
  free(a->cptr);
  free(a->ccell);
  free(a->cmark);
  memset(a, 0, sizeof *a);
}

/* The crease cell types a patch carries. */
static const ss_cell_type crease_types[] = {SS_VERTEX, SS_SEGMENT, SS_QUAD};
#define NCREASE_TYPES (sizeof crease_types / sizeof crease_types[0])

/* a->cptr, a->ccell: the crease cells at each vertex. */
static ss_status crease_incidence(const ss_cx *cx, ss_lim_adj *a, ss_error *err) {
  size_t n = 0;
  for (size_t i = 0; i < NCREASE_TYPES; i++)
    n += cx->nc[crease_types[i]] * (size_t)ss_cell_nverts(crease_types[i]);
  a->cptr = calloc(cx->nv + 1, sizeof *a->cptr);
  a->ccell = malloc((n + 1) * sizeof *a->ccell);
  if (!a->cptr || !a->ccell) return ss_error_nomem(err, "crease incidence");
  for (int pass = 0; pass < 2; pass++) {
    for (size_t i = 0; i < NCREASE_TYPES; i++) {
      ss_cell_type t = crease_types[i];
      int nvt = ss_cell_nverts(t);
      for (size_t c = 0; c < cx->nc[t]; c++)
        for (int j = 0; j < nvt; j++) {
          ss_idx v = ss_cx_cell(cx, t, c)[j];
          if (pass)
            a->ccell[a->cptr[v]++] = 4 * c + (size_t)t;
          else
            a->cptr[v + 1]++;
        }
    }
    if (!pass)
      for (size_t v = 0; v < cx->nv; v++)
        a->cptr[v + 1] += a->cptr[v];
  }
  for (size_t v = cx->nv; v > 0; v--)
    a->cptr[v] = a->cptr[v - 1];
  a->cptr[0] = 0;
  return SS_OK;
}

/* Sort 4 words ascending (a face's corners: qsort cost more than the rest of
 * the adjacency). */
static void sort4(uint32_t k[4]) {
  static const int net[5][2] = {{0, 1}, {2, 3}, {0, 2}, {1, 3}, {1, 2}};
  for (int i = 0; i < 5; i++) {
    const int a = net[i][0], b = net[i][1];
    if (k[a] > k[b]) {
      const uint32_t t = k[a];
      k[a] = k[b];
      k[b] = t;
    }
  }
}

ss_status ss_lim_adj_build(const ss_cx *cx, ss_lim_adj *a, ss_error *err) {
  ss_status st = SS_OK;
  ss_hash *h = NULL;
  memset(a, 0, sizeof *a);
  a->cx = cx;
  a->nh = cx->nc[SS_HEX];
  a->vptr = calloc(cx->nv + 1, sizeof *a->vptr);
  a->vcell = malloc((a->nh * 8 + 1) * sizeof *a->vcell);
  a->nb = malloc((a->nh * 6 + 1) * sizeof *a->nb);
  a->cmark = calloc(a->nh + 1, sizeof *a->cmark);
  if (!a->vptr || !a->vcell || !a->nb || !a->cmark) {
    st = ss_error_nomem(err, "hex adjacency");
    goto done;
  }
  for (size_t c = 0; c < a->nh; c++)
    for (int i = 0; i < 8; i++)
      a->vptr[ss_cx_cell(cx, SS_HEX, c)[i] + 1]++;
  for (size_t v = 0; v < cx->nv; v++)
    a->vptr[v + 1] += a->vptr[v];
  for (size_t c = 0; c < a->nh; c++)
    for (int i = 0; i < 8; i++)
      a->vcell[a->vptr[ss_cx_cell(cx, SS_HEX, c)[i]]++] = c;
  for (size_t v = cx->nv; v > 0; v--)
    a->vptr[v] = a->vptr[v - 1];
  a->vptr[0] = 0;
  for (size_t i = 0; i < a->nh * 6; i++)
    a->nb[i] = -1;
  if ((st = crease_incidence(cx, a, err))) goto done;
  if ((st = ss_hash_new(4, a->nh * 3 + 1, &h, err))) goto done;
  /* each face by its sorted corners; the value is the first (cell, face) */
  for (size_t c = 0; c < a->nh; c++) {
    const ss_idx *v = ss_cx_cell(cx, SS_HEX, c);
    for (int f = 0; f < 6; f++) {
      int axis = f / 2, side = f % 2, n = 0;
      uint32_t key[4];
      for (unsigned b = 0; b < 8; b++)
        if ((int)((b >> axis) & 1u) == side) key[n++] = v[cidx(b)];
      sort4(key);
      uint32_t found;
      int ins;
      if ((st = ss_hash_insert(h, key, (uint32_t)(c * 6 + (size_t)f), &found, &ins, err)))
        goto done;
      if (ins) continue;
      size_t oc = found / 6;
      int of = (int)(found % 6);
      if (a->nb[oc * 6 + (size_t)of] >= 0 || oc == c) {
        st = ss_error_set(err, SS_EINPUT,
                          "hexahedron %zu: a face is shared by more than two hexahedra "
                          "(non-manifold meshes are not supported by limit evaluation)",
                          c + 1);
        goto done;
      }
      a->nb[oc * 6 + (size_t)of] = (int64_t)c;
      a->nb[c * 6 + (size_t)f] = (int64_t)oc;
    }
  }
done:
  ss_hash_free(h);
  if (st) ss_lim_adj_free(a);
  return st;
}

ss_lim_frame ss_lim_frame_id(void) {
  ss_lim_frame g = {{0, 1, 2}, {0, 0, 0}};
  return g;
}

int ss_lim_frame_is_id(const ss_lim_frame *g) {
  for (int a = 0; a < 3; a++)
    if (g->perm[a] != a || g->flip[a]) return 0;
  return 1;
}

void ss_lim_frame_apply(const ss_lim_frame *g, const double xs[3], double xf[3],
                        double G[3][3]) {
  double y[3];
  for (int a = 0; a < 3; a++)
    y[a] = g->flip[a] ? 1.0 - xs[g->perm[a]] : xs[g->perm[a]];
  if (G) {
    memset(G, 0, 9 * sizeof(double));
    for (int a = 0; a < 3; a++)
      G[a][g->perm[a]] = g->flip[a] ? -1.0 : 1.0;
  }
  memcpy(xf, y, sizeof y);
}

/* Stored bits of framed bits b under frame g. */
static unsigned frame_bits(const ss_lim_frame *g, unsigned b) {
  unsigned s = 0;
  for (int a = 0; a < 3; a++)
    s |= (((b >> a) & 1u) ^ (unsigned)g->flip[a]) << g->perm[a];
  return s;
}

void ss_lim_patch_free(ss_lim_patch *p) {
  if (!p) return;
  free(p->key);
  free(p->src);
  free(p->pos);
  free(p->ckey);
  memset(p, 0, sizeof *p);
}

uint64_t ss_lim_patch_hash(const ss_lim_patch *p) {
  uint64_t h = 1469598103934665603ull ^ p->ncells;
  for (size_t i = 0; i < p->ncells * 8; i++) {
    h ^= p->key[i];
    h *= 1099511628211ull;
  }
  for (size_t i = 0; i < p->ncrease * SS_LIM_CREASE_W; i++) {
    h ^= p->ckey[i];
    h *= 1099511628211ull;
  }
  return h;
}

int ss_lim_patch_same(const ss_lim_patch *p, const ss_lim_patch *q) {
  return p->ncells == q->ncells && p->nv == q->nv && p->ncrease == q->ncrease &&
         !memcmp(p->key, q->key, p->ncells * 8 * sizeof *p->key) &&
         (!p->ncrease ||
          !memcmp(p->ckey, q->ckey, p->ncrease * SS_LIM_CREASE_W * sizeof *p->ckey));
}

static int cmp_size(const void *x, const void *y) {
  size_t a = *(const size_t *)x, b = *(const size_t *)y;
  return (a > b) - (a < b);
}

static int cmp_crease(const void *x, const void *y) {
  const uint32_t *a = x, *b = y;
  for (int i = 0; i < SS_LIM_CREASE_W; i++)
    if (a[i] != b[i]) return a[i] < b[i] ? -1 : 1;
  return 0;
}

/* w[1..n]: n vertex numbers of a cell of type t, in the crease key's order
 * (a quad cyclic from its smallest towards the smaller neighbour). */
static void crease_order(ss_cell_type t, uint32_t *w, int n) {
  uint32_t v[4];
  memcpy(v, w + 1, (size_t)n * sizeof *v);
  if (t == SS_SEGMENT && v[1] < v[0]) {
    w[1] = v[1];
    w[2] = v[0];
  } else if (t == SS_QUAD) {
    int m = 0;
    for (int i = 1; i < 4; i++)
      if (v[i] < v[m]) m = i;
    int dir = v[(m + 1) % 4] < v[(m + 3) % 4] ? 1 : 3;
    for (int i = 0; i < 4; i++)
      w[1 + i] = v[(m + dir * i) % 4];
  }
}

/* out->ncrease, out->ckey: the crease cells holding a corner (tv) of the
 * target, numbered by loc (the patch's numbering). */
static ss_status patch_creases(const ss_lim_adj *a, size_t t, const ss_idx *tv,
                               const int64_t *loc, ss_lim_patch *out, ss_error *err) {
  size_t n = 0;
  for (int i = 0; i < 8; i++)
    n += a->cptr[tv[i] + 1] - a->cptr[tv[i]];
  if (!n) return SS_OK;
  size_t *code = malloc(n * sizeof *code);
  out->ckey = malloc(n * SS_LIM_CREASE_W * sizeof *out->ckey);
  if (!code || !out->ckey) {
    free(code);
    return ss_error_nomem(err, "patch creases");
  }
  n = 0;
  for (int i = 0; i < 8; i++)
    for (size_t j = a->cptr[tv[i]]; j < a->cptr[tv[i] + 1]; j++)
      code[n++] = a->ccell[j];
  qsort(code, n, sizeof *code, cmp_size);
  for (size_t i = 0; i < n; i++) {
    if (i && code[i] == code[i - 1]) continue; /* met from two corners */
    ss_cell_type ty = (ss_cell_type)(code[i] & 3u);
    const ss_idx *cv = ss_cx_cell(a->cx, ty, code[i] / 4);
    int nvt = ss_cell_nverts(ty);
    uint32_t *w = out->ckey + out->ncrease * SS_LIM_CREASE_W;
    w[0] = (uint32_t)ty;
    for (int j = 1; j < SS_LIM_CREASE_W; j++)
      w[j] = UINT32_MAX;
    for (int j = 0; j < nvt; j++) {
      if (loc[cv[j]] < 0) {
        const size_t bad = code[i] / 4;
        free(code);
        return ss_error_set(err, SS_EINPUT,
                            "hexahedron %zu: %s %zu at one of its corners is not a face, "
                            "edge or corner of the hexahedra there (limit evaluation "
                            "needs creases on the hexahedra)",
                            t + 1, ss_cell_name(ty), bad + 1);
      }
      w[1 + j] = (uint32_t)loc[cv[j]];
    }
    crease_order(ty, w, nvt);
    out->ncrease++;
  }
  free(code);
  qsort(out->ckey, out->ncrease, SS_LIM_CREASE_W * sizeof *out->ckey, cmp_crease);
  return SS_OK;
}

/* One cell of the walk: which cell, the stored corner of each framed corner
 * (by framed bits), and its grid offset. */
typedef struct {
  size_t cell;
  int sig[8];
  int off[3];
} walk_cell;

/* Whether hex c shares a vertex with the 8 vertices tv. */
/* The member cells of the patch of hex t (corners tv): every hex at a corner
 * of t, each once, into mem; returns their number. */
static size_t member_cells(const ss_lim_adj *a, const ss_idx *tv, size_t *mem) {
  size_t nmem = 0;
  for (int i = 0; i < 8; i++)
    for (size_t j = a->vptr[tv[i]]; j < a->vptr[tv[i] + 1]; j++) {
      size_t c = a->vcell[j];
      int seen = 0;
      for (size_t m = 0; m < nmem && !seen; m++)
        seen = mem[m] == c;
      if (!seen) mem[nmem++] = c;
    }
  return nmem;
}

/* Number the corners of walked cell A (the head-th) in the patch: a vertex
 * met first gets the next number and A's grid position of it; one met before
 * is checked against its position (*posok = 0 and posbad where they
 * disagree). */
static void walk_number(const ss_cx *cx, const walk_cell *A, size_t head, int64_t *loc,
                        ss_lim_patch *out, int *posok) {
  const ss_idx *av = ss_cx_cell(cx, SS_HEX, A->cell);
  for (int i = 0; i < 8; i++) {
    unsigned b = cbits(i);
    ss_idx v = av[A->sig[b]];
    if (loc[v] < 0) {
      loc[v] = (int64_t)out->nv;
      out->src[out->nv] = v;
      for (int d = 0; d < 3; d++)
        out->pos[out->nv][d] = A->off[d] + (int)((b >> d) & 1u);
      out->nv++;
    } else {
      for (int d = 0; d < 3; d++)
        if (out->pos[loc[v]][d] != A->off[d] + (int)((b >> d) & 1u)) {
          *posok = 0;
          out->posbad |= 1u << d;
        }
    }
    out->key[head * 8 + (size_t)i] = (uint32_t)loc[v];
  }
}

/* The neighbour of walked cell A across its framed face (axis, side), if it
 * is a cell of the patch not walked yet (a->cmark 1: at a corner of the
 * target; then 2): appended to q at *tail, its frame carried over the shared
 * face.  SS_EINTERNAL if the face's vertices are not the neighbour's. */
static ss_status walk_across(const ss_lim_adj *a, const walk_cell *A, int axis,
                             unsigned side, walk_cell *q, size_t *tail, ss_error *err) {
  const ss_cx *cx = a->cx;
  const ss_idx *av = ss_cx_cell(cx, SS_HEX, A->cell);
  /* the stored face holding the framed face (axis, side) */
  unsigned fb[4];
  int n = 0;
  for (unsigned b = 0; b < 8; b++)
    if (((b >> axis) & 1u) == side) fb[n++] = b;
  unsigned s0 = cbits(A->sig[fb[0]]), agree = 7u;
  for (int j = 1; j < 4; j++)
    agree &= ~(cbits(A->sig[fb[j]]) ^ s0);
  int saxis = agree & 1u ? 0 : agree & 2u ? 1 : 2;
  int sside = (int)((s0 >> saxis) & 1u);
  int64_t B = a->nb[A->cell * 6 + (size_t)(2 * saxis + sside)];
  /* cmark: 1 a cell at a corner of t not walked yet (patch_walk) */
  if (B < 0 || a->cmark[B] != 1) return SS_OK;
  a->cmark[B] = 2;
  walk_cell *C = &q[*tail];
  C->cell = (size_t)B;
  const ss_idx *bv = ss_cx_cell(cx, SS_HEX, (size_t)B);
  /* shared corners: B's framed b (bit axis = 1 - side) is A's b ^ axis */
  unsigned shared_bits = 0, sb0 = 0;
  for (int j = 0; j < 4; j++) {
    unsigned bb = fb[j] ^ (1u << axis);
    ss_idx v = av[A->sig[fb[j]]];
    int k = -1;
    for (int m = 0; m < 8; m++)
      if (bv[m] == v) k = m;
    if (k < 0)
      return ss_error_set(err, SS_EINTERNAL, "patch walk: face vertex not in neighbour");
    C->sig[bb] = k;
    if (j == 0)
      sb0 = cbits(k), shared_bits = 7u;
    else
      shared_bits &= ~(cbits(k) ^ sb0);
  }
  int naxis = shared_bits & 1u ? 0 : shared_bits & 2u ? 1 : 2;
  for (int j = 0; j < 4; j++) {
    unsigned bb = fb[j] ^ (1u << axis);
    C->sig[fb[j]] = cidx(cbits(C->sig[bb]) ^ (1u << naxis));
  }
  for (int d = 0; d < 3; d++)
    C->off[d] = A->off[d] + (d == axis ? (side ? 1 : -1) : 0);
  (*tail)++;
  return SS_OK;
}

/* Regular: 27 cells, 64 vertices on distinct grid positions in [-1, 2]^3;
 * then out->net holds the grid. */
static void mark_regular(ss_lim_patch *out, int posok) {
  if (out->ncells == 27 && out->nv == 64 && posok && !out->ncrease) {
    int filled[64] = {0}, ok = 1;
    for (size_t v = 0; v < 64 && ok; v++) {
      int i = out->pos[v][0] + 1, j = out->pos[v][1] + 1, k = out->pos[v][2] + 1;
      if (i < 0 || i > 3 || j < 0 || j > 3 || k < 0 || k > 3 ||
          filled[i + 4 * j + 16 * k])
        ok = 0;
      else {
        filled[i + 4 * j + 16 * k] = 1;
        out->net[i + 4 * j + 16 * k] = (uint32_t)v;
      }
    }
    out->regular = ok;
  }
}

/* What patch_walk needs of hex t in every frame: the member cells (every
 * hex at a corner of t) and room for the walk's queue. */
typedef struct {
  size_t *mem;  /* the member cells */
  size_t nmem;  /* their number */
  size_t cap;   /* room: the cells at t's corners, with repeats */
  walk_cell *q; /* cap cells */
} walk_room;

static void room_free(walk_room *w) {
  free(w->mem);
  free(w->q);
}

static ss_status room_make(const ss_lim_adj *a, size_t t, walk_room *w, ss_error *err) {
  const ss_idx *tv = ss_cx_cell(a->cx, SS_HEX, t);
  memset(w, 0, sizeof *w);
  for (int i = 0; i < 8; i++)
    w->cap += a->vptr[tv[i] + 1] - a->vptr[tv[i]];
  w->mem = malloc((w->cap + 1) * sizeof *w->mem);
  w->q = malloc((w->cap + 1) * sizeof *w->q);
  if (!w->mem || !w->q) {
    room_free(w);
    return ss_error_nomem(err, "patch");
  }
  w->nmem = member_cells(a, tv, w->mem);
  return SS_OK;
}

/* ss_lim_patch_build with the room w of t; with bound (a patch of t in
 * another frame) the walk stops as soon as its key is known to compare above
 * bound's (*worse = 1, *out empty): the keys are written cell by cell in walk
 * order, so the first cell whose 8 words differ decides memcmp of the whole
 * keys. */
static ss_status patch_walk(const ss_lim_adj *a, size_t t, const ss_lim_frame *g,
                            int64_t *loc, const ss_lim_patch *bound, const walk_room *w,
                            int *worse, ss_lim_patch *out, ss_error *err) {
  ss_status st = SS_OK;
  *worse = 0;
  const ss_cx *cx = a->cx;
  const ss_idx *tv = ss_cx_cell(cx, SS_HEX, t);
  memset(out, 0, sizeof *out);
  const size_t cap = w->cap, nmem = w->nmem, *mem = w->mem;
  walk_cell *q = w->q;
  int posok = 1;
  out->key = malloc((cap * 8 + 1) * sizeof *out->key);
  out->src = malloc((cap * 8 + 1) * sizeof *out->src);
  out->pos = malloc((cap * 8 + 1) * sizeof *out->pos);
  if (!out->key || !out->src || !out->pos) {
    ss_lim_patch_free(out);
    return ss_error_nomem(err, "patch");
  }
  for (size_t m = 0; m < nmem; m++)
    a->cmark[mem[m]] = 1;
  a->cmark[t] = 2;
  /* the walk, breadth first: cells are numbered in the order they are
   * queued, and a cell's 6 faces are crossed (queueing its neighbours) in
   * order, cell by cell -- but only when the queue needs its next cell, so
   * that a frame refused at an early cell crossed few faces (the queue, and
   * so every key, is the same) */
  size_t head = 0, tail = 0, ex = 0;
  int face = 0;
  q[tail].cell = t;
  for (unsigned b = 0; b < 8; b++)
    q[tail].sig[b] = cidx(frame_bits(g, b));
  q[tail].off[0] = q[tail].off[1] = q[tail].off[2] = 0;
  tail++;
  for (;;) {
    for (; tail <= head && ex < tail; face = (face + 1) % 6, ex += face == 0)
      if ((st = walk_across(a, &q[ex], face / 2, (unsigned)face % 2, q, &tail, err)))
        goto done;
    if (head >= tail) break;
    walk_number(cx, &q[head], head, loc, out, &posok);
    if (bound && head < bound->ncells) {
      const int c =
          memcmp(out->key + head * 8, bound->key + head * 8, 8 * sizeof *out->key);
      if (c > 0) {
        *worse = 1;
        goto done;
      }
      if (c < 0) bound = NULL; /* below bound already: the whole walk is needed */
    }
    head++;
  }
  out->ncells = tail;
  if (tail != nmem) {
    st = ss_error_set(err, SS_EINPUT,
                      "hexahedron %zu: the cells at its corners are not connected "
                      "through faces (a non-manifold vertex; limit evaluation needs "
                      "manifold meshes)",
                      t + 1);
    goto done;
  }
  if ((st = patch_creases(a, t, tv, loc, out, err))) goto done;
  mark_regular(out, posok);
done:
  for (size_t v = 0; v < out->nv; v++)
    loc[out->src[v]] = -1;
  for (size_t m = 0; m < nmem; m++)
    a->cmark[mem[m]] = 0;
  if (st || *worse) ss_lim_patch_free(out);
  return st;
}

ss_status ss_lim_patch_build(const ss_lim_adj *a, size_t t, const ss_lim_frame *g,
                             int64_t *loc, ss_lim_patch *out, ss_error *err) {
  int worse;
  walk_room w;
  memset(out, 0, sizeof *out);
  ss_status st = room_make(a, t, &w, err);
  if (!st) st = patch_walk(a, t, g, loc, NULL, &w, &worse, out, err);
  room_free(&w);
  return st;
}

ss_status ss_lim_patch_canonical(const ss_lim_adj *a, size_t t, int64_t *loc,
                                 ss_lim_patch *out, ss_lim_frame *g, ss_error *err) {
  static const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2},
                                  {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  walk_room w;
  memset(out, 0, sizeof *out);
  ss_status st = room_make(a, t, &w, err);
  if (st) return st;
  for (int p = 0; p < 6; p++)
    for (int f = 0; f < 8; f++) {
      ss_lim_frame h;
      for (int d = 0; d < 3; d++) {
        h.perm[d] = perms[p][d];
        h.flip[d] = (f >> d) & 1;
      }
      ss_lim_patch cand;
      int worse = 0; /* its key above the best's: walk stopped early */
      if ((st = patch_walk(a, t, &h, loc, out->key ? out : NULL, &w, &worse, &cand,
                           err))) {
        ss_lim_patch_free(out);
        room_free(&w);
        return st;
      }
      if (worse) continue;
      int better = out->key == NULL;
      if (!better && cand.ncells == out->ncells) {
        int c = memcmp(cand.key, out->key, cand.ncells * 8 * sizeof *cand.key);
        if (!c && cand.ncrease == out->ncrease && cand.ncrease)
          c = memcmp(cand.ckey, out->ckey,
                     cand.ncrease * SS_LIM_CREASE_W * sizeof *cand.ckey);
        better = c < 0;
      }
      if (better) {
        ss_lim_patch_free(out);
        *out = cand;
        *g = h;
      } else {
        ss_lim_patch_free(&cand);
      }
    }
  room_free(&w);
  return SS_OK;
}

ss_status ss_lim_patch_complex(const ss_cx *cx, const ss_lim_patch *p, ss_cx **out,
                               ss_error *err) {
  ss_status st;
  ss_cx *c = NULL;
  *out = NULL;
  if ((st = ss_cx_new(cx->dim, &c, err))) return st;
  if ((st = ss_cx_reserve_vertices(c, p->nv, err)) ||
      (st = ss_cx_reserve_cells(c, SS_HEX, p->ncells, err)))
    goto done;
  for (size_t k = 0; k < p->ncrease; k++) {
    const uint32_t *w = p->ckey + k * SS_LIM_CREASE_W;
    if ((st = ss_cx_add_cell(c, (ss_cell_type)w[0], w + 1, 0, err))) goto done;
  }
  for (size_t v = 0; v < p->nv; v++)
    if ((st = ss_cx_add_vertex(c, cx->x + (size_t)p->src[v] * (size_t)cx->dim, 0, err)))
      goto done;
  for (size_t k = 0; k < p->ncells; k++) {
    ss_idx v[8];
    for (int i = 0; i < 8; i++)
      v[i] = p->key[k * 8 + (size_t)i];
    if ((st = ss_cx_add_cell(c, SS_HEX, v, 0, err))) goto done;
  }
done:
  if (st)
    ss_cx_free(c);
  else
    *out = c;
  return st;
}

void ss_lim_refined_free(ss_lim_refined *r) {
  if (!r) return;
  free(r->loc);
  ss_lim_adj_free(&r->fa);
  if (r->R) gsl_spmatrix_free(r->R);
  ss_cx_free(r->fine);
  memset(r, 0, sizeof *r);
}

ss_status ss_lim_refine(const ss_scheme *s, const ss_cx *pcx, int with_rows,
                        ss_lim_refined *out, ss_error *err) {
  memset(out, 0, sizeof *out);
  out->pcx = pcx;
  gsl_spmatrix *R = NULL;
  ss_status st = ss_scheme_refine(s, pcx, &out->fine, with_rows ? &R : NULL, err);
  out->R = R;
  if (st) return st;
  if ((st = ss_lim_adj_build(out->fine, &out->fa, err))) return st;
  out->loc = malloc((out->fine->nv + 1) * sizeof *out->loc);
  if (!out->loc) return ss_error_nomem(err, "patch scratch");
  for (size_t v = 0; v < out->fine->nv; v++)
    out->loc[v] = -1;
  return SS_OK;
}

ss_status ss_lim_cut(const ss_lim_refined *r, int k, int canonical, ss_lim_patch *child,
                     ss_lim_frame *g, ss_cx **ccx, double **W, ss_error *err) {
  ss_status st;
  const ss_cx *fine = r->fine, *pcx = r->pcx;
  const gsl_spmatrix *R = r->R;
  memset(child, 0, sizeof *child);
  *ccx = NULL;
  if (W) *W = NULL;
  if (W && !R) return ss_error_set(err, SS_EINTERNAL, "limit: rows not kept");
  /* child k of cell 0 is fine hex k, holding coarse corner k at its corner k */
  if (fine->nc[SS_HEX] < 8 ||
      ss_cx_cell(fine, SS_HEX, (size_t)k)[k] != ss_cx_cell(pcx, SS_HEX, 0)[k])
    return ss_error_set(
        err, SS_EINTERNAL,
        "limit: the split did not put child %d at corner %d of its parent", k, k);
  if (canonical)
    st = ss_lim_patch_canonical(&r->fa, (size_t)k, r->loc, child, g, err);
  else {
    *g = ss_lim_frame_id();
    st = ss_lim_patch_build(&r->fa, (size_t)k, g, r->loc, child, err);
  }
  if (st || (st = ss_lim_patch_complex(fine, child, ccx, err))) goto done;
  if (W) {
    size_t K = pcx->nv, Kc = child->nv;
    double *w = calloc(Kc * K + 1, sizeof *w);
    if (!w) {
      st = ss_error_nomem(err, "patch operator");
      goto done;
    }
    for (size_t i = 0; i < Kc; i++) {
      size_t q0 = child->src[i];
      for (int q = R->p[q0]; q < R->p[q0 + 1]; q++)
        w[i * K + (size_t)R->i[q]] = R->data[q];
    }
    *W = w;
  }
done:
  if (st) {
    ss_lim_patch_free(child);
    ss_cx_free(*ccx);
    *ccx = NULL;
  }
  return st;
}

ss_status ss_lim_step(const ss_scheme *s, const ss_cx *pcx, int k, int canonical,
                      ss_lim_patch *child, ss_lim_frame *g, ss_cx **ccx, double **W,
                      ss_error *err) {
  ss_lim_refined r;
  memset(child, 0, sizeof *child);
  *ccx = NULL;
  if (W) *W = NULL;
  ss_status st = ss_lim_refine(s, pcx, W != NULL, &r, err);
  if (!st) st = ss_lim_cut(&r, k, canonical, child, g, ccx, W, err);
  ss_lim_refined_free(&r);
  return st;
}
