/* ss_link.c — links as rotation systems: construction, validation, plantri
 * ASCII text, named links and triangle lists. */
#include "ss_link.h"

#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Vertex name in plantri ASCII (links of at most 52 vertices). */
static char vname(int v) {
  return (char)(v < 26 ? 'a' + v : 'A' + (v - 26));
}

static ss_status alloc_link(int k, int nnbr, ss_link **out, ss_error *err) {
  ss_link *l = calloc(1, sizeof *l);
  if (l) {
    l->k = k;
    l->off = malloc((size_t)(k + 1) * sizeof *l->off);
    l->nbr = malloc((size_t)(nnbr > 0 ? nnbr : 1) * sizeof *l->nbr);
  }
  if (!l || !l->off || !l->nbr) {
    ss_link_free(l);
    return ss_error_nomem(err, "link");
  }
  *out = l;
  return SS_OK;
}

void ss_link_free(ss_link *l) {
  if (!l) return;
  free(l->off);
  free(l->nbr);
  free(l);
}

ss_status ss_link_new(int k, const int *deg, const int *nbr, ss_link **out,
                      ss_error *err) {
  *out = NULL;
  if (k < 4 || k > SS_LINK_MAXK)
    return ss_error_set(err, SS_EINPUT, "a link needs 4..%d vertices, not %d",
                        SS_LINK_MAXK, k);
  long total = 0;
  for (int v = 0; v < k; v++) {
    if (deg[v] < 0 || deg[v] > k)
      return ss_error_set(err, SS_EINPUT, "vertex %d has degree %d", v + 1, deg[v]);
    total += deg[v];
  }
  ss_link *l = NULL;
  ss_status st = alloc_link(k, (int)total, &l, err);
  if (st) return st;
  l->off[0] = 0;
  for (int v = 0; v < k; v++)
    l->off[v + 1] = l->off[v] + deg[v];
  memcpy(l->nbr, nbr, (size_t)total * sizeof *nbr);
  if ((st = ss_link_validate(l, err))) {
    ss_link_free(l);
    return st;
  }
  *out = l;
  return SS_OK;
}

ss_status ss_link_copy(const ss_link *l, ss_link **out, ss_error *err) {
  int n = l->off[l->k];
  ss_status st = alloc_link(l->k, n, out, err);
  if (st) return st;
  memcpy((*out)->off, l->off, (size_t)(l->k + 1) * sizeof *l->off);
  memcpy((*out)->nbr, l->nbr, (size_t)n * sizeof *l->nbr);
  return SS_OK;
}

int ss_link_equal(const ss_link *a, const ss_link *b) {
  if (a->k != b->k) return 0;
  if (memcmp(a->off, b->off, (size_t)(a->k + 1) * sizeof *a->off)) return 0;
  return !memcmp(a->nbr, b->nbr, (size_t)a->off[a->k] * sizeof *a->nbr);
}

/* A directed edge (from, nbr[at]) keyed by its unordered ends. */
typedef struct {
  long key; /* min(ends) * k + max(ends) */
  int from; /* the vertex whose list holds it */
  int at;   /* its index in nbr */
} dirkey;

static int by_key(const void *pa, const void *pb) {
  const dirkey *a = pa, *b = pb;
  return a->key < b->key ? -1 : a->key > b->key;
}

/* twin[e] for every directed edge e = (v, nbr[e]): the position of v in the
 * list of nbr[e], or -1 if it is not there.  Sorting the edges by their
 * unordered ends pairs each with its reverse in O(E log E); searching the
 * lists was quadratic in the degree (bipyramid:99998 took 7 s to parse).
 * Needs lists without repeats.  Returns 0, or -1 when out of memory. */
