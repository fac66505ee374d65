/* ss_schur_impl.h — ss_schur's internals, shared by ss_schur.c (group,
 * enclosures, condition) and ss_schur_tie.c (the invariant subspaces, the
 * character norm, the basis).  Internal to analysis/spectrum. */
#ifndef SS_SCHUR_IMPL_H
#define SS_SCHUR_IMPL_H

#include "acb_mat.h"
#include "arb.h"
#include "arb_mat.h"

#include "ss_ball.h"
#include "ss_scc.h"
#include "ss_schur.h"

enum {
  SC_PREC = 64 /* working precision, bits: the entries' windows decide the
                   width, not this */
};

/* One root (internal): a ball and what is proven of it. */
typedef struct {
  ss_ball_root ball; /* the ball, |z|, counted: 1 when the enclosure counted
                        them, 0 bounds only (first: ss_ball_roots) */
  int count;         /* eigenvalues in it */
  long blk;          /* -1: A; else the component of C */
  int scalar;        /* 1: one eigenvalue, not defective (count 1, or a tie
                        proven by Schur's lemma) */
  double nlo, nhi;   /* <chi, chi> enclosed (0, 0: not computed) */
  int split;         /* k = 2 or 3: V is proven the sum of k distinct
                        irreducibles of real type (<chi, chi> = k and the
                        Frobenius-Schur indicators (1 / |G|) sum chi(g^2)
                        add up to k), so A on V is diagonalizable with real
                        eigenvalues, one per constituent (not proven equal) */
  acb_mat_struct Xc; /* of A, counted: n1 x count, Rump's enclosure of a
                        basis of its invariant subspace V */
  int has_xc;        /* 1 once Xc is initialised */
  arb_mat_struct X;  /* of A, once proven real: n1 x count, Re Xc, a real
                        basis of V */
  int has_x;         /* 1 once X is initialised */
} sc_root;

struct ss_schur {
  size_t n, n1;        /* size of S; its one-ring points */
  int m;               /* subdominant eigenvalues: 2 or 3 */
  size_t nrt;          /* roots */
  size_t cap;          /* roots allocated */
  sc_root *rt;         /* nrt of them, by decreasing midpoint modulus */
  ss_schur_root *pub;  /* nrt public copies, same order */
  ss_csr csr;          /* S's nonzero entries */
  ss_scc scc;          /* C's components */
  ss_ball_outcome out; /* the condition and on a pass the basis (n x m) */
  size_t lead[4];      /* on a pass: the roots of lambda1..m */
  int nlead;           /* ... how many */
};

/* A new root appended to s->rt (zeroed, its balls initialised), or NULL
 * when out of memory. */
sc_root *ss_schur_root_new(ss_schur *s);

/* The roots of the diagonal block B of S (blk: -1 the one-ring block A,
 * else C's component), appended to s->rt: the approximations clustered
 * (within 1e-6 relative), each cluster's invariant subspace enclosed by
 * Rump's method (its ball holds at least as many eigenvalues as the cluster
 * has members) and, when the balls are pairwise disjoint, counted (they
 * hold exactly that many: the counts add up to the size); of A, the basis
 * enclosure kept (Xc).  Otherwise the balls of acb_mat_eig_global_enclosure,
 * counting nothing.  0, 1 when not even those, -1 out of memory. */
int ss_schur_block(ss_schur *s, const acb_mat_t B, long blk);

/* Root r's real basis of V (r of A, counted, proven real): s->rt[r].X = Re
 * Xc (the frozen rows of Rump's method are real and invertible, so the real
 * parts are independent vectors of V, which is closed under conjugation).
 * 0, or 1 with why (len bytes) when there is no enclosure. */
int ss_schur_subspace(ss_schur *s, size_t r, char *why, size_t len);

/* The character norm <chi, chi> of the group (ng elements, group as
 * ss_schur_new) on root r's enclosed V, into s->rt[r].nlo, nhi; sets
 * s->rt[r].scalar when it is proven in (0.5, 1.5), s->rt[r].split (above)
 * when it and the indicators' sum are proven in (k - 0.5, k + 0.5), k = 2, 3.  0, or 1
 * with why when an element does not map the enclosure of V to itself or X_I is not proven
 * invertible; -1 out of memory. */
int ss_schur_character(ss_schur *s, size_t r, const size_t *group, size_t ng, char *why,
                       size_t len);

/* The basis on a pass (s->lead, each with X enclosed) completed over the
 * outer rows into s->lo, s->hi (n x m), from S's balls; 0, 1 with why when
 * a ball solve fails, -1 out of memory. */
int ss_schur_complete(ss_schur *s, const double *S, char *why, size_t len);

#endif
