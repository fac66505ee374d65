/* ss_report_ref.c — reference files of quoted values and the match rule
 * (ss_report_ref.h). */
#include "ss_report_ref.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_diag.h"

#define NFIELDS 10

static const char *const field_name[NFIELDS] = {"paper", "location",  "scheme",   "case",
                                                "range", "diagonals", "quantity", "value",
                                                "quote", "note"};

void ss_report_ref_free(ss_ref *ref) {
  if (!ref) return;
  for (size_t i = 0; i < ref->n; i++) {
    ss_ref_row *r = ref->row + i;
    free(r->file);
    free(r->paper);
    free(r->location);
    free(r->scheme);
    free(r->diagonals);
    free(r->quantity);
    free(r->value);
    free(r->quote);
    free(r->note);
    free(r->label);
  }
  free(ref->row);
  memset(ref, 0, sizeof *ref);
}

int ss_report_ref_quantity(const char *name, int *index) {
  static const char *const plain[] = {"two_ring",        "one_ring",   "verdict",
                                      "eigen_condition", "regularity", "jsr_threshold",
                                      "jsr_verdict",     "links",      NULL};
  *index = 0;
  for (int i = 0; plain[i]; i++)
    if (!strcmp(name, plain[i])) return 1;
  const char *digits = NULL;
  if (!strncmp(name, "lambda", 6))
    digits = name + 6;
  else if (!strncmp(name, "mult", 4))
    digits = name + 4;
  else if (!strncmp(name, "jsr_rho", 7))
    digits = name + 7;
  if (!digits || !isdigit((unsigned char)digits[0]) || digits[0] == '0') return 0;
  char *end;
  long i = strtol(digits, &end, 10);
  if (*end || i < 1 || i > 15) return 0;
  *index = (int)i;
  return 1;
}

/* A decimal as printed: [-]D+[.D+]; *decimals = digits after the point.
 * Returns the number of characters read, 0 if none. */
static size_t read_decimal(const char *s, double *x, int *decimals) {
  size_t i = 0;
  if (s[i] == '-') i++;
  size_t d0 = i;
  while (isdigit((unsigned char)s[i]))
    i++;
  if (i == d0) return 0;
  *decimals = 0;
  if (s[i] == '.') {
    size_t f0 = ++i;
    while (isdigit((unsigned char)s[i]))
      i++;
    if (i == f0) return 0;
    *decimals = (int)(i - f0);
  }
  char buf[64];
  if (i >= sizeof buf) return 0;
  memcpy(buf, s, i);
  buf[i] = '\0';
  *x = strtod(buf, NULL);
  return i;
}

/* A non-negative integer of at most 9 digits; characters read, 0 if none. */
static size_t read_uint(const char *s, long *v) {
  size_t i = 0;
  *v = 0;
  while (isdigit((unsigned char)s[i]) && i < 9)
    *v = 10 * *v + (s[i++] - '0');
  return isdigit((unsigned char)s[i]) ? 0 : i;
}

/* A number: a fraction a/b, a formula [A](k|n)[(+|-)B], or a decimal. */
static int eval_number(const char *v, int k, ss_ref_value *out) {
  long a = 0, b = 0;
  size_t i = read_uint(v, &a);
  if (i && v[i] == '/') {
    size_t j = read_uint(v + i + 1, &b);
    if (!j || v[i + 1 + j] || b == 0) return -1;
    out->x = (double)a / (double)b;
    out->tol = SS_REF_EXACT_TOL;
    out->exact = 1;
    return 0;
  }
  if (v[i] == 'k' || v[i] == 'n') {
    long coef = i ? a : 1, off = 0;
    const char *p = v + i + 1;
    if (*p == '+' || *p == '-') {
      size_t j = read_uint(p + 1, &off);
      if (!j || p[1 + j]) return -1;
      if (*p == '-') off = -off;
    } else if (*p) {
      return -1;
    }
    out->x = (double)(coef * k + off);
    out->tol = SS_REF_EXACT_TOL;
    out->exact = 1;
    return 0;
  }
  int dec = 0;
  size_t n = read_decimal(v, &out->x, &dec);
  if (!n || v[n]) return -1;
  out->tol = 0.5 * pow(10.0, -dec);
  out->exact = 0;
  return 0;
}

