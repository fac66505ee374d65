/* test_scc.c — the sparsity of S = [A 0; B C] and the strongly connected
 * components of its outer block C (ss_scc), against a brute-force
 * reachability closure computed here.
 *
 * Properties, on seeded random sparse matrices (outer blocks of 1..60 nodes,
 * densities from a path-like 1.2 edges per node to dense, self-loops and
 * one-ring columns mixed in) and on hand-made graphs:
 *   - ss_scc_check_form accepts exactly the matrices with S[i][j] = 0 for
 *     i < n1 <= j, and 0 < n1 <= n;
 *   - ss_csr_make: the compressed rows give back S entry for entry, columns
 *     increase in a row, mid[r] splits them at n1;
 *   - ss_scc_make: two outer nodes share a component iff each reaches the
 *     other (Warshall's closure of C's graph, here); the order works for
 *     block forward substitution: every edge i -> j of C has
 *     cid[j] <= cid[i]; comp, start, cid, pos are mutually consistent,
 *     every node in exactly one component; largest is the largest size;
 *   - relabelling the outer nodes (a permutation similarity of C) gives the
 *     same partition, relabelled, and the same number of components;
 *   - closed forms: a directed cycle of m nodes is one component of size m;
 *     a path is m components of one node, the sink first; a diagonal C is
 *     nc components.
 * Mutations this catches (tried by hand: the report of issue 33):
 *   - Tarjan's low-link taken over a cross edge to a node no longer on the
 *     stack (`on[w] &&` dropped): merges components that do not reach each
 *     other back -> "shared component without mutual reach";
 *   - the components numbered backwards in cid (n - 1 - c): cid no longer
 *     agrees with comp and start;
 *   - mid[] set one column early (j + 1 >= n1): the compressed-rows check. */
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include "ss_scc.h"
#include "ss_test.h"

/* Reachability closure of the n x n adjacency (row-major, 0/1) in place
 * (Warshall), reflexive. */
static void closure(unsigned char *R, size_t n) {
  for (size_t i = 0; i < n; i++)
    R[i * n + i] = 1;
  for (size_t k = 0; k < n; k++)
    for (size_t i = 0; i < n; i++)
      if (R[i * n + k])
        for (size_t j = 0; j < n; j++)
          R[i * n + j] |= R[k * n + j];
}

/* Check ss_csr_make and ss_scc_make on S (n x n, leading n1 x n1 invariant)
 * against the closure.  Returns the number of components (-1 on failure). */
