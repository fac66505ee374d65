/* ss_mesh_gmsh_scan.h — private: what a gmsh .msh file declares, read by a
 * structural scan of our own before gmsh reads it.
 *
 * gmsh's reader is lenient: a file whose $Elements count is one too low, whose
 * last entity block claims no elements, that is cut after $EndNodes, or whose
 * element lines list more nodes than their type has, reads with cells lost and
 * no error.  The scan walks the sections of versions 2 and 4.1 (ASCII and
 * binary) and checks that every count agrees with what follows it, every
 * element has the nodes of its type, the type is one read here, and every
 * section ends with its $End line; ss_mesh_gmsh.c then compares what gmsh
 * returns with the counts declared.  Version 4.0 ("4", "4.0") is refused:
 * its entity blocks are not checked.  Coordinates and tags are not interpreted
 * (gmsh does that); sections other than $MeshFormat, $Nodes and $Elements are
 * only required to end. */
#ifndef SS_MESH_GMSH_SCAN_H
#define SS_MESH_GMSH_SCAN_H

#include <stddef.h>

#include "ss_cx.h"
#include "ss_error.h"

/* The counts a .msh file declares (and the scan found consistent). */
typedef struct {
  int version;                 /* major version: 2 or 4 */
  int binary;                  /* 1: binary data sections, 0: ASCII */
  size_t nodes;                /* nodes in $Nodes */
  size_t elements;             /* elements in $Elements (all of them cells here) */
  size_t cells[SS_NCELLTYPES]; /* of the elements, how many of each cell type */
} ss_gmsh_decl;

/* Scan the .msh file at path (its first two lines already checked to be a
 * version 2 or 4.1 $MeshFormat) into *decl.  SS_EINPUT with "path:LINE:
 * $Section: problem" for any inconsistency: a count that does not match what
 * follows, an element line with more or fewer nodes than its type, an element
 * type that has no cell here (polygons, prisms, second order...), a missing
 * $End line, a file cut short, no $Nodes or no (or an empty) $Elements;
 * SS_EIO if the file cannot be read. */
ss_status ss_mesh_gmsh_scan(const char *path, ss_gmsh_decl *decl, ss_error *err);

/* The cell type of gmsh element type gt: 1 and *t set when it is one read
 * here (points, lines, triangles, quadrangles, tetrahedra, hexahedra, all of
 * the first order), else 0. */
int ss_mesh_gmsh_cell_type(int gt, ss_cell_type *t);

/* gmsh's name of its element type gt ("Prism 6"), or NULL for a type not
 * named here (types 1 to 37, 69, 92 and 93 are). */
const char *ss_mesh_gmsh_type_name(int gt);

#endif
