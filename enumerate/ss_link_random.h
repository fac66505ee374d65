/* ss_link_random.h — random links: convex hulls of random points on the sphere.
 *
 * k points drawn independently and uniformly on the unit sphere are, with
 * probability 1, in convex position with no four on a hull facet, so the
 * boundary of their convex hull is a simplicial triangulation of the sphere on
 * all k points: a link (ss_link.h).  This gives random links of any size, a
 * natural distribution (the combinatorics of random polytopes) next to the
 * exhaustive enumeration of small ones (ss_enum.h). */
#ifndef SS_LINK_RANDOM_H
#define SS_LINK_RANDOM_H

#include <gsl/gsl_rng.h>

#include "ss_api.h"
#include "ss_error.h"
#include "ss_link.h"

SS_BEGIN_DECLS

/* Number of point sets drawn before ss_link_random gives up. */
#define SS_LINK_RANDOM_TRIES 100

/* A random link on k vertices: the hull (ss_hull.h) of k points from
 * gsl_ran_dir_3d(r, ...), vertex i = i-th point.  If the hull is degenerate
 * or misses a point (probability 0, but doubles are finite) the points are
 * drawn again, at most SS_LINK_RANDOM_TRIES times in all.
 *
 * The result depends only on k and the state of r (3k draws per attempt, on
 * any platform with IEEE doubles), so a seeded generator reproduces it; r is
 * advanced.  *out is new, owned by the caller (ss_link_free).
 * SS_EINPUT if k is outside 4..SS_LINK_MAXK or r is NULL; SS_ENUMERIC if every
 * attempt was degenerate; SS_ENOMEM; SS_EINTERNAL from the hull shim.  On
 * failure *out = NULL.  Cost O(k log k) expected. */
ss_status ss_link_random(int k, gsl_rng *r, ss_link **out, ss_error *err);

SS_END_DECLS

#endif
