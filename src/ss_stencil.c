/* ss_stencil.c — reading stencil files.  See ss_stencil.h. */
#include "ss_stencil.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <ini.h>

#include "ss_expr.h"
#include "ss_stencil_impl.h"

static long long gcd_ll(long long a, long long b) {
  if (a < 0) a = -a;
  while (b) {
    const long long t = a % b;
    a = b;
    b = t;
  }
  return a ? a : 1;
}

/* Parse "[+-]digits[/digits]" (surrounding blanks allowed): 0, -1 if malformed,
 * -2 if well formed but a part has more than 17 digits (leading zeros aside). */
static int parse_rational(const char *s, rational *out) {
  while (isspace((unsigned char)*s))
    s++;
  int neg = 0;
  if (*s == '+' || *s == '-') neg = *s++ == '-';
  long long part[2] = {0, 1};
  for (int k = 0; k < 2; k++) {
    if (!isdigit((unsigned char)*s)) return -1;
    long long v = 0;
    int nd = 0;
    while (*s == '0' && isdigit((unsigned char)s[1]))
      s++; /* leading zeros are not digits of the value */
    while (isdigit((unsigned char)*s)) {
      if (++nd > 17) { /* keeps sums of a few terms exact in 63 bits */
        while (isdigit((unsigned char)*s) || *s == '/')
          s++;
        while (isspace((unsigned char)*s))
          s++;
        return *s ? -1 : -2; /* well-formed but too large: say so */
      }
      v = 10 * v + (*s++ - '0');
    }
    part[k] = v;
    if (k == 0 && *s != '/') break;
    if (k == 0) s++;
  }
  while (isspace((unsigned char)*s))
    s++;
  if (*s || part[1] == 0) return -1;
  const long long g = gcd_ll(part[0], part[1]);
  out->num = (neg ? -part[0] : part[0]) / g;
  out->den = part[1] / g;
  return 0;
}

/* sum += c * r, exactly; -1 on overflow. */
int ss_stencil_add_scaled(rational *sum, long long c, rational r) {
  long long a, b, d;
  if (__builtin_mul_overflow(sum->num, r.den, &a) ||
      __builtin_mul_overflow(c, r.num, &b) || __builtin_mul_overflow(b, sum->den, &b) ||
      __builtin_add_overflow(a, b, &a) || __builtin_mul_overflow(sum->den, r.den, &d))
    return -1;
  const long long g = gcd_ll(a, d);
  sum->num = a / g;
  sum->den = d / g;
  return 0;
}

static const char *const role_names[SS_NCELLTYPES][4] = {
    [SS_SEGMENT] = {"self", "other"},
    [SS_TRIANGLE] = {"self", "edge"},
    [SS_QUAD] = {"self", "edge", "opposite"},
    [SS_TET] = {"self", "edge"},
    [SS_HEX] = {"self", "edge", "face", "opposite"},
    [SS_OCT] = {"self", "edge", "opposite"},
};

/* Section names of the cell types: [mask.NAME]. */
static const char *const short_names[SS_NCELLTYPES] = {
    [SS_SEGMENT] = "segment", [SS_TRIANGLE] = "triangle", [SS_QUAD] = "quad",
    [SS_TET] = "tet",         [SS_HEX] = "hex",           [SS_OCT] = "oct",
};

/* Cell types each split takes in a stencil file. */
static int split_takes(ss_split_kind k, ss_cell_type t) {
  if (k == SS_SPLIT_MULTILINEAR) return t == SS_SEGMENT || t == SS_QUAD || t == SS_HEX;
  return t == SS_SEGMENT || t == SS_TRIANGLE || t == SS_TET || t == SS_OCT;
}

void ss_stencil_slot_clear(slot *sl) {
  ss_expr_free(sl->ex);
  free(sl->etext);
  for (int i = 0; i < sl->nov; i++) {
    ss_stencil_slot_clear(sl->ov[i]);
    free(sl->ov[i]);
  }
}

/* "KEY@N": KEY into base (cap bytes) and N into *n (0 without @).  0, or -1
 * when N is not a valence 1..SS_AVG_NMAX written in digits. */