static long check_matrix(const double *S, size_t n, size_t n1, const char *what) {
  const size_t nc = n - n1;
  ss_error err = {0};
  CHECK(ss_scc_check_form(S, n, n1, &err) == SS_OK, "%s: form refused: %s", what,
        err.msg);
  ss_csr A = {NULL, NULL, NULL, NULL};
  ss_scc K = {0, NULL, NULL, NULL, NULL, 0};
  long ncomp = -1;
  unsigned char *R = calloc(nc * nc + 1, 1);
  size_t *count = calloc(nc + 1, sizeof *count);
  if (!R || !count || ss_csr_make(S, n, n1, &A) || ss_scc_make(&A, n, n1, &K)) {
    CHECK(0, "%s: out of memory", what);
    goto done;
  }
  /* the compressed rows hold S, in order, split at n1 */
  int csr_ok = 1;
  for (size_t i = 0; i < n && csr_ok; i++) {
    size_t nz = 0;
    for (size_t j = 0; j < n; j++)
      nz += S[i * n + j] != 0.0;
    csr_ok &=
        A.ptr[i + 1] - A.ptr[i] == nz && A.ptr[i] <= A.mid[i] && A.mid[i] <= A.ptr[i + 1];
    for (size_t q = A.ptr[i]; q < A.ptr[i + 1] && csr_ok; q++) {
      csr_ok &= S[i * n + A.col[q]] == A.val[q];
      csr_ok &= q == A.ptr[i] || A.col[q - 1] < A.col[q];
      csr_ok &= (q < A.mid[i]) == (A.col[q] < n1);
    }
  }
  CHECK(csr_ok, "%s: compressed rows do not give back S", what);
  /* components against the closure of C's graph */
  for (size_t i = 0; i < nc; i++)
    for (size_t j = 0; j < nc; j++)
      R[i * nc + j] = S[(n1 + i) * n + n1 + j] != 0.0;
  closure(R, nc);
  ncomp = K.n;
  int consistent = K.start[0] == 0 && K.start[K.n] == nc;
  size_t largest = 0;
  for (long c = 0; c < K.n && consistent; c++) {
    const size_t b = K.start[c], sz = K.start[c + 1] - b;
    consistent &= sz > 0;
    largest = sz > largest ? sz : largest;
    for (size_t q = 0; q < sz && consistent; q++) {
      const size_t v = K.comp[b + q];
      consistent &= v < nc && K.cid[v] == (size_t)c && K.pos[v] == q;
      if (v < nc) count[v]++;
    }
  }
  for (size_t v = 0; v < nc && consistent; v++)
    consistent &= count[v] == 1;
  CHECK(consistent, "%s: comp/start/cid/pos inconsistent", what);
  CHECK(K.largest == largest, "%s: largest %zu, components say %zu", what, K.largest,
        largest);
  if (!consistent) goto done;
  size_t wrong_part = 0, wrong_order = 0, classes = 0;
  for (size_t i = 0; i < nc; i++) {
    int first = 1; /* i is the first node of its reach class */
    for (size_t j = 0; j < nc; j++) {
      const int mutual = R[i * nc + j] && R[j * nc + i];
      wrong_part += mutual != (K.cid[i] == K.cid[j]);
      if (j < i && mutual) first = 0;
      if (S[(n1 + i) * n + n1 + j] != 0.0) wrong_order += K.cid[j] > K.cid[i];
    }
    classes += (size_t)first;
  }
  CHECK(wrong_part == 0,
        "%s: %zu node pairs: shared component without mutual reach, "
        "or mutual reach in different components",
        what, wrong_part);
  CHECK(wrong_order == 0, "%s: %zu edges of C read a later component", what, wrong_order);
  CHECK((size_t)K.n == classes, "%s: %ld components, closure has %zu", what, K.n,
        classes);
done:
  ss_scc_free(&K);
  ss_csr_free(&A);
  free(R);
  free(count);
  return ncomp;
}

/* A random S with n1 one-ring rows (A dense lower triangular, invariant) and
 * an outer block of density p per entry (at least a sparse ring of edges to
 * make long cycles likely), B dense-ish. */
static double *random_matrix(gsl_rng *r, size_t n, size_t n1, double p) {
  double *S = calloc(n * n, sizeof *S);
  for (size_t i = 0; i < n1; i++)
    for (size_t j = 0; j <= i; j++)
      S[i * n + j] = gsl_rng_uniform_pos(r);
  for (size_t i = n1; i < n; i++)
    for (size_t j = 0; j < n; j++) {
      const double q = j < n1 ? 0.5 : p;
      if (gsl_rng_uniform(r) < q) S[i * n + j] = 1.0 + gsl_rng_uniform(r);
    }
  return S;
}

/* Permutation similarity of the outer block: node i becomes node perm[i]. */
static double *relabel(const double *S, size_t n, size_t n1, const size_t *perm) {
  double *T = calloc(n * n, sizeof *T);
  for (size_t i = 0; i < n; i++)
    for (size_t j = 0; j < n; j++) {
      const size_t a = i < n1 ? i : n1 + perm[i - n1], b = j < n1 ? j : n1 + perm[j - n1];
      T[a * n + b] = S[i * n + j];
    }
  return T;
}

static void test_random(void) {
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, 33);
  const double dens[5] = {0.0, 0.02, 0.05, 0.12, 0.5};
  for (int t = 0; t < 60; t++) {
    const size_t n1 = 1 + gsl_rng_uniform_int(r, 6), nc = 1 + gsl_rng_uniform_int(r, 60);
    const size_t n = n1 + nc;
    const double p = dens[t % 5] + (t % 5 ? 0.0 : 1.2 / (double)nc);
    double *S = random_matrix(r, n, n1, p);
    char what[64];
    snprintf(what, sizeof what, "random %d (n1 %zu, nc %zu, p %.3f)", t, n1, nc, p);
    const long k = check_matrix(S, n, n1, what);
    /* relabelled: the same number of components (the partition itself is
     * checked against the closure of the relabelled graph) */
    size_t *perm = malloc(nc * sizeof *perm);
    for (size_t i = 0; i < nc; i++)
      perm[i] = i;
    gsl_ran_shuffle(r, perm, nc, sizeof *perm);
    double *T = relabel(S, n, n1, perm);
    strcat(what, " relabelled");
    CHECK(check_matrix(T, n, n1, what) == k, "%s: component count changed", what);
    free(perm);
    free(T);
    free(S);
  }
  gsl_rng_free(r);
}

