/* ss_certify.h — the certified path of one case (`--certify`; DESIGN section
 * 10, "certified verdicts").
 *
 * After the double-precision analysis (ss_local, ss_eig, ss_charmap_judge,
 * ss_charmap_injectivity) of a case, with ss_charmap_opts.similarity and
 * exact_lazy a rational S first goes to the verified similarity (ss_simil.h),
 * which proves generic passes (condition and basis, then step 2 below) from
 * one approximate diagonalisation per diagonal block; where it decides
 * nothing, and otherwise always, the exact path:
 *   1. the exact spectrum of S (ss_exact: rational S, factored characteristic
 *      polynomials, isolated roots) decides the eigenvalue condition, which
 *      replaces the double-precision one when it is proven and becomes
 *      undecided ("not certified: ...") when it is not;
 *   2. on a proven pass, the enclosed subdominant basis (ss_exact_basis)
 *      proves the regularity verdict and the injectivity verdict where it can
 *      (ss_charmap_certify);
 *   3. on a proven failure, there is no characteristic map: regularity is
 *      undecided ("no characteristic map"), unless the double path already
 *      failed it for complex or defective subdominant eigenvalues.
 * Nothing passes without proof: every verdict that could not be proven is
 * undecided with the reason, the double-precision verdict quoted in it.
 * Injectivity keeps the double path's pass (exact predicates on the double
 * net) with certified = 0: the tables say so. */
#ifndef SS_CERTIFY_H
#define SS_CERTIFY_H

#include "ss_api.h"
#include "ss_charmap.h"
#include "ss_eig.h"
#include "ss_exact.h"
#include "ss_local.h"

SS_BEGIN_DECLS

/* What the exact path adds to one case. */
typedef struct {
  ss_verdict cond;   /* the eigenvalue condition, proven (certified) or
                        undecided */
  double seconds;    /* time the exact path took (wall clock) */
  const char *route; /* what proved or tried to: "exact" (NULL: the same),
                        "verified similarity" (a pass, ss_simil.h, with
                        ss_charmap_opts.similarity),
                        "Fourier blocks in balls" (ss_fourier.h), "balls,
                        ties by Schur's lemma" (ss_schur.h), "Fourier blocks
                        in balls, then ties by Schur's lemma" (an edge both
                        left undecided), or "none tried" (nothing tried: without
                        certify, or weights not rational where no ball route
                        applies); a static string */
} ss_certified;

/* Run the exact path on case c (M, e from the double path; cm, reg, inj its
 * map and verdicts, or cm NULL without a map).  reg and inj are updated in
 * place (verdicts, reasons, certified flags).  *x (may be NULL) receives the
 * exact spectrum, owned by the caller (ss_exact_free), NULL when it could not
 * be built or was not needed (the verified similarity proved the pass).  A scheme whose
 * weights are not small rationals is not an error: everything is then "not certified",
 * except at surface vertices and edges, whose condition the Fourier blocks in balls may
 * prove (ss_fourier.h), and at volume vertices and the edges the blocks leave undecided,
 * the balls with ties by Schur's lemma (ss_schur.h); *x stays NULL then.  SS_ENOMEM;
 * SS_EINPUT for malformed inputs. */
ss_status ss_certify(const ss_local *M, const ss_case *c, const ss_eig *e,
                     const ss_charmap *cm, const ss_charmap_opts *o, ss_regularity *reg,
                     ss_charmap_inj *inj, ss_certified *out, ss_exact **x, ss_error *err);

/* The three verdicts of case c once its eigenstructure e is known, as every
 * command judges them: regularity (ss_charmap_judge, which may deepen M's
 * ring, and the symmetry test), injectivity (ss_charmap_injectivity) and,
 * with certify, the exact path (ss_certify) — unless the scheme's weights are
 * known not to be rational (ss_scheme_weights_rational; for volume cases
 * ss_scheme_volume_weights_rational, the weights their rows read): then the three are
 * unproven, "weights not rational", and *x stays NULL (a surface vertex or an
 * edge goes to the Fourier route instead, a volume vertex to the Schur route).  *cm
 * (caller frees; NULL without a map) and *x (may be NULL; caller frees; set only with
 * certify) as there; out->cond is e's condition unless certify proves or unproves it.
 * Errors: those of the calls. */
ss_status ss_certify_verdicts(const ss_scheme *s, const ss_case *c, ss_local *M,
                              const ss_eig *e, const ss_charmap_opts *o, int certify,
                              ss_charmap **cm, ss_regularity *reg, ss_charmap_inj *inj,
                              ss_certified *out, ss_exact **x, ss_error *err);

SS_END_DECLS

#endif