int ss_stencil_key_at(const char *key, char *base, size_t cap, long *n) {
  const char *at = strchr(key, '@');
  const size_t len = at ? (size_t)(at - key) : strlen(key);
  snprintf(base, cap, "%.*s", (int)(len < cap ? len : cap - 1), key);
  *n = 0;
  if (!at) return 0;
  char *end = NULL;
  errno = 0;
  const long v = isdigit((unsigned char)at[1]) ? strtol(at + 1, &end, 10) : -1;
  if (v < 1 || v > SS_AVG_NMAX || errno || *end) return -1;
  *n = v;
  return 0;
}

/* inih's line reader over R->text: copies the next line (at most num - 1
 * bytes, a longer line in pieces) and counts lines, so that the handler knows
 * the line it is called for (the line of the last piece read). */
static char *read_line(char *str, int num, void *stream) {
  reader *R = stream;
  if (!*R->next || num < 2) return NULL;
  R->line = R->newlines + 1;
  int k = 0;
  while (k < num - 1 && R->next[k])
    if (R->next[k++] == '\n') {
      R->newlines++;
      break;
    }
  memcpy(str, R->next, (size_t)k);
  str[k] = '\0';
  R->next += k;
  if (k > 0 && str[k - 1] != '\n' && *R->next) { /* too long: cut, keep counting */
    while (*R->next && *R->next != '\n')
      R->next++;
    if (*R->next) R->next++, R->newlines++;
    if (!R->long_line) R->long_line = R->line;
  }
  return str;
}

static int cell_type_of(const char *s, ss_cell_type *t) {
  for (int k = 0; k < SS_NCELLTYPES; k++)
    if (short_names[k] && !strcmp(s, short_names[k])) {
      *t = (ss_cell_type)k;
      return 0;
    }
  return -1;
}

static int param_key(reader *R, const char *key, const char *value);

/* The slot a key writes: sl itself (n = 0), or a new override of sl at
 * valence n; NULL with R->msg set (repeated valence, too many, no base). */
slot *ss_stencil_slot_for(reader *R, slot *sl, int given, long n, const char *section,
                          const char *key) {
  if (n == 0) return sl;
  if (!given) {
    snprintf(R->msg, sizeof R->msg,
             "[%.64s] %.64s: give the weight at every valence first (a key without @)",
             section, key);
    return NULL;
  }
  for (int i = 0; i < sl->nov; i++)
    if (sl->ovn[i] == n) {
      snprintf(R->msg, sizeof R->msg, "[%.64s] %.64s is given twice", section, key);
      return NULL;
    }
  if (sl->nov == MAXOVER) {
    snprintf(R->msg, sizeof R->msg, "[%.64s] %.64s: more than %d valences apart", section,
             key, MAXOVER);
    return NULL;
  }
  if (!(sl->ov[sl->nov] = calloc(1, sizeof *sl->ov[0]))) {
    R->nomem = 1;
    snprintf(R->msg, sizeof R->msg, "out of memory");
    return NULL;
  }
  sl->ovn[sl->nov] = n;
  return sl->ov[sl->nov++];
}

