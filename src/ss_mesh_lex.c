/* ss_mesh_lex.c — the line-aware tokenizer of the mesh readers. */
#include "ss_mesh_lex.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

void ss_lex_init(ss_lex *lx, FILE *f, const char *name, int comments, ss_error *err) {
  memset(lx, 0, sizeof *lx);
  lx->f = f;
  lx->name = name;
  lx->comments = comments;
  lx->err = err;
}

void ss_lex_done(ss_lex *lx) {
  free(lx->line);
  lx->line = NULL;
  lx->pos = NULL;
}

static int is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
}

/* Read the next line into lx->line.  0 on success, 1 at EOF, -1 on error. */
static int read_line(ss_lex *lx) {
  if (lx->eof) return 1;
  errno = 0;
  ssize_t n = getline(&lx->line, &lx->line_cap, lx->f);
  if (n < 0) {
    lx->pos = NULL;
    if (ferror(lx->f)) return -1;
    lx->eof = 1;
    return 1;
  }
  lx->lineno++;
  if ((size_t)n != strlen(lx->line)) {
    /* An embedded NUL: treat the rest of the line as garbage the caller sees. */
    lx->line[strlen(lx->line)] = '\x01';
  }
  if (lx->comments) {
    char *hash = strchr(lx->line, '#');
    if (hash) *hash = '\0';
  }
  lx->pos = lx->line;
  return 0;
}

char *ss_lex_next_on_line(ss_lex *lx) {
  char *p = lx->pos;
  if (!p) return NULL;
  while (*p && is_space(*p))
    p++;
  if (!*p) {
    lx->pos = p;
    return NULL;
  }
  char *tok = p;
  while (*p && !is_space(*p))
    p++;
  if (*p) *p++ = '\0';
  lx->pos = p;
  lx->tok_line = lx->lineno;
  return tok;
}

char *ss_lex_next(ss_lex *lx, ss_status *st) {
  *st = SS_OK;
  for (;;) {
    char *tok = ss_lex_next_on_line(lx);
    if (tok) return tok;
    int r = read_line(lx);
    if (r > 0) return NULL;
    if (r < 0) {
      *st = ss_error_set(lx->err, SS_EIO, "%s:%ld: read error", lx->name, lx->lineno);
      return NULL;
    }
  }
}

char *ss_lex_next_line(ss_lex *lx, ss_status *st) {
  *st = SS_OK;
  for (;;) {
    int r = read_line(lx);
    if (r > 0) return NULL;
    if (r < 0) {
      *st = ss_error_set(lx->err, SS_EIO, "%s:%ld: read error", lx->name, lx->lineno);
      return NULL;
    }
    char *tok = ss_lex_next_on_line(lx);
    if (tok) return tok;
  }
}

ss_status ss_lex_fail(ss_lex *lx, const char *fmt, ...) {
  char buf[400];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(buf, sizeof buf, fmt, ap);
  va_end(ap);
  long line = lx->tok_line ? lx->tok_line : lx->lineno;
  return ss_error_set(lx->err, SS_EINPUT, "%s:%ld: %s", lx->name, line, buf);
}

/* Tokens are quoted in messages; cut long ones so the message stays one line. */
#define QUOTED(tok) (int)(strlen(tok) > 40 ? 40 : strlen(tok)), (tok)

ss_status ss_lex_double(ss_lex *lx, const char *tok, const char *what, double *out) {
  char *end;
  errno = 0;
  double v = strtod(tok, &end);
  if (end == tok || *end != '\0')
    return ss_lex_fail(lx, "%s '%.*s' is not a number", what, QUOTED(tok));
  if (!isfinite(v) || errno == ERANGE) {
    if (!(errno == ERANGE && isfinite(v) && fabs(v) < 1.0)) /* underflow is fine */
      return ss_lex_fail(lx, "%s '%.*s' is not a finite number", what, QUOTED(tok));
  }
  *out = v;
  return SS_OK;
}

ss_status ss_lex_int(ss_lex *lx, const char *tok, const char *what, long long lo,
                     long long hi, long long *out) {
  char *end;
  errno = 0;
  long long v = strtoll(tok, &end, 10);
  if (end == tok || *end != '\0')
    return ss_lex_fail(lx, "%s '%.*s' is not an integer", what, QUOTED(tok));
  if (errno == ERANGE || v < lo || v > hi)
    return ss_lex_fail(lx, "%s %.*s is out of range %lld..%lld", what, QUOTED(tok), lo,
                       hi);
  *out = v;
  return SS_OK;
}
