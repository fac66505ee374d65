/* ss_canon.h — private: canonical codes of rotation systems, shared by the
 * public link functions (ss_link_canon.c) and the generator (ss_enum.c).
 *
 * A start is a half-edge x -> w and a turning direction.  From it, vertices
 * are numbered in breadth-first order, each vertex's neighbours visited
 * around it in that direction starting from the edge by which it was reached
 * (x itself: from w).  The code lists, vertex by vertex in that numbering, the
 * numbers of its neighbours in visiting order, each list closed by k.  Two
 * rotation systems are isomorphic, orientation-preservingly or by a
 * reflection, iff their least codes over all starts and both directions are
 * equal; the starts that reach the least code are in bijection with the
 * automorphisms.  Restricting the starts to an isomorphism-invariant set of
 * half-edges keeps the least code an invariant and is cheaper. */
#ifndef SS_CANON_H
#define SS_CANON_H

typedef struct {
  int k;          /* vertices */
  const int *off; /* off[v]: first half-edge of v (lists may have gaps) */
  const int *deg; /* deg[v] */
  const int *nbr; /* nbr[off[v] + i]: i-th neighbour of v in cyclic order */
  const int *inv; /* inv[h]: the reverse half-edge of h, or NULL: found by
                     searching the neighbour's list when a vertex is reached
                     (cheaper when most starts are abandoned early) */
} ss_cgraph;

typedef struct {
  int maxcode;     /* capacity of code/best: >= 2E + k */
  int maxk;        /* capacity of the per-vertex arrays */
  int maxbest;     /* capacity of `labels`, in labellings */
  int *code;       /* the code being built */
  int *best;       /* the least code so far; its length is ncode */
  int ncode;       /* length of best */
  int *label;      /* label[v] during a run */
  int *order;      /* order[i] = vertex numbered i during a run */
  int *entry;      /* entry[v]: list position v was reached from */
  int *best_order; /* order of the first start reaching the least code */
  int *labels;     /* nbest labellings (k ints each) reaching the least code */
  int nbest;       /* starts reaching the least code (= |Aut| with all starts) */
} ss_canon_ws;

/* Workspace for graphs of at most maxk vertices and maxcode code entries,
 * recording up to maxbest least labellings.  NULL on allocation failure. */
ss_canon_ws *ss_canon_ws_new(int maxk, int maxcode, int maxbest);
void ss_canon_ws_free(ss_canon_ws *w);

/* Fill inv (size: the half-edge index range) for g's lists. */
void ss_canon_inverse(int k, const int *off, const int *deg, const int *nbr, int *inv);

/* Least code over the starts: starts[3 j] = vertex, starts[3 j + 1] = position
 * in its list, starts[3 j + 2] = turning direction (+1: along the list, -1:
 * against it).  The least code and the set of starts reaching it do not depend
 * on the order of the starts; the work does (a start is abandoned at its first
 * entry above the least code so far), so callers put likely winners first.
 * best_order and labels[0] belong to the first start reaching the least code.
 * Returns 0, or 1 as soon as a start from index nfirst on gives a code below
 * the least of the first nfirst (then w holds nothing useful): a caller that
 * needs the least code to be reached from its first starts stops there
 * (nfirst = nstarts: never). */
int ss_canon_run(const ss_cgraph *g, const int *starts, int nstarts, int nfirst,
                 ss_canon_ws *w);

#endif