static int handle(reader *R, const char *section, const char *key, const char *value) {
  if (!strcmp(section, "param")) return param_key(R, key, value);
  if (R->collect) return 1; /* the [param] pass reads nothing else */
  if (!strcmp(section, "scheme")) {
    if (!strcmp(key, "name")) {
      if (R->have_name++) goto repeated;
      if (!*value || strlen(value) >= sizeof R->name) {
        snprintf(R->msg, sizeof R->msg, "[scheme] name must have 1..%zu characters",
                 sizeof R->name - 1);
        return 0;
      }
      strcpy(R->name, value);
    } else if (!strcmp(key, "family")) {
      if (R->have_family++) goto repeated;
      R->family = !strcmp(value, "points")       ? FAM_POINTS
                  : !strcmp(value, "neighbours") ? FAM_NEIGHBOURS
                                                 : FAM_AVERAGING;
      if (strcmp(value, "averaging") && R->family == FAM_AVERAGING) {
        snprintf(R->msg, sizeof R->msg,
                 "[scheme] family '%.64s' is unknown (known: averaging, points, "
                 "neighbours)",
                 value);
        return 0;
      }
    } else if (!strcmp(key, "split")) {
      if (R->have_split++) goto repeated;
      if (!strcmp(value, "multilinear"))
        R->split = SS_SPLIT_MULTILINEAR;
      else if (!strcmp(value, "tetoct"))
        R->split = SS_SPLIT_TETOCT;
      else {
        snprintf(R->msg, sizeof R->msg,
                 "[scheme] split '%.64s' is unknown (known: multilinear, tetoct)", value);
        return 0;
      }
    } else {
      snprintf(R->msg, sizeof R->msg,
               "[scheme] key '%.64s' is unknown (known: name, family, split)", key);
      return 0;
    }
    return 1;
  }
  const int rk = ss_stencil_rule_key(R, section, key, value);
  if (rk >= 0) return rk;
  if (strncmp(section, "mask.", 5)) {
    snprintf(R->msg, sizeof R->msg,
             "section [%.64s] is unknown (known: [scheme], [param], [mask.TYPE], "
             "[volume|surface|crease.POINT], [vertex], [edge], [centre], "
             "[boundary.vertex|edge])",
             section);
    return 0;
  }
  ss_cell_type t;
  if (cell_type_of(section + 5, &t)) {
    snprintf(R->msg, sizeof R->msg,
             "[%.64s]: unknown cell type '%.64s' (known: segment, triangle, quad, "
             "tet, hex, oct)",
             section, section + 5);
    return 0;
  }
  R->has_mask[t] = 1;
  int r = -1;
  char base[64];
  long at = 0;
  const int bad_at = ss_stencil_key_at(key, base, sizeof base, &at);
  for (int q = 0; q < ss_cell_nroles(t) && !bad_at; q++)
    if (!strcmp(base, role_names[t][q])) r = q;
  if (r < 0) {
    char known[64] = "";
    for (int q = 0; q < ss_cell_nroles(t); q++)
      snprintf(known + strlen(known), sizeof known - strlen(known), "%s%s", q ? ", " : "",
               role_names[t][q]);
    snprintf(R->msg, sizeof R->msg, "[%.64s]: role '%.64s' is unknown (known: %s)",
             section, key, known);
    return 0;
  }
  if (!at && R->given[t] & (1u << r)) goto repeated;
  slot *dst =
      ss_stencil_slot_for(R, &R->m[t][r], (int)(R->given[t] >> r & 1u), at, section, key);
  if (!dst) return 0;
  const int ok = ss_stencil_weight_key(R, section, key, value, dst);
  if (ok && !at) R->given[t] |= 1u << r;
  return ok;
repeated:
  snprintf(R->msg, sizeof R->msg, "[%.64s] %.64s is given twice", section, key);
  return 0;
}

/* A weight into *w: text (value with the parameters' values), written as
 * value in the file. */
static int weight_text(reader *R, const char *section, const char *key, const char *text,
                       const char *value, slot *w) {
  const int pr = parse_rational(text, &w->w);
  if (pr == -2) {
    snprintf(R->msg, sizeof R->msg,
             "[%.32s] %s = '%.40s': a numerator or denominator has more than 17 digits "
             "(weights are summed exactly in 64-bit integers; reduce the fraction)",
             section, key, value);
    return 0;
  }
  w->keyline = R->line;
  if (pr) { /* not p/q: an expression */
    ss_error xe = {0};
    if (ss_expr_new(text, &w->ex, &xe)) {
      R->nomem |= xe.status == SS_ENOMEM;
      snprintf(R->msg, sizeof R->msg, "[%.64s] %s = '%.64s'%.160s", section, key, value,
               xe.msg);
      return 0;
    }
    if (!(w->etext = strdup(value))) {
      R->nomem = 1;
      snprintf(R->msg, sizeof R->msg, "out of memory");
      return 0;
    }
  }
  return 1;
}

int ss_stencil_weight_key(reader *R, const char *section, const char *key,
                          const char *value, slot *w) {
  char *sub = NULL; /* value with the parameters' values, or NULL */
  if (R->pv && R->pv->n && !(sub = ss_stencil_substitute(value, R->pv, R->used))) {
    R->nomem = 1;
    snprintf(R->msg, sizeof R->msg, "out of memory");
    return 0;
  }
  const int ok = weight_text(R, section, key, sub ? sub : value, value, w);
  free(sub);
  return ok;
}

/* inih's handler: handle, keeping the first complaint and its line (inih
 * goes on after an error and reports the first error's line). */
