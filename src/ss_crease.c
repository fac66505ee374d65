/* ss_crease.c — crease classification of surface complexes. */
#include "ss_crease.h"

#include <stdlib.h>

void ss_crease_free(ss_crease *c) {
  if (!c) return;
  free(c->nface);
  free(c->sharp);
  free(c->nedge);
  free(c->kind);
  free(c);
}

ss_status ss_crease_classify(const ss_cx *fine, const ss_split *L, ss_cell_type face,
                             int children_at_edge, ss_crease **out, ss_error *err) {
  *out = NULL;
  const size_t nf = fine->nv, nc = L->ncoarse;
  ss_crease *c = calloc(1, sizeof *c);
  uint32_t *ncrease = calloc(nc + 1, sizeof *ncrease);
  uint32_t *nodd = calloc(nc + 1, sizeof *nodd); /* crease edges not in 2 faces */
  ss_status st = SS_OK;
  if (!c || !ncrease || !nodd) goto nomem;
  c->nface = calloc(nf + 1, sizeof *c->nface);
  c->sharp = calloc(nf + 1, 1);
  c->nedge = calloc(nc + 1, sizeof *c->nedge);
  c->kind = calloc(nc + 1, 1);
  if (!c->nface || !c->sharp || !c->nedge || !c->kind) goto nomem;

  const int fn = ss_cell_nverts(face);
  for (size_t i = 0; i < fine->nc[face] * (size_t)fn; i++)
    c->nface[fine->cells[face][i]]++;
  for (size_t i = 0; i < fine->nc[SS_SEGMENT] * 2; i++) {
    ss_idx x = fine->cells[SS_SEGMENT][i];
    if (ss_split_npar(L, x) == 2) c->sharp[x] = 1;
  }
  for (size_t x = nc; x < nf; x++) {
    if (ss_split_npar(L, x) != 2) continue;
    const int odd = c->nface[x] != 2u * (uint32_t)children_at_edge;
    if (odd) c->sharp[x] = 1;
    for (size_t q = L->ptr[x]; q < L->ptr[x + 1]; q++) {
      ss_idx a = L->parent[q];
      c->nedge[a]++;
      if (c->sharp[x]) ncrease[a]++;
      if (odd) nodd[a]++;
    }
  }
  for (size_t v = 0; v < nc; v++) {
    unsigned char k;
    if (c->nedge[v] == 0 || ncrease[v] >= 3 || (ncrease[v] == 1 && nodd[v]))
      k = SS_CORNER;
    else if (ncrease[v] == 2)
      k = SS_CREASE;
    else
      k = SS_SMOOTH;
    c->kind[v] = k;
  }
  for (size_t i = 0; i < fine->nc[SS_VERTEX]; i++) {
    ss_idx v = fine->cells[SS_VERTEX][i];
    if (v < nc) c->kind[v] = SS_CORNER;
  }
  goto done;
nomem:
  st = ss_error_nomem(err, "crease classification");
done:
  free(ncrease);
  free(nodd);
  if (st) {
    ss_crease_free(c);
    c = NULL;
  }
  *out = c;
  return st;
}
