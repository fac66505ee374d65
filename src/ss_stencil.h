/* ss_stencil.h — stencil files: schemes described by data (DESIGN section 3).
 *
 * A stencil file is an INI file (read with inih) naming a rule family and its
 * exact rational weights:
 *
 *   [scheme]
 *   name = tetoct-variant
 *   family = averaging        ; or points (below)
 *   split = tetoct            ; or multilinear
 *   [mask.tet]                ; roles: self, edge
 *   self = -1/16
 *   edge = 17/48
 *   [mask.oct]                ; roles: self, edge, opposite
 *   ...
 *
 * Cell types and their roles (the role of a cell vertex relative to the
 * vertex being moved, ss_cell_role): split multilinear takes mask.segment
 * (self, other), mask.quad (self, edge, opposite) and mask.hex (self, edge,
 * face, opposite); split tetoct takes mask.segment, mask.triangle (self,
 * edge), mask.tet (self, edge) and mask.oct (self, edge, opposite).  Corner
 * vertices (vertex cells) always keep their place.  The scheme takes exactly
 * the cell types that have a mask; every mask lists every role of its type.
 *
 * Weights are rationals `p/q` or integers (an optional sign, decimal digits,
 * q > 0), or expressions in the valence n (ss_expr.h: read by libmatheval,
 * exact by FLINT where rational; n = the number of cells the averaging rule
 * divides by at the fine vertex moved).  A mask's weights, each counted once
 * per cell vertex of that role, must sum to 1 — exactly when rational — at
 * every valence n = 1..SS_AVG_NMAX.  Any violation — missing [scheme] or key,
 * unknown family, split, section, cell type, role or name, a repeated key, a
 * malformed weight, a weight not finite at some n, a sum other than 1 — is
 * SS_EINPUT with a message "FILE:LINE: ..." naming the key or section (the
 * first error of the file), and the valence n where it depends on one.
 *
 * The points family (family = points; ss_scheme.h, ss_points): every new
 * point a weighted sum of named averages over the coarse elements at its
 * element X (containing X or contained in it): `vertex` (the mean of the old
 * points), `edge` (of the edge midpoints), `face` (of the face centroids),
 * `cell` (of the cell centroids); n = the number of elements of the place's
 * top dimension at X.  Sections [PLACE.POINT]: PLACE volume (points of a hex
 * mesh off its surface; n hexes), surface (the boundary faces and quad cells
 * of a hex mesh, as ccsolid takes them, or a triangle surface; n faces),
 * crease (crease curves and vertices after ss_crease.h; n crease edges);
 * POINT vertex, edge, face, cell up to the place's dimension; keys the
 * averages up to it, absent ones 0.  split multilinear (hexes, quads,
 * segments, vertices) needs volume.vertex, volume.edge, volume.face,
 * surface.vertex, surface.edge and crease.vertex; split tetoct (triangle
 * surfaces on Loop's 1-to-4 split; no volume sections, no face points)
 * needs surface.vertex, surface.edge and crease.vertex.  Sections not given
 * (volume.cell, surface.face, crease.edge) are the centroid; corners stay.
 * The weights of each section must sum to 1 at every n (exactly when
 * rational); no [mask.*] sections.  [volume.axis] (multilinear, optional):
 * the rule of an old vertex on an extraordinary edge (ss_points.axis: 2m
 * hexes, its link the bipyramid over m != 4; n = 2m) in place of
 * volume.vertex, keys vertex, along (the mean of the midpoints of the two
 * edges of valence m), across (of the m others), edge, face, cell; along
 * and across in any other section are refused.  data/stencils/ccsolid.ini,
 * ccsolid-tensor.ini and loop.ini are the built-in ccsolid, ccsolid-tensor
 * and loop so written.
 *
 * The neighbours family (family = neighbours, split tetoct; ss_scheme.h,
 * ss_neighbours): the box-spline paper's rules over rho, the neighbours by
 * an edge or an octahedron's major diagonal.  Sections and keys: [vertex]
 * self, rho (n = |rho(x)|, rho shared by the n); [edge] ends, rho (ends
 * shared by the two ends, n = |rho(a) ∩ rho(b)|; the midpoint when n = 0);
 * [centre] diagonal, equator (the octahedron centre: the two ends of its
 * major diagonal, its other four corners; n = 6); [boundary.vertex] self,
 * ring and [boundary.edge] ends, opposite (Loop-like rules on the faces held
 * by one cell; n boundary neighbours, or vertices opposite the edge).  All
 * five needed.  data/stencils/boxspline.ini is the built-in boxspline.
 *
 * A weight given apart at one valence: KEY@N = VALUE (N = 1..SS_AVG_NMAX,
 * after KEY itself, at most 16 per key) replaces KEY's value at n = N, in
 * every family (box-spline's (3.5) is edge ends@4 and rho@4).  The sums are
 * checked at N with it.  With a [param] name in VALUE it is a parameter of
 * one valence for `subspectra tune`.
 *
 * Parameters: a [param] section names values that weights use by name,
 *
 *   [param]
 *   a = ?(-7/4, 5/4)          ; free: `subspectra tune` chooses it in [lo, hi]
 *   b = 3/16                  ; fixed: a named constant (what tune writes)
 *   [mask.hex]
 *   self = a^3
 *
 * A name is a C identifier of at most 31 characters, neither n nor a name
 * libmatheval knows (functions, constants: ss_stencil_reserved); a value
 * is p/q or ?(LO, HI) with rational LO < HI, |LO|, |HI| <= 1000.  Where a
 * weight uses a parameter its text is read with every occurrence of the
 * name replaced by "(num/den)", so a weight with parameters is an
 * expression (ss_expr.h: needs libmatheval) and exact where rational.  At
 * most SS_STENCIL_MAXPARAMS parameters; each must be used by some weight.
 * ss_stencil_parse and ss_stencil_load refuse a file with a free parameter
 * ("FILE:LINE: [param] a is free (a range ?(LO, HI)): choose it with
 * `subspectra tune`"); ss_stencil_parse_at reads it with values given. */