static int handler(void *user, const char *section, const char *key, const char *value) {
  reader *R = user;
  char first[sizeof R->msg];
  memcpy(first, R->msg, sizeof first);
  const int ok = handle(R, section, key, value);
  if (!ok && !R->msg_line)
    R->msg_line = R->line;
  else if (!ok)
    memcpy(R->msg, first, sizeof first);
  return ok;
}

/* Line number (1-based) of the first line of text that is "[section]" after
 * trimming, or 0. */
int ss_stencil_section_line(const char *text, const char *section) {
  int line = 1;
  const size_t n = strlen(section);
  for (const char *p = text; *p; line++) {
    const char *e = strchr(p, '\n');
    const char *q = p;
    while (q < (e ? e : p + strlen(p)) && isspace((unsigned char)*q))
      q++;
    if (*q == '[' && !strncmp(q + 1, section, n) && q[n + 1] == ']') return line;
    if (!e) break;
    p = e + 1;
  }
  return 0;
}

/* Weight sl, key `key` of section sec, at every valence (only n = 1 unless
 * it reads n): into *w; *varies |= it reads n.  SS_EINPUT "WHERE:LINE: [SEC]
 * KEY = 'EXPR' is not finite at n = N ...", SS_ENOMEM. */
ss_status ss_stencil_weight_at(const slot *sl, const char *key, const char *where,
                               const char *sec, weight_values *w, int *varies,
                               ss_error *err) {
  const ss_expr *e = sl->ex;
  const int reads = e && ss_expr_uses_n(e);
  *varies |= reads;
  for (long n = 1; n <= (reads ? SS_AVG_NMAX : 1); n++) {
    ss_expr_value v = {0.0, 1, sl->w.num, sl->w.den};
    if (!e) v.value = (double)v.num / (double)v.den; /* as it always was */
    ss_error xe = {0};
    const ss_status st = e ? ss_expr_eval(e, n, &v, &xe) : SS_OK;
    if (st == SS_ENOMEM) return ss_error_nomem(err, "weight expression");
    if (st)
      return ss_error_set(err, SS_EINPUT, "%s:%d: [%s] %s = '%.80s'%s", where,
                          sl->keyline, sec, key, sl->etext, xe.msg);
    w->d[n] = v.value;
    w->exact[n] = (unsigned char)v.rational;
    w->q[n] = (rational){v.num, v.den};
  }
  for (long n = 2; !reads && n <= SS_AVG_NMAX; n++) {
    w->d[n] = w->d[1];
    w->exact[n] = w->exact[1];
    w->q[n] = w->q[1];
  }
  *varies |= sl->nov > 0;
  for (int i = 0; i < sl->nov; i++) { /* KEY@N: the value at valence N */
    const slot *o = sl->ov[i];
    const long n = sl->ovn[i];
    ss_expr_value v = {(double)o->w.num / (double)o->w.den, 1, o->w.num, o->w.den};
    ss_error xe = {0};
    const ss_status st = o->ex ? ss_expr_eval(o->ex, n, &v, &xe) : SS_OK;
    if (st == SS_ENOMEM) return ss_error_nomem(err, "weight expression");
    if (st)
      return ss_error_set(err, SS_EINPUT, "%s:%d: [%s] %s@%ld = '%.80s'%s", where,
                          o->keyline, sec, key, n, o->etext, xe.msg);
    w->d[n] = v.value;
    w->exact[n] = (unsigned char)v.rational;
    w->q[n] = (rational){v.num, v.den};
  }
  return SS_OK;
}

/* Check that the weights of type t sum to 1 over the cell's vertices (each
 * with its role relative to vertex 0) at valence n: exactly when they are
 * all rational there, else within 1e-12 (and then *all_rational = 0). */
