/* ss_diag.c — major-diagonal choices for tet meshes.  See ss_diag.h. */
#include "ss_diag.h"

#include <stdlib.h>
#include <string.h>

const char *ss_diag_name(ss_diag_mode m) {
  return m == SS_DIAG_SKEW     ? "skew"
         : m == SS_DIAG_CENTER ? "center"
         : m == SS_DIAG_PROPER ? "proper"
                               : "bfs";
}

int ss_diag_parse(const char *name, ss_diag_mode *out) {
  if (!strcmp(name, "bfs"))
    *out = SS_DIAG_BFS;
  else if (!strcmp(name, "skew"))
    *out = SS_DIAG_SKEW;
  else if (!strcmp(name, "center"))
    *out = SS_DIAG_CENTER;
  else if (!strcmp(name, "proper"))
    *out = SS_DIAG_PROPER;
  else
    return -1;
  return 0;
}

/* The pairs of opposite edges of a tet in its vertex order, and for each the
 * even permutation that moves it to (0,1), (2,3). */
static const int pair_edges[3][2][2] = {
    {{0, 1}, {2, 3}}, {{0, 2}, {1, 3}}, {{0, 3}, {1, 2}}};
static const int pair_perm[3][4] = {{0, 1, 2, 3}, {0, 2, 3, 1}, {0, 3, 1, 2}};

static void apply_pair(ss_idx *v, int p) {
  ss_idx w[4];
  for (int i = 0; i < 4; i++)
    w[i] = v[pair_perm[p][i]];
  memcpy(v, w, sizeof w);
}

/* Sorted edge key. */
static uint64_t edge_key(ss_idx a, ss_idx b) {
  return a < b ? ((uint64_t)a << 32) | b : ((uint64_t)b << 32) | a;
}

/* Faces of tets, for adjacency: sorted triple and the tet. */
typedef struct {
  ss_idx v[3];
  size_t tet;
} tface;

static int tface_cmp(const void *a, const void *b) {
  const tface *x = a, *y = b;
  for (int i = 0; i < 3; i++)
    if (x->v[i] != y->v[i]) return x->v[i] < y->v[i] ? -1 : 1;
  return (x->tet > y->tet) - (x->tet < y->tet);
}

