/* fuzz_mutate.c — seeded text mutations for the fuzzers.  See fuzz_mutate.h. */
#include "fuzz_mutate.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

const char *const fz_link_seeds[] = {
    "4 bcd,adc,abd,acb", "5 bcd,ace,aed,abec,bdc", "6 bcde,aefc,abfd,acfe,adfb,bedc",
    "6 2 3 4 5,1 5 6 3,1 2 6 4,1 3 6 5,1 4 6 2,2 5 4 3",
    "7 bcdef,afgc,abgd,acge,adgf,aegb,bfedc", "7 bcdefg,agc,abgd,acgfe,adf,aedg,afdcb",
    "7 bgecdf,afdceg,aebd,acbf,agbc,adb,abe",
    "8 bcdefgh,ahc,abhd,ache,adhf,aehg,afh,agfedcb", "  4   bcd , adc,abd,acb  \n",
    "tetrahedron", "octahedron", "icosahedron", "bipyramid:3", "bipyramid:5",
    "bipyramid:7",
    /* invalid on purpose: mutations of near misses reach the validator */
    "4 bcd,acd,abd,acb", "5 bcde,adc,abd,acb,bcd", "4 bbd,adc,abd,acb", NULL};

const char *fz_kind_name(fz_kind k) {
  static const char *const names[FZ_NKINDS] = {"link", "mesh", "stencil"};
  return k < FZ_NKINDS ? names[k] : "?";
}

static int reserve(fz_buf *b, size_t n) {
  if (n + 1 <= b->cap) return 0;
  size_t cap = b->cap ? b->cap : 64;
  while (cap < n + 1)
    cap *= 2;
  char *p = realloc(b->data, cap);
  if (!p) return -1;
  b->data = p;
  b->cap = cap;
  return 0;
}

int fz_buf_set(fz_buf *b, const char *p, size_t n) {
  if (reserve(b, n)) return -1;
  memmove(b->data, p, n);
  b->len = n;
  b->data[n] = '\0';
  return 0;
}

void fz_buf_free(fz_buf *b) {
  free(b->data);
  b->data = NULL;
  b->len = b->cap = 0;
}

/* Replace bytes [at, at + del) by n bytes at p. */
static int splice(fz_buf *b, size_t at, size_t del, const char *p, size_t n) {
  if (at > b->len) at = b->len;
  if (del > b->len - at) del = b->len - at;
  if (b->len - del + n > FZ_MAXLEN) return 0; /* too long: leave it */
  if (reserve(b, b->len - del + n)) return -1;
  memmove(b->data + at + n, b->data + at + del, b->len - at - del);
  memcpy(b->data + at, p, n);
  b->len = b->len - del + n;
  b->data[b->len] = '\0';
  return 0;
}

