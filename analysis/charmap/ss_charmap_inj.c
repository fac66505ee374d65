/* ss_charmap_inj.c — injectivity of the characteristic map: the symmetry test,
 * then the PL degree and overlaps (ss_inject) on the two-ring.  Method:
 * ss_charmap.h. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_charmap.h"
#include "ss_inject.h"

ss_status ss_charmap_injectivity(const ss_charmap *cm, const ss_regularity *reg,
                                 ss_charmap_inj *out, ss_error *err) {
  memset(out, 0, sizeof *out);
  ss_verdict *v = &out->verdict;
  if (reg->sym.found) {
    v->verdict = SS_FAIL;
    snprintf(v->reason, sizeof v->reason,
             "psi o sigma = psi for %s, of order %d: the %zu two-ring points sigma "
             "moves share their images with others",
             reg->sym.what, reg->sym.order, reg->sym.moved);
    return SS_OK;
  }
  const int m = cm->dim;
  const size_t n = cm->n;
  /* the net with psi(p) appended as point n, and the cells off the centre */
  double *x = malloc(((n + 1) * (size_t)m) * sizeof *x);
  ss_cell_type *ct = malloc((cm->ncells + 1) * sizeof *ct);
  size_t *cor = malloc((cm->ncells * SS_MAXCELLVERTS + 1) * sizeof *cor);
  ss_status st = SS_OK;
  if (!x || !ct || !cor) {
    st = ss_error_nomem(err, "injectivity test");
    goto done;
  }
  memcpy(x, cm->x, n * (size_t)m * sizeof *x);
  memcpy(x + n * (size_t)m, cm->centre, (size_t)m * sizeof *x);
  size_t nring = 0;
  for (size_t c = 0; c < cm->ncells; c++) {
    const size_t *q = cm->corner + c * SS_MAXCELLVERTS;
    int centre = 0;
    for (int j = 0; j < SS_MAXCELLVERTS; j++)
      centre |= q[j] == 0;
    if (centre) continue;
    ct[nring] = cm->ctype[c];
    memcpy(cor + nring * SS_MAXCELLVERTS, q, SS_MAXCELLVERTS * sizeof *q);
    nring++;
  }
  /* The degree is read from the whole net, the overlaps from the ring; the
   * whole net's overlaps (a superset of the ring's pairs, about as costly
   * again) matter only when the ring has none and the degree is undecided:
   * an overlap of a centre cell then turns "undecided" into a fail. */
  ss_injectivity whole, ring;
  if ((st = ss_inject_test_parts(x, m, n + 1, cm->ctype, cm->corner, cm->ncells, n,
                                 SS_INJECT_DEGREE, &whole, err)) ||
      (st = ss_inject_test_parts(x, m, n + 1, ct, cor, nring, n, SS_INJECT_OVERLAPS,
                                 &ring, err)))
    goto done;
  if (!ring.overlaps && whole.verdict.verdict == SS_UNDECIDED &&
      (st = ss_inject_test(x, m, n + 1, cm->ctype, cm->corner, cm->ncells, n, &whole,
                           err)))
    goto done;
  out->degree = whole.degree;
  out->overlaps = ring.overlaps;
  if (ring.overlaps) {
    v->verdict = SS_FAIL;
    snprintf(v->reason, sizeof v->reason,
             "%zu pairs of ring cells that share no vertex have meeting images (e.g. "
             "two-ring cells %zu and %zu); degree %d",
             ring.overlaps, ring.first[0], ring.first[1], whole.degree);
  } else if (whole.verdict.verdict == SS_UNDECIDED) {
    v->verdict = SS_UNDECIDED;
    snprintf(v->reason, sizeof v->reason, "degree: %.400s", whole.verdict.reason);
  } else if (whole.degree != 1 && whole.degree != -1) {
    v->verdict = SS_FAIL;
    snprintf(v->reason, sizeof v->reason,
             "the image of the two-ring's boundary winds %d times about psi(p)",
             whole.degree);
  } else {
    v->verdict = SS_PASS;
  }
done:
  free(x);
  free(ct);
  free(cor);
  return st;
}
