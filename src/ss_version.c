/* ss_version.c — the library's version string (ss_version.h). */
#include "ss_version.h"

const char *ss_version(void) {
  return SS_VERSION_STRING;
}
