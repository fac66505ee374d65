/* ss_testlink.c — links for the tests. */
#include "ss_testlink.h"

#include <stdio.h>
#include <stdlib.h>

ss_link *ss_testlink_scrambled(const ss_link *l, unsigned seed, int mirror) {
  const int k = l->k;
  int *perm = malloc((size_t)k * sizeof *perm), *inv = malloc((size_t)k * sizeof *inv);
  int *deg = malloc((size_t)k * sizeof *deg),
      *nbr = malloc((size_t)l->off[k] * sizeof *nbr);
  srand(seed);
  for (int v = 0; v < k; v++)
    perm[v] = v;
  for (int v = k - 1; v > 0; v--) {
    int j = rand() % (v + 1), t = perm[v];
    perm[v] = perm[j], perm[j] = t;
  }
  for (int v = 0; v < k; v++)
    inv[perm[v]] = v;
  int n = 0;
  for (int nv = 0; nv < k; nv++) {
    int v = inv[nv], d = ss_link_deg(l, v), r = rand() % d;
    deg[nv] = d;
    for (int i = 0; i < d; i++) {
      int j = mirror ? (r - i + d) % d : (r + i) % d;
      nbr[n++] = perm[l->nbr[l->off[v] + j]];
    }
  }
  ss_link *out = NULL;
  ss_error err = {0};
  if (ss_link_new(k, deg, nbr, &out, &err)) fprintf(stderr, "scrambled: %s\n", err.msg);
  free(perm), free(inv), free(deg), free(nbr);
  return out;
}
