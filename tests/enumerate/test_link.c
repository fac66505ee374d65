/* test_link.c — links: text form and validation, canonical forms (invariant
 * under relabelling, rotation of the lists and reflection; distinct for
 * distinct links), automorphism group orders of the named links, and the
 * generator: the published counts for k <= 12, every link valid and distinct,
 * parts disjoint and complete. */
#include <stdlib.h>
#include <string.h>

#include "ss_enum.h"
#include "ss_link.h"
#include "ss_test.h"
#include "ss_testlink.h"

/* ---- collecting canonical forms from the generator ---- */

typedef struct {
  char **s;
  size_t n, cap;
  long invalid;
} strset;

static int collect(const ss_link *l, void *ctx) {
  strset *set = ctx;
  ss_error err = {0};
  ss_link *c = NULL;
  char *text = NULL;
  if (ss_link_validate(l, &err)) set->invalid++;
  if (ss_link_canonical(l, &c, NULL, &err) || ss_link_format(c, &text, &err)) return 1;
  ss_link_free(c);
  if (set->n == set->cap) {
    set->cap = set->cap ? 2 * set->cap : 1024;
    set->s = realloc(set->s, set->cap * sizeof *set->s);
  }
  set->s[set->n++] = text;
  return 0;
}

static int cmp_str(const void *a, const void *b) {
  return strcmp(*(char *const *)a, *(char *const *)b);
}

static size_t distinct(strset *set) {
  qsort(set->s, set->n, sizeof *set->s, cmp_str);
  size_t d = set->n ? 1 : 0;
  for (size_t i = 1; i < set->n; i++)
    d += strcmp(set->s[i], set->s[i - 1]) != 0;
  return d;
}

static void strset_free(strset *set) {
  for (size_t i = 0; i < set->n; i++)
    free(set->s[i]);
  free(set->s);
  memset(set, 0, sizeof *set);
}

static const uint64_t known[] = {0, 0, 0, 0, 1, 1, 2, 5, 14, 50, 233, 1249, 7595};

static void test_counts(void) {
  ss_error err = {0};
  uint64_t c[SS_ENUM_MAXK + 1];
  ss_enum_opts o = {4, 12, 0, 1};
  REQUIRE_OK_VOID(ss_enum_links(&o, NULL, NULL, c, &err), &err);
  for (int k = 4; k <= 12; k++)
    CHECK(c[k] == known[k], "k = %d: %llu links, expected %llu", k,
          (unsigned long long)c[k], (unsigned long long)known[k]);
  /* every link valid, and no two isomorphic (canonical forms distinct) */
  for (int k = 4; k <= 10; k++) {
    strset set = {0};
    ss_enum_opts ok = {k, k, 0, 1};
    REQUIRE_OK_VOID(ss_enum_links(&ok, collect, &set, c, &err), &err);
    CHECK(set.invalid == 0, "k = %d: %ld invalid links", k, set.invalid);
    CHECK(set.n == known[k] && distinct(&set) == known[k], "k = %d: %zu distinct of %zu",
          k, distinct(&set), set.n);
    strset_free(&set);
  }
}

static void test_parts(void) {
  ss_error err = {0};
  const int ks[] = {9, 11, 12}, ns[] = {4, 7, 3};
  for (int t = 0; t < 3; t++) {
    int k = ks[t], N = ns[t];
    strset all = {0};
    uint64_t sizes[8], c[SS_ENUM_MAXK + 1];
    for (int i = 0; i < N; i++) {
      ss_enum_opts o = {k, k, i, N};
      size_t before = all.n;
      REQUIRE_OK_VOID(ss_enum_links(&o, collect, &all, c, &err), &err);
      sizes[i] = all.n - before;
    }
    /* disjoint and complete: N parts give each link exactly once */
    CHECK(all.n == known[k] && distinct(&all) == known[k],
          "k = %d in %d parts: %zu links, %zu distinct, expected %llu", k, N, all.n,
          distinct(&all), (unsigned long long)known[k]);
    if (k >= 11)
      for (int i = 0; i < N; i++)
        CHECK(sizes[i] > known[k] / (2 * (uint64_t)N),
              "k = %d part %d/%d has %llu links: far below 1/N", k, i, N,
              (unsigned long long)sizes[i]);
    strset_free(&all);
  }
  ss_enum_opts bad = {4, 8, 3, 3};
  uint64_t c[SS_ENUM_MAXK + 1];
  CHECK(ss_enum_links(&bad, NULL, NULL, c, &err) == SS_EINPUT, "part 3/3 refused");
  ss_enum_opts bad2 = {3, 8, 0, 1};
  CHECK(ss_enum_links(&bad2, NULL, NULL, c, &err) == SS_EINPUT, "k = 3 refused");
}