/* Algorithm 2; match = 1 turns its "fewest shared edges" into "most". */
static ss_status choose_bfs(ss_cx *cx, int match, ss_error *err) {
  const size_t nt = cx->nc[SS_TET];
  if (nt == 0) return SS_OK;
  tface *F = malloc(4 * nt * sizeof *F);
  size_t *nbr = malloc(4 * nt * sizeof *nbr), *queue = malloc(nt * sizeof *queue);
  unsigned char *seen = calloc(nt, 1), *done = calloc(nt, 1);
  ss_status st = SS_OK;
  if (!F || !nbr || !queue || !seen || !done) {
    st = ss_error_nomem(err, "major diagonals");
    goto out;
  }
  for (size_t t = 0; t < nt; t++) {
    const ss_idx *v = ss_cx_cell(cx, SS_TET, t);
    for (int f = 0; f < 4; f++) {
      tface *x = F + 4 * t + f;
      int k = 0;
      for (int i = 0; i < 4; i++)
        if (i != f) x->v[k++] = v[i];
      for (int i = 1; i < 3; i++)
        for (int j = i; j > 0 && x->v[j - 1] > x->v[j]; j--) {
          ss_idx s = x->v[j];
          x->v[j] = x->v[j - 1];
          x->v[j - 1] = s;
        }
      x->tet = t;
      nbr[4 * t + f] = SIZE_MAX;
    }
  }
  qsort(F, 4 * nt, sizeof *F, tface_cmp);
  for (size_t i = 0; i + 1 < 4 * nt; i++)
    if (!memcmp(F[i].v, F[i + 1].v, sizeof F[i].v)) {
      /* record each as the other's neighbour in a free slot */
      for (int s = 0; s < 2; s++) {
        const size_t a = F[i + s].tet, b = F[i + 1 - s].tet;
        for (int f = 0; f < 4; f++)
          if (nbr[4 * a + f] == SIZE_MAX) {
            nbr[4 * a + f] = b;
            break;
          }
      }
    }
  for (size_t root = 0; root < nt; root++) {
    if (seen[root]) continue;
    size_t head = 0, tail = 0;
    queue[tail++] = root;
    seen[root] = 1;
    while (head < tail) {
      const size_t t = queue[head++];
      /* the set s: edges of visited neighbours' diagonals */
      uint64_t s[8];
      int ns = 0;
      for (int f = 0; f < 4; f++) {
        const size_t u = nbr[4 * t + f];
        if (u == SIZE_MAX) continue;
        if (done[u]) {
          const ss_idx *w = ss_cx_cell(cx, SS_TET, u);
          s[ns++] = edge_key(w[0], w[1]);
          s[ns++] = edge_key(w[2], w[3]);
        } else if (!seen[u]) {
          seen[u] = 1;
          queue[tail++] = u;
        }
      }
      ss_idx *v = ss_cx_cell(cx, SS_TET, t);
      int best = 0, bestc = match ? -1 : 3;
      for (int p = 0; p < 3; p++) {
        int c = 0;
        for (int e = 0; e < 2; e++) {
          const uint64_t k = edge_key(v[pair_edges[p][e][0]], v[pair_edges[p][e][1]]);
          for (int i = 0; i < ns; i++)
            c += s[i] == k;
        }
        if (match ? c > bestc : c < bestc) best = p, bestc = c;
      }
      apply_pair(v, best);
      done[t] = 1;
    }
  }
out:
  free(F);
  free(nbr);
  free(queue);
  free(seen);
  free(done);
  return st;
}

/* Whether (a, b, c, d) is an even permutation of the tet order v. */
static int even_order(const ss_idx *v, const ss_idx *o) {
  int pos[4];
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++)
      if (o[i] == v[j]) pos[i] = j;
  int inv = 0;
  for (int i = 0; i < 4; i++)
    for (int j = i + 1; j < 4; j++)
      inv += pos[i] > pos[j];
  return inv % 2 == 0;
}

ss_status ss_diag_choose(ss_cx *cx, ss_diag_mode m, ss_idx v0, ss_idx v1, ss_error *err) {
  if (m == SS_DIAG_BFS || m == SS_DIAG_PROPER)
    return choose_bfs(cx, m == SS_DIAG_PROPER, err);
  size_t hits = 0;
  for (size_t t = 0; t < cx->nc[SS_TET]; t++) {
    ss_idx *v = ss_cx_cell(cx, SS_TET, t);
    int h0 = -1, h1 = -1;
    for (int i = 0; i < 4; i++)
      h0 = v[i] == v0 ? i : h0, h1 = v[i] == v1 ? i : h1;
    if (h0 < 0 || h1 < 0) continue;
    ss_idx rest[2];
    int k = 0;
    for (int i = 0; i < 4; i++)
      if (i != h0 && i != h1) rest[k++] = v[i];
    ss_idx o[4] = {v0, v1, rest[0], rest[1]};
    if (!even_order(v, o)) o[2] = rest[1], o[3] = rest[0]; /* c_i, c_i+1 */
    if (m == SS_DIAG_SKEW) { /* (v0, c_i, c_i+1, v1): pairs v0 c_i, c_i+1 v1 */
      const ss_idx w[4] = {o[0], o[2], o[3], o[1]};
      memcpy(v, w, sizeof w);
    } else {
      memcpy(v, o, sizeof o);
    }
    hits++;
  }
  if (!hits)
    return ss_error_set(err, SS_EINPUT, "major diagonals: (%u, %u) is no edge of a tet",
                        (unsigned)v0, (unsigned)v1);
  return SS_OK;
}
