/* ss_ball.c — arb balls as doubles (ss_ball.h). */
#include "ss_ball.h"

void ss_ball_doubles(const arb_t x, double *lo, double *hi) {
  arf_t t;
  arf_init(t);
  arb_get_lbound_arf(t, x, 64);
  *lo = arf_get_d(t, ARF_RND_FLOOR);
  arb_get_ubound_arf(t, x, 64);
  *hi = arf_get_d(t, ARF_RND_CEIL);
  arf_clear(t);
}
