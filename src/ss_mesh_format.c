/* ss_mesh_format.c — the mesh formats: which a path names, their names,
 * which are read and written, and the lists of them for messages.  Below
 * every reader and writer and below ss_mesh.c's dispatch, so that a reader
 * (ss_mesh_gmsh.c) can name the formats without calling back up. */
#include <string.h>
#include <strings.h>

#include "ss_mesh.h"

int ss_mesh_gmsh_available(void) {
  /* the build's choice (meson option gmsh): ss_mesh_gmsh.c reads .msh or is
   * the stub that refuses it */
  return SS_HAVE_GMSH;
}

ss_mesh_format ss_mesh_format_from_path(const char *path) {
  const char *dot = strrchr(path, '.');
  const char *slash = strrchr(path, '/');
  if (!dot || (slash && dot < slash)) return SS_MESH_AUTO;
  if (!strcasecmp(dot, ".mesh")) return SS_MESH_MEDIT;
  if (!strcasecmp(dot, ".vtk")) return SS_MESH_VTK;
  if (!strcasecmp(dot, ".vtu")) return SS_MESH_VTU;
  if (!strcasecmp(dot, ".obj")) return SS_MESH_OBJ;
  if (!strcasecmp(dot, ".msh")) return SS_MESH_GMSH;
  if (!strcasecmp(dot, ".node") || !strcasecmp(dot, ".ele") || !strcasecmp(dot, ".face"))
    return SS_MESH_TETGEN;
  return SS_MESH_AUTO;
}

int ss_mesh_format_readable(ss_mesh_format fmt) {
  return fmt == SS_MESH_MEDIT || fmt == SS_MESH_OBJ || fmt == SS_MESH_TETGEN ||
         fmt == SS_MESH_VTK || (fmt == SS_MESH_VTU && ss_mesh_vtu_available()) ||
         (fmt == SS_MESH_GMSH && ss_mesh_gmsh_available());
}

int ss_mesh_format_writable(ss_mesh_format fmt) {
  return fmt == SS_MESH_MEDIT || fmt == SS_MESH_OBJ || fmt == SS_MESH_VTK ||
         fmt == SS_MESH_VTU || (fmt == SS_MESH_GMSH && ss_mesh_gmsh_available());
}

const char *ss_mesh_readable_list(void) {
  static const char *const list[2][2] = {
      {".mesh (Medit), .obj, .vtk or .node/.ele (TetGen); .msh needs a build with "
       "gmsh, .vtu one with libxml2",
       ".mesh (Medit), .obj, .vtk, .vtu or .node/.ele (TetGen); .msh needs a build "
       "with gmsh"},
      {".mesh (Medit), .obj, .vtk, .msh (gmsh) or .node/.ele (TetGen); .vtu needs a "
       "build with libxml2",
       ".mesh (Medit), .obj, .vtk, .vtu, .msh (gmsh) or .node/.ele (TetGen)"}};
  return list[ss_mesh_gmsh_available() != 0][ss_mesh_vtu_available() != 0];
}

const char *ss_mesh_writable_list(void) {
  return ss_mesh_gmsh_available()
             ? ".mesh (Medit), .vtk, .vtu, .msh (gmsh 4.1) or .obj"
             : ".mesh (Medit), .vtk, .vtu or .obj; .msh needs a build "
               "with gmsh";
}

const char *ss_mesh_format_name(ss_mesh_format fmt) {
  switch (fmt) {
  case SS_MESH_MEDIT:
    return "medit";
  case SS_MESH_VTK:
    return "vtk";
  case SS_MESH_VTU:
    return "vtu";
  case SS_MESH_OBJ:
    return "obj";
  case SS_MESH_GMSH:
    return "gmsh";
  case SS_MESH_TETGEN:
    return "tetgen";
  default:
    return "auto";
  }
}

ss_mesh_format ss_mesh_format_from_name(const char *name) {
  if (!strcasecmp(name, "mesh")) return SS_MESH_MEDIT;
  if (!strcasecmp(name, "msh")) return SS_MESH_GMSH;
  for (int f = SS_MESH_MEDIT; f <= SS_MESH_VTU; f++)
    if (!strcasecmp(name, ss_mesh_format_name((ss_mesh_format)f)))
      return (ss_mesh_format)f;
  return SS_MESH_AUTO;
}
