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

/* An exact rational num/den, den > 0, in lowest terms. */
typedef struct {
  long long num, den;
} rational;

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
static int add_scaled(rational *sum, long long c, rational r) {
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

typedef struct {
  char name[64]; /* [scheme] name */
  int have_name, have_family, have_split;
  ss_split_kind split;
  rational w[SS_NCELLTYPES][4];  /* weights by type and role (constant ones) */
  ss_expr *ex[SS_NCELLTYPES][4]; /* the weights that are expressions, or NULL */
  char *etext[SS_NCELLTYPES][4]; /* an expression's text, for messages */
  int keyline[SS_NCELLTYPES][4]; /* the line of each weight */
  unsigned given[SS_NCELLTYPES]; /* bit r: role r given */
  int has_mask[SS_NCELLTYPES];   /* a [mask.*] section seen */
  char msg[384];                 /* the handler's first complaint */
  int msg_line;                  /* its line (1-based), 0 before any */
  const char *text;              /* the file's text, read line by line */
  const char *next;              /* where the next line starts in text */
  int line;                      /* line of the text last handed to inih */
  int newlines;                  /* newlines in text before next */
  int long_line;                 /* first line longer than inih's buffer, or 0 */
} reader;

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

static int handle(reader *R, const char *section, const char *key, const char *value) {
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
      if (strcmp(value, "averaging")) {
        snprintf(R->msg, sizeof R->msg,
                 "[scheme] family '%.64s' is unknown (known: averaging)", value);
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
  if (strncmp(section, "mask.", 5)) {
    snprintf(R->msg, sizeof R->msg,
             "section [%.64s] is unknown (known: [scheme], [mask.TYPE])", section);
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
  for (int q = 0; q < ss_cell_nroles(t); q++)
    if (!strcmp(key, role_names[t][q])) r = q;
  if (r < 0) {
    char known[64] = "";
    for (int q = 0; q < ss_cell_nroles(t); q++)
      snprintf(known + strlen(known), sizeof known - strlen(known), "%s%s", q ? ", " : "",
               role_names[t][q]);
    snprintf(R->msg, sizeof R->msg, "[%.64s]: role '%.64s' is unknown (known: %s)",
             section, key, known);
    return 0;
  }
  if (R->given[t] & (1u << r)) goto repeated;
  const int pr = parse_rational(value, &R->w[t][r]);
  if (pr == -2) {
    snprintf(R->msg, sizeof R->msg,
             "[%.32s] %s = '%.40s': a numerator or denominator has more than 17 digits "
             "(weights are summed exactly in 64-bit integers; reduce the fraction)",
             section, key, value);
    return 0;
  }
  R->keyline[t][r] = R->line;
  if (pr) { /* not p/q: an expression */
    ss_error xe = {0};
    if (ss_expr_new(value, &R->ex[t][r], &xe)) {
      snprintf(R->msg, sizeof R->msg, "[%.64s] %s = '%.64s'%.160s", section, key, value,
               xe.msg);
      return 0;
    }
    if (!(R->etext[t][r] = strdup(value))) {
      snprintf(R->msg, sizeof R->msg, "out of memory");
      return 0;
    }
  }
  R->given[t] |= 1u << r;
  return 1;
repeated:
  snprintf(R->msg, sizeof R->msg, "[%.64s] %.64s is given twice", section, key);
  return 0;
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
static int section_line(const char *text, const char *section) {
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

/* The values of one weight at the valences n = 1..SS_AVG_NMAX. */
typedef struct {
  double d[SS_AVG_NMAX + 1];            /* the value */
  rational q[SS_AVG_NMAX + 1];          /* the exact value, where exact[n] */
  unsigned char exact[SS_AVG_NMAX + 1]; /* 1: rational (q[n]) */
} weight_values;

/* Weight r of type t at every valence (only n = 1 unless it reads n): into
 * *w; *varies |= it reads n.  SS_EINPUT "WHERE:LINE: [SEC] KEY = 'EXPR' is
 * not finite at n = N ...", SS_ENOMEM. */
static ss_status weight_at(const reader *R, ss_cell_type t, int r, const char *where,
                           const char *sec, weight_values *w, int *varies,
                           ss_error *err) {
  const ss_expr *e = R->ex[t][r];
  const int reads = e && ss_expr_uses_n(e);
  *varies |= reads;
  for (long n = 1; n <= (reads ? SS_AVG_NMAX : 1); n++) {
    ss_expr_value v = {0.0, 1, R->w[t][r].num, R->w[t][r].den};
    if (!e) v.value = (double)v.num / (double)v.den; /* as it always was */
    ss_error xe = {0};
    const ss_status st = e ? ss_expr_eval(e, n, &v, &xe) : SS_OK;
    if (st == SS_ENOMEM) return ss_error_nomem(err, "weight expression");
    if (st)
      return ss_error_set(err, SS_EINPUT, "%s:%d: [%s] %s = '%.80s'%s", where,
                          R->keyline[t][r], sec, role_names[t][r], R->etext[t][r],
                          xe.msg);
    w->d[n] = v.value;
    w->exact[n] = (unsigned char)v.rational;
    w->q[n] = (rational){v.num, v.den};
  }
  for (long n = 2; !reads && n <= SS_AVG_NMAX; n++) {
    w->d[n] = w->d[1];
    w->exact[n] = w->exact[1];
    w->q[n] = w->q[1];
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
    overflow |= add_scaled(&sum, 1, w[ss_cell_role(t, 0, j)].q[n]);
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
    st = weight_at(R, t, r, where, sec, w + r, &varies, err);
  for (long n = 1; !st && n <= (varies ? SS_AVG_NMAX : 1); n++)
    st = sum_at(t, w, n, varies, where, sec, line, &vary->rational, err);
  for (int r = 0; r < nr && !st; r++) {
    a->mask[t][r] = w[r].d[1];
    if (!R->ex[t][r] || !ss_expr_uses_n(R->ex[t][r])) continue;
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

ss_status ss_stencil_parse(const char *text, const char *where, ss_scheme **out,
                           ss_error *err) {
  *out = NULL;
  reader *R = calloc(1, sizeof *R);
  if (!R) return ss_error_nomem(err, "stencil");
  double *tabs[SS_NCELLTYPES][4] = {{NULL}}; /* the valence tables of vary */
  ss_averaging_vary vary = {{{NULL}}, 1};
  R->text = R->next = text;
  const int rc = ini_parse_stream(read_line, R, handler, R);
  ss_status st = SS_OK;
  if (R->long_line && (rc == 0 || R->long_line <= rc)) {
    st = ss_error_set(err, SS_EINPUT, "%s:%d: a line longer than %d characters", where,
                      R->long_line, INI_MAX_LINE - 2);
    goto done;
  }
  if (rc != 0) { /* the first error: the handler's, or a line inih cannot read */
    st = ss_error_set(err, SS_EINPUT, "%s:%d: %s", where, rc,
                      R->msg_line == rc ? R->msg : "not an INI line");
    goto done;
  }
  const int sl = section_line(text, "scheme");
  if (!R->have_name || !R->have_family || !R->have_split) {
    st = ss_error_set(err, SS_EINPUT, "%s:%d: [scheme] needs name, family and split%s",
                      where, sl ? sl : 1, sl ? "" : " (no [scheme] section)");
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
    const int line = section_line(text, sec);
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
      ss_expr_free(R->ex[t][r]);
      free(R->etext[t][r]);
      free(tabs[t][r]);
    }
  free(R);
  return st;
}

ss_status ss_stencil_load(const char *path, ss_scheme **out, uint64_t *identity,
                          ss_error *err) {
  *out = NULL;
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
  const ss_status st = ss_stencil_parse(buf, path, out, err);
  free(buf);
  return st;
}
