/* ss_psi_spoke.h — the spokes of a vertex case: the sign of det Dpsi in the
 * thin tube round each edge from p of valence other than 4, which psi's
 * polynomial pieces never reach (ss_psi.h; DESIGN section 5, "The spokes").
 *
 * Near a spoke of valence n, psi(x, y) = a(x) + B(x) chi(y) + o(|chi|), x
 * along the spoke, y across it, chi the edge's 2D characteristic map
 * (eigenvalue mu), so det Dpsi(x, y) = det[a'(x) | B(x)] det Dchi(y) + smaller
 * terms: the spoke coefficient s(x) = det[a' | B] decides the tube's sign.
 *
 * How s is computed (ss_limit_edge.h): at sample points x0 = 1/2 + i/16, i =
 * 0..8, of the spoke's part in the ring (x0 in [1/2, 1] of the cell's edge
 * from p, p at 0), in each of the n cells round the spoke, the stationary
 * run at x0 is eigen-decomposed; its modes give a'(x0) (eigenvalue 1/2) and
 * B(x0), chi (the across pair), and the leading term of det Dpsi at a probe
 * 2^-SS_PSI_SPOKE_PROBE from the spoke in that cell (both cross parameters),
 *     s_c(x0) = det[a' | B] det Dchi(probe)   (the cell's parameters),
 * which is s(x0) times a factor of one sign in each cell (det Dchi on the
 * cell's sector; positive when chi is regular and oriented like the cells),
 * and has the sign of det Dpsi there.  Beside it, det Dpsi at the same probe
 * by ss_limit_eval (another code path: the layered shortcut for MLCA); the
 * two differ by the dropped modes, relatively at most about
 * (next/|mu|)^SS_PSI_SPOKE_PROBE, and a sample whose signs differ is counted
 * (ndisagree).
 *
 * Classes (per spoke, over its n x 9 samples):
 *   sign change  samples of both strict signs: psi folds across a surface
 *                through the spoke (or chi is not regular); the two samples
 *                are the witnesses;
 *   degenerate   some sample with s relatively below SS_PSI_SPOKE_DEGENERATE
 *                (ss_limit_edge's rel: |det[a' | B]| against the cube of
 *                the run's patch size, so a' = 0, B of rank < 2 and a' in
 *                B's span all count), and no strict sign change: psi is
 *                degenerate on the spoke (s = 0 where such a sample lies:
 *                forced by a symmetry of the link -- a reflection fixing
 *                the spoke with psi o sigma = R psi, det R = +1, see
 *                tests/psi/test_psi_spoke.c -- or psi mapping the spoke to
 *                a point, or an isolated zero);
 *   one sign     every sample of one strict sign (smin = the least |s|).
 *
 * Proven: nothing.  Evidence in double precision at finitely many points:
 * a sign change between samples is a statement about the leading term (two
 * samples of opposite sign with |s| well above the correction), not a proof;
 * one sign at 9 points per cell does not exclude a zero between them; and
 * the degenerate threshold cannot tell s = 0 from |s| < 1e-8.  What it
 * relies on: the eigen-decomposition of the run at x0 (LAPACK, condition up
 * to SS_LIMIT_MAXCOND), chi regular (not checked here beyond the cross
 * comparison with ss_limit_eval). */
#ifndef SS_PSI_SPOKE_H
#define SS_PSI_SPOKE_H

#include <stddef.h>

#include "ss_api.h"
#include "ss_error.h"
#include "ss_limit.h"
#include "ss_local.h"
#include "ss_scheme.h"

SS_BEGIN_DECLS

#define SS_PSI_SPOKE_SAMPLES    9    /* x0 = 1/2 + i/16, i = 0..8, per cell */
#define SS_PSI_SPOKE_PROBE      12   /* the probe at 2^-12 from the spoke */
#define SS_PSI_SPOKE_DEGENERATE 1e-8 /* relative |s| below which s counts as 0 */

/* What a spoke is. */
typedef enum {
  SS_SPOKE_ONE_SIGN = 0, /* s of one strict sign at every sample */
  SS_SPOKE_SIGN_CHANGE,  /* samples of both strict signs */
  SS_SPOKE_DEGENERATE    /* some sample with s = 0 (relatively), no sign change */
} ss_psi_spoke_class;

