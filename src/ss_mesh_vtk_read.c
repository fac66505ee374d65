/* ss_mesh_vtk_read.c — legacy VTK (.vtk) unstructured grids: not yet read. */
#include "ss_mesh.h"

ss_status ss_mesh_read_vtk(const char *path, ss_cx **out, ss_mesh_fields *names,
                           ss_error *err) {
  (void)names;
  *out = NULL;
  return ss_error_set(err, SS_EINPUT, "%s: legacy VTK is not read yet", path);
}