ss_status ss_report_ref_eval(const char *v, int k, ss_ref_value *out, ss_error *err) {
  memset(out, 0, sizeof *out);
  if (!strcmp(v, "pass") || !strcmp(v, "fail") || !strcmp(v, "undecided")) {
    out->kind = SS_REF_VERDICT;
    snprintf(out->verdict, sizeof out->verdict, "%s", v);
    return SS_OK;
  }
  if (v[0] == '>') {
    if (eval_number(v + 1, k, out))
      return ss_error_set(err, SS_EINPUT, "value '%s': expected '>' and a number", v);
    out->kind = SS_REF_GREATER;
    return SS_OK;
  }
  if (eval_number(v, k, out))
    return ss_error_set(err, SS_EINPUT,
                        "value '%s': expected a decimal (0.4101), a fraction (1/2), a "
                        "formula in k or n (5k-5), a bound (>1/4) or pass, fail, "
                        "undecided",
                        v);
  out->kind = SS_REF_NUMBER;
  return SS_OK;
}

int ss_report_ref_match(const ss_ref_value *q, double c) {
  if (!isfinite(c)) return 0;
  if (q->kind == SS_REF_GREATER) return c > q->x;
  if (q->kind != SS_REF_NUMBER) return 0;
  /* the slack absorbs the rounding of the decimal-to-binary conversions, so
   * that a value exactly half a unit away still matches */
  return fabs(c - q->x) <= q->tol * (1.0 + 1e-9) + 1e-15 * fabs(q->x);
}

int ss_report_ref_applies(const ss_ref_row *r, const char *scheme, ss_case_kind kind,
                          int k, const char *diagonals) {
  return ss_report_ref_applies_label(r, scheme, kind, k, diagonals, NULL);
}

int ss_report_ref_applies_label(const ss_ref_row *r, const char *scheme,
                                ss_case_kind kind, int k, const char *diagonals,
                                const char *label) {
  if (strcmp(r->scheme, scheme) || r->kind != kind) return 0;
  if (r->label && (!label || strcmp(r->label, label))) return 0;
  if (kind != SS_CASE_FACE && (k < r->lo || k > r->hi)) return 0;
  if (strcmp(r->diagonals, "-") && (!diagonals || strcmp(r->diagonals, diagonals)))
    return 0;
  return 1;
}

/* The four kinds a quoted value names (edge-point is a result only). */
static int parse_kind(const char *s, ss_case_kind *out) {
  ss_case_kind k;
  if (ss_case_kind_parse(s, &k) || k == SS_CASE_EDGE_POINT) return -1;
  *out = k;
  return 0;
}

/* "A", "A..B", either with ":LABEL" (*label points at LABEL in s, else
 * NULL). */
static int parse_range(const char *s, int *lo, int *hi, const char **label) {
  long a, b;
  size_t i = read_uint(s, &a);
  if (!i) return -1;
  b = a;
  *label = NULL;
  if (s[i] && s[i] != ':') {
    if (strncmp(s + i, "..", 2)) return -1;
    size_t j = read_uint(s + i + 2, &b);
    if (!j || (s[i + 2 + j] && s[i + 2 + j] != ':')) return -1;
    i += 2 + j;
  }
  if (s[i] == ':') {
    if (!s[i + 1]) return -1;
    *label = s + i + 1;
  }
  if (a < 3 || b < a || b > 1000) return -1;
  *lo = (int)a;
  *hi = (int)b;
  return 0;
}

