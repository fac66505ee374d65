/* ss_error.h — status codes and the caller-held error message.
 *
 * Every fallible library function returns an ss_status and, when it fails,
 * writes a one-line message into an ss_error the caller owns.  Library code
 * never prints, exits or aborts; the command-line tool maps statuses to exit
 * codes (SS_EINPUT -> 2, and so on). */
#ifndef SS_ERROR_H
#define SS_ERROR_H

#include <stddef.h>

#include "ss_api.h"

SS_BEGIN_DECLS

typedef enum {
  SS_OK = 0,    /* success */
  SS_ENOMEM,    /* an allocation failed */
  SS_EINPUT,    /* malformed or unsupported input (file, option, mesh) */
  SS_EIO,       /* a file could not be opened, read or written */
  SS_ENUMERIC,  /* a numerical routine failed or lost accuracy */
  SS_EINTERNAL, /* an invariant of the library itself was violated */
  SS_NSTATUS    /* number of codes; not a status */
} ss_status;

/* Message buffer filled by a failing call.  Zero-initialise before use. */
typedef struct {
  ss_status status; /* the status of the failure, SS_OK if none recorded */
  char msg[512];    /* "file:line: problem" or a plain sentence, NUL-terminated */
} ss_error;

/* Record a failure: sets err->status and formats err->msg (printf-style),
 * escaped by ss_error_escape: messages quote the user's input, which may be
 * binary garbage, and must not send raw bytes to a terminal.  err may be NULL
 * (then nothing is recorded).  Returns st so callers can write
 * `return ss_error_set(err, SS_EINPUT, ...)`. */
ss_status ss_error_set(ss_error *err, ss_status st, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* Copy src into dst (cap bytes, cap > 0, always NUL-terminated) with every
 * byte outside printable ASCII written as an escape: \t, \n, \r, \\ is
 * not escaped (it is printable), others as \xHH (so UTF-8 file names appear
 * escaped too: a message's bytes are exactly what was typed or read).  An
 * escape that does not fit is left out whole, never cut.  Returns dst. */
char *ss_error_escape(char *dst, size_t cap, const char *src);

/* Record an allocation failure with a standard message naming what. */
ss_status ss_error_nomem(ss_error *err, const char *what);

/* A short constant name of a status ("ok", "out of memory", ...). */
const char *ss_status_name(ss_status st);

SS_END_DECLS

#endif
