/* ss_mesh.c — reading and writing a mesh file: the format chosen
 * (ss_mesh_format.c), the file opened, and the reader or writer of
 * ss_mesh_medit.c, ss_mesh_vtk.c, ss_mesh_obj.c, ss_mesh_gmsh.c or
 * ss_mesh_tetgen.c called. */
#include "ss_mesh.h"

#include <errno.h>
#include <math.h>
#include <string.h>

#include "ss_outfile.h"

ss_status ss_mesh_read(const char *path, ss_mesh_format fmt, ss_cx **out, ss_error *err) {
  *out = NULL;
  if (fmt == SS_MESH_AUTO) fmt = ss_mesh_format_from_path(path);
  if (fmt == SS_MESH_AUTO)
    return ss_error_set(err, SS_EINPUT, "%s: cannot tell the mesh format (read: %s)",
                        path, ss_mesh_readable_list());
  if (fmt == SS_MESH_VTK || fmt == SS_MESH_VTU)
    return ss_error_set(err, SS_EINPUT, "%s: VTK files are written, not read (read: %s)",
                        path, ss_mesh_readable_list());
  if (fmt == SS_MESH_GMSH) return ss_mesh_read_gmsh(path, out, err);
  if (fmt == SS_MESH_TETGEN) return ss_mesh_read_tetgen(path, out, err);
  FILE *f = fopen(path, "r");
  if (!f) return ss_error_set(err, SS_EIO, "%s: %s", path, strerror(errno));
  ss_status st = fmt == SS_MESH_MEDIT ? ss_mesh_read_medit(f, path, out, err)
                                      : ss_mesh_read_obj(f, path, out, err);
  fclose(f);
  return st;
}

ss_status ss_mesh_write(const char *path, ss_mesh_format fmt, const ss_cx *cx,
                        const ss_mesh_write_opts *opts, ss_error *err) {
  ss_status st = SS_OK;
  if (fmt == SS_MESH_AUTO) fmt = ss_mesh_format_from_path(path);
  if (!ss_mesh_format_writable(fmt))
    return ss_error_set(err, SS_EINPUT, "%s: %s (write: %s)", path,
                        fmt == SS_MESH_AUTO ? "cannot tell the mesh format"
                                            : "this format is read, not written",
                        ss_mesh_writable_list());
  for (size_t i = 0; i < cx->nv * (size_t)cx->dim; i++)
    if (!isfinite(cx->x[i]))
      return ss_error_set(err, SS_EINPUT,
                          "%s: vertex %zu has a non-finite coordinate (%g): not written "
                          "(no reader would accept it)",
                          path, i / (size_t)cx->dim + 1, cx->x[i]);
  /* a temporary file renamed over path: never a half-written mesh */
  ss_outfile *out;
  if ((st = ss_outfile_open(path, &out, err))) return st;
  FILE *f = ss_outfile_file(out);
  switch (fmt) {
  case SS_MESH_MEDIT:
    st = ss_mesh_write_medit(f, cx, opts, err);
    break;
  case SS_MESH_VTK:
    st = ss_mesh_write_vtk(f, cx, err);
    break;
  case SS_MESH_VTU:
    st = ss_mesh_write_vtu(f, cx, err);
    break;
  default:
    st = ss_mesh_write_obj(f, cx, err);
    break;
  }
  /* the writer saw the stream fail ("write error"): the commit names why */
  if (st == SS_EIO && ferror(f)) st = SS_OK;
  if (st) {
    ss_outfile_abort(out);
  } else {
    st = ss_outfile_commit(out, err);
  }
  if (st && err && !strstr(err->msg, path)) {
    char msg[sizeof err->msg];
    snprintf(msg, sizeof msg, "%s", err->msg);
    ss_error_set(err, st, "%s: %s", path, msg);
  }
  return st;
}
