/* ss_mesh_gmsh_api.h — private to the gmsh reader and writer
 * (ss_mesh_gmsh.c, ss_mesh_gmsh_write.c): gmsh's C API opened with dlopen
 * (ss_mesh_gmsh.c says why it is not linked) and the one process-wide lock
 * around its global state.  Only in a build with gmsh (SS_HAVE_GMSH). */
#ifndef SS_MESH_GMSH_API_H
#define SS_MESH_GMSH_API_H

#include <gmshc.h>

#include "ss_error.h"

/* gmsh's C API as function pointers, looked up by ss_gmsh_api_load.  The
 * types come from gmshc.h, so a changed signature is a compile error. */
#define SS_GMSH_FUNCS(X)                                                                 \
  X(gmshInitialize)                                                                      \
  X(gmshFinalize)                                                                        \
  X(gmshFree)                                                                            \
  X(gmshOpen)                                                                            \
  X(gmshWrite)                                                                           \
  X(gmshOptionSetNumber)                                                                 \
  X(gmshOptionGetString)                                                                 \
  X(gmshLoggerGetLastError)                                                              \
  X(gmshModelAdd)                                                                        \
  X(gmshModelAddDiscreteEntity)                                                          \
  X(gmshModelAddPhysicalGroup)                                                           \
  X(gmshModelGetDimension)                                                               \
  X(gmshModelGetEntities)                                                                \
  X(gmshModelGetPhysicalGroupsForEntity)                                                 \
  X(gmshModelMeshAddNodes)                                                               \
  X(gmshModelMeshAddElementsByType)                                                      \
  X(gmshModelMeshGetNodes)                                                               \
  X(gmshModelMeshGetElements)                                                            \
  X(gmshModelMeshGetElementProperties)                                                   \
  X(gmshViewAdd)                                                                         \
  X(gmshViewAddHomogeneousModelData)                                                     \
  X(gmshViewWrite)                                                                       \
  X(gmshViewGetTags)                                                                     \
  X(gmshViewGetIndex)                                                                    \
  X(gmshViewGetHomogeneousModelData)

typedef struct {
#define SS_GMSH_FIELD(f) __typeof__(f) *f; /* gmsh's function f */
  SS_GMSH_FUNCS(SS_GMSH_FIELD)
#undef SS_GMSH_FIELD
} ss_gmsh_api;

/* Open libgmsh and fill g.  The handle is never closed: the child process
 * that calls this exits after its work.  SS_EINPUT naming path, the library
 * and dlerror's text. */
ss_status ss_gmsh_api_load(ss_gmsh_api *g, const char *path, ss_error *err);

/* The text of gmsh's last error into buf, or a fallback. */
void ss_gmsh_last_error(const ss_gmsh_api *g, char *buf, size_t n);

/* gmsh's API is global state: one use at a time in the whole process. */
void ss_gmsh_lock(void);
void ss_gmsh_unlock(void);

/* gmshInitialize, quiet (General.Terminal 0, Verbosity 0), keeping the
 * process's locale, which gmshInitialize changes: *saved holds it for
 * ss_gmsh_end.  SS_EINPUT naming path; SS_ENOMEM. */
ss_status ss_gmsh_begin(const ss_gmsh_api *g, const char *path, char **saved,
                        ss_error *err);
/* gmshFinalize and the locale restored (saved freed). */
void ss_gmsh_end(const ss_gmsh_api *g, char *saved);

#endif