static ss_status sum_at(ss_cell_type t, const weight_values *w, long n, int varies,
                        const char *where, const char *sec, int line, int *all_rational,
                        ss_error *err) {
  const int nv = ss_cell_nverts(t);
  char at[48] = "";
  if (varies) snprintf(at, sizeof at, " at n = %ld", n);
  int exact = 1;
  for (int j = 0; j < nv; j++)
    exact &= w[ss_cell_role(t, 0, j)].exact[n];
  if (!exact) {
    *all_rational = 0;
    double sum = 0.0;
    for (int j = 0; j < nv; j++)
      sum += w[ss_cell_role(t, 0, j)].d[n];
    if (!(fabs(sum - 1.0) <= 1e-12))
      return ss_error_set(err, SS_EINPUT,
                          "%s:%d: [%s]: the weights sum to %.17g%s over the %d vertices "
                          "of a %s, not 1 (within 1e-12: some weight is not rational)",
                          where, line, sec, sum, at, nv, ss_cell_name(t));
    return SS_OK;
  }
  rational sum = {0, 1};
  int overflow = 0;
  for (int j = 0; j < nv; j++)
    overflow |= ss_stencil_add_scaled(&sum, 1, w[ss_cell_role(t, 0, j)].q[n]);
  if (overflow)
    return ss_error_set(err, SS_EINPUT,
                        "%s:%d: [%s]: weights too large to sum exactly in 64 bits%s",
                        where, line, sec, at);
  if (sum.num != sum.den)
    return ss_error_set(
        err, SS_EINPUT,
        "%s:%d: [%s]: the weights sum to %lld/%lld%s over the %d vertices "
        "of a %s, not 1",
        where, line, sec, sum.num, sum.den, at, nv, ss_cell_name(t));
  return SS_OK;
}

/* The weights of type t: a->mask[t] (the value at n = 1 for a weight that
 * reads n), and for those that read n a table in tabs[r] (owned by the
 * caller) named by vary->w[t][r]; every valence's sum checked.  Errors as
 * weight_at and sum_at. */
static ss_status mask_weights(const reader *R, ss_cell_type t, const char *where,
                              const char *sec, int line, ss_averaging *a,
                              ss_averaging_vary *vary, double **tabs, ss_error *err) {
  const int nr = ss_cell_nroles(t);
  weight_values *w = malloc((size_t)nr * sizeof *w);
  if (!w) return ss_error_nomem(err, "stencil weights");
  int varies = 0;
  ss_status st = SS_OK;
  for (int r = 0; r < nr && !st; r++)
    st = ss_stencil_weight_at(&R->m[t][r], role_names[t][r], where, sec, w + r, &varies,
                              err);
  for (long n = 1; !st && n <= (varies ? SS_AVG_NMAX : 1); n++)
    st = sum_at(t, w, n, varies, where, sec, line, &vary->rational, err);
  for (int r = 0; r < nr && !st; r++) {
    a->mask[t][r] = w[r].d[1];
    const slot *sl = &R->m[t][r];
    if (!sl->nov && (!sl->ex || !ss_expr_uses_n(sl->ex))) continue;
    if (!(tabs[r] = malloc(sizeof w[r].d))) {
      st = ss_error_nomem(err, "stencil weights");
      break;
    }
    memcpy(tabs[r], w[r].d, sizeof w[r].d);
    vary->w[t][r] = tabs[r];
  }
  free(w);
  return st;
}
int ss_stencil_reserved(const char *name) {
  static const char *const names[] = {
      "n",     "exp",   "log",   "sqrt",    "sin",  "cos",     "tan",   "cot",
      "sec",   "csc",   "asin",  "acos",    "atan", "acot",    "asec",  "acsc",
      "sinh",  "cosh",  "tanh",  "coth",    "sech", "csch",    "asinh", "acosh",
      "atanh", "acoth", "asech", "acsch",   "abs",  "step",    "delta", "nandelta",
      "erf",   "e",     "log2e", "log10e",  "ln2",  "ln10",    "pi",    "pi_2",
      "pi_4",  "2_pi",  "sqrt2", "sqrt1_2", "1_pi", "2_sqrtpi"};
  for (size_t i = 0; i < sizeof names / sizeof *names; i++)
    if (!strcmp(name, names[i])) return 1;
  return 0;
}

/* A parameter's rational: p/q with |p|, q of at most 6 digits and |p/q| <=
 * 1000 (it is written into expressions, whose literals have at most 6
 * digits).  0 or -1. */
static int param_rational(const char *s, rational *q) {
  return parse_rational(s, q) || q->num > 999999 || q->num < -999999 || q->den > 999999 ||
                 q->num > 1000 * q->den || q->num < -1000 * q->den
             ? -1
             : 0;
}

