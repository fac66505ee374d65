/* ss_error.c — recording failures in a caller-held ss_error. */
#include "ss_error.h"

#include <stdarg.h>
#include <stdio.h>

ss_status ss_error_set(ss_error *err, ss_status st, const char *fmt, ...) {
  if (err) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err->msg, sizeof err->msg, fmt, ap);
    va_end(ap);
    err->status = st;
  }
  return st;
}

ss_status ss_error_nomem(ss_error *err, const char *what) {
  return ss_error_set(err, SS_ENOMEM, "out of memory (%s)", what);
}

const char *ss_status_name(ss_status st) {
  static const char *const names[SS_NSTATUS] = {
      "ok",        "out of memory",     "bad input",
      "i/o error", "numerical failure", "internal error"};
  return (st >= SS_OK && st < SS_NSTATUS) ? names[st] : "unknown status";
}
