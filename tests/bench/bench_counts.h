/* bench_counts.h — the published numbers of triangulations of the sphere
 * with minimum degree 3, mirror images identified (DESIGN section 6), for
 * k = 0..16 vertices: what the benchmarks check the generator's counts
 * against. */
#ifndef BENCH_COUNTS_H
#define BENCH_COUNTS_H

static const unsigned long long published[] = {
    0, 0, 0, 0, 1, 1, 2, 5, 14, 50, 233, 1249, 7595, 49566, 339722, 2406841, 17490241};

#endif