static int twins(const ss_link *l, int *twin) {
  const long ne = l->off[l->k];
  dirkey *d = malloc(((size_t)ne + 1) * sizeof *d);
  if (!d) return -1;
  for (int v = 0; v < l->k; v++)
    for (int i = l->off[v]; i < l->off[v + 1]; i++) {
      const long a = v < l->nbr[i] ? v : l->nbr[i], b = v < l->nbr[i] ? l->nbr[i] : v;
      d[i] = (dirkey){a * l->k + b, v, i};
      twin[i] = -1;
    }
  qsort(d, (size_t)ne, sizeof *d, by_key);
  for (long i = 0; i + 1 < ne; i++)
    if (d[i].key == d[i + 1].key && d[i].from != d[i + 1].from) {
      const int w = d[i + 1].from; /* d[i] = (v, w) */
      twin[d[i].at] = d[i + 1].at - l->off[w];
      twin[d[i + 1].at] = d[i].at - l->off[d[i].from];
      i++;
    }
  free(d);
  return 0;
}

/* Vertex number for messages: 1-based, as in the numeric text form. */
static const char *NAME(int v, char buf[16]) {
  snprintf(buf, 16, "%d", v + 1);
  return buf;
}

ss_status ss_link_validate(const ss_link *l, ss_error *err) {
  const int k = l->k;
  char b1[16], b2[16];
  if (k < 4)
    return ss_error_set(err, SS_EINPUT, "a link needs at least 4 vertices, not %d", k);
  int *seenby = malloc((size_t)k * sizeof *seenby); /* last list w was met in */
  int *twin = malloc(((size_t)l->off[k] + 1) * sizeof *twin);
  if (!seenby || !twin) {
    free(seenby);
    free(twin);
    return ss_error_nomem(err, "link validation");
  }
  ss_status st = SS_OK;
  for (int v = 0; v < k; v++)
    seenby[v] = -1;
  for (int v = 0; v < k && !st; v++) {
    int d = ss_link_deg(l, v);
    for (int i = 0; i < d; i++) {
      int w = l->nbr[l->off[v] + i];
      if (w < 0 || w >= k) {
        st = ss_error_set(err, SS_EINPUT, "vertex %s: neighbour %d is not a vertex",
                          NAME(v, b1), w + 1);
        break;
      }
      if (w == v) {
        st = ss_error_set(err, SS_EINPUT, "vertex %s lists itself (a loop)", NAME(v, b1));
        break;
      }
      if (seenby[w] == v) {
        st = ss_error_set(err, SS_EINPUT, "vertex %s lists %s twice (a multi-edge)",
                          NAME(v, b1), NAME(w, b2));
        break;
      }
      seenby[w] = v;
    }
    if (!st && d < 3)
      st = ss_error_set(err, SS_EINPUT, "vertex %s has degree %d (at least 3 needed)",
                        NAME(v, b1), d);
  }
  free(seenby);
  if (!st && twins(l, twin)) st = ss_error_nomem(err, "link validation");
  for (int v = 0; v < k && !st; v++)
    for (int i = l->off[v]; i < l->off[v + 1] && !st; i++)
      if (twin[i] < 0)
        st = ss_error_set(
            err, SS_EINPUT,
            "adjacency is not symmetric: %s lists %s but %s does not list %s",
            NAME(v, b1), NAME(l->nbr[i], b2), b2, b1);
  /* Every corner (v; w, w') closes a triangle: around w, w' is followed by v,
   * i.e. w' precedes v (at position twin) in w's list. */
  for (int v = 0; v < k && !st; v++) {
    int d = ss_link_deg(l, v);
    for (int i = 0; i < d && !st; i++) {
      int w = l->nbr[l->off[v] + i], w2 = l->nbr[l->off[v] + (i + 1) % d];
      int dw = ss_link_deg(l, w);
      if (l->nbr[l->off[w] + (twin[l->off[v] + i] + dw - 1) % dw] != w2)
        st = ss_error_set(err, SS_EINPUT,
                          "the rotations do not form triangles: around vertex %d, %d "
                          "follows %d, but around %d, %d does not follow %d",
                          v + 1, w2 + 1, w + 1, w + 1, v + 1, w2 + 1);
    }
  }
  free(twin);
  if (st) return st;
  /* Connected, and Euler characteristic 2 (every face is a triangle). */
  int *stack = malloc((size_t)k * sizeof *stack);
  char *seen = calloc((size_t)k, 1);
  if (!stack || !seen) {
    free(stack);
    free(seen);
    return ss_error_nomem(err, "link validation");
  }
  int top = 0, nseen = 1;
  stack[top++] = 0;
  seen[0] = 1;
  while (top) {
    int v = stack[--top];
    for (int i = l->off[v]; i < l->off[v + 1]; i++)
      if (!seen[l->nbr[i]]) {
        seen[l->nbr[i]] = 1;
        nseen++;
        stack[top++] = l->nbr[i];
      }
  }
  free(stack);
  free(seen);
  if (nseen != k)
    return ss_error_set(err, SS_EINPUT, "not connected: %d of %d vertices reachable",
                        nseen, k);
  long e2 = l->off[k]; /* 2E = 3F */
  long chi = k - e2 / 2 + e2 / 3;
  if (chi != 2)
    return ss_error_set(err, SS_EINPUT,
                        "not a sphere: V - E + F = %d - %ld + %ld = %ld (a sphere has 2)",
                        k, e2 / 2, e2 / 3, chi);
  return SS_OK;
}

