/* ss_expr.c — weight expressions: libmatheval reads them, FLINT's
 * polynomial parser gives the exact value where it is rational (ss_expr.h). */
#include "ss_expr.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#if SS_HAVE_MATHEVAL
#include <pthread.h>

#include <flint/fmpq_mpoly.h>
#include <matheval.h>
#endif

struct ss_expr {
  char *text;  /* the expression as written */
  void *eval;  /* libmatheval's evaluator */
  int uses_n;  /* 1 if the expression reads n */
  size_t nsub; /* occurrences of the identifier n in text */
};

#if SS_HAVE_MATHEVAL
/* libmatheval's parser keeps its state in globals (flex and bison): one
 * reader at a time.  Evaluation writes the variables' values into the
 * evaluator, so one evaluation at a time too. */
static pthread_mutex_t matheval_lock = PTHREAD_MUTEX_INITIALIZER;
#endif

int ss_expr_available(void) {
  return SS_HAVE_MATHEVAL;
}

void ss_expr_free(ss_expr *e) {
  if (!e) return;
#if SS_HAVE_MATHEVAL
  if (e->eval) evaluator_destroy(e->eval);
#endif
  free(e->text);
  free(e);
}

int ss_expr_uses_n(const ss_expr *e) {
  return e->uses_n;
}

#if SS_HAVE_MATHEVAL
/* Whether text[i] starts the identifier "n" (a whole word). */
static int is_n_at(const char *text, size_t i) {
  const int before = i > 0 && (isalnum((unsigned char)text[i - 1]) || text[i - 1] == '_');
  const char a = text[i + 1];
  return text[i] == 'n' && !before && !(isalnum((unsigned char)a) || a == '_');
}

/* The literal check: only libmatheval's characters, no decimal point,
 * integer literals of at most 6 digits (so that FLINT's exact powers stay
 * small).  0 or -1 with a message. */
static int literals_ok(const char *text, ss_error *err) {
  for (size_t i = 0; text[i]; i++) {
    /* libmatheval's scanner echoes characters it has no rule for to stdout
     * (flex's default): keep to its alphabet */
    if (text[i] != '.' && !isalnum((unsigned char)text[i]) &&
        !strchr("_ \t+-*/^()", text[i])) {
      if (isprint((unsigned char)text[i]))
        ss_error_set(err, SS_EINPUT, ": the character '%c' is not part of an expression",
                     text[i]);
      else
        ss_error_set(err, SS_EINPUT, ": the byte 0x%02x is not part of an expression",
                     (unsigned char)text[i]);
      return -1;
    }
    if (text[i] == '.') {
      ss_error_set(err, SS_EINPUT,
                   ": a decimal point (decimals are not exact: write p/q)");
      return -1;
    }
    if (isdigit((unsigned char)text[i]) &&
        !(i > 0 && (isalpha((unsigned char)text[i - 1]) || text[i - 1] == '_'))) {
      size_t k = i;
      while (isdigit((unsigned char)text[k]))
        k++;
      if (k - i > 6) {
        ss_error_set(err, SS_EINPUT,
                     ": an integer of more than 6 digits (write a smaller fraction)");
        return -1;
      }
      i = k - 1;
    }
  }
  return 0;
}

#endif

ss_status ss_expr_new(const char *text, ss_expr **out, ss_error *err) {
  *out = NULL;
#if !SS_HAVE_MATHEVAL
  (void)text;
  return ss_error_set(err, SS_EINPUT,
                      " is not a rational p/q (digits, optional sign, q > 0), and other "
                      "expressions need GNU libmatheval, which this build did not find");
#else
  if (literals_ok(text, err)) return SS_EINPUT;
  ss_expr *e = calloc(1, sizeof *e);
  if (!e || !(e->text = strdup(text))) {
    free(e);
    return ss_error_nomem(err, "expression");
  }
  pthread_mutex_lock(&matheval_lock);
  e->eval = evaluator_create(e->text);
  char **names = NULL;
  int count = 0;
  if (e->eval) evaluator_get_variables(e->eval, &names, &count);
  ss_status st = SS_OK;
  if (!e->eval)
    st = ss_error_set(err, SS_EINPUT,
                      " is not a rational p/q nor an expression libmatheval reads "
                      "(integers, n, + - * / ^, parentheses, cos, sin, sqrt, pi, ...)");
  for (int i = 0; !st && i < count; i++) {
    if (!strcmp(names[i], "n")) {
      e->uses_n = 1;
      continue;
    }
    st = ss_error_set(err, SS_EINPUT, ": the name '%.40s' is unknown (known: n)",
                      names[i]);
  }
  pthread_mutex_unlock(&matheval_lock);
  for (size_t i = 0; e->text[i]; i++)
    e->nsub += (size_t)is_n_at(e->text, i);
  if (st) {
    ss_expr_free(e);
    return st;
  }
  *out = e;
  return SS_OK;
#endif
}

#if SS_HAVE_MATHEVAL
/* text with every identifier n replaced by "(N)": FLINT's input. */
static char *substitute(const ss_expr *e, long n) {
  char num[32];
  const int len = snprintf(num, sizeof num, "(%ld)", n);
  const size_t size = strlen(e->text) + e->nsub * (size_t)len + 1;
  char *s = malloc(size), *p = s;
  if (!s) return NULL;
  for (size_t i = 0; e->text[i]; i++) {
    if (is_n_at(e->text, i)) {
      memcpy(p, num, (size_t)len);
      p += len;
    } else {
      *p++ = e->text[i];
    }
  }
  *p = '\0';
  return s;
}

