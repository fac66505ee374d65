/* ss_psi_tube.h — the sign of det Dψ proven in the tube round a spoke
 * (issue 34, section 3; DESIGN section 5, "Tubes proven").
 *
 * Input: a box of ψ's ring left uncovered by the polynomial pieces, with its
 * exact layered structure (ss_limit_tube.h): points P (4 layers along the
 * spoke x ncol columns across, enclosed), the runs' cross factor F and the
 * three regular quadrants' factors G_c, so that ψ on the box minus the spoke
 * is the union over m >= 0 and c of the tricubics of nets (I_4 (x) G_c F^m) P.
 *
 * Spectrum of F, proven (ss_exact, dimension 2): 1 simple, then mu a double
 * real root, non-defective, above every other root; an enclosure of a basis X
 * (ncol x 2) of mu's eigenspace.  With T = [1 | X | E] (E the unit vectors
 * of all rows but three pivots, T invertible, proven in ball arithmetic),
 * T^-1 F T = [diag(1, mu, mu)  C; 0  N] exactly (the first three columns of T
 * are invariant), and with T^-1 P = [alpha; beta], tau_m = (N / mu)^m:
 *     F^m P = 1 (a - mu^m C_1 tau_m b1) + mu^m X (b - C_mu tau_m bmu)
 *             + mu^m E tau_m beta,
 * a = alpha_1 + C_1 b1, b = alpha_mu + C_mu bmu, b1 = (I - N)^-1 beta, bmu =
 * (mu I - N)^-1 beta (ball arithmetic, solves proven).  So
 *     along the spoke:  F^m P = 1 a + mu^m (Vy_m - 1 C_1 tau_m b1)
 *     across it:        mu^-m F^m P = Vy_m + (a multiple of 1),
 *     Vy_m = X (b - C_mu tau_m bmu) + E tau_m beta,
 * and a multiple of 1 changes no difference across (G_c's rows sum to 1).
 * The sign of det Dψ on layer m's quadrant c is that of det[∂_along of net
 * G_c(1 a + mu^m (...)) | ∂_across of net G_c Vy_m] (the across columns
 * scaled by mu^-m > 0): ss_psi_piece_sign_interval3 on the two nets.
 *
 * Layers m = 0 .. m0 - 1 are judged directly with tau_m computed, in windows
 * [0, 1), [1, 2), [2, 4), [4, 8), ... (a window at once with the hulls of its
 * tau_m beta and mu^m, halved down to single layers where that does not
 * settle it), and after each window every layer m >= m0 (its end) at once with tau_m
 * replaced by the matrix of entries in
 * [-eps, eps] and mu^m by [0, mu^m0], where eps = max ||tau_r||_inf over r in
 * [m0, m0 + q) for a q with ||tau_q||_inf <= 1 (then ||tau_m|| <= eps for
 * every m >= m0).  All of them of one strict sign: det Dψ has that sign on
 * the whole box minus the spoke, proven (every tau_m a product of two earlier
 * powers, tau_h tau_(m-h) with h the largest power of two below m, so that
 * its ball is not the m-fold product of |N / mu|'s; m0 <= 127).  The tail's
 * leading term is
 * det[a' | B] det Dchi, so this is the "det[a' | B] of one strict sign
 * and chi regular", with the error terms bounded rather than neglected.
 *
 * A fold.  A single layer m whose quadrant c is proven to take both signs
 * (two exact values of opposite strict signs, ss_psi_bernstein.h) proves
 * that ψ folds: the quadrant's true net is G_c F^m P = G_c Vx_m (Vx_m = F^m
 * P as above), whose across differences are mu^m those of G_c Vy_m, so
 * det Dψ in the quadrant's parameters is mu^2m times the det judged; in
 * the box's parameters the across axes are 2^(m+1) times finer.  The two
 * points and their enclosures are returned in the box's parameters (the
 * quadrant is [L, L + 2^-(m+1)] across, L = its corner bit's offset in the
 * layer's corner region [0, 2^-m] or [1 - 2^-m, 1], and the whole box
 * along). */
#ifndef SS_PSI_TUBE_H
#define SS_PSI_TUBE_H

#include "ss_api.h"
#include "ss_error.h"
#include "ss_limit_tube.h"

SS_BEGIN_DECLS

/* What the proof in one tube box found. */
typedef struct {
  int sign;           /* +1 / -1: det Dψ proven of that strict sign on the box
                         minus the spoke; 0: not proven (why says why) */
  int layers;         /* m0: the layers judged directly before the tail */
  double mu;          /* the across eigenvalue (midpoint of its enclosure) */
  double ratio;       /* |next root| / mu (midpoints): the tail's rate */
  double eps;         /* the tail bound used, or NaN */
  char why[200];      /* sign 0: the reason; else empty */
  int fold;           /* 1 if one layer's quadrant was proven to take both signs
                         (sign 0): psi folds in the tube, witnessed below */
  int fold_layer;     /* with fold: that layer m */
  double where[2][3]; /* with fold: two points in the box's parameters
                         [0,1]^3 */
  double det[2][2];   /* with fold: enclosures of det Dψ there, derivatives
                         in the box's parameters, of opposite strict signs */
} ss_psi_tube_result;

/* What F alone determines (its spectrum, eigenspace, change of basis and the
 * powers of N / mu), kept between the boxes of one case: the boxes along a
 * spoke share their cross-section.  Opaque; not shared between threads. */
typedef struct ss_psi_tube_cache ss_psi_tube_cache;

/* A new, empty cache (NULL out of memory); free with ss_psi_tube_cache_free
 * (NULL is a no-op). */
ss_psi_tube_cache *ss_psi_tube_cache_new(void);
void ss_psi_tube_cache_free(ss_psi_tube_cache *c);

/* Prove the sign of det Dψ in tube t (its points enclosed: t->lo, t->hi
 * must be set), reading F's rationals with maxden as the exact path does,
 * each piece judged with subdivision down to piece_depth (and, where that
 * leaves doubt, SS_PSI_MAXDEPTH); cache may be NULL.  A tube the method
 * cannot settle is not an error: sign 0 with the reason.  SS_EINPUT for a
 * tube without an enclosure; SS_ENOMEM. */
ss_status ss_psi_tube_sign(const ss_limit_tube *t, long maxden, int piece_depth,
                           ss_psi_tube_cache *cache, ss_psi_tube_result *r,
                           ss_error *err);

SS_END_DECLS

#endif
