/* ss_error.c — recording failures in a caller-held ss_error. */
#include "ss_error.h"

#include <stdarg.h>
#include <stdio.h>

char *ss_error_escape(char *dst, size_t cap, const char *src) {
  static const char hex[] = "0123456789abcdef";
  size_t k = 0;
  for (const unsigned char *p = (const unsigned char *)src; *p; p++) {
    char e[5];
    size_t n = 0;
    if (*p >= 0x20 && *p < 0x7f)
      e[n++] = (char)*p;
    else if (*p == '\t' || *p == '\n' || *p == '\r') {
      e[n++] = '\\';
      e[n++] = *p == '\t' ? 't' : *p == '\n' ? 'n' : 'r';
    } else {
      e[n++] = '\\';
      e[n++] = 'x';
      e[n++] = hex[*p >> 4];
      e[n++] = hex[*p & 15];
    }
    if (k + n >= cap) break;
    for (size_t i = 0; i < n; i++)
      dst[k++] = e[i];
  }
  dst[k] = '\0';
  return dst;
}

ss_status ss_error_set(ss_error *err, ss_status st, const char *fmt, ...) {
  if (err) {
    char raw[sizeof err->msg];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(raw, sizeof raw, fmt, ap);
    va_end(ap);
    ss_error_escape(err->msg, sizeof err->msg, raw);
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
