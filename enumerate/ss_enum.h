/* ss_enum.h — every link (triangulation of the sphere) with a given number of
 * vertices, each exactly once up to isomorphism and reflection.
 *
 * Method: canonical construction paths (McKay 1998) over the expansions of
 * Batagelj and of Brinkmann & McKay's plantri: starting from the tetrahedron,
 * a new vertex of degree 3 is put into a face (E3), of degree 4 onto an edge
 * (E4: the edge is removed and the new vertex joined to its quadrilateral), or
 * of degree 5 at a corner (E5: two edges at a vertex are removed and the new
 * vertex joined to the pentagon).  Every triangulation with k >= 5 vertices
 * reduces by the inverse of one of these at a vertex of minimum degree, so a
 * link is accepted from its parent only when the new vertex is, up to
 * automorphism, the canonical reduction of minimum degree, and expansions of
 * a parent are tried once per orbit of its automorphism group.  Memory is a
 * fixed workspace per depth: nothing grows with the number of links.
 *
 * Parts: with nparts > 1 the tree is cut at a level s where it is wide; part
 * i handles the subtrees whose root has index = i (mod nparts) at level s and
 * the nodes above s with that residue.  Parts are disjoint, their union is
 * everything, and each is about 1/nparts of the work. */
#ifndef SS_ENUM_H
#define SS_ENUM_H

#include <stdint.h>

#include "ss_api.h"
#include "ss_link.h"

SS_BEGIN_DECLS

#define SS_ENUM_MAXK 20 /* largest k enumerated (k = 20 has ~10^11 links) */

typedef struct {
  int kmin, kmax; /* visit links with kmin..kmax vertices, 4 <= kmin <= kmax */
  int part;       /* this part, 0 <= part < nparts */
  int nparts;     /* number of parts, >= 1 */
} ss_enum_opts;

/* Called for each link; l is valid only during the call.  Return nonzero to
 * stop the enumeration (ss_enum_links then returns SS_OK). */
typedef int (*ss_enum_visit)(const ss_link *l, void *ctx);

/* Enumerate.  visit may be NULL (count only).  counts, if not NULL, receives
 * counts[k] for k = 0..SS_ENUM_MAXK (links visited with k vertices).
 * SS_EINPUT for bad options, SS_ENOMEM. */
ss_status ss_enum_links(const ss_enum_opts *o, ss_enum_visit visit, void *ctx,
                        uint64_t *counts, ss_error *err);

/* The level at which parts are cut for these options (for progress output and
 * tests). */
int ss_enum_split_level(const ss_enum_opts *o);

SS_END_DECLS

#endif
