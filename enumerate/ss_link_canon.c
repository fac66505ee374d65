/* ss_link_canon.c — canonical forms, isomorphism and automorphisms of links,
 * by the least breadth-first code over every start (ss_canon.h). */
#include <stdlib.h>
#include <string.h>

#include "ss_canon.h"
#include "ss_link.h"

typedef struct {
  ss_cgraph g;
  int *deg, *inv, *starts;
  ss_canon_ws *w;
} run;

static void run_free(run *r) {
  free(r->deg);
  free(r->inv);
  free(r->starts);
  ss_canon_ws_free(r->w);
}

/* Least code of l over all starts. */
static ss_status run_all(const ss_link *l, run *r, ss_error *err) {
  memset(r, 0, sizeof *r);
  const int k = l->k, e2 = l->off[k];
  r->deg = malloc((size_t)k * sizeof *r->deg);
  r->inv = malloc((size_t)e2 * sizeof *r->inv);
  r->starts = malloc((size_t)e2 * 6 * sizeof *r->starts);
  r->w = ss_canon_ws_new(k, e2 + k, 2 * e2);
  if (!r->deg || !r->inv || !r->starts || !r->w) {
    run_free(r);
    return ss_error_nomem(err, "canonical form");
  }
  for (int v = 0; v < k; v++) {
    r->deg[v] = ss_link_deg(l, v);
    for (int i = 0; i < r->deg[v]; i++)
      for (int d = 0; d < 2; d++) {
        int *st = r->starts + 6 * (l->off[v] + i) + 3 * d;
        st[0] = v, st[1] = i, st[2] = d ? -1 : 1;
      }
  }
  ss_canon_inverse(k, l->off, r->deg, l->nbr, r->inv);
  r->g = (ss_cgraph){k, l->off, r->deg, l->nbr, r->inv};
  ss_canon_run(&r->g, r->starts, 2 * e2, 2 * e2, r->w);
  return SS_OK;
}

ss_status ss_link_canonical(const ss_link *l, ss_link **out, int *perm, ss_error *err) {
  *out = NULL;
  run r;
  ss_status st = run_all(l, &r, err);
  if (st) return st;
  const int k = l->k;
  ss_link *c = calloc(1, sizeof *c);
  if (c) {
    c->k = k;
    c->off = malloc((size_t)(k + 1) * sizeof *c->off);
    c->nbr = malloc((size_t)l->off[k] * sizeof *c->nbr);
  }
  if (!c || !c->off || !c->nbr) {
    ss_link_free(c);
    run_free(&r);
    return ss_error_nomem(err, "canonical form");
  }
  /* the least code lists each vertex's neighbours, closed by k */
  int v = 0, n = 0;
  c->off[0] = 0;
  for (int i = 0; i < r.w->ncode; i++) {
    if (r.w->best[i] == k) {
      c->off[++v] = n;
    } else {
      c->nbr[n++] = r.w->best[i];
    }
  }
  if (perm)
    for (int x = 0; x < k; x++)
      perm[r.w->best_order[x]] = x;
  run_free(&r);
  *out = c;
  return SS_OK;
}

int ss_link_isomorphic(const ss_link *a, const ss_link *b) {
  if (a->k != b->k || a->off[a->k] != b->off[b->k]) return 0;
  ss_link *ca, *cb;
  if (ss_link_canonical(a, &ca, NULL, NULL)) return -1;
  if (ss_link_canonical(b, &cb, NULL, NULL)) {
    ss_link_free(ca);
    return -1;
  }
  int same = ss_link_equal(ca, cb);
  ss_link_free(ca);
  ss_link_free(cb);
  return same;
}

ss_status ss_link_automorphisms(const ss_link *l, int **aut, int *naut, ss_error *err) {
  run r;
  ss_status st = run_all(l, &r, err);
  if (st) return st;
  const int k = l->k, n = r.w->nbest;
  int *a = malloc((size_t)n * (size_t)k * sizeof *a);
  if (!a) {
    run_free(&r);
    return ss_error_nomem(err, "automorphisms");
  }
  /* labelling j composed with the inverse of the first: v -> best_order[label_j(v)] */
  for (int j = 0; j < n; j++)
    for (int v = 0; v < k; v++)
      a[(size_t)j * (size_t)k + (size_t)v] =
          r.w->best_order[r.w->labels[(size_t)j * (size_t)k + (size_t)v]];
  /* put the identity first */
  for (int j = 0; j < n; j++) {
    int id = 1;
    for (int v = 0; v < k && id; v++)
      id = a[(size_t)j * (size_t)k + (size_t)v] == v;
    if (id && j) {
      for (int v = 0; v < k; v++) {
        int t = a[v];
        a[v] = a[(size_t)j * (size_t)k + (size_t)v];
        a[(size_t)j * (size_t)k + (size_t)v] = t;
      }
      break;
    }
  }
  run_free(&r);
  *aut = a;
  *naut = n;
  return SS_OK;
}