/* A sample: a probe point near the spoke with s and det Dpsi there. */
typedef struct {
  size_t cell;     /* the two-ring cell (index into M's cells, round p) */
  double at[3];    /* the probe's parameters in that cell */
  double on[3];    /* the spoke's point x0 in that cell's parameters */
  int axis;        /* the spoke's axis in that cell (0 u, 1 v, 2 w) */
  double x0;       /* the spoke parameter (0 at p, 1 at the cell's far end) */
  double s;        /* the leading term s_c(x0) (above) */
  double rel;      /* s relative to the patch (ss_limit_edge's rel) */
  double det_eval; /* det Dpsi at the probe by ss_limit_eval */
} ss_psi_spoke_sample;

/* One spoke. */
typedef struct {
  int vertex;               /* the link vertex at its end (0-based: 'a' + vertex)
                               in M's link (a pipeline's: the canonical form the
                               report prints) */
  int valence;              /* n, its degree in the link (cells round the spoke) */
  ss_psi_spoke_class cls;   /* the class (above) */
  int sign;                 /* one sign: +1 or -1; otherwise 0 */
  size_t nsamples;          /* samples taken (n x SS_PSI_SPOKE_SAMPLES) */
  size_t ndegenerate;       /* of these, below SS_PSI_SPOKE_DEGENERATE */
  size_t ndisagree;         /* of these, sign(s) != sign(det_eval) (both nonzero) */
  double reldiff;           /* largest |s - det_eval| / |det_eval| */
  double smin;              /* least |s| over the samples */
  double smax;              /* largest |s| */
  double relmin;            /* least relative |s| */
  double mu;                /* |mu|, the across eigenvalue */
  double gap;               /* next / |mu| at the samples (largest) */
  ss_psi_spoke_sample min;  /* the sample of least |s| */
  ss_psi_spoke_sample w[2]; /* sign change: a sample of s > 0 [0] and s < 0 [1] */
} ss_psi_spoke;

/* The spokes of one vertex case. */
typedef struct {
  size_t n;                          /* spokes (edges from p of valence other than 4) */
  ss_psi_spoke *spoke;               /* n of them, by link vertex */
  size_t none, nchange, ndegenerate; /* how many of each class */
  double seconds;                    /* thread CPU time */
} ss_psi_spokes;

/* Classify the spokes of vertex case M (hex cells; L the limit evaluator of
 * its two-ring with the characteristic map's net, as ss_psi_judge builds
 * it).  *out is the caller's (ss_psi_spokes_free).  SS_EINPUT when M is not
 * a hex vertex case; SS_ENUMERIC when a spoke's run has no usable
 * eigen-decomposition (ss_limit_edge_model); SS_ENOMEM. */
ss_status ss_psi_spokes_classify(ss_limit *L, const ss_local *M, ss_psi_spokes *out,
                                 ss_error *err);

/* The same from scheme s and net x (M->n2 points, 3 coordinates each):
 * builds the evaluator.  SS_EINPUT also when s has no limit evaluator. */
ss_status ss_psi_spokes_of(const ss_scheme *s, const ss_local *M, const double *x,
                           ss_psi_spokes *out, ss_error *err);

/* Free the spokes' array (the struct itself is the caller's). */
void ss_psi_spokes_free(ss_psi_spokes *r);

/* sp's class from its samples (sp->sign holding bits 1 positive and 2
 * negative, as they were seen; set to the class's sign): sign change,
 * degenerate, one sign (above); (ss_psi_spoke_class)-1 and sign 0 when it
 * has no samples. */
void ss_psi_spoke_classify(ss_psi_spoke *sp);

/* A spoke's name, as verdicts and JSON give it: its link vertex v (0-based)
 * as plantri's letter ('a' + v) when v < 26, else "#" and v + 1. */
void ss_psi_spoke_name(int v, char name[16]);

/* The name of a class: "one sign", "sign change", "degenerate". */
const char *ss_psi_spoke_class_name(ss_psi_spoke_class c);

/* The limit evaluator of M's two-ring (its hex cells, in M's order) with
 * points x (M->n2 x 3): psi on the cells round p.  SS_EINPUT (from
 * ss_limit_new) when s has none; SS_ENOMEM. */
ss_status ss_psi_two_ring_limit(const ss_scheme *s, const ss_local *M, const double *x,
                                ss_limit **out, ss_error *err);

SS_END_DECLS

#endif
