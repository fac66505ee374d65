/* ss_expr.h — weight expressions of stencil files (DESIGN section 3): a
 * weight that depends on the valence n, e.g. `3/8 + cos(2*pi/n)/4`, read
 * and evaluated by libraries, never by a parser of ours.
 *
 * GNU libmatheval reads the expression (syntax, names, its value in double
 * precision).  Its value at a valence is rational — and then exact — when
 * FLINT's polynomial parser (fmpq_mpoly_set_str_pretty) reads the expression
 * with n replaced by the valence's digits: only integers, +, -, *, / and
 * non-negative integer powers, the operations of a field, so the value is
 * the exact rational FLINT computes.  Anything else (cos, sin, sqrt, pi,
 * fractional or negative powers, decimal exponents) is "not rational": the
 * double value is used, and the certified path proves nothing about a scheme
 * with such a weight.  The two readings must agree (relative 1e-9) or the
 * expression is refused, so the libraries cannot read it differently
 * unnoticed (e.g. the associativity of ^).
 *
 * Internal to the stencil module (not installed, not exported: no
 * SS_BEGIN_DECLS).  Built without libmatheval
 * (meson option matheval), ss_expr_new refuses every expression, saying so. */
#ifndef SS_EXPR_H
#define SS_EXPR_H

#include <stddef.h>

#include "ss_error.h"

typedef struct ss_expr ss_expr; /* opaque: a read expression */

/* The value of an expression at one valence. */
typedef struct {
  double value;       /* the value; when rational, num / den correctly rounded */
  int rational;       /* 1: exactly num / den (FLINT's reading) */
  long long num, den; /* when rational: the value in lowest terms, den > 0 */
} ss_expr_value;

/* Whether expressions can be read (the build found libmatheval). */
int ss_expr_available(void);

/* Read text (copied).  The only variable is n; literals are integers (a
 * decimal point is refused: 0.1 is not exact — write 1/10).  SS_EINPUT with a
 * message (no file or line: the caller adds them) for a syntax error, an
 * unknown name, a decimal literal, an integer literal of more than 6 digits,
 * or no libmatheval; SS_ENOMEM.  *out is the caller's (ss_expr_free).  Not
 * thread-safe with other ss_expr_new calls' libmatheval parser state: a
 * mutex serialises them. */
ss_status ss_expr_new(const char *text, ss_expr **out, ss_error *err);

/* Free; NULL is a no-op. */
void ss_expr_free(ss_expr *e);

/* Whether e reads the valence n (0 for a constant expression). */
int ss_expr_uses_n(const ss_expr *e);

/* The value of e at valence n >= 1 into *out.  SS_EINPUT "is not finite at
 * n = N (a division by zero?)" when libmatheval's value is not finite, and
 * when FLINT's exact reading divides by exactly 0 (a zero divisor that
 * rounding made nonzero in libmatheval's double value, then multiplied by 0:
 * 0*(1/(1/49*49 - 1))), when the rational FLINT reads differs from
 * libmatheval's value, or when a rational's numerator or denominator does not
 * fit in 63 bits; SS_ENOMEM.  Cost: one
 * parse of the expression. */
ss_status ss_expr_eval(const ss_expr *e, long n, ss_expr_value *out, ss_error *err);

#endif
