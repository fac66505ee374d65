/* ss_stencil.h — stencil files: schemes described by data (DESIGN section 3).
 *
 * A stencil file is an INI file (read with inih) naming a rule family and its
 * exact rational weights:
 *
 *   [scheme]
 *   name = tetoct-variant
 *   family = averaging        ; the only family so far
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
 * first error of the file), and the valence n where it depends on one. */
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

/* As ss_stencil_load, from the text of a file; `where` names it in messages. */
ss_status ss_stencil_parse(const char *text, const char *where, ss_scheme **out,
                           ss_error *err);

SS_END_DECLS

#endif
