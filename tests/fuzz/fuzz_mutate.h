/* fuzz_mutate.h — seeded mutations of text inputs for the fuzzers (fuzz_parse,
 * fuzz_gen): byte flips, inserted and deleted bytes, duplicated, swapped and
 * deleted lines, numbers replaced by extremes (1e308, -0, nan, inf, huge
 * integers, 0, -1, ...), empty lines, truncation and splices.
 *
 * Every mutant is a function of (seed, iteration) alone: fz_rng_for gives each
 * iteration a generator of its own, so `--seed S --only I` replays iteration I
 * without running the ones before it. */
#ifndef FUZZ_MUTATE_H
#define FUZZ_MUTATE_H

#include <stddef.h>
#include <stdio.h>

#include <gsl/gsl_rng.h>

#define FZ_MAXLEN 65536 /* mutants never grow beyond this many bytes */

/* A byte buffer (may hold NUL bytes); data[len] is always a NUL. */
typedef struct {
  char *data; /* len bytes plus a terminating NUL; malloc'd */
  size_t len; /* bytes held */
  size_t cap; /* bytes allocated (> len) */
} fz_buf;

/* What is mutated: selects the dictionary of tokens that may be inserted. */
typedef enum { FZ_LINK = 0, FZ_MESH, FZ_STENCIL, FZ_NKINDS } fz_kind;

/* Name of a kind ("link", "mesh", "stencil"). */
const char *fz_kind_name(fz_kind k);

/* Set b to a copy of n bytes at p; 0, or -1 when out of memory. */
int fz_buf_set(fz_buf *b, const char *p, size_t n);
/* Release b's memory (b itself is not freed). */
void fz_buf_free(fz_buf *b);

/* Seed the mt19937 generator r for iteration `iter` of the run with `seed`
 * (splitmix64 of both, so neighbouring iterations are unrelated). */
void fz_rng_for(gsl_rng *r, unsigned long seed, unsigned long iter);

/* Replace b by a mutant of itself: 1 to 4 mutations (kind-specific tokens
 * among them); `other` (may be NULL) is a second input of the same kind for
 * splices.  0, or -1 when out of memory. */
int fz_mutate(gsl_rng *r, fz_kind kind, fz_buf *b, const fz_buf *other);

/* Write n bytes at p to f escaped as in C: printable ASCII as is, backslash
 * doubled, \n \r \t, everything else \xHH.  At most `max` input bytes
 * (0 = all), then "..." if cut. */
void fz_escape(FILE *f, const char *p, size_t n, size_t max);

/* 1 if the NUL-terminated s holds a byte < 0x20 or >= 0x7f, else 0. */
int fz_has_raw(const char *s);

/* The built-in link seeds: plantri ASCII (letters and numbers) and names,
 * NULL-terminated. */
extern const char *const fz_link_seeds[];

#endif