/* "?(LO, HI)": 0 with the bounds, -1 if malformed. */
static int param_range(const char *value, ss_stencil_param *p) {
  char buf[128];
  const char *v = value;
  while (isspace((unsigned char)*v))
    v++;
  if (strncmp(v, "?(", 2) || strlen(v) >= sizeof buf) return -1;
  strcpy(buf, v + 2);
  char *comma = strchr(buf, ','), *close = strrchr(buf, ')');
  if (!comma || !close || close < comma) return -1;
  for (const char *t = close + 1; *t; t++)
    if (!isspace((unsigned char)*t)) return -1;
  *comma = *close = '\0';
  rational lo, hi;
  if (param_rational(buf, &lo) || param_rational(comma + 1, &hi) ||
      !(lo.num * hi.den < hi.num * lo.den))
    return -1;
  p->free = 1;
  p->lo[0] = lo.num, p->lo[1] = lo.den, p->hi[0] = hi.num, p->hi[1] = hi.den;
  return 0;
}

/* A key of [param] in the parameters pass: a name and its value or range. */
static int param_key(reader *R, const char *key, const char *value) {
  ss_stencil_params *P = R->collect ? R->collect : &R->own;
  int ident = (isalpha((unsigned char)key[0]) || key[0] == '_') && strlen(key) < 32;
  for (const char *k = key; ident && *k; k++)
    ident = isalnum((unsigned char)*k) || *k == '_';
  if (!ident || ss_stencil_reserved(key)) {
    snprintf(R->msg, sizeof R->msg,
             "[param] '%.64s' is not a parameter's name (an identifier of at most 31 "
             "characters, not n nor a name of libmatheval's such as pi or cos)",
             key);
    return 0;
  }
  for (int i = 0; i < P->n; i++)
    if (!strcmp(P->p[i].name, key)) {
      snprintf(R->msg, sizeof R->msg, "[param] %.64s is given twice", key);
      return 0;
    }
  if (P->n == SS_STENCIL_MAXPARAMS) {
    snprintf(R->msg, sizeof R->msg, "[param]: more than %d parameters",
             SS_STENCIL_MAXPARAMS);
    return 0;
  }
  ss_stencil_param *p = P->p + P->n;
  memset(p, 0, sizeof *p);
  strcpy(p->name, key);
  p->line = R->line;
  rational q;
  if (!param_rational(value, &q))
    p->num = q.num, p->den = q.den;
  else if (param_range(value, p)) {
    snprintf(R->msg, sizeof R->msg,
             "[param] %.64s = '%.64s' is neither p/q nor ?(LO, HI) with rationals LO < "
             "HI (at most 6 digits each, |LO|, |HI| <= 1000)",
             key, value);
    return 0;
  }
  P->n++;
  return 1;
}

/* value with every identifier that names a parameter of pv replaced by
 * "(num/den)", counting uses in used[]; NULL out of memory. */
char *ss_stencil_substitute(const char *value, const ss_stencil_params *pv, int *used) {
  const size_t len = strlen(value);
  char *out = malloc(len * 17 + 1), *o = out; /* "a" grows to "(-999999/999999)" */
  if (!out) return NULL;
  for (size_t i = 0; i < len;) {
    const int start =
        (isalpha((unsigned char)value[i]) || value[i] == '_') &&
        !(i > 0 && (isalnum((unsigned char)value[i - 1]) || value[i - 1] == '_'));
    size_t k = i;
    while (start && k < len && (isalnum((unsigned char)value[k]) || value[k] == '_'))
      k++;
    int hit = -1;
    for (int p = 0; start && p < pv->n; p++)
      if (strlen(pv->p[p].name) == k - i && !strncmp(value + i, pv->p[p].name, k - i))
        hit = p;
    if (hit < 0) {
      const size_t m = start ? k - i : 1;
      memcpy(o, value + i, m);
      o += m, i += m;
      continue;
    }
    o += sprintf(o, "(%lld/%lld)", pv->p[hit].num, pv->p[hit].den);
    used[hit]++;
    i = k;
  }
  *o = '\0';
  return out;
}

