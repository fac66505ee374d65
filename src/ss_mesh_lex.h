/* ss_mesh_lex.h — private: a whitespace tokenizer over a text stream that knows
 * the line of every token, for the mesh readers' "file:line: problem" messages.
 *
 * Lines are read whole (getline), so a token never spans lines and memory is
 * bounded by the longest line.  '#' starts a comment that runs to the end of
 * the line when comments are enabled. */
#ifndef SS_MESH_LEX_H
#define SS_MESH_LEX_H

#include <stdint.h>
#include <stdio.h>

#include "ss_error.h"

typedef struct {
  FILE *f;          /* the stream (not owned) */
  const char *name; /* file name for messages (not owned) */
  char *line;       /* current line buffer (owned, from getline) */
  size_t line_cap;  /* allocated size of line */
  char *pos;        /* next unread character of line, NULL before the first */
  long lineno;      /* 1-based number of the current line, 0 before the first */
  long tok_line;    /* line of the token last returned */
  int comments;     /* nonzero: '#' starts a comment */
  int eof;          /* the stream is exhausted */
  ss_error *err;    /* where failures are recorded (not owned) */
} ss_lex;

/* Start lexing f; name is used in messages, failures go to err. */
void ss_lex_init(ss_lex *lx, FILE *f, const char *name, int comments, ss_error *err);
/* Release the line buffer. */
void ss_lex_done(ss_lex *lx);

/* Next token of the stream, or NULL at end of file (*st = SS_OK) or on a read
 * error (*st = SS_EIO, message in err).  The token stays valid until the next
 * call; it is NUL-terminated in place. */
char *ss_lex_next(ss_lex *lx, ss_status *st);
/* Next token on the current line only, or NULL if the line has no more. */
char *ss_lex_next_on_line(ss_lex *lx);
/* Advance to the next non-empty line and return its first token, or NULL at
 * end of file / read error as for ss_lex_next. */
char *ss_lex_next_line(ss_lex *lx, ss_status *st);

/* Fail with "name:line: problem" at the line of the last token. */
ss_status ss_lex_fail(ss_lex *lx, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* Parse a whole token as a finite double / as an integer in [lo, hi].
 * SS_EINPUT with "name:line: WHAT 'tok' is not a number" and the like. */
ss_status ss_lex_double(ss_lex *lx, const char *tok, const char *what, double *out);
ss_status ss_lex_int(ss_lex *lx, const char *tok, const char *what, long long lo,
                     long long hi, long long *out);

#endif
