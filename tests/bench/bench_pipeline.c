/* bench_pipeline.c — the whole MLCA vertex pipeline per case (rule -> local
 * matrix -> eigenstructure -> regularity, ss_result_compute, what a sweep runs
 * per case) against bare LAPACK dgeev on the same one-ring block (issue 20),
 * measured side by side in one run on a sample of the links with k vertices:
 *   (a) pipeline time over dgeev time, and the share of the extraction of the
 *       local matrix from the global rule (target: within 2x of dgeev);
 *   (b) cases per second with 1 and 2 threads over the same sample (OpenMP,
 *       as `sweep` runs them, without the store), the speed-up (target
 *       >= 1.8 on 2 cores), the CPU time per wall second (below the
 *       number of threads: the threads waited for a processor, a loaded
 *       machine) and the cases per CPU second relative to one thread (below
 *       1: the threads cost each other work: locks, allocation, memory).
 * Part (a) is timed in thread CPU time, so that it means something on a
 * loaded machine; part (b) in wall time, which is what a sweep takes.
 * Options: --k K (4..16, default 12; 16 takes a quarter minute to enumerate), --samples N
 * (default 100: every count/N-th link of the enumeration), --jobs J (default 2), --scheme
 * S (default mlca; tetoct for the tet/oct split).
 *
 * --phases [--k K] [--scheme S] [--samples N]: where a case's time goes
 * instead of (a) and (b): the thread CPU time of each stage of the real
 * pipeline (ss_result_compute_ws with the library's timing hook,
 * ss_pipeline_workspace.times: clocks read between the stages, nothing else
 * changes) per case, mean and median, in ms and as multiples of the bare
 * dgeev on the same one-ring block; the ring construction alone (the ring's
 * cells and rows on levels that exist, ss_local_ring_deepen on kept levels)
 * measured on a second extraction beside it.
 *
 * --phases --certify [--k K] [--scheme S] [--samples N] [--psi-depth D]:
 * where a certified case's time goes (bench_pipeline_certify.c; default 10
 * links, psi not judged as sweep runs it, --psi-depth 4 as analyze): each
 * certified stage's CPU per case (the double path's stages, the exact
 * spectrum's, the interval Jacobians per ring level, psi's parts) beside the
 * double path's whole, best of 3 runs per case.
 *
 * --exact-full (with --certify, either mode): every factor of the exact
 * spectrum proven irreducible, as before issue 37's lazy factoring
 * (ss_result_opts.exact_full), for comparisons in one binary.
 *
 * --project [--kmax K] [--samples N] [--certify [--psi-depth D]]: the
 * exhaustive sweeps projected (issue 20; certified, as `sweep --certify`
 * computes each case, with --certify: issue 37).  For each k = 4..K (default 16) every
 * count/N-th link (default N = 50; all of them when count <= N), count the published
 * number, which the generator's count in the same pass must equal; the pipeline's thread
 * CPU per case on one thread: mean with its 95 % interval (Student's t, as if the evenly
 * spaced sample were a random one), median; the CPU-hours of the whole k (count x mean)
 * and of all k' <= k (half-widths summed in quadrature); then the thread efficiency e =
 * cases per CPU second with
 * --jobs threads over those with one, on the k = 13 sample, and the wall
 * time on 2 free cores = CPU / (2 min(e, 1)).  It is a projection of the
 * pipeline alone: enumeration, canonical forms and the store are not in it
 * (the real `sweep` below says how much they add).  The double path, as
 * `sweep` without --certify runs: certified sweeps cost 3-9x more per case
 * (bench_certify; reports/README.md: about 0.5 s per MLCA k = 12 link).
 *
 * The "k = 13 (58,716 links)" counts every link with 4..13
 * vertices, the sweep `--vertices 4..13`: 1 + 1 + 2 + 5 + 14 + 50 + 233 +
 * 1249 + 7595 + 49566 = 58,716 (49,566 is k = 13 alone, the published
 * number, which `enumerate links --count` reproduces); its "17.5 M" is k =
 * 16 alone (17,490,241).  Not a mistake.
 *
 * Measured 2026-12-03 12:12-12:16 UTC (load 7.2-9.9; this process got
 * 84 s of CPU in 242 s wall), --project --samples 100, MLCA:
 *    k      links  sampled  mean ms [95 %]        median  CPU-h k  CPU-h <= k [95 %]
 *   <=9        73    all     6-20                                0.000
 *   10        233    116   28.9 [ 24.4,  33.4]     18.6    0.002     0.002
 *   11      1,249    104   36.4 [ 30.5,  42.3]     22.1    0.013     0.015
 *   12      7,595    101   46.6 [ 39.6,  53.6]     25.7    0.098     0.113
 *   13     49,566    100   68.6 [ 59.8,  77.3]     36.3    0.944     1.057 [0.94, 1.18]
 *   14    339,722    100   74.8 [ 66.1,  83.4]     98.2    7.06      8.11  [7.29, 8.94]
 *   15  2,406,841    100   86.1 [ 75.9,  96.4]    112.9   57.6      65.7   [58.8, 72.6]
 *   16 17,490,241    100  122.9 [110.2, 135.5]    155.6  597       663    [601, 725]
 *   e = 0.97 (2 threads; CPU/wall 0.41: no free second core), so on 2 free
 *   cores: k <= 13 33 min [29, 36], k <= 14 4.2 h, k <= 15 34 h, k <= 16
 *   340 h (14 days).
 *   A second run, the default --samples 50 (other links: the stride doubled,
 *   so none of the first run's; 12:21-12:23, load 4.7-6.1, 58 s CPU in
 *   107 s wall): mean ms k = 12 48.7 [37.6, 59.7], 13 79.1 [64.6, 93.7],
 *   14 97.5 [82.2, 112.7], 15 123.8 [107.1, 140.6], 16 109.7 [92.0,
 *   127.4]; CPU-h k <= 13 1.21, k <= 14 10.4, k <= 15 93, k <= 16 626;
 *   e = 0.96; k <= 13 38 min on 2 cores.  The first run's 100 links at
 *   k = 13 once more (12:24, --kmax 13 --jobs 1): 64.4 ms against 68.6,
 *   so timing noise is about 6 %; but the two samples differ at k = 14 and
 *   15 by more than their intervals allow: the t-interval understates the
 *   error (the cost is heavy-tailed and not independent of the order of
 *   the enumeration), so read each projection as +-30 %, not as its
 *   printed interval.  The interval is sampling error only; a CPU second
 *   on a loaded machine (shared caches and memory bandwidth) also moves:
 *   k = 12 measured 54 ms per case below, on 102 other links.  The random
 *   links of bench_sweep.sh are easier than the enumerated ones (its k =
 *   16 estimate of 113 h used random links, before the ring was judged).
 * The real command, the same day, for the cross-check:
 *   /usr/bin/time -v subspectra sweep --scheme mlca --vertices 13
 *     --part 1/40 --jobs 2 --db /tmp/x.db     (load 8.6 at the start, 7.7 at
 *   the end): 1378 cases (parts are subtrees of the generator, not equal
 *   slices: 1/40 of 49,566 is 1239), 87.6 s CPU (user + system), 4 min 10 s
 *   wall (34 % of a core on average of the 2 asked for).  Scaled by 40:
 *   58.4 min CPU = 0.97 CPU-h for k = 13; scaled by cases (49,566 / 1378):
 *   63.6 ms per case, 0.88 CPU-h, inside the projection's interval for the
 *   pipeline alone (0.82-1.06 CPU-h at k = 13), so enumeration and store
 *   add little.  Its wall time, scaled by 40: 2 h 47 min on this loaded
 *   machine.
 *   A second part, --part 7/40 (load 6.6 at the start, 3.8 at the end):
 *   1252 cases, 96.0 s CPU, 2 min 56 s wall (54 % of a core); 76.7 ms per
 *   case, scaled by 40 1.07 CPU-h, by cases 1.06.  The parts differ by
 *   20 % per case (subtrees of different links); the two pooled: 183.7 s
 *   for 2630 cases, 69.8 ms per case, 0.96 CPU-h for k = 13, beside the
 *   bench's 68.6 ms and 0.94.
 * Does "k <= 13 under 30 minutes on this 2-core machine" hold?  By
 * projection (not a timed exhaustive run): CPU for k <= 13 = 0.11 CPU-h
 * (k <= 12, bench) + 0.88 to 1.07 (k = 13 from the two sweep parts; 0.96
 * pooled) or 0.89-1.09 (bench's three runs), i.e. 0.99-1.21 CPU-h, / 2
 * cores / e = 0.96-0.97: 30-38 minutes (pooled parts 33, bench runs 30,
 * 33 and 38).  No: every central estimate lies at or above 30 minutes.  Pipeline
 * speed-ups of 10-20 % would be needed; and a machine as loaded as today's (a third to a
 * half of a core per process) takes hours.
 *
 * Measured 2026-12-03, one run each, on the 2-core machine shared with four
 * other engineers' builds (load 4-10; this process got 0.5-1 of a core),
 * thread CPU time for (a):
 *   main (dd13ff2) and this branch (the injectivity test computing only what
 *   it reads and deciding most pairs of pieces by orientation predicates,
 *   the deeper ring refining only its new level and judging only its new
 *   cells, the hex test's Lagrange weights from a table), the same 102 MLCA
 *   links k = 12 in the same run:
 *     pipeline 178.8 -> 54.4 ms per case (median 116.8 -> 26.2, slowest
 *     561 -> 131), extraction 16.1 -> 14.7 ms (9 % -> 27 %), dgeev 2.1 ms;
 *     pipeline / dgeev 83.9 -> 28.9.
 *   branch: MLCA k = 14 (41 links) 80.6 ms, extraction 19.2, dgeev 3.49,
 *     ratio 23.1; tet/oct k = 12 13.0 ms vs dgeev 0.082 ms (ratio 158): its
 *     one-ring block has only k + 1 rows, so its dgeev is nearly free and the
 *     ratio says little.
 *   The 2x target is out of reach as the pipeline is built: the extraction
 *   alone (refining the star level by level from the global rule) is 5-8x
 *   dgeev for MLCA, and the regularity test on up to three ring levels (the
 *   Jacobian's Bernstein subdivision, depth 6, on every ring cell), the
 *   deeper ring's extra refinement and the overlap test come on top; only
 *   stencils derived once per scheme and cell configuration, instead of
 *   refining per case, could remove the first.
 *   (b) could not show a speed-up on that machine (CPU per wall second
 *   0.5-1.2 with 2 threads: the second core was seldom free); cases per CPU
 *   second with 2 threads were 0.94-1.01 of one thread's (MLCA k = 12 and
 *   14, tet/oct; 0.81-0.98 in a run under load 10; `sweep --jobs 1/2` of
 *   the same 102 links into fresh stores: 0.91 and 0.99, identical rows):
 *   the threads cost each other little, so on two free cores the speed-up
 *   would be about 1.8-2.
 *
 * The regularity side (branch i20reg: everything in ss_result_compute but
 * the local matrix), 2026-12-03 14:23-14:25 UTC, load 2.7-3.2, main's
 * binary (d712994) and the branch's run side by side, one core each
 * (--jobs 1; paired, so both see the same load), part (a), 102 links:
 *   k = 12, three pairs: pipeline 65.9 -> 59.9, 62.2 -> 58.4, 60.6 -> 56.9
 *     ms (-6 to -9 %); without the extraction 48.6 -> 42.2, 46.0 -> 42.1,
 *     44.5 -> 40.4 ms (-9 to -13 %); median 28.4 -> 26.7, slowest 127 -> 118.
 *   k = 13, two pairs: 66.9 -> 61.9 and 79.7 -> 71.7 ms (-7.5, -10 %);
 *     without the extraction -12 and -13 %.
 *   callgrind, 12 links k = 12 (instructions, free of load): pipeline 9.88
 *   -> 9.28 G; Jacobian test (ss_jac_cell) 2.08 -> 1.78 G, injectivity
 *   0.96 -> 0.66 G.  What changed: the scaled Jacobian's edge lengths once
 *   per hex edge (hypot was most of ss_jac_cell's time), the Bernstein
 *   conversion and split without an integer division per coefficient, and
 *   the overlap test's orientation predicates each computed once per pair
 *   of cells (a hex's 24 tets share 15 points) with the pieces'
 *   orientations kept.  Stores unchanged bit for bit (MLCA k 4..11 and edges
 *   3..8, tet/oct, box-spline, a certified MLCA store).  What is left,
 *   perf at k = 12 and 13 (share of the pipeline's CPU): the deeper ring's
 *   refinement (ss_local_ring_deepen) 45-47 %, the local matrix 29-32 %,
 *   injectivity 9-11 %, Jacobian test 4-6 %, eigen 4 %: the regularity
 *   side proper is now about a fifth of a case; the deeper ring, a
 *   refinement, is the next target.
 *
 * The refinement side (branch i20refine: the rule -> local matrix and the
 * ring's levels), 2026-12-03 14:38-14:41 UTC, load 1.4-3.7, main (31954ee,
 * with the regularity side above) and the branch rebased on it, run
 * alternately, --jobs 1, part (a), 102 links k = 12, best of 3: pipeline
 * 49.7 -> 31.3 ms per case (the three pairs 49.7/31.3, 50.5/32.8,
 * 54.5/33.9), extraction 13.9 -> 6.7 ms, dgeev 1.83-1.86 ms: pipeline /
 * dgeev 27 -> 17.  --project --kmax 13 --samples 100, the two run back to
 * back (14:39-14:41, load 1.4-1.6): mean ms k = 10 25.9 -> 16.0, 11 31.3 ->
 * 21.6, 12 44.3 -> 30.3, 13 63.3 -> 40.1; CPU-h k <= 13 0.978 -> 0.624;
 * wall on 2 free cores 29 -> 20 min (e = 1.03 and 0.93; 19 min at e = 1),
 * so k <= 13 under 30 minutes holds by projection, with the +-30 % above
 * only just.  callgrind (instructions, free of load), --samples 8: 8.49 G
 * (d712994) -> 5.76 G (the branch before the rebase).  What changed: R is
 * written row by row (the averaging rule walks each fine vertex's cells in
 * order, so no triplet list is bucketed and merged), each cell's parents
 * merged once and its sums reused across its vertices of equal valence, the
 * rule run only for the rows that can be read (inner vertices) and without
 * positions, levels indexed by a hash of their coordinates instead of a
 * sort, the split tabulated.  Every entry of R is summed in the same order
 * as before: stores unchanged bit for bit (MLCA 4..10 and edges 3..8,
 * tet/oct 4..9 and 3..8, box-spline 4..9).  What is left of the
 * refinement, perf at k = 12 (share of the pipeline's CPU): the rule's
 * emission 13 %, the levels' boundary marks (inner_marks, a facet sort per
 * level) 6-7 %, the split 7 %, merging cells' parents 3-4 %; the boundary
 * marks could be derived from the coarser level's (a fine facet is on the
 * boundary iff its coarse one is), and the split and the rule share the
 * parent lookups.
 *
 * Both merged (main c83aa33), the machine otherwise idle, 2026-12-03:
 *   the exhaustive sweep TIMED (14:46-15:05 UTC, load 0.4-2.0 from the sweep
 *   itself): `/usr/bin/time -v subspectra sweep --scheme mlca --vertices
 *   4..13 --jobs 2` 58,716 cases in 18 min 59 s wall, 2249.6 s user + 5.3 s
 *   system (0.63 CPU-h; 198 % of a CPU), 88 MB resident: k <= 13 under 30
 *   minutes, measured.  Per case from the store: k = 12 31.3 ms, 13 40.0 ms.
 *   --k 14 (15:07, load 0.4): pipeline 55.5 ms, extraction 9.5, dgeev 3.59,
 *   ratio 15.4; (b) 18.3 -> 33.5 cases/s, speed-up 1.83.
 *   --project --samples 50 (15:07): CPU-h k <= 13 0.725 [0.61, 0.84] (timed:
 *   0.63), k <= 14 6.6 [5.7, 7.5], k <= 15 52 [46, 58], k <= 16 378 [328,
 *   428]; e = 1.15 on the k = 13 sample (2.25x one thread's cases/s: above
 *   1 is noise of a short sample; the wall times use min(e, 1)).
 *
 * THE FLOOR, --phases (main 7dcbfe1 + the timing hook, 2026-12-03 16:02 UTC,
 * load 2.0-2.6: a reference sweep beside it, one core free; thread CPU, so
 * the load shows little), mean (median) per case in multiples of the bare
 * dgeev, MLCA k = 12 (102 links, 43 of them needing the deeper ring level) /
 * k = 14 (101 links, 59 deeper) / tet/oct k = 12 (102, 58 deeper):
 *   stage                                 k = 12        k = 14        tet/oct
 *   extraction (S, ring levels 0-1)       3.44 (3.49)   2.61 (2.68)   23.4 (24.6)
 *     of which the ring's construction    0.19          0.14          0.94
 *   eigen (dgeevx on the blocks, vectors,
 *     condition numbers, groups)          1.60 (1.67)   1.47 (1.51)   5.45 (5.65)
 *   charmap net + normalisation           0.03          0.03          0.34
 *   Jacobian test, levels 0-1             0.72 (0.33)   0.61 (0.71)   5.21 (6.96)
 *   deeper ring level: refinement         5.04 (0)      5.11 (7.10)   43.9 (63.4)
 *     of which the ring's construction    0.42          0.47          2.85
 *   deeper ring level: Jacobian test      3.28 (0)      3.13 (4.34)   23.6 (36.8)
 *   symmetry test                         0.03          0.01          0.21
 *   injectivity test                      2.89 (2.20)   2.67 (2.31)   6.63 (5.78)
 *   whole pipeline                        17.1 (8.58)   15.7 (18.5)   109 (141)
 *   bare dgeev, ms                        2.12 (2.08)   3.44 (3.40)   0.084 (0.081)
 *   (canonical link, major diagonals: <= 0.01; the stages sum to the whole
 *   within 0.1 %.)  Per link that needs the deeper level, k = 12: its
 *   refinement 25.3 ms (12x dgeev) and its Jacobian test 16.5 ms (7.8x).
 * What this says, plainly: the 2x target cannot be met without changing the
 * regularity test DESIGN.md section 10 prescribes.  Three stages alone
 * exceed 2x dgeev on their own at k = 12 and 14: the injectivity test
 * (2.7-2.9x), the extraction (2.6-3.5x) and, averaged over the links, the
 * deeper ring level (refinement 5x + its Jacobian test 3x); the eigen stage
 * alone is 1.5-1.7x (it runs dgeevx with eigenvectors and condition numbers
 * on every diagonal block, not one bare dgeev), so even with a free
 * extraction and a free regularity test the pipeline would sit at 1.5x.
 * The regularity side alone (map, Jacobian on up to three ring levels,
 * deeper refinement, symmetry, injectivity) is 12x dgeev (11.6 at k = 14).
 * A verdict judged on the ring as DESIGN prescribes costs, on the median
 * passing link, the Jacobian test 0.3-0.7x plus the injectivity test 2.2x:
 * already above 2x with everything else free.  For tet/oct the one-ring
 * block is 13 x 13 and its dgeev 0.08 ms: the eigen stage alone is 5.5x and
 * the Jacobian test on levels 0-1 alone 5x; the target is meaningless there.
 * Speed-ups can still cut the whole (the deeper ring's refinement is the
 * largest stage: 29-40 % of the CPU), but not to 2x.
 *
 * SPEED (branch i20phase, every sum in the same order: stores identical row
 * for row, MLCA 4..10 + edges 3..8 and k = 11, tet/oct 4..9 + 3..8,
 * box-spline 4..9, and against main also catmull-clark, loop, ccsolid, the
 * tet/oct face, box-spline edges and face, a certified MLCA store):
 *   - a refined level's boundary marks from the coarse level's boundary
 *     facets through the split's parent lists (a fine facet occurs once iff
 *     its coarse one does) instead of grouping the fine level's 8x as many
 *     facets; equal to the old marks on every case of those stores (checked
 *     under -DSS_CHECK_MARKS);
 *   - the finest level an extraction or a ring reads (level w + 2, and the
 *     deeper ring's w + 3) gets the rule only for its rows inside Omega_w
 *     (the only ones read there); the labels' rows and, when a level is
 *     added below (the deeper ring), the other inner rows are computed later
 *     and merged row by row (each row the same bits whichever rows are asked
 *     with it, ss_scheme_step_rows); cells with no wanted row not merged.
 * Measured 2026-12-03 16:19-16:21 UTC, load 1.7-2.3 (others' work; one core
 * free), main 7dcbfe1 and the branch alternately, --jobs 1, part (a), best
 * of 3 (each pair run back to back):
 *   MLCA k = 12: pipeline 32.0 -> 28.6 ms (-11 %), extraction 6.79 -> 5.56
 *     ms (-18 %), median 16.3 -> 14.4, slowest 78 -> 73; pipeline / dgeev
 *     15.5-16.8 -> 14.8-15.2;
 *   MLCA k = 14: 47.7 -> 46.7 ms (-2 %), extraction 8.31 -> 7.35 (-12 %),
 *     ratio 15.4-16.3 -> 15.0 (59 of 101 links take the deeper level, where
 *     the rows deferred on level w + 2 are computed after all);
 *   tet/oct k = 12: 10.65 -> 7.30 ms (-31 %), extraction 2.35 -> 1.30,
 *     ratio 116-126 -> 103-105.
 * callgrind (instructions, free of load; the whole bench, --samples 10):
 *   ss_result_compute_ws k = 12 5.884 -> 5.404 G (-8.2 %), k = 14 5.871 ->
 *   5.406 G (-7.9 %); every extraction (ss_local_new_ws) -19 %, the deeper
 *   ring (ss_local_ring_deepen) -15 %.
 * --phases on the branch (16:28, load 1.5-2.0), multiples of dgeev, mean:
 *   k = 12: extraction 2.66, eigen 1.64, Jacobian 0.72 + deeper level
 *   refinement 3.77 + its Jacobian 3.08, injectivity 2.62; whole 14.6
 *   (17.1 on main); per link needing the deeper level 22.1 ms refinement.
 *   k = 14: extraction 2.20, eigen 1.51, deeper refinement 4.33, its
 *   Jacobian 3.30, injectivity 2.74; whole 14.8 (15.7 on main).
 *   tet/oct: extraction 15.8, deeper refinement 31.4; whole 88.7 (109).
 * What is left (callgrind, k = 12, share of the instructions): the Jacobian
 *   test 25 % (hex_sign_d 17 %: Bernstein subdivision, every box's values
 *   needed for the counts and the minimum), the rule's emission 23 %, the
 *   split 7.5 %, eigen 9 %, injectivity 9 %.  Not done: the split and the
 *   rule sharing the parents' lookups (ss_sink_cells_prepare 5 %), a
 *   per-configuration stencil cache (the rule 23 % and the split would go;
 *   the largest remaining step).  Tried and dropped: the hex test's boxes
 *   split in place instead of copied (-0.4 % of instructions).
 *
 * THE JACOBIAN TEST (branch i20jac, 2026-12-03; the same bits: stores identical
 * row for row, MLCA 4..10 + edges 3..8 and k = 11, tet/oct 4..9 + 3..8,
 * box-spline 4..9).  callgrind (k = 12, --samples 20) showed the hex test's
 * time was not the Bernstein subdivision (nearly every ring cell is decided by
 * its 27 first coefficients) but the 27 Lagrange values: a loop reading and
 * testing 648 table weights per hex, more than half of them 0.  Now:
 *   - those weights are compile-time constants and the 27 values are written
 *     out term by term (the zero terms drop out of the code), each sum in the
 *     same order as before; the cube corner order as constants (test_jac pins
 *     it to ss_cx's) instead of 32 ss_cube_corner_* calls per hex;
 *   - tets and octahedra: each edge (centroid vector) length of the scaled
 *     Jacobian once, not at both ends (in four octants).
 * Instructions (callgrind): ss_result_compute_ws 6.81 -> 6.07 G (-11 %),
 *   ss_jac_cell 1.55 -> 0.81 G (-47 %; per hex 12.9k -> 6.8k, of which the
 *   Lagrange values 2.1k, the rest of the sign test 1.1k, the scaled Jacobian
 *   with its 24 hypot calls 2.6k, checks and the flat threshold 1.0k).
 * Timed 17:05-17:13 UTC, load 1.5-3.2 (others' work), main fa0c8a1 and the
 *   branch alternately, --jobs 1, best of 3 (thread CPU):
 *   MLCA k = 12 --phases: pipeline 26.2 -> 23.4 ms, in x dgeev 15.9-16.7 ->
 *     13.7-14.3; Jacobian test levels 0-1 0.75-0.79 -> 0.45-0.47 x dgeev,
 *     the deeper level's 3.10-3.26 -> 1.76-1.79 x (per link needing it 16.1
 *     -> 9.1 ms);  part (a): pipeline / dgeev 15.7-16.2 -> 14.2-14.9.
 *   MLCA k = 14 part (a): pipeline 41.6 -> 33.6 ms, ratio 15.1-15.8 ->
 *     13.2-14.0.
 *   tet/oct k = 12 --phases: pipeline 6.18 -> 5.10 ms (-17 %); Jacobian test
 *     levels 0-1 0.40 -> 0.21 ms, deeper level 1.71 -> 0.93 ms.
 *   The machine's speed moved by 20 % between runs (dgeev 1.5-2.0 ms at
 *   k = 12): read the multiples of dgeev, not the ms.  What is left of the
 *   Jacobian test is mostly the scaled Jacobian's hypot (its bits are
 *   stored, so it stays) and the Lagrange values themselves. */