/* ---- text ---- */

ss_status ss_link_format(const ss_link *l, char **out, ss_error *err) {
  const int k = l->k;
  const int numeric = k > 52;
  size_t cap = 16 + (size_t)l->off[k] * (numeric ? 8 : 1) + (size_t)k;
  char *s = malloc(cap);
  if (!s) return ss_error_nomem(err, "link text");
  size_t n = (size_t)snprintf(s, cap, "%d ", k);
  for (int v = 0; v < k; v++) {
    if (v) s[n++] = ',';
    for (int i = l->off[v]; i < l->off[v + 1]; i++) {
      if (numeric)
        n +=
            (size_t)snprintf(s + n, cap - n, i > l->off[v] ? " %d" : "%d", l->nbr[i] + 1);
      else
        s[n++] = vname(l->nbr[i]);
    }
  }
  s[n] = '\0';
  *out = s;
  return SS_OK;
}

/* Name value of a plantri ASCII character, or -1. */
static int char_vertex(char c) {
  if (c >= 'a' && c <= 'z') return c - 'a';
  if (c >= 'A' && c <= 'Z') return 26 + (c - 'A');
  return -1;
}

ss_status ss_link_parse(const char *text, ss_link **out, ss_error *err) {
  *out = NULL;
  while (isspace((unsigned char)*text))
    text++;
  /* plantri's default output is binary; only its ASCII form (-a) is a text */
  if (!strncmp(text, ">>planar_code", 13))
    return ss_error_set(err, SS_EINPUT,
                        "this is plantri's binary planar_code (its default output): run "
                        "plantri with -a to write links as ASCII text");
  if (isalpha((unsigned char)*text)) {
    char name[64];
    size_t n = strcspn(text, " \t\r\n");
    if (n >= sizeof name) n = sizeof name - 1;
    memcpy(name, text, n);
    name[n] = '\0';
    const char *rest = text + strcspn(text, " \t\r\n");
    while (isspace((unsigned char)*rest))
      rest++;
    if (*rest) return ss_error_set(err, SS_EINPUT, "unexpected text after '%s'", name);
    return ss_link_named(name, out, err);
  }
  char *end;
  errno = 0;
  long k = strtol(text, &end, 10);
  if (end == text)
    return ss_error_set(err, SS_EINPUT,
                        "expected a vertex count or a link name, found '%.20s'", text);
  if (errno || k < 4 || k > SS_LINK_MAXK)
    return ss_error_set(err, SS_EINPUT, "vertex count %.*s is not in 4..%d",
                        (int)(end - text < 20 ? end - text : 20), text, SS_LINK_MAXK);
  if (!isspace((unsigned char)*end))
    return ss_error_set(err, SS_EINPUT, "expected a space after the vertex count %ld", k);
  const char *p = end;
  while (isspace((unsigned char)*p))
    p++;
  int numeric = isdigit((unsigned char)*p);
  int *deg = calloc((size_t)k, sizeof *deg);
  size_t cap = (size_t)(6 * k), nn = 0;
  int *nbr = malloc(cap * sizeof *nbr);
  ss_status st = SS_OK;
  if (!deg || !nbr) {
    st = ss_error_nomem(err, "link");
    goto done;
  }
  int v = 0;
  for (;;) {
    /* one neighbour list, up to ',' or the end of the text */
    while (*p && *p != ',' && !(*p == '\n' || *p == '\r')) {
      if (*p == ' ' || *p == '\t') {
        p++;
        continue;
      }
      int w;
      if (numeric) {
        if (!isdigit((unsigned char)*p)) {
          st = ss_error_set(err, SS_EINPUT, "vertex %d: '%c' is not a vertex number",
                            v + 1, *p);
          goto done;
        }
        long x = strtol(p, &end, 10);
        p = end;
        w = (x >= 1 && x <= k) ? (int)x - 1 : -1;
        if (w < 0) {
          st = ss_error_set(err, SS_EINPUT, "vertex %d: neighbour %ld is not in 1..%ld",
                            v + 1, x, k);
          goto done;
        }
      } else {
        w = char_vertex(*p);
        if (w < 0 || w >= k) {
          st = ss_error_set(err, SS_EINPUT,
                            "vertex %c: '%c' is not a vertex of a %ld-vertex link",
                            vname(v < 52 ? v : 0), *p, k);
          goto done;
        }
        p++;
      }
      if (v >= k) {
        st = ss_error_set(err, SS_EINPUT, "more than %ld neighbour lists", k);
        goto done;
      }
      if (nn == cap) {
        int *q = realloc(nbr, 2 * cap * sizeof *q);
        if (!q) {
          st = ss_error_nomem(err, "link");
          goto done;
        }
        nbr = q;
        cap *= 2;
      }
      nbr[nn++] = w;
      deg[v]++;
    }
    v++;
    if (*p != ',') break;
    p++;
    if (v >= k) {
      st = ss_error_set(err, SS_EINPUT, "more than %ld neighbour lists", k);
      goto done;
    }
  }
  while (isspace((unsigned char)*p))
    p++;
  if (*p) {
    st = ss_error_set(err, SS_EINPUT, "unexpected '%.20s' after the neighbour lists", p);
    goto done;
  }
  if (v != k) {
    st = ss_error_set(err, SS_EINPUT,
                      "the vertex count is %ld but there are %d neighbour lists", k, v);
    goto done;
  }
  st = ss_link_new((int)k, deg, nbr, out, err);
done:
  free(deg);
  free(nbr);
  return st;
}

