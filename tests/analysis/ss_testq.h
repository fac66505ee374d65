/* ss_testq.h — exact rationals of doubles for the tests that check
 * enclosures against exact arithmetic (test_jac_midrad.c,
 * test_charmap_push.c).  Header only. */
#ifndef SS_TESTQ_H
#define SS_TESTQ_H

#include <flint/fmpq.h>

#include "arf.h"

/* q = d exactly (d finite), through arb's arf */
static inline void ss_testq_set_d(fmpq_t q, double d) {
  arf_t a;
  arf_init(a);
  arf_set_d(a, d);
  arf_get_fmpq(q, a);
  arf_clear(a);
}

#endif