/* Canonical forms of scrambled and mirrored copies equal the original's. */
static int check_invariance(const ss_link *l, void *ctx) {
  long *bad = ctx;
  ss_link *c0 = NULL;
  if (ss_link_canonical(l, &c0, NULL, NULL)) return 1;
  for (unsigned s = 1; s <= 3; s++) {
    ss_link *m = ss_testlink_scrambled(l, s * 7919u + (unsigned)l->k, (int)(s & 1));
    ss_link *c1 = NULL;
    if (!m || ss_link_canonical(m, &c1, NULL, NULL) || !ss_link_equal(c0, c1)) (*bad)++;
    /* the canonical form of a canonical form is itself */
    ss_link *c2 = NULL;
    if (c1 && (ss_link_canonical(c1, &c2, NULL, NULL) || !ss_link_equal(c1, c2)))
      (*bad)++;
    ss_link_free(m), ss_link_free(c1), ss_link_free(c2);
  }
  ss_link_free(c0);
  return 0;
}

static void test_canonical(void) {
  ss_error err = {0};
  long bad = 0;
  uint64_t c[SS_ENUM_MAXK + 1];
  ss_enum_opts o = {4, 10, 0, 1};
  REQUIRE_OK_VOID(ss_enum_links(&o, check_invariance, &bad, c, &err), &err);
  CHECK(bad == 0, "%ld relabelled or mirrored links canonicalize differently", bad);

  /* perm maps the link onto its canonical form */
  ss_link *l = NULL, *cl = NULL;
  REQUIRE_OK_VOID(ss_link_named("bipyramid:7", &l, &err), &err);
  int perm[9];
  REQUIRE_OK_VOID(ss_link_canonical(l, &cl, perm, &err), &err);
  int ok = 1;
  for (int v = 0; v < l->k; v++)
    for (int i = l->off[v]; i < l->off[v + 1]; i++) {
      int w = l->nbr[i], pv = perm[v], pw = perm[w], found = 0;
      for (int j = cl->off[pv]; j < cl->off[pv + 1]; j++)
        found |= cl->nbr[j] == pw;
      ok &= found;
    }
  CHECK(ok, "perm is an isomorphism onto the canonical form");
  /* a chiral pair: mirror images are identified */
  ss_link *m = ss_testlink_scrambled(l, 5, 1);
  CHECK(m && ss_link_isomorphic(l, m) == 1, "mirror image isomorphic");
  ss_link *o8 = NULL;
  REQUIRE_OK_VOID(ss_link_named("bipyramid:6", &o8, &err), &err);
  CHECK(ss_link_isomorphic(l, o8) == 0, "bipyramids 7 and 6 differ");
  ss_link_free(m), ss_link_free(o8), ss_link_free(l), ss_link_free(cl);
}