/* ---- from triangles ---- */

typedef struct {
  int a, b; /* directed edge a -> b */
  int t;    /* triangle holding it */
} dedge;

static int cmp_dedge(const void *x, const void *y) {
  const dedge *p = x, *q = y;
  if (p->a != q->a) return p->a < q->a ? -1 : 1;
  if (p->b != q->b) return p->b < q->b ? -1 : 1;
  return 0;
}

/* Index of the directed edge (a, b) in the sorted array, or -1. */
static long find_dedge(const dedge *e, long n, int a, int b) {
  long lo = 0, hi = n - 1;
  while (lo <= hi) {
    long mid = (lo + hi) / 2;
    if (e[mid].a == a && e[mid].b == b) return mid;
    if (e[mid].a < a || (e[mid].a == a && e[mid].b < b))
      lo = mid + 1;
    else
      hi = mid - 1;
  }
  return -1;
}

/* The edges of the triangles tri (ntri of them, vertices 0..k-1), both
 * ways round, into u (6 ntri entries).  SS_EINPUT for a vertex out of
 * range or a triangle repeating one. */
static ss_status tri_dedges(int k, int ntri, const int *tri, dedge *u, ss_error *err) {
  for (int t = 0; t < ntri; t++)
    for (int j = 0; j < 3; j++) {
      int a = tri[3 * t + j], b = tri[3 * t + (j + 1) % 3];
      if (a < 0 || a >= k)
        return ss_error_set(err, SS_EINPUT, "triangle %d: vertex %d is not in 1..%d",
                            t + 1, a + 1, k);
      if (a == b || a == tri[3 * t + (j + 2) % 3])
        return ss_error_set(err, SS_EINPUT, "triangle %d repeats vertex %d", t + 1,
                            a + 1);
      u[6 * t + 2 * j] = (dedge){a, b, t};
      u[6 * t + 2 * j + 1] = (dedge){b, a, t};
    }
  return SS_OK;
}