/* FLINT's context with a flag beside it: the parser's ring callbacks get
 * ctx back, and ours needs the flag (ctx first, so &ctx[0] is the whole). */
typedef struct {
  fmpq_mpoly_ctx_struct ctx; /* FLINT's context (one variable, unused) */
  int divzero;               /* set when a divisor was exactly 0 */
} flint_reader;

/* The parser's division A = B / C, as FLINT's own callback
 * (fmpq_mpoly_divides) but refusing an exact zero divisor — which FLINT
 * would answer with flint_throw, an abort — by failing the parse. */
static int divides_or_refuse(void *a, const void *b, const void *c, const void *ctx) {
  flint_reader *F = (flint_reader *)ctx;
  if (fmpq_mpoly_is_zero(c, &F->ctx)) {
    F->divzero = 1;
    return 0;
  }
  return fmpq_mpoly_divides(a, b, c, &F->ctx);
}

/* FLINT's exact reading of s (no variables left): 1 with *q, 0 if FLINT's
 * polynomial parser does not read it as a rational constant, -1 if it
 * divides by an exact zero.  fmpq_mpoly_set_str_pretty's own steps with the
 * division callback replaced: that function would abort on such a divisor,
 * which libmatheval's double value misses when rounding made it nonzero
 * and the quotient is then multiplied by 0 (0*(1/(1/49*49 - 1))). */
static int flint_rational(const char *s, fmpq_t q) {
  flint_reader F = {.divzero = 0};
  fmpq_mpoly_t A;
  mpoly_parse_t E;
  fmpq_mpoly_ctx_init(&F.ctx, 1, ORD_LEX);
  fmpq_mpoly_init(A, &F.ctx);
  mpoly_void_ring_init_fmpq_mpoly_ctx(E->R, &F.ctx);
  E->R->ctx = &F; /* the callbacks see F (F.ctx is its first member) */
  E->R->divides = divides_or_refuse;
  mpoly_parse_init(E);
  /* no terminal: the polynomial has no name to read ("_" before) */
  const int parsed = mpoly_parse_parse(E, A, s, (slong)strlen(s)) == 0;
  mpoly_parse_clear(E);
  const int ok = parsed && fmpq_mpoly_is_fmpq(A, &F.ctx);
  if (ok) fmpq_mpoly_get_fmpq(q, A, &F.ctx);
  fmpq_mpoly_clear(A, &F.ctx);
  fmpq_mpoly_ctx_clear(&F.ctx);
  return F.divzero ? -1 : ok;
}
#endif

ss_status ss_expr_eval(const ss_expr *e, long n, ss_expr_value *out, ss_error *err) {
  memset(out, 0, sizeof *out);
#if !SS_HAVE_MATHEVAL
  (void)e;
  (void)n;
  return ss_error_set(err, SS_EINTERNAL, "expressions need libmatheval");
#else
  char *names[1] = {"n"};
  double values[1] = {(double)n};
  pthread_mutex_lock(&matheval_lock);
  const double v = evaluator_evaluate(e->eval, 1, names, values);
  pthread_mutex_unlock(&matheval_lock);
  if (!isfinite(v))
    return ss_error_set(err, SS_EINPUT, " is not finite at n = %ld (a division by zero?)",
                        n);
  out->value = v;
  /* A divisor that is exactly 0 gives an infinite or NaN double, unless
   * rounding made it nonzero, as in 1/(1/49*49 - 1) = -9e15 in doubles:
   * such values are far from every weight and refused here; multiplied by 0
   * (0*(1/(1/49*49 - 1))) they are finite and FLINT's exact reading finds
   * the zero divisor (flint_rational). */
  if (!(fabs(v) <= 1048576.0))
    return ss_error_set(err, SS_EINPUT, " is %.6g at n = %ld, beyond 2^20", v, n);
  char *s = substitute(e, n);
  if (!s) return ss_error_nomem(err, "expression");
  fmpq_t q;
  fmpq_init(q);
  ss_status st = SS_OK;
  const int fr = flint_rational(s, q);
  if (fr < 0)
    st = ss_error_set(err, SS_EINPUT,
                      " divides by exactly 0 at n = %ld (rounding hides it from the "
                      "double value %.17g)",
                      n, v);
  else if (fr) {
    const double qd = fmpq_get_d(q);
    if (!fmpz_fits_si(fmpq_numref(q)) || !fmpz_fits_si(fmpq_denref(q)))
      st = ss_error_set(err, SS_EINPUT,
                        " at n = %ld: a numerator or denominator beyond 63 bits", n);
    else if (!(fabs(qd - v) <= 1e-9 * fmax(1.0, fabs(v))))
      st = ss_error_set(err, SS_EINPUT,
                        " at n = %ld: libmatheval reads %.17g and FLINT %.17g (write it "
                        "with parentheses)",
                        n, v, qd);
    else {
      out->rational = 1;
      out->num = fmpz_get_si(fmpq_numref(q));
      out->den = fmpz_get_si(fmpq_denref(q));
      /* as constant weights are converted (ss_stencil.c): exact when both
       * fit in 53 bits, then one correctly rounded division */
      out->value = (double)out->num / (double)out->den;
    }
  }
  fmpq_clear(q);
  free(s);
  return st;
#endif
}