static uint64_t splitmix64(uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

void fz_rng_for(gsl_rng *r, unsigned long seed, unsigned long iter) {
  uint64_t h = splitmix64(splitmix64((uint64_t)seed) ^ (uint64_t)iter);
  gsl_rng_set(r, (unsigned long)(h & 0xffffffffu));
}

static size_t pick(gsl_rng *r, size_t n) {
  return n ? (size_t)gsl_rng_uniform_int(r, (unsigned long)n) : 0;
}

/* Numbers that break readers: extremes, signed zeros, non-finite values,
 * integers just past every width, and things that only look like numbers. */
static const char *const extremes[] = {
    "1e308",
    "1.7e308",
    "-1.7e308",
    "1.8e308",
    "1e-308",
    "4.9e-324",
    "-0",
    "-0.0",
    "0",
    "-1",
    "1",
    "nan",
    "-nan",
    "inf",
    "-inf",
    "infinity",
    "2147483647",
    "2147483648",
    "-2147483649",
    "4294967295",
    "4294967296",
    "9223372036854775807",
    "9223372036854775808",
    "-9223372036854775809",
    "18446744073709551616",
    "99999999999999999999999999",
    "100000",
    "99998",
    "0x10",
    "1e",
    "1..2",
    "1/0",
    "0/0",
    "-1/3",
    "12345678901234567/3",
    "123456789012345678/1",
    "",
};
#define NEXTREMES (sizeof extremes / sizeof extremes[0])

/* Bytes worth inserting: separators of every format, digits, letters at the
 * ends of the plantri alphabet, control and non-ASCII bytes. */
static const char special[] = " ,\n\r\t#/[]=;:-+.e0123456789azAZ\x01\x1b\x7f\x80\xc3\xff";

/* Tokens of each kind's grammar. */
static const char *const dict_link[] = {
    ",", ",,", " ", "\n", "bipyramid:", "tetrahedron", "octahedron", "icosahedron",
    "a", "z",  "Z", "52", "53",         "0",           "\xc3\xa9",   "\x1b[31m",
};
static const char *const dict_mesh[] = {
    "\nVertices\n",
    "\nTetrahedra\n",
    "\nHexahedra\n",
    "\nOctahedra\n",
    "\nTriangles\n",
    "\nQuadrilaterals\n",
    "\nEdges\n",
    "\nCorners\n",
    "\nEnd\n",
    "\nDimension 2\n",
    "\nDimension 4\n",
    "\nDimension 3\n",
    "\nNormals\n1\n",
    "\nPrisms\n",
    "\nMeshVersionFormatted 9\n",
    "\nv 0 0 0\n",
    "\nf 1 2 3\n",
    "\nf -1 -2 -3\n",
    "\nl 1 2\n",
    "\np 1\n",
    "\nf 1/1/1 2//2 3/3\n",
    "\ncurv 0 1 1 2\n",
    " # ",
    "\x1b[31m",
};
static const char *const dict_stencil[] = {
    "\n[scheme]\n",
    "\n[mask.tet]\n",
    "\n[mask.oct]\n",
    "\n[mask.hex]\n",
    "\n[mask.quad]\n",
    "\n[mask.segment]\n",
    "\n[mask.triangle]\n",
    "\n[mask.x]\n",
    "\nname = x\n",
    "\nfamily = averaging\n",
    "\nsplit = multilinear\n",
    "\nsplit = tetoct\n",
    "\nself = 1\n",
    "\nedge = 0\n",
    "\nopposite = 1/2\n",
    "\nface = -1/8\n",
    "\nother = 1/2\n",
    " ; ",
    "[",
    "]",
    "=",
    "\x1b[31m",
};

static const char *dict_word(gsl_rng *r, fz_kind kind) {
  switch (kind) {
  case FZ_LINK:
    return dict_link[pick(r, sizeof dict_link / sizeof dict_link[0])];
  case FZ_MESH:
    return dict_mesh[pick(r, sizeof dict_mesh / sizeof dict_mesh[0])];
  default:
    return dict_stencil[pick(r, sizeof dict_stencil / sizeof dict_stencil[0])];
  }
}

/* Lines: start offsets of every line of b (at most cap), their count. */
static size_t line_starts(const fz_buf *b, size_t *start, size_t cap) {
  size_t n = 0;
  if (cap == 0) return 0;
  start[n++] = 0;
  for (size_t i = 0; i < b->len && n < cap; i++)
    if (b->data[i] == '\n' && i + 1 < b->len) start[n++] = i + 1;
  return n;
}

/* End (exclusive, after its newline if any) of the line starting at s. */
static size_t line_end(const fz_buf *b, size_t s) {
  const char *nl = memchr(b->data + s, '\n', b->len - s);
  return nl ? (size_t)(nl - b->data) + 1 : b->len;
}

static int is_digit(char c) {
  return c >= '0' && c <= '9';
}

/* A random number token of b: [at, at + n).  0 if found. */
static int find_number(gsl_rng *r, const fz_buf *b, size_t *at, size_t *n) {
  size_t count = 0, s[256], e[256];
  for (size_t i = 0; i < b->len && count < 256;) {
    if (is_digit(b->data[i]) ||
        ((b->data[i] == '-' || b->data[i] == '+' || b->data[i] == '.') &&
         i + 1 < b->len && is_digit(b->data[i + 1]))) {
      size_t j = i + 1;
      while (j < b->len && (is_digit(b->data[j]) || b->data[j] == '.' ||
                            b->data[j] == 'e' || b->data[j] == 'E' ||
                            ((b->data[j] == '-' || b->data[j] == '+') &&
                             (b->data[j - 1] == 'e' || b->data[j - 1] == 'E'))))
        j++;
      s[count] = i;
      e[count++] = j;
      i = j;
    } else
      i++;
  }
  if (!count) return -1;
  size_t k = pick(r, count);
  *at = s[k];
  *n = e[k] - s[k];
  return 0;
}

/* One mutation of b. */
static int mutate_once(gsl_rng *r, fz_kind kind, fz_buf *b, const fz_buf *other) {
  size_t lines[1024];
  const int op = (int)pick(r, 14);
  switch (op) {
  case 0: /* flip one bit */
    if (b->len) b->data[pick(r, b->len)] ^= (char)(1u << pick(r, 8));
    return 0;
  case 1: /* set a byte: special or any */
    if (b->len)
      b->data[pick(r, b->len)] = gsl_rng_uniform(r) < 0.5
                                     ? special[pick(r, sizeof special - 1)]
                                     : (char)pick(r, 256);
    return 0;
  case 2: { /* insert 1..8 bytes */
    char ins[8];
    size_t n = 1 + pick(r, 8);
    for (size_t i = 0; i < n; i++)
      ins[i] = gsl_rng_uniform(r) < 0.7 ? special[pick(r, sizeof special - 1)]
                                        : (char)pick(r, 256);
    return splice(b, pick(r, b->len + 1), 0, ins, n);
  }
  case 3: { /* delete 1..16 bytes */
    size_t at = pick(r, b->len + 1);
    return splice(b, at, 1 + pick(r, 16), "", 0);
  }
  case 4:   /* duplicate a line */
  case 5:   /* swap two lines */
  case 6: { /* delete a line */
    size_t n = line_starts(b, lines, 1024);
    if (!n) return 0;
    size_t a = lines[pick(r, n)], ae = line_end(b, a);
    if (op == 6) return splice(b, a, ae - a, "", 0);
    char *copy = malloc(ae - a + 2);
    if (!copy) return -1;
    memcpy(copy, b->data + a, ae - a);
    size_t cn = ae - a;
    if (!cn || copy[cn - 1] != '\n') copy[cn++] = '\n';
    int rc;
    if (op == 4)
      rc = splice(b, ae, 0, copy, cn);
    else {
      size_t c = lines[pick(r, n)], ce = line_end(b, c);
      if (c == a) {
        free(copy);
        return 0;
      }
      if (c < a) { /* move line a before line c */
        rc = splice(b, a, ae - a, "", 0);
        if (!rc) rc = splice(b, c, 0, copy, cn);
      } else { /* move line a after line c */
        rc = splice(b, ce, 0, copy, cn);
        if (!rc) rc = splice(b, a, ae - a, "", 0);
      }
    }
    free(copy);
    return rc;
  }
  case 7:
  case 8: { /* a number replaced by an extreme (twice as likely as others) */
    size_t at, n;
    if (find_number(r, b, &at, &n)) return 0;
    const char *x = extremes[pick(r, NEXTREMES)];
    return splice(b, at, n, x, strlen(x));
  }
  case 9: { /* an empty line */
    size_t n = line_starts(b, lines, 1024);
    return splice(b, n ? lines[pick(r, n)] : 0, 0,
                  gsl_rng_uniform(r) < 0.5 ? "\n" : "\r\n",
                  gsl_rng_uniform(r) < 0.5 ? 1 : 2);
  }
  case 10: /* truncate */
    if (b->len) {
      b->len = pick(r, b->len);
      b->data[b->len] = '\0';
    }
    return 0;
  case 11: { /* a word of the format's grammar */
    const char *w = dict_word(r, kind);
    size_t at = pick(r, b->len + 1);
    return splice(b, at, gsl_rng_uniform(r) < 0.3 ? 1 + pick(r, 4) : 0, w, strlen(w));
  }
  case 12: { /* splice: a chunk of the other input (or of b itself) */
    const fz_buf *src = other && other->len ? other : b;
    if (!src->len) return 0;
    size_t s = pick(r, src->len), n = 1 + pick(r, src->len - s);
    char *copy = malloc(n);
    if (!copy) return -1;
    memcpy(copy, src->data + s, n);
    int rc = splice(b, pick(r, b->len + 1), gsl_rng_uniform(r) < 0.5 ? pick(r, n + 1) : 0,
                    copy, n);
    free(copy);
    return rc;
  }
  default: { /* a letter replaced by another (plantri names, keywords) */
    size_t cand[256], nc = 0;
    for (size_t i = 0; i < b->len && nc < 256; i++) {
      char c = b->data[i];
      if ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z')) cand[nc++] = i;
    }
    if (!nc) return 0;
    size_t u = pick(r, 52);
    b->data[cand[pick(r, nc)]] = (char)(u < 26 ? 'a' + u : 'A' + (u - 26));
    return 0;
  }
  }
}

int fz_mutate(gsl_rng *r, fz_kind kind, fz_buf *b, const fz_buf *other) {
  /* 1 mutation half the time, then 2, 3, 4 ever less often */
  int n = 1;
  while (n < 4 && gsl_rng_uniform(r) < 0.5)
    n++;
  for (int i = 0; i < n; i++)
    if (mutate_once(r, kind, b, other)) return -1;
  return 0;
}

void fz_escape(FILE *f, const char *p, size_t n, size_t max) {
  size_t m = max && n > max ? max : n;
  for (size_t i = 0; i < m; i++) {
    unsigned char c = (unsigned char)p[i];
    if (c == '\\')
      fputs("\\\\", f);
    else if (c == '\n')
      fputs("\\n", f);
    else if (c == '\r')
      fputs("\\r", f);
    else if (c == '\t')
      fputs("\\t", f);
    else if (c < 0x20 || c >= 0x7f)
      fprintf(f, "\\x%02x", c);
    else
      fputc(c, f);
  }
  if (m < n) fputs("...", f);
}

int fz_has_raw(const char *s) {
  for (; *s; s++)
    if ((unsigned char)*s < 0x20 || (unsigned char)*s >= 0x7f) return 1;
  return 0;
}