/* Every undirected edge in exactly two triangles: u, the nu edges of
 * tri_dedges, is sorted and each run of equal edges counted.  SS_EINPUT. */
static ss_status check_two_per_edge(dedge *u, long nu, ss_error *err) {
  qsort(u, (size_t)nu, sizeof *u, cmp_dedge);
  for (long i = 0; i < nu;) {
    long j = i;
    while (j < nu && u[j].a == u[i].a && u[j].b == u[i].b)
      j++;
    if (j - i != 2)
      return ss_error_set(err, SS_EINPUT, "edge %d-%d is in %ld triangles, not 2",
                          u[i].a + 1, u[i].b + 1, j - i);
    i = j;
  }
  return SS_OK;
}

/* Orient the ntri triangles tri coherently, by propagation from triangle 0:
 * neighbours across an edge traverse it oppositely (u: the sorted edges of
 * check_two_per_edge, nu of them); a triangle to turn has its corners 1 and
 * 2 swapped.  flip and queue: ntri entries of scratch.  SS_EINPUT when the
 * surface is not orientable or not connected. */
static ss_status orient(int ntri, int *tri, const dedge *u, long nu, signed char *flip,
                        int *queue, ss_error *err) {
  for (int t = 0; t < ntri; t++)
    flip[t] = -1;
  flip[0] = 0;
  int qh = 0, qt = 0;
  queue[qt++] = 0;
  while (qh < qt) {
    int t = queue[qh++];
    for (int j = 0; j < 3; j++) {
      int a = tri[3 * t + j], b = tri[3 * t + (j + 1) % 3];
      long e = find_dedge(u, nu, a, b);
      while (e > 0 && u[e - 1].a == a && u[e - 1].b == b)
        e--;
      int s = u[e].t == t ? u[e + 1].t : u[e].t;
      /* does s traverse a -> b? */
      int same = 0;
      for (int i = 0; i < 3; i++)
        if (tri[3 * s + i] == a && tri[3 * s + (i + 1) % 3] == b) same = 1;
      int want = flip[t] ^ same;
      if (flip[s] < 0) {
        flip[s] = (signed char)want;
        queue[qt++] = s;
      } else if (flip[s] != want) {
        return ss_error_set(err, SS_EINPUT,
                            "the triangles do not form an orientable surface");
      }
    }
  }
  if (qt != ntri)
    return ss_error_set(err, SS_EINPUT, "the triangles do not form a connected surface");
  for (int t = 0; t < ntri; t++)
    if (flip[t]) {
      int s = tri[3 * t + 1];
      tri[3 * t + 1] = tri[3 * t + 2];
      tri[3 * t + 2] = s;
    }
  return SS_OK;
}

/* The number of triangles at each of the k vertices into deg (zero on
 * entry).  SS_EINPUT for a vertex in fewer than 3. */