#ifndef SS_STENCIL_H
#define SS_STENCIL_H

#include <stdint.h>

#include "ss_api.h"
#include "ss_scheme.h"

SS_BEGIN_DECLS

/* Read the stencil file at path and build its scheme (*out, caller frees with
 * ss_scheme_free; named by the file's `name`).  If identity is not NULL it
 * receives a 64-bit FNV-1a hash of the file's bytes, so results can be keyed
 * by the stencil's content.  SS_EIO if the file cannot be read; SS_EINPUT as
 * above; SS_ENOMEM. */
ss_status ss_stencil_load(const char *path, ss_scheme **out, uint64_t *identity,
                          ss_error *err);

/* The text of the stencil file at path (*text, NUL-terminated, the caller
 * frees it) and, if identity is not NULL, the hash ss_stencil_load gives.
 * SS_EIO if it cannot be read; SS_EINPUT for a NUL byte or more than 16 MB;
 * SS_ENOMEM. */
ss_status ss_stencil_read(const char *path, char **text, uint64_t *identity,
                          ss_error *err);

/* As ss_stencil_load, from the text of a file; `where` names it in messages. */
ss_status ss_stencil_parse(const char *text, const char *where, ss_scheme **out,
                           ss_error *err);

#define SS_STENCIL_MAXPARAMS 16 /* parameters of one file at most */

/* A parameter of a stencil file, its value or its range. */
typedef struct {
  char name[32];      /* the identifier */
  int line;           /* its line in the file (1-based) */
  int free;           /* 1: ?(lo, hi), to be chosen; 0: fixed at num/den */
  long long num, den; /* fixed: the value, lowest terms, den > 0 */
  long long lo[2];    /* free: the lower bound, numerator and denominator */
  long long hi[2];    /* free: the upper bound (lo < hi) */
} ss_stencil_param;

/* The parameters of a file, in the order of the file. */
typedef struct {
  ss_stencil_param p[SS_STENCIL_MAXPARAMS]; /* n parameters */
  int n;                                    /* their number */
} ss_stencil_params;

/* Read the [param] section of a stencil file's text into *out (the other
 * sections are not checked here).  SS_EINPUT "WHERE:LINE: ..." for a
 * malformed name or value, a reserved or repeated name, too many
 * parameters, a line inih cannot read. */
ss_status ss_stencil_read_params(const char *text, const char *where,
                                 ss_stencil_params *out, ss_error *err);

/* As ss_stencil_parse, with the parameters' values taken from values (as
 * ss_stencil_read_params returned them, every parameter fixed: free = 0,
 * num/den set; a parameter left free is SS_EINPUT).  values's names must be
 * the file's, in its order (SS_EINPUT otherwise).  Besides
 * ss_stencil_parse's errors: a parameter no weight uses, "num/den" of more
 * than 6 digits (expressions' literal limit). */
ss_status ss_stencil_parse_at(const char *text, const char *where,
                              const ss_stencil_params *values, ss_scheme **out,
                              ss_error *err);

/* Whether name is reserved in expressions (n, libmatheval's functions and
 * constants): not a parameter's name. */
int ss_stencil_reserved(const char *name);

SS_END_DECLS

#endif
