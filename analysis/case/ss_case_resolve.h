/* ss_case_resolve.h — a case as the analysis judges it and as results
 * report it, built once (DESIGN sections 5 and 10).
 *
 * A vertex case's link is put in canonical form (ss_link_canonical), so that
 * isomorphic or mirrored links give results equal to the last bit; a link
 * that makes the vertex a point on an extraordinary edge of valence n
 * (ss_case_edge_point) is judged as that edge case and reported as kind
 * edge-point; a quasi48 surface vertex gets its 4-8 class
 * (ss_case_class48).  The star of the judged case is built on demand, once. */
#ifndef SS_CASE_RESOLVE_H
#define SS_CASE_RESOLVE_H

#include <stddef.h>

#include "ss_api.h"
#include "ss_case.h"

SS_BEGIN_DECLS

/* A case as asked, as analysed and as reported. */
typedef struct {
  ss_case asked;     /* as the caller named it; its link is NOT kept (NULL) */
  ss_case judged;    /* as analysed: the canonical link (canon), or the edge
                        case of an edge point; the class filled in */
  ss_case_kind kind; /* as reported: SS_CASE_EDGE_POINT for an edge point,
                        else asked.kind */
  ss_link *canon;    /* vertex: the link's canonical form (owned); else NULL */
  char *text;        /* vertex: canon in plantri ASCII; else "" (owned) */
  int k;             /* vertex, edge-point: vertices of the link; edge and
                        surface vertex: the valence n; face: 0 */
  int valence;       /* edge, surface vertex, edge-point: the valence n;
                        else 0 */
  int cls;           /* quasi48 surface vertex: the 4-8 class analysed (4 or
                        8); else 0 */
  size_t cells;      /* cells around the centre: 2k - 4 for a vertex (also an
                        edge point), n for an edge or surface vertex, 2 for
                        the face */
  ss_star *star;     /* the judged case's star once ss_case_resolved_star
                        built it (owned), else NULL */
} ss_case_resolved;

/* Resolve case c of scheme s into *r (which need not be initialised; on
 * failure it is left cleared).  SS_EINPUT for a vertex case without a link;
 * SS_ENOMEM.  Free what r holds with ss_case_resolved_clear. */
ss_status ss_case_resolve(const ss_scheme *s, const ss_case *c, ss_case_resolved *r,
                          ss_error *err);

/* The star of r's judged case (ss_case_star), built at the first call and
 * kept in r->star.  Errors as ss_case_star. */
ss_status ss_case_resolved_star(const ss_scheme *s, ss_case_resolved *r,
                                const ss_star **star, ss_error *err);

/* Release what r owns and zero it.  NULL is a no-op. */
void ss_case_resolved_clear(ss_case_resolved *r);

SS_END_DECLS

#endif