static ss_status count_degrees(int k, int ntri, const int *tri, int *deg, ss_error *err) {
  for (int t = 0; t < ntri; t++)
    for (int j = 0; j < 3; j++)
      deg[tri[3 * t + j]]++;
  for (int v = 0; v < k; v++)
    if (deg[v] < 3)
      return ss_error_set(err, SS_EINPUT,
                          "vertex %d is in %d triangles (at least 3 needed)", v + 1,
                          deg[v]);
  return SS_OK;
}

/* The directed edges (a, b) of the oriented triangles, each with the third
 * vertex of its triangle (in the field t), into u, sorted: 3 ntri of them.
 * Around a, triangle (a, b, c) says c follows b. */
static void next_dedges(int ntri, const int *tri, dedge *u) {
  for (int t = 0; t < ntri; t++)
    for (int j = 0; j < 3; j++) {
      int a = tri[3 * t + j], b = tri[3 * t + (j + 1) % 3];
      u[3 * t + j] = (dedge){a, b, tri[3 * t + (j + 2) % 3]}; /* t = the third vertex */
    }
  qsort(u, (size_t)(3L * ntri), sizeof *u, cmp_dedge);
}

/* The rotation system: the neighbours of each vertex v in turn into
 * nbr[pos[v] .. pos[v] + deg[v]), walking w -> next(w) = the third vertex of
 * the triangle on (v, w) through u, the nu edges of next_dedges; pos (k + 1
 * offsets) is filled here.  SS_EINPUT when the triangles around a vertex do
 * not close into one cycle. */
static ss_status walk_rotations(int k, const int *deg, const dedge *u, long nu, int *nbr,
                                int *pos, ss_error *err) {
  pos[0] = 0;
  for (int v = 0; v < k; v++)
    pos[v + 1] = pos[v] + deg[v];
  for (int v = 0; v < k; v++) {
    long e0 = find_dedge(u, nu, v, u[pos[v]].b);
    int w = u[e0].b;
    for (int i = 0; i < deg[v]; i++) {
      nbr[pos[v] + i] = w;
      long e = find_dedge(u, nu, v, w);
      if (e < 0)
        return ss_error_set(err, SS_EINPUT, "the triangles around vertex %d do not close",
                            v + 1);
      w = u[e].t;
    }
    if (w != nbr[pos[v]])
      return ss_error_set(err, SS_EINPUT,
                          "the triangles around vertex %d form more than one cycle",
                          v + 1);
  }
  return SS_OK;
}

ss_status ss_link_from_triangles(int k, int ntri, const int *tri_in, ss_link **out,
                                 ss_error *err) {
  *out = NULL;
  if (k < 4 || k > SS_LINK_MAXK)
    return ss_error_set(err, SS_EINPUT, "a link needs 4..%d vertices, not %d",
                        SS_LINK_MAXK, k);
  if (ntri != 2 * k - 4)
    return ss_error_set(err, SS_EINPUT,
                        "%d triangles on %d vertices: a sphere has 2k - 4 = %d", ntri, k,
                        2 * k - 4);
  ss_status st = SS_OK;
  int *tri = malloc((size_t)ntri * 3 * sizeof *tri);
  signed char *flip = calloc((size_t)ntri, 1);
  int *queue = malloc((size_t)ntri * sizeof *queue);
  dedge *u = malloc((size_t)ntri * 6 * sizeof *u); /* undirected: both directions */
  int *deg = calloc((size_t)k, sizeof *deg), *nbr = NULL, *pos = NULL;
  if (!tri || !flip || !queue || !u || !deg) {
    st = ss_error_nomem(err, "link");
    goto done;
  }
  memcpy(tri, tri_in, (size_t)ntri * 3 * sizeof *tri);
  if ((st = tri_dedges(k, ntri, tri, u, err)) ||
      (st = check_two_per_edge(u, 6L * ntri, err)) ||
      (st = orient(ntri, tri, u, 6L * ntri, flip, queue, err)) ||
      (st = count_degrees(k, ntri, tri, deg, err)))
    goto done;
  next_dedges(ntri, tri, u); /* u is reused: the first table is done with */
  nbr = malloc((size_t)(3L * ntri) * sizeof *nbr);
  pos = malloc(((size_t)k + 1) * sizeof *pos);
  if (!nbr || !pos) {
    st = ss_error_nomem(err, "link");
    goto done;
  }
  if ((st = walk_rotations(k, deg, u, 3L * ntri, nbr, pos, err))) goto done;
  st = ss_link_new(k, deg, nbr, out, err);
done:
  free(tri);
  free(flip);
  free(queue);
  free(u);
  free(deg);
  free(nbr);
  free(pos);
  return st;
}

