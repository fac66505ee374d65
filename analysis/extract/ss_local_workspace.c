/* ss_local_workspace.c — the extraction's scratch memory (ss_local.h,
 * ss_local_workspace): buffers kept between cases, grown on demand. */
#include <stdlib.h>
#include <string.h>

#include "ss_local_impl.h"

ss_local_workspace *ss_local_workspace_new(void) {
  return calloc(1, sizeof(ss_local_workspace));
}

/* Free w's buffers and empty it (w itself stays). */
void ss_local_ws_release(ss_local_workspace *w) {
  free(w->dense);
  free(w->colmap);
  free(w->mark);
  free(w->facet);
  free(w->bucket);
  memset(w, 0, sizeof *w);
}

void ss_local_workspace_free(ss_local_workspace *w) {
  if (!w) return;
  ss_local_ws_release(w);
  free(w);
}

/* A block of at least n elements of size sz in place of p (capacity *cap):
 * p itself when it holds them, else a larger block (p freed: its contents
 * are scratch).  NULL when out of memory (p freed, *cap 0). */
void *ss_local_ws_grow(void *p, size_t *cap, size_t n, size_t sz) {
  if (p && n <= *cap) return p;
  free(p);
  p = malloc((n + 1) * sz);
  *cap = p ? n : 0;
  return p;
}