static void test_closed_forms(void) {
  enum { N1 = 2, M = 9, N = N1 + M };
  double S[N * N];
  ss_csr A = {NULL, NULL, NULL, NULL};
  ss_scc K = {0, NULL, NULL, NULL, NULL, 0};
  /* a directed cycle through the outer nodes (and self-loops, which are no
   * edges of the component graph): one component of M */
  memset(S, 0, sizeof S);
  S[0] = S[N + 1] = 1.0;
  for (int i = 0; i < M; i++) {
    S[(N1 + i) * N + N1 + (i + 1) % M] = 0.5;
    S[(N1 + i) * N + N1 + i] = 0.25;
    S[(N1 + i) * N + i % N1] = 0.25;
  }
  CHECK(check_matrix(S, N, N1, "cycle") == 1, "a cycle is one component");
  if (!ss_csr_make(S, N, N1, &A) && !ss_scc_make(&A, N, N1, &K))
    CHECK(K.n == 1 && K.largest == M, "cycle: %ld components, largest %zu", K.n,
          K.largest);
  ss_scc_free(&K);
  ss_csr_free(&A);
  /* a path i -> i + 1: M components of one node; node M - 1 (the sink)
   * reads nothing, so it comes first */
  memset(S, 0, sizeof S);
  S[0] = S[N + 1] = 1.0;
  for (int i = 0; i + 1 < M; i++)
    S[(N1 + i) * N + N1 + i + 1] = 1.0;
  CHECK(check_matrix(S, N, N1, "path") == M, "a path is M components");
  if (!ss_csr_make(S, N, N1, &A) && !ss_scc_make(&A, N, N1, &K)) {
    CHECK(K.largest == 1 && K.comp[0] == M - 1, "path: largest %zu, first node %zu",
          K.largest, K.comp[0]);
    for (int i = 0; i < M; i++)
      CHECK(K.cid[i] == (size_t)(M - 1 - i), "path: node %d in component %zu", i,
            K.cid[i]);
  }
  ss_scc_free(&K);
  ss_csr_free(&A);
  /* diagonal C: each node alone */
  memset(S, 0, sizeof S);
  for (int i = 0; i < N; i++)
    S[i * N + i] = 1.0 / (i + 1);
  CHECK(check_matrix(S, N, N1, "diagonal") == M, "a diagonal C is M components");
  /* no outer block at all (n1 = n) */
  CHECK(check_matrix(S, N, N, "no outer block") == 0, "n1 = n: no components");
}

static void test_form(void) {
  enum { N = 4 };
  double S[N * N] = {0};
  for (int i = 0; i < N; i++)
    S[i * N + i] = 1.0;
  ss_error err = {0};
  CHECK(ss_scc_check_form(S, N, 2, &err) == SS_OK, "diagonal refused");
  S[1 * N + 3] = 0.5; /* the one-ring row 1 reads outer column 3 */
  err.msg[0] = '\0';
  CHECK(ss_scc_check_form(S, N, 2, &err) == SS_EINPUT && strstr(err.msg, "S[1][3]"),
        "a one-ring row reading outside: %s", err.msg);
  CHECK(ss_scc_check_form(S, N, 4, &err) == SS_OK, "n1 = n has no outer columns");
  CHECK(ss_scc_check_form(S, N, 0, &err) == SS_EINPUT, "n1 = 0 accepted");
  CHECK(ss_scc_check_form(S, N, 5, &err) == SS_EINPUT, "n1 > n accepted");
  CHECK(ss_scc_check_form(NULL, N, 2, &err) == SS_EINPUT, "NULL accepted");
  S[3 * N + 1] = 0.5; /* an outer row reading the one-ring: allowed (B) */
  S[1 * N + 3] = 0.0;
  CHECK(ss_scc_check_form(S, N, 2, &err) == SS_OK, "B refused");
}

int main(void) {
  test_form();
  test_closed_forms();
  test_random();
  return ss_test_done("scc");
}