ss_status ss_link_triangles(const ss_link *l, int **tri_out, int *ntri, ss_error *err) {
  int *tri = malloc((size_t)(2 * l->k - 4) * 3 * sizeof *tri);
  if (!tri) return ss_error_nomem(err, "link triangles");
  int n = 0;
  for (int v = 0; v < l->k; v++) {
    int d = ss_link_deg(l, v);
    for (int i = 0; i < d; i++) {
      int w = l->nbr[l->off[v] + i], w2 = l->nbr[l->off[v] + (i + 1) % d];
      if (w > v && w2 > v && n < 2 * l->k - 4) {
        tri[3 * n] = v;
        tri[3 * n + 1] = w;
        tri[3 * n + 2] = w2;
        n++;
      }
    }
  }
  *tri_out = tri;
  *ntri = n;
  return SS_OK;
}

/* ---- named links ---- */

ss_status ss_link_named(const char *name, ss_link **out, ss_error *err) {
  *out = NULL;
  static const int tet[] = {0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2};
  static const int oct[] = {0, 1, 2, 0, 2, 4, 0, 4, 5, 0, 5, 1,
                            3, 2, 1, 3, 4, 2, 3, 5, 4, 3, 1, 5};
  if (!strcmp(name, "tetrahedron")) return ss_link_from_triangles(4, 4, tet, out, err);
  if (!strcmp(name, "octahedron")) return ss_link_from_triangles(6, 8, oct, out, err);
  if (!strcmp(name, "icosahedron")) {
    int t[60], n = 0;
    for (int i = 0; i < 5; i++) {
      int u0 = 1 + i, u1 = 1 + (i + 1) % 5, l0 = 6 + i, l1 = 6 + (i + 1) % 5;
      int f[4][3] = {{0, u0, u1}, {u0, l0, u1}, {u1, l0, l1}, {11, l1, l0}};
      for (int j = 0; j < 4; j++)
        for (int c = 0; c < 3; c++)
          t[n++] = f[j][c];
    }
    return ss_link_from_triangles(12, 20, t, out, err);
  }
  if (!strncmp(name, "bipyramid:", 10)) {
    char *end;
    errno = 0;
    long N = strtol(name + 10, &end, 10);
    if (end == name + 10 || *end || errno || N < 3 || N > SS_LINK_MAXK - 2)
      return ss_error_set(err, SS_EINPUT,
                          "'%s': bipyramid:N needs an equator of N = 3..%d vertices",
                          name, SS_LINK_MAXK - 2);
    int *t = malloc((size_t)N * 6 * sizeof *t);
    if (!t) return ss_error_nomem(err, "bipyramid");
    for (int i = 0; i < N; i++) {
      int a = i, b = (int)((i + 1) % N);
      int *f = t + 6 * i;
      f[0] = (int)N, f[1] = a, f[2] = b;
      f[3] = (int)N + 1, f[4] = b, f[5] = a;
    }
    ss_status st = ss_link_from_triangles((int)N + 2, 2 * (int)N, t, out, err);
    free(t);
    return st;
  }
  return ss_error_set(err, SS_EINPUT,
                      "unknown link '%s' (names: tetrahedron, octahedron, icosahedron, "
                      "bipyramid:N; or plantri ASCII such as '4 bcd,adc,abd,acb')",
                      name);
}