#include <malloc.h>
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_statistics_double.h>

#include "bench_counts.h"
#include "bench_pipeline_certify.h"
#include "ss_eig.h"
#include "ss_enum.h"
#include "ss_local.h"
#include "ss_result.h"

static double clock_s(clockid_t id) {
  struct timespec t;
  clock_gettime(id, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static double now(void) {
  return clock_s(CLOCK_MONOTONIC);
}

/* Part (a) counts this thread's CPU time: on a machine loaded by other work
 * the wall time of a case is mostly waiting for a processor. */
static double cpu(void) {
  return clock_s(CLOCK_THREAD_CPUTIME_ID);
}

typedef struct {
  long stride, seen; /* take every stride-th link */
  long offset;       /* ... starting with link number offset (0-based) */
  ss_link **l;       /* the sample */
  size_t n, cap;     /* links taken, room */
  int failed;        /* out of memory copying */
} sample;

static int take(const ss_link *l, void *vs) {
  sample *s = vs;
  if (s->seen++ % s->stride != s->offset) return 0;
  if (s->n == s->cap) {
    s->cap = s->cap ? 2 * s->cap : 64;
    ss_link **q = realloc(s->l, s->cap * sizeof *q);
    if (!q) return s->failed = 1;
    s->l = q;
  }
  ss_error err = {0};
  if (ss_link_copy(l, &s->l[s->n], &err)) return s->failed = 1;
  s->n++;
  return 0;
}

/* Seconds of one bare dgeev on the one-ring block of link l (one-ring rows
 * and columns of S); < 0 on failure. */
static double bare_dgeev(const ss_scheme *sc, const ss_link *l) {
  ss_error err = {0};
  ss_case cs = {SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0};
  ss_local *M = NULL;
  if (ss_local_new(sc, &cs, &M, &err)) return -1.0;
  const size_t n1 = M->n1, n2 = M->n2;
  double *A = malloc(n1 * n1 * sizeof *A), *re = malloc(n1 * sizeof *re),
         *im = malloc(n1 * sizeof *im);
  double t = -1.0;
  if (A && re && im) {
    for (size_t i = 0; i < n1; i++)
      memcpy(A + i * n1, M->S + i * n2, n1 * sizeof *A);
    const double t0 = cpu();
    if (!ss_eig_dense(A, n1, re, im, &err)) t = cpu() - t0;
  }
  free(A), free(re), free(im);
  ss_local_free(M);
  return t;
}

/* Seconds of extracting the local matrix of link l; < 0 on failure. */
static double extraction(const ss_scheme *sc, const ss_link *l) {
  ss_error err = {0};
  ss_case cs = {SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0};
  ss_local *M = NULL;
  const double t0 = cpu();
  ss_status st = ss_local_new(sc, &cs, &M, &err);
  const double t = cpu() - t0;
  ss_local_free(M);
  return st ? -1.0 : t;
}

static int cmp_double(const void *a, const void *b) {
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* ---- --phases: where a case's time goes ---- */

enum {
  PH_CANON,
  PH_EXTRACT,
  PH_RING,
  PH_DIAG,
  PH_EIG,
  PH_MAP,
  PH_JAC,
  PH_DEEPEN,
  PH_DEEPRING,
  PH_DEEPJAC,
  PH_SYM,
  PH_INJ,
  PH_SUM,
  PH_PIPE,
  PH_DGEEV,
  NPH
};

static const char *const ph_name[NPH] = {
    "canonical link",
    "extraction (local matrix, ring levels 0-1)",
    "  of which: ring construction (levels 0-1)",
    "major diagonals",
    "eigen (LAPACK + post-processing)",
    "charmap net + normalisation",
    "Jacobian test (two-ring cells, levels 0-1)",
    "deeper ring level: refinement + ring",
    "  of which: ring construction (levels 0-2)",
    "deeper ring level: Jacobian test",
    "symmetry test",
    "injectivity test",
    "sum of the stages",
    "pipeline (ss_result_compute_ws, timed whole)",
    "bare dgeev on the one-ring block",
};

/* Thread CPU seconds of rebuilding M's ring (kept levels) with nring levels:
 * the ring construction alone when the levels exist, else with the levels'
 * refinement; < 0 on failure. */
static double ring_time(const ss_scheme *sc, const ss_case *cs, int nring, ss_local *M) {
  ss_error err = {0};
  const double t0 = cpu();
  const ss_status st = ss_local_ring_deepen(sc, cs, nring, M, &err);
  return st ? -1.0 : cpu() - t0;
}

/* --phases: each stage of ss_result_compute_ws in thread CPU time (the
 * library's timing hook, ss_pipeline_workspace.times, in the real pipeline,
 * one case at a time); then, outside the pipeline on a second extraction
 * with kept levels, the ring construction alone (ss_local_ring_deepen with
 * levels that exist), and for the links that needed a deeper ring level
 * the share of the ring construction in that step.  Mean and median per
 * case, in ms and as multiples of the mean (median) bare dgeev. */
static int phases(const ss_scheme *sc, const ss_result_opts *ro, const sample *s) {
  const size_t n = s->n;
  double *t = calloc(NPH * n + 1, sizeof *t); /* t[ph * n + i] */
  ss_pipeline_workspace *w = ss_pipeline_workspace_new();
  ss_pipeline_times tm;
  int failed = 0;
  long ndeep = 0;
  if (!t || !w) return 1;
  w->times = &tm;
  for (size_t i = 0; i < n; i++) {
    ss_error err = {0};
    ss_case cs = {SS_CASE_VERTEX, s->l[i], 0, SS_DIAG_BFS, 0};
    ss_result r;
    memset(&tm, 0, sizeof tm);
    const double t0 = cpu();
    const ss_status st = ss_result_compute_ws(sc, &cs, ro, w, &r, &err);
    t[PH_PIPE * n + i] = cpu() - t0;
    if (!st) ss_result_clear(&r);
    failed += st != SS_OK;
    const ss_charmap_times *c = &tm.charmap;
    const double v[] = {tm.canon, tm.extract,  0.0,         tm.diagonals,
                        tm.eig,   c->map,      c->jacobian, c->deepen,
                        0.0,      c->deep_jac, c->symmetry, c->injective};
    double sum = 0.0;
    for (int p = 0; p < PH_SUM; p++) {
      t[p * n + i] = v[p];
      if (p != PH_RING && p != PH_DEEPRING) sum += v[p];
    }
    t[PH_SUM * n + i] = sum;
    /* the ring construction alone, on a second extraction (the pipeline
     * analyses the canonical link; the same link up to labels here) */
    ss_local_opts lo = ss_local_defaults();
    lo.keep_levels = 1;
    ss_local *M = NULL;
    if (ss_local_new_opts(sc, &cs, &lo, &M, &err)) {
      failed++;
      continue;
    }
    const double tr = ring_time(sc, &cs, M->nring, M);
    t[PH_RING * n + i] = fmax(tr, 0.0);
    failed += tr < 0.0;
    if (c->deep) {
      ndeep++;
      const double ta = ring_time(sc, &cs, ro->ring_levels, M); /* refines */
      const double tb = ring_time(sc, &cs, ro->ring_levels, M); /* ring only */
      t[PH_DEEPRING * n + i] = fmax(tb, 0.0);
      failed += ta < 0.0 || tb < 0.0;
    }
    ss_local_free(M);
    const double tb = bare_dgeev(sc, s->l[i]);
    t[PH_DGEEV * n + i] = fmax(tb, 0.0);
    failed += tb < 0.0;
  }
  double mean[NPH], med[NPH];
  for (int p = 0; p < NPH; p++) {
    mean[p] = gsl_stats_mean(t + p * n, 1, n);
    qsort(t + p * n, n, sizeof *t, cmp_double);
    med[p] = gsl_stats_median_from_sorted_data(t + p * n, 1, n);
  }
  printf("(phases) thread CPU per case over the %zu links (%ld needed the deeper ring "
         "level); x dgeev = over the mean (median) bare dgeev; medians do not add up\n",
         n, ndeep);
  printf("  %-46s %9s %9s %9s %9s %6s\n", "stage", "mean ms", "x dgeev", "median ms",
         "x dgeev", "share");
  for (int p = 0; p < NPH; p++)
    printf("  %-46s %9.3f %9.2f %9.3f %9.2f %5.1f%%\n", ph_name[p], 1e3 * mean[p],
           mean[p] / mean[PH_DGEEV], 1e3 * med[p], med[p] / med[PH_DGEEV],
           100.0 * mean[p] / mean[PH_PIPE]);
  if (ndeep)
    printf("  deeper ring level, over the %ld links that needed it: refinement + ring "
           "%.3f ms, Jacobian test %.3f ms per such link\n",
           ndeep, 1e3 * mean[PH_DEEPEN] * (double)n / (double)ndeep,
           1e3 * mean[PH_DEEPJAC] * (double)n / (double)ndeep);
  printf("  extraction + eigen alone = %.2f x dgeev; the regularity side (map, "
         "Jacobian, deeper level, symmetry, injectivity) alone %.2f x\n",
         (mean[PH_EXTRACT] + mean[PH_EIG]) / mean[PH_DGEEV],
         (mean[PH_MAP] + mean[PH_JAC] + mean[PH_DEEPEN] + mean[PH_DEEPJAC] +
          mean[PH_SYM] + mean[PH_INJ]) /
             mean[PH_DGEEV]);
  ss_pipeline_workspace_free(w);
  free(t);
  if (failed) printf("failures: %d\n", failed);
  return failed ? 1 : 0;
}

/* The pipeline on link i of the sample; 0 or 1 (failed). */
static int pipeline(const ss_scheme *sc, const ss_result_opts *ro, const ss_link *l) {
  ss_error err = {0};
  ss_case cs = {SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0};
  ss_result r;
  ss_status st = ss_result_compute(sc, &cs, ro, &r, &err);
  if (!st) ss_result_clear(&r);
  return st != SS_OK;
}

/* (b): the sample on 1 .. jobs threads, wall time.  Returns the cases per
 * CPU second with `jobs` threads over those with one thread (the thread
 * efficiency, which a loaded machine does not hide as it hides the
 * speed-up); failures are added to *failed. */
static double threads(const ss_scheme *sc, const ss_result_opts *ro, const sample *s,
                      int jobs, int *failed) {
  double rate1 = 0.0, per_cpu1 = 0.0, eff = 1.0;
  for (int nt = 1; nt <= jobs; nt++) {
    int bad = 0;
    const double w0 = now(), c0 = clock_s(CLOCK_PROCESS_CPUTIME_ID);
    const long n = (long)s->n;
#pragma omp parallel for schedule(dynamic, 1) num_threads(nt) reduction(+ : bad)
    for (long i = 0; i < n; i++)
      bad += pipeline(sc, ro, s->l[i]);
    const double wall = now() - w0, cpus = clock_s(CLOCK_PROCESS_CPUTIME_ID) - c0;
    *failed += bad;
    const double rate = (double)s->n / wall;
    if (nt == 1) rate1 = rate, per_cpu1 = (double)s->n / cpus;
    eff = (double)s->n / cpus / per_cpu1;
    printf("(b) %d thread%s: %7.1f cases/s, speed-up %.2f, CPU/wall %.2f, cases per CPU "
           "second %.2f of 1 thread's%s\n",
           nt, nt == 1 ? " " : "s", rate, rate / rate1, cpus / wall, eff,
           nt > 1 ? (rate / rate1 >= 0.9 * nt ? "   (target >= 1.8 on 2 cores: met)"
                                              : "   (target >= 1.8 on 2 cores: NOT met)")
                  : "");
  }
  return eff;
}

static void sample_clear(sample *s) {
  for (size_t i = 0; i < s->n; i++)
    ss_link_free(s->l[i]);
  free(s->l);
  *s = (sample){0};
}

/* ---- --project: the exhaustive sweeps projected from samples ---- */

typedef struct {
  double mean, median; /* CPU seconds per case over the sample */
  double half;         /* half-width of the 95 % interval of the mean (0: all) */
  size_t n;            /* cases timed */
  int all;             /* the sample is every link with k vertices */
} k_cost;

/* Time the pipeline (thread CPU, one thread) on every stride-th link with k
 * vertices, the stride from the published count so that one pass of the
 * generator suffices, the first taken at stride/2; the generator's count is
 * checked against the published one.  The sample is left in *s.  The
 * interval is Student's t on the sample as if it were a simple random
 * sample; the sample is systematic (evenly spaced in the generator's order),
 * which is as good unless the cost has a period in that order. */
static int cost_of_k(const ss_scheme *sc, const ss_result_opts *ro, int k, long want,
                     sample *s, k_cost *c, int *failed) {
  ss_enum_opts o = {k, k, 0, 1};
  uint64_t counts[SS_ENUM_MAXK + 1] = {0};
  ss_error err = {0};
  s->stride = (long)(published[k] / (unsigned long long)want);
  if (s->stride < 1) s->stride = 1;
  s->offset = s->stride / 2;
  if (ss_enum_links(&o, take, s, counts, &err) || s->failed) return 1;
  if (counts[k] != published[k]) {
    printf("k = %d: the generator counts %llu links, DIFFERS from the published %llu\n",
           k, (unsigned long long)counts[k], published[k]);
    return 1;
  }
  double *t = malloc(s->n * sizeof *t);
  if (!t) return 1;
  for (size_t i = 0; i < s->n; i++) {
    const double t0 = cpu();
    *failed += pipeline(sc, ro, s->l[i]);
    t[i] = cpu() - t0;
  }
  qsort(t, s->n, sizeof *t, cmp_double);
  c->n = s->n;
  c->all = s->n == counts[k];
  c->mean = gsl_stats_mean(t, 1, s->n);
  c->median = gsl_stats_median_from_sorted_data(t, 1, s->n);
  c->half = !c->all && s->n >= 2 ? gsl_cdf_tdist_Pinv(0.975, (double)(s->n - 1)) *
                                       gsl_stats_sd(t, 1, s->n) / sqrt((double)s->n)
                                 : 0.0;
  free(t);
  return 0;
}

/* The projection: for k = 4..kmax the CPU time of sweeping every link with
 * k vertices (count x mean CPU per case) with its 95 % interval, summed over
 * k (the intervals' half-widths in quadrature: the samples are independent),
 * then the thread efficiency e measured on the k = 13 sample with 1 and
 * `jobs` threads, and the wall time on 2 free cores = CPU / (2 min(e, 1)). */
static int project(const ss_scheme *sc, const ss_result_opts *ro, long want, int kmax,
                   int jobs) {
  printf("projection of exhaustive vertex sweeps, %s, pipeline CPU per case (one "
         "thread, thread CPU time) on every count/%ld-th link of the enumeration\n",
         ss_scheme_name(sc), want);
  printf("  k      links  sampled  mean ms (95 %% interval)  median   CPU-h this k   "
         "CPU-h k <= this (95 %% interval)\n");
  double hours = 0.0, var = 0.0, hours13 = 0.0, half13 = 0.0;
  int failed = 0;
  sample s13 = {0};
  double cum_h[SS_ENUM_MAXK + 1] = {0}, cum_half[SS_ENUM_MAXK + 1] = {0};
  for (int k = 4; k <= kmax; k++) {
    sample s = {0};
    k_cost c = {0};
    if (cost_of_k(sc, ro, k, want, &s, &c, &failed)) {
      sample_clear(&s);
      sample_clear(&s13);
      return 1;
    }
    const double n = (double)published[k], h = n * c.mean / 3600.0,
                 hh = n * c.half / 3600.0;
    hours += h;
    var += hh * hh;
    cum_h[k] = hours, cum_half[k] = sqrt(var);
    printf(
        " %2d %10llu  %7zu%s %7.1f [%6.1f, %6.1f]  %6.1f  %12.3f   %10.3f [%.3f, %.3f]\n",
        k, published[k], c.n, c.all ? " all" : "    ", 1e3 * c.mean,
        1e3 * (c.mean - c.half), 1e3 * (c.mean + c.half), 1e3 * c.median, h, hours,
        hours - sqrt(var), hours + sqrt(var));
    fflush(stdout);
    if (k == (kmax < 13 ? kmax : 13)) {
      s13 = s;
      hours13 = hours, half13 = sqrt(var);
    } else
      sample_clear(&s);
  }
  const int ke = kmax < 13 ? kmax : 13;
  printf("thread efficiency e, measured on the k = %d sample:\n", ke);
  const double e = threads(sc, ro, &s13, jobs, &failed);
  const double ec = e < 1.0 ? e : 1.0;
  printf("wall time of the exhaustive sweep on 2 free cores = CPU / (2 x min(e, 1)), "
         "e = %.2f:\n",
         e);
  for (int k = 13; k <= kmax; k++)
    printf("  k <= %2d: %9.3f CPU-h [%.3f, %.3f], wall %8.3f h [%.3f, %.3f] = %.0f min\n",
           k, cum_h[k], cum_h[k] - cum_half[k], cum_h[k] + cum_half[k],
           cum_h[k] / (2 * ec), (cum_h[k] - cum_half[k]) / (2 * ec),
           (cum_h[k] + cum_half[k]) / (2 * ec), 60.0 * cum_h[k] / (2 * ec));
  unsigned long long links13 = 0;
  for (int k = 4; k <= 13; k++)
    links13 += published[k];
  if (kmax >= 13)
    printf("k <= 13 (%llu links) under 30 minutes on 2 cores, by projection (not a timed "
           "exhaustive run; pipeline only, without enumeration and store): %s "
           "(%.1f min, 95 %% interval [%.1f, %.1f])\n",
           links13,
           60.0 * (hours13 + half13) / (2 * ec) < 30.0   ? "yes"
           : 60.0 * (hours13 - half13) / (2 * ec) > 30.0 ? "no"
                                                         : "undecided by this sample",
           60.0 * hours13 / (2 * ec), 60.0 * (hours13 - half13) / (2 * ec),
           60.0 * (hours13 + half13) / (2 * ec));
  printf("(the intervals are sampling error as if the sample were random; runs with "
         "other links differed by more, about +-30 %%: see the header)\n");
  sample_clear(&s13);
  if (failed) printf("failures: %d\n", failed);
  return failed ? 1 : 0;
}

int main(int argc, char **argv) {
  int k = 12, jobs = 2, proj = 0, kmax = 16, ph = 0, cert = 0, psi_depth = 0, full = 0;
  long want = 0;
  const char *scheme = "mlca";
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--project")) {
      proj = 1;
      continue;
    }
    if (!strcmp(argv[i], "--phases")) {
      ph = 1;
      continue;
    }
    if (!strcmp(argv[i], "--certify")) {
      cert = 1;
      continue;
    }
    if (!strcmp(argv[i], "--exact-full")) {
      full = 1;
      continue;
    }
    if (i + 1 == argc) break;
    if (!strcmp(argv[i], "--k")) k = atoi(argv[i + 1]);
    if (!strcmp(argv[i], "--kmax")) kmax = atoi(argv[i + 1]);
    if (!strcmp(argv[i], "--samples")) want = atol(argv[i + 1]);
    if (!strcmp(argv[i], "--jobs")) jobs = atoi(argv[i + 1]);
    if (!strcmp(argv[i], "--scheme")) scheme = argv[i + 1];
    if (!strcmp(argv[i], "--psi-depth")) psi_depth = atoi(argv[i + 1]);
    i++;
  }
  if (!want) want = proj ? 50 : cert ? 10 : 100;
  if (k < 4 || k > 16 || kmax < 4 || kmax > 16 || want < 1 || jobs < 1 || psi_depth < 0 ||
      psi_depth > 8 || (cert && !ph && !proj) || (full && !cert)) {
    fprintf(stderr, "bench_pipeline: --k 4..16, --kmax 4..16, --samples >= 1, --jobs "
                    ">= 1, --psi-depth 0..8, --certify with --phases or --project, "
                    "--exact-full with --certify\n");
    return 2;
  }
#if defined(M_MMAP_THRESHOLD) && defined(M_TRIM_THRESHOLD)
  mallopt(M_MMAP_THRESHOLD, 32 << 20); /* keep freed memory, as subspectra does */
  mallopt(M_TRIM_THRESHOLD, 128 << 20);
#endif
  ss_error err = {0};
  ss_scheme *sc = NULL;
  if (ss_scheme_new(scheme, &sc, &err)) {
    fprintf(stderr, "bench_pipeline: %s\n", err.msg);
    return 2;
  }
  if (proj) { /* --certify: what `sweep --certify` computes per case */
    ss_result_opts pro = ss_result_defaults();
    pro.certify = cert;
    pro.psi_depth = psi_depth;
    pro.exact_full = full;
    if (cert) printf("certified (sweep --certify%s)\n", psi_depth ? " --psi-depth" : "");
    const int rc = project(sc, &pro, want, kmax, jobs);
    ss_scheme_free(sc);
    return rc;
  }
  /* one pass: the stride from the published count (as --project), the
   * generator's count checked against it */
  ss_enum_opts o = {k, k, 0, 1};
  uint64_t counts[SS_ENUM_MAXK + 1] = {0};
  sample s = {0};
  s.stride = (long)published[k] / want > 1 ? (long)published[k] / want : 1;
  if (ss_enum_links(&o, take, &s, counts, &err) || s.failed) return 1;
  if (counts[k] != published[k]) {
    printf("k = %d: the generator counts %llu links, DIFFERS from the published %llu\n",
           k, (unsigned long long)counts[k], published[k]);
    return 1;
  }
  const ss_result_opts ro = ss_result_defaults();
  printf("%s vertex pipeline, %zu of the %llu links with k = %d (every %ld-th)\n", scheme,
         s.n, (unsigned long long)counts[k], k, s.stride);
  if (ph) {
    const int rc =
        cert ? bench_certify_phases(sc, s.l, s.n, psi_depth, full) : phases(sc, &ro, &s);
    for (size_t i = 0; i < s.n; i++)
      ss_link_free(s.l[i]);
    free(s.l);
    ss_scheme_free(sc);
    return rc;
  }

  /* (a) one thread, case by case */
  double t_pipe = 0.0, t_ext = 0.0, t_bare = 0.0;
  double *tp = malloc(s.n * sizeof *tp);
  int failed = 0;
  if (!tp) return 1;
  for (size_t i = 0; i < s.n; i++) {
    const double t0 = cpu();
    failed += pipeline(sc, &ro, s.l[i]);
    tp[i] = cpu() - t0;
    t_pipe += tp[i];
    const double te = extraction(sc, s.l[i]), tb = bare_dgeev(sc, s.l[i]);
    failed += te < 0.0 || tb < 0.0;
    t_ext += fmax(te, 0.0);
    t_bare += fmax(tb, 0.0);
  }
  printf("(a) per case: pipeline %.2f ms (extraction %.2f ms, %.0f %%), bare dgeev on "
         "the one-ring block %.3f ms\n",
         1e3 * t_pipe / s.n, 1e3 * t_ext / s.n, 100.0 * t_ext / t_pipe,
         1e3 * t_bare / s.n);
  qsort(tp, s.n, sizeof *tp, cmp_double);
  printf("    pipeline per case: median %.2f ms, slowest %.2f ms (links whose "
         "regularity needs deeper ring levels)\n",
         1e3 * tp[s.n / 2], 1e3 * tp[s.n - 1]);
  printf("    pipeline / dgeev: %.1f   (target <= 2)\n", t_pipe / t_bare);
  free(tp);

  /* (b) the same cases on 1 .. jobs threads */
  threads(sc, &ro, &s, jobs, &failed);
  if (failed) printf("failures: %d\n", failed);
  for (size_t i = 0; i < s.n; i++)
    ss_link_free(s.l[i]);
  free(s.l);
  ss_scheme_free(sc);
  return failed ? 1 : 0;
}