/* |Aut| with reflections: the full symmetry groups of the solids. */
static void test_automorphisms(void) {
  const struct {
    const char *name;
    int order;
  } t[] = {{"tetrahedron", 24}, {"octahedron", 48},  {"icosahedron", 120},
           {"bipyramid:3", 12}, {"bipyramid:4", 48}, {"bipyramid:5", 20},
           {"bipyramid:9", 36}};
  for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
    ss_error err = {0};
    ss_link *l = NULL;
    int *aut = NULL, n = 0;
    REQUIRE_OK_VOID(ss_link_named(t[i].name, &l, &err), &err);
    REQUIRE_OK_VOID(ss_link_automorphisms(l, &aut, &n, &err), &err);
    CHECK(n == t[i].order, "%s: %d automorphisms, expected %d", t[i].name, n, t[i].order);
    /* each is an automorphism: adjacency preserved; the first is the identity */
    int ok = 1;
    for (int j = 0; j < n; j++)
      for (int v = 0; v < l->k; v++)
        for (int e = l->off[v]; e < l->off[v + 1]; e++) {
          int a = aut[j * l->k + v], b = aut[j * l->k + l->nbr[e]], f = 0;
          for (int q = l->off[a]; q < l->off[a + 1]; q++)
            f |= l->nbr[q] == b;
          ok &= f;
        }
    for (int v = 0; v < l->k; v++)
      ok &= aut[v] == v;
    CHECK(ok, "%s: maps preserve adjacency, identity first", t[i].name);
    free(aut);
    ss_link_free(l);
  }
}

static void test_text(void) {
  ss_error err = {0};
  ss_link *l = NULL;
  REQUIRE_OK_VOID(ss_link_parse("4 bcd,adc,abd,acb", &l, &err), &err);
  char *s = NULL;
  REQUIRE_OK_VOID(ss_link_format(l, &s, &err), &err);
  CHECK(!strcmp(s, "4 bcd,adc,abd,acb"), "round trip: %s", s);
  free(s);
  ss_link_free(l);
  /* numeric form for large links, and its round trip */
  REQUIRE_OK_VOID(ss_link_named("bipyramid:60", &l, &err), &err);
  REQUIRE_OK_VOID(ss_link_format(l, &s, &err), &err);
  ss_link *back = NULL;
  REQUIRE_OK_VOID(ss_link_parse(s, &back, &err), &err);
  CHECK(ss_link_equal(l, back), "numeric round trip");
  free(s);
  ss_link_free(l), ss_link_free(back);

  /* a 3x3 triangulated torus: consistent rotations, wrong Euler characteristic */
  char torus[200];
  int n = snprintf(torus, sizeof torus, "9 ");
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      static const int d[6][2] = {{1, 0}, {0, 1}, {-1, 1}, {-1, 0}, {0, -1}, {1, -1}};
      if (i || j) torus[n++] = ',';
      for (int q = 0; q < 6; q++)
        torus[n++] = (char)('a' + ((i + d[q][0] + 3) % 3) * 3 + (j + d[q][1] + 3) % 3);
    }
  torus[n] = '\0';
  const struct {
    const char *text, *words;
  } bad[] = {
      {"5 bcd,adc,abd,acb", "vertex count is 5 but there are 4 neighbour lists"},
      {"4 bcd,adc,abd", "vertex count is 4 but there are 3 neighbour lists"},
      {"4 bcd,adc,abd,acb,abc", "more than 4 neighbour lists"},
      {"4 bcd,acd,abd,acb", "rotations do not form triangles"},
      {"4 bce,adc,abd,acb", "'e' is not a vertex of a 4-vertex link"},
      {"4 bbd,adc,abd,acb", "multi-edge"},
      {"4 acd,adc,abd,acb", "lists itself"},
      {"5 bcd,acd,abd,abc,ab", "degree 2"},
      {"5 bcde,adc,abd,acb,bcd", "not symmetric: 1 lists 5 but 5 does not list 1"},
      {torus, "not a sphere: V - E + F = 9 - 27 + 18 = 0"},
      {"3 bc,ac,ab", "vertex count 3 is not in 4.."},
      {"x", "unknown link 'x'"},
      {"bipyramid:2", "N = 3.."},
      {"4bcd", "expected a space"},
      {"", "expected a vertex count"},
  };
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
    ss_error e = {0};
    ss_link *x = NULL;
    ss_status st = ss_link_parse(bad[i].text, &x, &e);
    CHECK(st == SS_EINPUT && x == NULL && strstr(e.msg, bad[i].words),
          "'%s': status %d, message '%s', expected '%s'", bad[i].text, (int)st, e.msg,
          bad[i].words);
    ss_link_free(x);
  }
}

