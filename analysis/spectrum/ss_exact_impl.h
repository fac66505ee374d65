/* ss_exact_impl.h — the inside of an ss_exact, shared by its stages: the
 * rational matrix (ss_exact_rational.c), the factors and roots by blocks
 * (ss_exact_factor.c; the roots' isolation, ss_exact_isolate.c), the order and the
 * condition (ss_exact_condition.c), the subdominant basis (ss_exact_basis.c), and the
 * object that runs them (ss_exact.c), which alone calls the others' stages: calls run one
 * way. Not a public header. */
#ifndef SS_EXACT_IMPL_H
#define SS_EXACT_IMPL_H

#include <flint/fmpq.h>
#include <flint/fmpz_mat.h>
#include <flint/fmpz_poly.h>
#include <flint/fmpz_poly_factor.h>

#include "acb.h"
#include "arb_mat.h"
#include "arb.h"

#include "ss_exact.h"
#include "ss_scc.h"

/* A rational entry of S in lowest terms. */
typedef struct {
  long long num; /* numerator */
  long long den; /* denominator, > 0 (at most maxden) */
} ss_exact_rat;

/* One distinct irreducible factor over Q of the characteristic polynomial (or,
 * with ss_exact_opts.lazy, a squarefree one not proven irreducible: unproven). */
typedef struct {
  fmpz_poly_t f; /* primitive, positive leading coefficient */
  int mult;      /* multiplicity in the characteristic polynomial of S */
  long prec;     /* precision its roots were last isolated at, bits */
  size_t root0;  /* its first root in ss_exact.rt (deg f consecutive roots) */
  long refl;     /* the factor whose roots are minus its roots, or -1 */
  int exact_nsq; /* 1 if |root|^2 is rational (linear factors, quadratics with
                    complex roots, cyclotomic factors) */
  int unproven;  /* 1: squarefree but not proven irreducible (ss_exact_opts.lazy:
                    the one-ring block's simple part, ss_exact_factor_lazy) */
} ss_exact_factor;

/* One distinct eigenvalue (internal). */
typedef struct {
  size_t factor;  /* index into ss_exact.fac */
  acb_struct z;   /* isolating ball: contains this root and no other root of
                     its factor */
  arb_struct mod; /* enclosure of |z| */
  fmpq nsq;       /* |z|^2 when the factor has exact_nsq */
  int real;       /* 1 if proven real */
  size_t cls;     /* its class of proven-equal moduli (a root index) */
} ss_exact_rt;

struct ss_exact {
  size_t n, n1;         /* size of S and of its one-ring block A */
  ss_exact_opts o;      /* options used */
  int m;                /* subdominant eigenvalues (= o.dim) */
  ss_csr A;             /* the pattern of S (values as read, in doubles) */
  ss_exact_rat *q;      /* A.ptr[n] rational values, parallel to A.col */
  ss_scc K;             /* components of the outer block */
  size_t nblk;          /* diagonal blocks: 0 = A, 1 + c = outer component c */
  size_t *bstart;       /* nblk + 1 offsets into bfac, bmult */
  size_t *bfac;         /* factors of each block's characteristic polynomial */
  int *bmult;           /* ... with their multiplicities in that block */
  size_t *brep;         /* nblk: the first block with the same entries as
                           block b (b itself if none; outer blocks > 1 x 1
                           only, else b) */
  int lazy_bad;         /* 1: with ss_exact_opts.lazy, an unproven factor met
                           another block's factor (start again with
                           fmpz_poly_factor) */
  fmpz dA;              /* lazy: the lcm of the one-ring block's denominators
                           (its eigenvalues times dA are the roots of the monic
                           integer polynomial factored: a rational one is an
                           integer) */
  size_t nfac;          /* distinct factors */
  size_t facalloc;      /* allocated entries of fac */
  ss_exact_factor *fac; /* the merged factors */
  size_t nrt;           /* distinct roots (0 if a block was too large) */
  ss_exact_rt *rt;      /* nrt roots, factor by factor */
  size_t *order;        /* nrt root indices in the order of ss_exact_roots */
  ss_exact_root *roots; /* nrt public roots in that order */
  ss_verdict cond;      /* the certified eigenvalue condition */
  int certified;        /* 1 if cond is proven */
  size_t nlead;         /* on a certified pass: distinct roots among lambda1..m */
  size_t lead[4];       /* ... their indices into rt, in order (each root's copies
                           all among lambda1..m: no tie with lambda_m+1) */
  /* the subdominant basis (ss_exact_basis.c) */
  ss_status bstatus;      /* SS_OK if lo, hi hold it */
  char bmsg[512];         /* the message when bstatus != SS_OK */
  double *lo, *hi;        /* n * m each, column-major, or NULL */
  long long *bnum, *bden; /* the exact basis when lambda1..m are rational and
                             it fits in int64, else NULL */
  arb_ptr qb;             /* A.ptr[n] balls of q at qb_prec bits (the basis
                             enclosure's cache: each entry converted once per
                             precision, not once per root and use), or NULL */
  long qb_prec;           /* their precision */
  size_t nev;             /* eigenvalues in ev (the blocks of size >= 2) */
  double *ev;             /* 2 nev: the diagonal blocks' eigenvalues in doubles
                             (re, im interleaved; LAPACK), seeds of the roots'
                             isolation only; NULL if none */
  size_t *evb;            /* nev: the block each is of (0: A, 1 + c: outer
                             component c) */
  long *evf;              /* nev: the factor each was given to, or -1 */
};

