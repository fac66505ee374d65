/* ss_cli_reproduce_text.c — the text `reproduce` writes is built in growing
 * buffers and written whole (ss_outfile.h); the cells its writers share
 * (eigenvalues, verdicts, case labels) are formatted here, once. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

#include "ss_cli_reproduce.h"
#include "ss_outfile.h"

int ss_sb_printf(ss_strbuf *b, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  int need = vsnprintf(NULL, 0, fmt, ap);
  va_end(ap);
  if (need < 0) return -1;
  if (b->n + (size_t)need + 1 > b->cap) {
    size_t nc = b->cap ? b->cap : 4096;
    while (nc < b->n + (size_t)need + 1)
      nc *= 2;
    char *ns = realloc(b->s, nc);
    if (!ns) return -1;
    b->s = ns;
    b->cap = nc;
  }
  va_start(ap, fmt);
  vsnprintf(b->s + b->n, (size_t)need + 1, fmt, ap);
  va_end(ap);
  b->n += (size_t)need;
  return 0;
}

void ss_sb_cell(ss_strbuf *b, const char *s) {
  for (; *s; s++)
    ss_sb_printf(b, *s == '|' ? "\\|" : "%c", *s);
}

void ss_sb_verdict(ss_strbuf *b, const ss_verdict *v, int certified) {
  ss_sb_printf(b, "%s%s", ss_verdict_name(v->verdict), certified ? " ✓" : "");
  if (v->reason[0]) {
    ss_sb_printf(b, " (");
    ss_sb_cell(b, v->reason);
    ss_sb_printf(b, ")");
  }
}

ss_status ss_sb_write_file(const char *path, const ss_strbuf *b, ss_error *err) {
  ss_outfile *out;
  ss_status st = ss_outfile_open(path, &out, err);
  if (st) return st;
  if (b->n) fwrite(b->s, 1, b->n, ss_outfile_file(out)); /* checked by the commit */
  return ss_outfile_commit(out, err);
}

int ss_reproduce_is_real(const ss_result_eigval *v) {
  return fabs(v->im) <= 1e-12 * fabs(v->re);
}

void ss_reproduce_eig_text(const ss_result_eigval *v, char *buf, size_t n) {
  if (ss_reproduce_is_real(v))
    snprintf(buf, n, "%.6f", v->re);
  else
    snprintf(buf, n, "%.4f%+.4fi", v->re, v->im);
}

const char *ss_reproduce_case_label(const ss_result *r, char *buf, size_t n) {
  if (ss_result_has_link(r))
    snprintf(buf, n, "k = %d", r->k);
  else if (r->kind == SS_CASE_FACE)
    snprintf(buf, n, "face");
  else if (r->cls)
    snprintf(buf, n, "n = %d, class %d", r->k, r->cls);
  else
    snprintf(buf, n, "n = %d", r->k);
  return buf;
}