/* Check the fields f[0..9] of one line and store them as row r. */
static ss_status parse_row(char **f, const char *path, long lineno, ss_ref_row *r,
                           ss_error *err) {
  const char *label = NULL;
  memset(r, 0, sizeof *r);
  for (int i = 0; i < NFIELDS - 1; i++)
    if (!f[i][0])
      return ss_error_set(err, SS_EINPUT, "%s:%ld: field %d (%s) is empty", path, lineno,
                          i + 1, field_name[i]);
  for (const char *p = f[2]; *p; p++)
    if (!islower((unsigned char)*p) && !isdigit((unsigned char)*p) && *p != '-')
      return ss_error_set(err, SS_EINPUT, "%s:%ld: scheme '%s' is not a scheme name",
                          path, lineno, f[2]);
  if (parse_kind(f[3], &r->kind))
    return ss_error_set(err, SS_EINPUT,
                        "%s:%ld: case '%s': expected vertex, edge, face or "
                        "surface-vertex",
                        path, lineno, f[3]);
  if (r->kind == SS_CASE_FACE) {
    if (strcmp(f[4], "-"))
      return ss_error_set(err, SS_EINPUT, "%s:%ld: range '%s': a face case takes '-'",
                          path, lineno, f[4]);
  } else if (parse_range(f[4], &r->lo, &r->hi, &label)) {
    return ss_error_set(err, SS_EINPUT,
                        "%s:%ld: range '%s': expected A or A..B with 3 <= A <= B <= "
                        "1000, optionally followed by :LABEL",
                        path, lineno, f[4]);
  }
  ss_diag_mode dm;
  if (strcmp(f[5], "-") && ss_diag_parse(f[5], &dm))
    return ss_error_set(err, SS_EINPUT,
                        "%s:%ld: diagonals '%s': expected -, bfs, proper, skew or center",
                        path, lineno, f[5]);
  int index;
  if (!ss_report_ref_quantity(f[6], &index))
    return ss_error_set(err, SS_EINPUT,
                        "%s:%ld: quantity '%s': expected lambda1..lambda15, "
                        "mult1..mult15, two_ring, one_ring, verdict, eigen_condition, "
                        "regularity, links, jsr_threshold, jsr_verdict or "
                        "jsr_rho1..jsr_rho15",
                        path, lineno, f[6]);
  ss_ref_value v;
  ss_error e2 = {0};
  if (ss_report_ref_eval(f[7], r->kind == SS_CASE_FACE ? 0 : r->lo, &v, &e2))
    return ss_error_set(err, SS_EINPUT, "%s:%ld: %s", path, lineno, e2.msg);
  const int is_verdict = !strcmp(f[6], "verdict") || !strcmp(f[6], "eigen_condition") ||
                         !strcmp(f[6], "regularity") || !strcmp(f[6], "jsr_verdict");
  if (is_verdict != (v.kind == SS_REF_VERDICT))
    return ss_error_set(err, SS_EINPUT, "%s:%ld: quantity %s takes %s, not '%s'", path,
                        lineno, f[6], is_verdict ? "pass, fail or undecided" : "a number",
                        f[7]);
  r->file = strdup(path);
  r->line = lineno;
  r->paper = strdup(f[0]);
  r->location = strdup(f[1]);
  r->scheme = strdup(f[2]);
  r->diagonals = strdup(f[5]);
  r->quantity = strdup(f[6]);
  r->value = strdup(f[7]);
  r->quote = strdup(f[8]);
  r->note = strdup(f[9]);
  r->label = label ? strdup(label) : NULL;
  if (!r->file || !r->paper || !r->location || !r->scheme || !r->diagonals ||
      !r->quantity || !r->value || !r->quote || !r->note || (label && !r->label))
    return ss_error_nomem(err, "reference row");
  return SS_OK;
}

ss_status ss_report_ref_load(const char *path, ss_ref *ref, ss_error *err) {
  FILE *f = fopen(path, "r");
  if (!f) return ss_error_set(err, SS_EIO, "%s: cannot open: %s", path, strerror(errno));
  ss_status st = SS_OK;
  char *line = NULL;
  size_t cap = 0;
  long lineno = 0;
  ssize_t len;
  while ((len = getline(&line, &cap, f)) >= 0) {
    lineno++;
    while (len > 0 && (line[len - 1] == '\n' || line[len - 1] == '\r'))
      line[--len] = '\0';
    if ((size_t)len != strlen(line)) {
      st = ss_error_set(err, SS_EINPUT, "%s:%ld: NUL byte in line", path, lineno);
      goto done;
    }
    const char *p = line;
    while (*p == ' ')
      p++;
    if (*p == '\0' || *p == '#') continue;
    char *fld[NFIELDS];
    int nf = 0;
    for (char *s = line;;) {
      char *tab = strchr(s, '\t');
      if (nf < NFIELDS) fld[nf] = s;
      nf++;
      if (!tab) break;
      *tab = '\0';
      s = tab + 1;
    }
    if (nf != NFIELDS) {
      st = ss_error_set(err, SS_EINPUT,
                        "%s:%ld: %d tab-separated fields, expected %d (paper, location, "
                        "scheme, case, range, diagonals, quantity, value, quote, note)",
                        path, lineno, nf, NFIELDS);
      goto done;
    }
    if (ref->n == ref->cap) {
      size_t nc = ref->cap ? 2 * ref->cap : 64;
      ss_ref_row *nr = realloc(ref->row, nc * sizeof *nr);
      if (!nr) {
        st = ss_error_nomem(err, "reference rows");
        goto done;
      }
      ref->row = nr;
      ref->cap = nc;
    }
    ss_ref_row *r = ref->row + ref->n;
    st = parse_row(fld, path, lineno, r, err);
    ref->n++; /* a partly filled row is freed with the others */
    if (st) {
      if (st != SS_ENOMEM) {
        ref->n--;
        free(r->file);
      }
      goto done;
    }
  }
  if (ferror(f)) st = ss_error_set(err, SS_EIO, "%s: read error", path);
done:
  free(line);
  fclose(f);
  return st;
}