/* Largest denominator bound accepted (so that numerators fit in 64 bits with
 * room to spare). */
#define SS_EXACT_MAXDEN_LIMIT (1L << 31)

/* ss_exact_rational with the acceptance |s - p/q| <= reltol max(1, |s|)
 * (0 < reltol < 1) instead of 2^-40: the rational of denominator at most
 * maxden nearest to s, 1 with *p / *q in lowest terms (q > 0), else 0. */
int ss_exact_rational_within(double s, long maxden, double reltol, long long *p,
                             long long *q);

/* Reconstruct every entry of S (n x n, row-major) into x->A and x->q and
 * check the row sums (ss_exact_rational.c).  SS_ENUMERIC naming the entry or
 * row, SS_ENOMEM. */
ss_status ss_exact_reconstruct(ss_exact *x, const double *S, ss_error *err);

/* The factors of every diagonal block, merged (ss_exact_factor.c).
 * SS_ENOMEM. */
ss_status ss_exact_all_blocks(ss_exact *x, ss_error *err);

/* The rows (= columns) of block b of S: the one-ring, or outer component
 * b - 1 (ss_exact_factor.c).  Returns their number; idx has room for the
 * largest block. */
size_t ss_exact_block_rows(const ss_exact *x, size_t b, size_t *idx);

/* The root count, reflections, exact moduli, and first isolation
 * (ss_exact_factor.c).  SS_ENOMEM. */
ss_status ss_exact_roots_init(ss_exact *x, ss_error *err);

/* Classes, order and condition, refining the factors an open comparison
 * depends on until the condition is decided or nothing can be refined; then
 * the public roots (ss_exact_condition.c).  SS_ENOMEM, SS_EINTERNAL. */
ss_status ss_exact_decide(ss_exact *x, ss_error *err);

