/* ss_mesh.c — reading and writing a mesh file: the format chosen
 * (ss_mesh_format.c), the file opened, and the reader or writer of
 * ss_mesh_medit.c, ss_mesh_vtk.c, ss_mesh_obj.c, ss_mesh_gmsh.c or
 * ss_mesh_tetgen.c called. */
#include "ss_mesh.h"

#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <math.h>
#include <string.h>

#include "ss_outfile.h"

void ss_mesh_fields_default(int dim, ss_mesh_fields *f) {
  memset(f, 0, sizeof *f);
  f->n = dim > 3 ? dim - 3 : 0;
  snprintf(f->name[0], sizeof f->name[0], "w");
  for (int i = 1; i < f->n; i++)
    snprintf(f->name[i], sizeof f->name[i], "x%d", i + 4);
}

/* Names as every writer can hold them (a legacy VTK token, an XML
 * attribute, a JSON key, a text column): characters other than letters,
 * digits, '_', '-', '.' and '+' become '_'; an empty name "field". */
static void sanitize(ss_mesh_fields *f) {
  for (int i = 0; i < f->n; i++) {
    char *s = f->name[i];
    if (!*s) snprintf(s, SS_FIELD_NAME_MAX, "field");
    for (; *s; s++)
      if (!isalnum((unsigned char)*s) && !strchr("_-.+", *s)) *s = '_';
  }
}

ss_status ss_mesh_read(const char *path, ss_mesh_format fmt, ss_cx **out, ss_error *err) {
  return ss_mesh_read_fields(path, fmt, out, NULL, err);
}

ss_status ss_mesh_read_fields(const char *path, ss_mesh_format fmt, ss_cx **out,
                              ss_mesh_fields *names, ss_error *err) {
  ss_mesh_fields tmp;
  if (!names) names = &tmp;
  ss_mesh_fields_default(0, names);
  *out = NULL;
  if (fmt == SS_MESH_AUTO) fmt = ss_mesh_format_from_path(path);
  if (fmt == SS_MESH_AUTO)
    return ss_error_set(err, SS_EINPUT, "%s: cannot tell the mesh format (read: %s)",
                        path, ss_mesh_readable_list());
  if (fmt == SS_MESH_VTU || fmt == SS_MESH_VTK || fmt == SS_MESH_GMSH) {
    const ss_status st = fmt == SS_MESH_VTU ? ss_mesh_read_vtu(path, out, names, err)
                         : fmt == SS_MESH_VTK
                             ? ss_mesh_read_vtk(path, out, names, err)
                             : ss_mesh_read_gmsh_fields(path, out, names, err);
    sanitize(names);
    return st;
  }
  if (fmt == SS_MESH_TETGEN) return ss_mesh_read_tetgen(path, out, err);
  FILE *f = fopen(path, "r");
  if (!f) return ss_error_set(err, SS_EIO, "%s: %s", path, strerror(errno));
  ss_status st = fmt == SS_MESH_MEDIT ? ss_mesh_read_medit(f, path, out, err)
                                      : ss_mesh_read_obj(f, path, out, err);
  fclose(f);
  if (!st) ss_mesh_fields_default((*out)->dim, names);
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
    st = ss_mesh_write_vtk(f, cx, opts, err);
    break;
  case SS_MESH_VTU:
    st = ss_mesh_write_vtu(f, cx, opts, err);
    break;
  case SS_MESH_GMSH:
    st = ss_mesh_write_gmsh(f, path, cx, opts, err);
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