ss_status ss_stencil_read_params(const char *text, const char *where,
                                 ss_stencil_params *out, ss_error *err) {
  memset(out, 0, sizeof *out);
  reader *R = calloc(1, sizeof *R);
  if (!R) return ss_error_nomem(err, "stencil");
  R->text = R->next = text;
  R->collect = out;
  const int rc = ini_parse_stream(read_line, R, handler, R);
  ss_status st = SS_OK;
  /* a [param] error that is the file's first; a line inih cannot read or
   * too long is left to the weights pass, which sees every error in order */
  if (R->nomem)
    st = ss_error_nomem(err, "stencil");
  else if (rc != 0 && R->msg_line == rc)
    st = ss_error_set(err, SS_EINPUT, "%s:%d: %s", where, rc, R->msg);
  free(R);
  return st;
}

/* ss_stencil_parse with the parameters' values pv (all fixed). */
static ss_status parse_with(const char *text, const char *where,
                            const ss_stencil_params *pv, ss_scheme **out, ss_error *err) {
  *out = NULL;
  reader *R = calloc(1, sizeof *R);
  if (!R) return ss_error_nomem(err, "stencil");
  double *tabs[SS_NCELLTYPES][4] = {{NULL}}; /* the valence tables of vary */
  ss_averaging_vary vary = {{{NULL}}, 1};
  R->text = R->next = text;
  R->pv = pv;
  const int rc = ini_parse_stream(read_line, R, handler, R);
  ss_status st = SS_OK;
  if (R->long_line && (rc == 0 || R->long_line <= rc)) {
    st = ss_error_set(err, SS_EINPUT, "%s:%d: a line longer than %d characters", where,
                      R->long_line, INI_MAX_LINE - 2);
    goto done;
  }
  if (R->nomem) {
    st = ss_error_nomem(err, "stencil weights");
    goto done;
  }
  if (rc != 0) { /* the first error: the handler's, or a line inih cannot read */
    st = ss_error_set(err, SS_EINPUT, "%s:%d: %s", where, rc,
                      R->msg_line == rc ? R->msg : "not an INI line");
    goto done;
  }
  for (int i = 0; i < pv->n; i++)
    if (!R->used[i]) {
      st = ss_error_set(err, SS_EINPUT, "%s:%d: [param] %s is used by no weight", where,
                        pv->p[i].line, pv->p[i].name);
      goto done;
    }
  const int sl = ss_stencil_section_line(text, "scheme");
  if (!R->have_name || !R->have_family || !R->have_split) {
    st = ss_error_set(err, SS_EINPUT, "%s:%d: [scheme] needs name, family and split%s",
                      where, sl ? sl : 1, sl ? "" : " (no [scheme] section)");
    goto done;
  }
  if (R->family != FAM_AVERAGING || R->nrs) {
    st = ss_stencil_build_rules(R, text, where, sl, out, err);
    goto done;
  }
  ss_averaging a;
  memset(&a, 0, sizeof a);
  a.split = R->split;
  a.accepts[SS_VERTEX] = 1;
  a.mask[SS_VERTEX][0] = 1.0;
  int nmask = 0;
  for (int t = 0; t < SS_NCELLTYPES; t++) {
    if (!R->has_mask[t]) continue;
    char sec[32];
    snprintf(sec, sizeof sec, "mask.%s", short_names[t]);
    const int line = ss_stencil_section_line(text, sec);
    if (!split_takes(R->split, (ss_cell_type)t)) {
      st = ss_error_set(err, SS_EINPUT, "%s:%d: [%s]: split %s does not make %s", where,
                        line, sec,
                        R->split == SS_SPLIT_MULTILINEAR ? "multilinear" : "tetoct",
                        ss_cell_plural((ss_cell_type)t));
      goto done;
    }
    const int nr = ss_cell_nroles((ss_cell_type)t);
    for (int r = 0; r < nr; r++)
      if (!(R->given[t] & (1u << r))) {
        st = ss_error_set(err, SS_EINPUT, "%s:%d: [%s] lacks the role '%s'", where, line,
                          sec, role_names[t][r]);
        goto done;
      }
    if ((st =
             mask_weights(R, (ss_cell_type)t, where, sec, line, &a, &vary, tabs[t], err)))
      goto done;
    a.accepts[t] = 1;
    nmask++;
  }
  if (nmask == 0) {
    st = ss_error_set(err, SS_EINPUT, "%s:%d: no [mask.TYPE] section", where, sl);
    goto done;
  }
  st = ss_scheme_averaging_vary_new(R->name, &a, &vary, out, err);
done:
  for (int t = 0; t < SS_NCELLTYPES; t++)
    for (int r = 0; r < 4; r++) {
      ss_stencil_slot_clear(&R->m[t][r]);
      free(tabs[t][r]);
    }
  for (int i = 0; i < NRSEC * RKEYS; i++)
    ss_stencil_slot_clear(&R->rs[i / RKEYS][i % RKEYS]);
  free(R);
  return st;
}