/* Set the condition: verdict v, certified or not, the reason from fmt. */
void ss_exact_set_verdict(ss_exact *x, ss_verdict_kind v, int certified, const char *fmt,
                          ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

/* Compute the basis on a certified pass (sets bstatus, bmsg, lo, hi, bnum,
 * bden).  Returns SS_ENOMEM or SS_OK; a basis that cannot be certified is not
 * a failure of this call (bstatus says so). */
ss_status ss_exact_basis_make(ss_exact *x, ss_error *err);

/* Isolate the roots of factor k at precision prec (sets z, mod, real), a
 * refinement from the balls it has when it was isolated before
 * (ss_exact_isolate.c).  Squarefree input only: the factors are
 * irreducible, or (lazy) squarefree by construction. */
void ss_exact_isolate(ss_exact *x, size_t k, long prec);

/* The d roots of the squarefree integer polynomial f (degree d >= 1) into
 * roots, with what arb_fmpz_poly_complex_roots(roots, f, 0, target_prec)
 * guarantees: isolating balls, each of relative accuracy >= target_prec
 * bits, the real ones with an exact zero imaginary part, sorted as
 * _acb_vec_sort_pretty sorts them, each complex root of positive imaginary
 * part followed by its conjugate.  Durand-Kerner starts from seeds (d balls,
 * e.g. the same roots at a lower precision, or the block's eigenvalues) at
 * twice target_prec; without seeds, when that attempt does not isolate, and
 * for factors of the form g(x^n) or with the root 0, it is
 * arb_fmpz_poly_complex_roots itself (ss_exact_isolate.c). */
void ss_exact_complex_roots(acb_ptr roots, const fmpz_poly_t f, acb_srcptr seeds,
                            slong target_prec);

/* Rump's enclosure of a simple real eigenpair of the real ball matrix A
 * (n x n, n >= 2) near lam (its midpoint used) and the approximate
 * eigenvector Xa (n x 1, its last row frozen), in real balls at prec
 * (ss_exact_rump.c): 1 with X (n x 1) enclosing the eigenvector whose last
 * entry is Xa's and lr the eigenvalue, when the inclusion is proven; else 0
 * (X, lr unspecified). */
int ss_exact_rump_real(arb_mat_t X, arb_t lr, const arb_mat_t A, const arb_t lam,
                       const arb_mat_t Xa, slong prec);

/* Rump's T = I - R M (ss_exact_rump.c), M = A - l I with its last column
 * replaced by -Xa (A n x n balls, l a ball, Xa n x 1), R given as n x n
 * doubles r (row-major, exact): computed in doubles by BLAS with a radius
 * bounding every rounding error and M's balls, so that T contains I - R M
 * for every M in them.  0, or -1 (memory, a value not finite). */
int ss_exact_rump_tmat(arb_mat_t T, const double *r, const arb_mat_t A, const arb_t l,
                       const arb_mat_t Xa, slong prec);

/* Each diagonal block's eigenvalues in doubles (LAPACK on its rationals
 * rounded) given to the factors of its characteristic polynomial, as seeds
 * of their first isolation (x->ev, x->evb, x->evf; ss_exact_isolate.c):
 * the one-ring block's and, since tet/oct's one-ring block is small (15 at
 * k = 14) and its degree-20+ factors are the outer blocks', the outer
 * components' too.  0, or -1 when out of memory; LAPACK failing is not a
 * failure (no seeds for that block). */
int ss_exact_eigen_seeds(ss_exact *x);

/* The first half of ss_exact_eigen_seeds, before the factoring: the blocks'
 * eigenvalues into x->ev, x->evb (also the candidates of the factors' linear
 * parts, ss_exact_factor_poly).  0, or -1 when out of memory. */
int ss_exact_eigen_values(ss_exact *x);

/* The principal submatrix of S on rows and columns idx[0..len) scaled to
 * integers: D = the lcm of its entries' denominators, M = D times it (M
 * initialised len x len by the caller).  Returns 0, or -1 when out of
 * memory. */
int ss_exact_principal(const ss_exact *x, const size_t *idx, size_t len, fmpz_t D,
                       fmpz_mat_t M);

/* As ss_exact_principal, each row scaled by its own denominator: d[r] = the lcm
 * of the denominators of row r's entries in the submatrix (d initialised to
 * len entries by the caller), N = diag(d) times it (initialised len x len).
 * Returns 0, or -1 when out of memory. */
int ss_exact_principal_rows(const ss_exact *x, const size_t *idx, size_t len, fmpz *d,
                            fmpz_mat_t N);

/* P = det(x diag(d) - N) = (prod d_r) det(x - B), B = diag(d)^-1 N the rational
 * matrix whose row r is N's over d[r] (N n x n, n >= 1, d > 0): B's
 * characteristic polynomial times prod d_r, an integer polynomial, computed
 * modulo primes above 2^62 with a bound from B's row sums and Frobenius norm
 * (ss_exact_charpoly.c).  FLINT aborts if out of memory. */
void ss_exact_charpoly(fmpz_poly_t P, const fmpz_mat_t N, const fmpz *d);

/* The factors of G (degree >= 1, integer coefficients, the polynomial of
 * scale times the one-ring block) into fac as ss_exact_opts.lazy asks
 * (ss_exact_squarefree.c): FLINT's irreducible factors of every squarefree
 * part, except the simple part (exponent 1) when it has degree >= 12 after
 * its linear factors are divided out (found from cand: ncand complex doubles,
 * re and im interleaved, the block's eigenvalues; a candidate is used only
 * when it is an exact root): that rest is kept whole.  Returns its index in
 * fac, or -1 when every factor is FLINT's.  FLINT aborts if out of memory. */
slong ss_exact_factor_lazy(fmpz_poly_factor_t fac, const fmpz_poly_t G,
                           const fmpz_t scale, const double *cand, size_t ncand);

/* The entry S[i][j] as a rational (0 where S has no entry). */
void ss_exact_get(const ss_exact *x, size_t i, size_t j, fmpq_t v);

#endif
