/* ss_mesh_gmsh_api.c — gmsh's C API opened with dlopen, its lock, and its
 * quiet start (ss_mesh_gmsh_api.h). */
#include <stdio.h>

#if SS_HAVE_GMSH
#include <dlfcn.h>
#include <locale.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "ss_mesh_gmsh_api.h"

#define SS_STR_(x) #x
#define SS_STR(x)  SS_STR_(x)
/* The soname of the gmsh whose header this was compiled against. */
#define SS_GMSH_SONAME                                                                   \
  "libgmsh.so." SS_STR(GMSH_API_VERSION_MAJOR) "." SS_STR(GMSH_API_VERSION_MINOR)

ss_status ss_gmsh_api_load(ss_gmsh_api *g, const char *path, ss_error *err) {
  void *h = dlopen(SS_GMSH_SONAME, RTLD_NOW | RTLD_LOCAL);
  if (!h)
    return ss_error_set(err, SS_EINPUT, "%s: cannot load gmsh (%s): %s", path,
                        SS_GMSH_SONAME, dlerror());
    /* dlsym returns an object pointer; ISO C has no conversion to a function
     * pointer, so the bits are copied (POSIX guarantees they are one) */
#define SS_GMSH_LOAD(f)                                                                  \
  {                                                                                      \
    void *p = dlsym(h, #f);                                                              \
    if (!p)                                                                              \
      return ss_error_set(err, SS_EINPUT, "%s: %s has no %s: %s", path, SS_GMSH_SONAME,  \
                          #f, dlerror());                                                \
    memcpy(&g->f, &p, sizeof p);                                                         \
  }
  SS_GMSH_FUNCS(SS_GMSH_LOAD)
#undef SS_GMSH_LOAD
  return SS_OK;
}

/* the only mutable static of the library: gmsh's own state is static */
static pthread_mutex_t gmsh_lock = PTHREAD_MUTEX_INITIALIZER;

void ss_gmsh_lock(void) {
  pthread_mutex_lock(&gmsh_lock);
}

void ss_gmsh_unlock(void) {
  pthread_mutex_unlock(&gmsh_lock);
}

void ss_gmsh_last_error(const ss_gmsh_api *g, char *buf, size_t n) {
  char *e = NULL;
  int ierr = 0;
  g->gmshLoggerGetLastError(&e, &ierr);
  snprintf(buf, n, "%s", !ierr && e && *e ? e : "gmsh could not read the file");
  g->gmshFree(e);
}

ss_status ss_gmsh_begin(const ss_gmsh_api *g, const char *path, char **saved,
                        ss_error *err) {
  /* gmshInitialize sets the locale from the environment: keep the caller's */
  const char *cur = setlocale(LC_ALL, NULL);
  *saved = cur ? strdup(cur) : NULL;
  if (cur && !*saved) return ss_error_nomem(err, "locale name");
  int ierr = 0;
  g->gmshInitialize(0, NULL, 0, &ierr);
  if (ierr) {
    if (*saved) setlocale(LC_ALL, *saved);
    free(*saved);
    *saved = NULL;
    return ss_error_set(err, SS_EINPUT, "%s: gmsh could not be initialised", path);
  }
  g->gmshOptionSetNumber("General.Terminal", 0, &ierr);
  g->gmshOptionSetNumber("General.Verbosity", 0, &ierr);
  return SS_OK;
}

void ss_gmsh_end(const ss_gmsh_api *g, char *saved) {
  int ierr = 0;
  g->gmshFinalize(&ierr);
  if (saved) setlocale(LC_ALL, saved);
  free(saved);
}
#else
/* ISO C forbids an empty translation unit */
typedef int ss_mesh_gmsh_api_unused;
#endif
