/* ss_limit_edge.h — the leading terms of the limit of a hex mesh (ss_limit.h)
 * near a point on an extraordinary edge, from the eigen-decomposition of the
 * stationary run there.
 *
 * Let x0 be a point of a cell's edge (two of its three parameters 0 or 1)
 * that lies on an extraordinary edge of valence n, its along-parameter dyadic
 * (a few binary digits), so that after a few steps x0 is a corner b of the
 * current sub-cell and every further step is the stationary run into b, W =
 * V diag(lambda) V^-1.  Write the sub-cell's patch points P = sum_i V_i c_i^T
 * (c_i in R^3) and phi_i for the limit of the net V_i: phi_i(b + (y - b)/2) =
 * lambda_i phi_i(y).  Near b the limit is
 *     psi = a + c_h phi_h + B chi + (terms of smaller |lambda|),
 * a = the eigenvalue-1 part (the point), phi_h the real eigenvalue-1/2 modes
 * (linear along the edge: the derivative a' along it, read as 2 phi_h(b +
 * e_along / 2), ss_limit.h's fixed-point Jacobian), and chi = (phi_i,
 * phi_i+1) the largest remaining pair (eigenvalue mu, the edge's subdominant
 * across it: a complex pair or a double real one).  At a probe point off the
 * edge, on the cross-section through x0, the model's Jacobian has rows a'
 * (along) and B Dchi (across), so
 *     det D(model) = det[a' | B] det Dchi   (in the cell's parameters, up to
 *                                           the sign of the axes' order),
 * the leading term of det Dpsi at the probe: they differ by terms of relative
 * size about (next / |mu|)^j at distance 2^-j from the edge.  Its sign is the
 * sign of the spoke coefficient det[a' | B] times that of det Dchi, and it is
 * independent of the eigenbasis chosen (B G^-1 and G chi give the same).
 *
 * Independence from ss_limit_eval: the walk to x0 is the plain one (never
 * the tensor shortcut, eq. (1)), and the modes come from the run's own
 * eigenvectors, not from differences of limit points.  Double precision.
 * chi's walk to the probe is kept with the run (ss_lim_trans.chi) and
 * copied for a later call that reaches the same run at the same point: a
 * function of the two alone, so the results are those of a fresh walk, bit
 * for bit (tests/psi/test_psi_spoke.c). */
#ifndef SS_LIMIT_EDGE_H
#define SS_LIMIT_EDGE_H

#include <stddef.h>

#include "ss_api.h"
#include "ss_error.h"
#include "ss_limit.h"

SS_BEGIN_DECLS

/* The leading terms of the limit at a point on an extraordinary edge. */
typedef struct {
  int axis;         /* the edge's axis in the cell's parameters (0 u, 1 v, 2 w) */
  double mu[2];     /* the across eigenvalue (real, imaginary part) */
  double next;      /* largest |lambda| below |mu| (other than the real 1/2
                       modes): the corrections shrink like (next/|mu|)^j */
  int steps;        /* plain steps walked before the stationary run */
  double a[3];      /* the limit point on the edge */
  double da[3];     /* a': its derivative along the edge (cell parameter) */
  double B[3][2];   /* columns: the coefficients of chi's two components */
  double chi_at[2]; /* chi at the probe */
  double jac[3][3]; /* the model's Jacobian at the probe: rows d/du, d/dv,
                       d/dw (row axis = a', the others B Dchi) */
  double det;       /* its determinant: the leading term of det Dpsi at the
                       probe, in the cell's parameters */
  double hadamard;  /* |det| / the product of jac's row norms, in [0, 1]: 0
                       when the model is degenerate */
  double det_coef;  /* det[a' | B] in this eigenbasis (not canonical: the
                       basis of chi is LAPACK's, unit vectors; its sign times
                       that of the cross-section's det Dchi is det's) */
  double rel;       /* |det_coef| / (2^steps S^3), S the largest distance of
                       a patch point from the first at the run (a' is a
                       derivative in the cell's parameter, of the size of S
                       2^steps): the spoke coefficient relative to the
                       patch's size; small when a' is (nearly) 0, B of rank
                       < 2, or a' in B's span */
} ss_limit_edge;

/* The leading terms at x (on the edge of cell `cell` along `axis`: the two
 * other parameters 0 or 1; x may be the edge's end) with the model's Jacobian at `probe`
 * (the same along-parameter, off the edge, in the cell), both dyadic enough that the
 * probe stays in x's sub-cell until x is a corner of it (at most 60 steps).  SS_EINPUT
 * for points that do not fit or an x that is not on an extraordinary edge (a regular
 * sub-cell reached, or no stationary run); SS_ENUMERIC when the run is defective, has no
 * eigenvalue-1/2 mode along the edge or no single pair across it; SS_ENOMEM; the errors
 * of a refinement step. */
ss_status ss_limit_edge_model(ss_limit *L, size_t cell, const double x[3], int axis,
                              const double probe[3], ss_limit_edge *out, ss_error *err);

SS_END_DECLS

#endif