ss_status ss_stencil_parse(const char *text, const char *where, ss_scheme **out,
                           ss_error *err) {
  *out = NULL;
  ss_stencil_params pv;
  ss_status st = ss_stencil_read_params(text, where, &pv, err);
  if (st) { /* the weights pass meets the same error, or an earlier one */
    const ss_error first = *err;
    if (parse_with(text, where, &pv, out, err) == SS_OK) {
      ss_scheme_free(*out);
      *out = NULL;
      *err = first;
    }
    return err->status;
  }
  for (int i = 0; !st && i < pv.n; i++)
    if (pv.p[i].free)
      st = ss_error_set(err, SS_EINPUT,
                        "%s:%d: [param] %s is free (a range ?(LO, HI)): choose it with "
                        "`subspectra tune`",
                        where, pv.p[i].line, pv.p[i].name);
  return st ? st : parse_with(text, where, &pv, out, err);
}

ss_status ss_stencil_parse_at(const char *text, const char *where,
                              const ss_stencil_params *values, ss_scheme **out,
                              ss_error *err) {
  *out = NULL;
  ss_stencil_params pv;
  const ss_status st = ss_stencil_read_params(text, where, &pv, err);
  if (st) return st;
  if (values->n != pv.n)
    return ss_error_set(err, SS_EINPUT, "%s: %d parameter values for %d parameters",
                        where, values->n, pv.n);
  for (int i = 0; i < pv.n; i++) {
    const ss_stencil_param *v = values->p + i;
    if (strcmp(v->name, pv.p[i].name) || v->free || v->den <= 0 || v->num > 999999 ||
        v->num < -999999 || v->den > 999999)
      return ss_error_set(err, SS_EINPUT,
                          "%s:%d: [param] %s: the value given is not p/q of at most 6 "
                          "digits each (or names another parameter)",
                          where, pv.p[i].line, pv.p[i].name);
  }
  return parse_with(text, where, values, out, err);
}

ss_status ss_stencil_read(const char *path, char **text, uint64_t *identity,
                          ss_error *err) {
  *text = NULL;
  FILE *f = fopen(path, "rb");
  if (!f) return ss_error_set(err, SS_EIO, "%s: %s", path, strerror(errno));
  size_t cap = 4096, n = 0;
  char *buf = malloc(cap);
  while (buf) {
    if (n + 1 >= cap) {
      if (cap > (1u << 24)) { /* a stencil is a few lines; refuse a huge file */
        free(buf);
        fclose(f);
        return ss_error_set(err, SS_EINPUT, "%s: larger than 16 MB, not a stencil file",
                            path);
      }
      char *nb = realloc(buf, cap *= 2);
      if (!nb) break;
      buf = nb;
    }
    const size_t got = fread(buf + n, 1, cap - n - 1, f);
    n += got;
    if (got == 0) break;
  }
  const int bad = ferror(f);
  fclose(f);
  if (!buf) return ss_error_nomem(err, "stencil file");
  if (bad) {
    free(buf);
    return ss_error_set(err, SS_EIO, "%s: read error", path);
  }
  buf[n] = '\0';
  if (strlen(buf) != n) {
    free(buf);
    return ss_error_set(err, SS_EINPUT, "%s: contains a NUL byte, not a stencil file",
                        path);
  }
  if (identity) {
    uint64_t h = 1469598103934665603ull;
    for (size_t i = 0; i < n; i++)
      h = (h ^ (unsigned char)buf[i]) * 1099511628211ull;
    *identity = h;
  }
  *text = buf;
  return SS_OK;
}

ss_status ss_stencil_load(const char *path, ss_scheme **out, uint64_t *identity,
                          ss_error *err) {
  *out = NULL;
  char *text = NULL;
  ss_status st = ss_stencil_read(path, &text, identity, err);
  if (!st) st = ss_stencil_parse(text, path, out, err);
  free(text);
  return st;
}