static void test_from_triangles(void) {
  ss_error err = {0};
  /* octahedron faces with arbitrary orientations: oriented and accepted */
  int t[] = {0, 1, 2, 0, 4, 2, 0, 4, 5, 0, 5, 1, 3, 2, 1, 3, 2, 4, 3, 5, 4, 3, 1, 5};
  ss_link *l = NULL, *o = NULL;
  REQUIRE_OK_VOID(ss_link_from_triangles(6, 8, t, &l, &err), &err);
  REQUIRE_OK_VOID(ss_link_named("octahedron", &o, &err), &err);
  CHECK(ss_link_isomorphic(l, o) == 1, "octahedron from unoriented triangles");
  int *tri = NULL, nt = 0;
  REQUIRE_OK_VOID(ss_link_triangles(l, &tri, &nt, &err), &err);
  ss_link *back = NULL;
  CHECK(nt == 8, "8 triangles");
  REQUIRE_OK_VOID(ss_link_from_triangles(6, nt, tri, &back, &err), &err);
  CHECK(ss_link_isomorphic(l, back) == 1, "triangles round trip");
  free(tri);
  ss_link_free(l), ss_link_free(o), ss_link_free(back);
  /* an edge in three triangles */
  const int t3[] = {0, 1, 2, 0, 1, 3, 0, 1, 4, 2, 3, 4, 1, 2, 3, 0, 2, 4};
  CHECK(ss_link_from_triangles(5, 6, t3, &l, &err) == SS_EINPUT &&
            strstr(err.msg, "edge 1-2 is in 3 triangles"),
        "non-manifold edge refused: %s", err.msg);
}

/* Messages quote the input escaped (binary garbage was echoed raw to the
 * terminal), and a pole of degree 10^5 is validated (bipyramid:99998 took
 * seconds in a quadratic neighbour search; the fuzzers time parses out). */
static void test_escaped(void) {
  ss_link *l = NULL;
  ss_error err = {0};
  CHECK(ss_link_parse("ab\x01"
                      "c\xff\x1b[31m d",
                      &l, &err) == SS_EINPUT &&
            !l,
        "garbage accepted");
  CHECK(strstr(err.msg, "ab\\x01c\\xff\\x1b[31m") != NULL, "message: %s", err.msg);
  for (const char *p = err.msg; *p; p++)
    CHECK((unsigned char)*p >= 0x20 && (unsigned char)*p < 0x7f, "raw byte 0x%02x in: %s",
          (unsigned char)*p, err.msg);
  char buf[8];
  CHECK(!strcmp(ss_error_escape(buf, sizeof buf, "abc\x01\x02"), "abc\\x01"),
        "an escape is never cut: \"%s\"", buf);
  CHECK(!strcmp(ss_error_escape(buf, sizeof buf, "a\tb\n"), "a\\tb\\n"), "\"%s\"", buf);
  REQUIRE_OK_VOID(ss_link_named("bipyramid:99998", &l, &err), &err);
  CHECK(l->k == 100000, "bipyramid:99998 has %d vertices", l->k);
  ss_link_free(l);
  /* an asymmetric or non-triangular rotation is still named as before */
  CHECK(ss_link_parse("4 bcd,acd,abd,abc", &l, &err) == SS_EINPUT &&
            strstr(err.msg, "do not form triangles"),
        "%s", err.msg);
  CHECK(ss_link_parse("5 bcd,acd,abd,abc,abc", &l, &err) == SS_EINPUT &&
            strstr(err.msg, "not symmetric"),
        "%s", err.msg);
}

int main(void) {
  test_escaped();
  test_text();
  test_from_triangles();
  test_automorphisms();
  test_canonical();
  test_counts();
  test_parts();
  return ss_test_done("link");
}
