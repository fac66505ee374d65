/* ss_cli_sweep_opts.c — the command line of `subspectra sweep`: its usage
 * text, its options parsed once into an ss_sweep_opts, and the check of the
 * cases asked for against the scheme.  The bottom of the sweep's files: the
 * sweep's life (ss_cli_sweep_run.c) starts here, on every MPI rank alike. */
#include <getopt.h>
#include <stdio.h>

#include <omp.h>

#include "ss_cli.h"
#include "ss_cli_sweep.h"
#include "ss_enum.h"
#include "ss_jac.h"

static const char *const sweep_usage =
    "usage: subspectra sweep (--scheme S | --stencil FILE) CASES [--db FILE]\n"
    "                        [--jobs N] [--part I/N] [--tol T] [--depth D]\n"
    "                        [--diagonals D] [--certify] [--psi-depth N]\n"
    "                        [--psi-tubes]\n"
    "                        [--max-memory SIZE] [--progress | --quiet]\n"
    "\n"
    "Analyse every case asked for, exactly as `subspectra analyze` does, and store\n"
    "each result in a SQLite results store (schema in docs/sweep.md).  Results are\n"
    "keyed by the scheme's identity (its name, or the hash of the stencil file's\n"
    "bytes, with --tol, --depth, --diagonals, --certify and --psi-depth), the case\n"
    "and the canonical link:\n"
    "a rerun skips the cases already stored, so an interrupted sweep (even by\n"
    "SIGKILL) resumes where it stopped, and no case is ever stored twice.\n"
    "\n"
    "cases (one or more):\n"
    "  --vertices A..B   every vertex link with A..B vertices (4 <= A <= B <= 20;\n"
    "                    the number of links grows about 7-fold per vertex: 7595\n"
    "                    at 12, 2.4 million at 15); for surface schemes\n"
    "                    (catmull-clark, loop) the vertex valences A..B (3..1000)\n"
    "  --edges A..B      points on edges of valence A..B (3 <= A <= B <= 1000)\n"
    "  --face            the point inside the face of two tets (split tetoct)\n"
    "  --links FILE      the vertex links in FILE, one per line (plantri ASCII or a\n"
    "                    name; '#' comments); '-' reads standard input; a link\n"
    "                    isomorphic to an earlier one (or one --vertices covers)\n"
    "                    is run once and counted as repeated\n"
    "options:\n"
    "  -s, --scheme S    a built-in scheme (mlca, tetoct, boxspline, ...; as\n"
    "                    `analyze --scheme`)\n"
    "  --stencil FILE    a stencil file instead of --scheme\n"
    "  --db FILE         the results store (default subspectra.db; created if\n"
    "                    missing; a file that is not a subspectra store is refused,\n"
    "                    and one that cannot be written is named as such: read-only\n"
    "                    file system or permissions, or locked by another program)\n"
    "  -j, --jobs N      threads (default: the number of processors; under MPI,\n"
    "                    of each computing rank: its machine's processors shared\n"
    "                    by the computing ranks there)\n"
    "  --part I/N        only part I of N (0 <= I < N): the enumeration is split\n"
    "                    into N disjoint parts covering every case, for N processes\n"
    "                    or machines; join their stores with `subspectra merge`\n"
    "  --tol T           relative tolerance for equal eigenvalues (default 1e-6;\n"
    "                    exact in the identity: 1.0000006e-6 is not 1e-6)\n"
    "  --depth D         hex subdivision depth of the Jacobian test (0..12, default "
    "6)\n"
    "  --diagonals D     major diagonals (boxspline): bfs (default) or proper; skew\n"
    "                    or center with --edges only\n"
    "  --certify         prove the verdicts (the exact path of `analyze --certify`);\n"
    "                    what cannot be proven is stored as undecided\n"
    "  --psi-depth N     judge psi itself on its polynomial pieces, as `analyze\n"
    "                    --psi-depth N` does (mlca, ccsolid vertices), the ring cut\n"
    "                    in boxes down to side 2^-N (0..8, default 0: not); the\n"
    "                    store keeps psi's verdict and shares, and what each verdict\n"
    "                    was judged on (`report --format json`)\n"
    "  --psi-tubes       with --certify and --psi-depth (mlca): prove the tubes\n"
    "                    round the spokes too, as `analyze --psi-tubes` (seconds\n"
    "                    per case); the identity says psi-tubes\n"
    "  --max-memory SIZE memory budget shared by the threads (K, M, G, T: powers of\n"
    "                    1000; default half the physical memory, 3/4 of ulimit -v\n"
    "                    and -d when set): a case whose estimate exceeds SIZE / N\n"
    "                    (N threads) is not run but reported as an error, with\n"
    "                    the estimate\n"
    "  --format F        text (default) or json: the final summary also as one\n"
    "                    JSON object on standard output\n";

/* (strings of their own: C's limit on a string literal's length) */
static const char *const sweep_usage_end =
    "  --progress        progress lines on standard error even when it is not a\n"
    "                    terminal (a line a second, for a log)\n"
    "  -q, --quiet       no progress lines (the summary and the messages of\n"
    "                    failed cases stay)\n"
    "  -h, --help        this text\n"
    "\n"
    "Progress (cases done / total, rate, ETA, failures so far; with --certify how\n"
    "many computed cases were proven) goes to standard error while it is a\n"
    "terminal (a live line; --progress: also to a file or a pipe, --quiet:\n"
    "never); otherwise only the final summary is printed.\n"
    "SIGINT or SIGTERM: the cases being computed are finished and stored, the\n"
    "summary printed, and the sweep ends (rerun the same command to resume);\n"
    "while the links are still being counted it ends at once, saying so.\n"
    "Exit status: 0 every case passes both conditions, 1 some case fails, is\n"
    "undecided or could not be analysed, 2 bad usage, a bad link or store file,\n"
    "or a case out of memory or beyond the memory budget (the others still run).\n";

static const char *const sweep_usage_mpi =
    "\n"
#if SS_HAVE_MPI
    "One MPI job: `mpirun -n R subspectra sweep ...` (or srun): rank 0 enumerates\n"
    "the cases, skips the stored ones, hands the rest out in small pieces to\n"
    "whichever rank asks next, and writes the one store --db; ranks 1..R-1\n"
    "compute.  Progress (a line a minute: mpirun's standard error is a pipe)\n"
    "and the summary come from rank 0 only.  A killed rank loses only its piece\n"
    "in flight; the same command resumes.  --jobs: threads of each computing\n"
    "rank.  With one rank, or without mpirun, the sweep runs as above.\n";
#else
    "This build has no MPI (meson option mpi): for several machines use --part\n"
    "and merge.\n";
#endif

enum {
  O_STENCIL = 256,
  O_VERT,
  O_EDGES,
  O_FACE,
  O_LINKS,
  O_DB,
  O_PART,
  O_TOL,
  O_DEPTH,
  O_DIAG,
  O_FORMAT,
  O_CERTIFY,
  O_PSI,
  O_TUBES,
  O_MAXMEM,
  O_PROGRESS
};

static const struct option sweep_options[] = {
    {"scheme", required_argument, NULL, 's'},
    {"stencil", required_argument, NULL, O_STENCIL},
    {"vertices", required_argument, NULL, O_VERT},
    {"edges", required_argument, NULL, O_EDGES},
    {"face", no_argument, NULL, O_FACE},
    {"links", required_argument, NULL, O_LINKS},
    {"db", required_argument, NULL, O_DB},
    {"jobs", required_argument, NULL, 'j'},
    {"part", required_argument, NULL, O_PART},
    {"tol", required_argument, NULL, O_TOL},
    {"depth", required_argument, NULL, O_DEPTH},
    {"diagonals", required_argument, NULL, O_DIAG},
    {"format", required_argument, NULL, O_FORMAT},
    {"certify", no_argument, NULL, O_CERTIFY},
    {"psi-depth", required_argument, NULL, O_PSI},
    {"psi-tubes", no_argument, NULL, O_TUBES},
    {"max-memory", required_argument, NULL, O_MAXMEM},
    {"progress", no_argument, NULL, O_PROGRESS},
    {"quiet", no_argument, NULL, 'q'},
    {"help", no_argument, NULL, 'h'},
    {NULL, 0, NULL, 0}};

/* One option c (its argument in optarg) into o: -1 to go on, else the exit
 * status (0 after --help, 2 with the message printed). */
static int parse_option(int c, char **argv, ss_sweep_opts *o) {
  switch (c) {
  case 's':
    o->scheme = optarg;
    break;
  case O_STENCIL:
    o->stencil = optarg;
    break;
  case O_VERT:
    if (ss_cli_parse_range(optarg, &o->va, &o->vb) || o->va > o->vb)
      return ss_cli_usage_error("sweep", "--vertices '%s' is not A..B with A <= B",
                                optarg);
    o->vtext = optarg;
    break;
  case O_EDGES:
    if (ss_cli_parse_range(optarg, &o->ea, &o->eb) || o->ea < 3 || o->eb > 1000 ||
        o->ea > o->eb)
      return ss_cli_usage_error(
          "sweep", "--edges '%s' is not A..B with 3 <= A <= B <= 1000", optarg);
    break;
  case O_FACE:
    o->face = 1;
    break;
  case O_LINKS:
    o->links = optarg;
    break;
  case O_DB:
    o->db = optarg;
    break;
  case 'j':
    if (ss_cli_parse_int(optarg, 1, 1024, &o->jobs))
      return ss_cli_usage_error("sweep", "--jobs '%s' is not an integer in 1..1024",
                                optarg);
    o->jobs_given = 1;
    break;
  case O_PART:
    if (ss_cli_parse_part(optarg, &o->part, &o->nparts))
      return ss_cli_usage_error("sweep", "--part '%s': need integers 0 <= I < N", optarg);
    break;
  case O_TOL:
    if (ss_cli_opt_tol("sweep", optarg, &o->tol)) return SS_EXIT_USAGE;
    break;
  case O_DEPTH:
    if (ss_cli_opt_depth("sweep", optarg, &o->depth)) return SS_EXIT_USAGE;
    break;
  case O_DIAG:
    if (ss_diag_parse(optarg, &o->diag))
      return ss_cli_usage_error(
          "sweep", "--diagonals: expected bfs, proper, skew or center, not '%s'", optarg);
    o->diag_given = 1;
    break;
  case O_CERTIFY:
    o->certify = 1;
    break;
  case O_PSI:
    if (ss_cli_parse_int(optarg, 0, 8, &o->psi_depth))
      return ss_cli_usage_error(
          "sweep", "--psi-depth: expects an integer in 0..8, not '%s'", optarg);
    break;
  case O_TUBES:
    o->psi_tubes = 1;
    break;
  case O_MAXMEM:
    if (ss_cli_parse_bytes(optarg, &o->max_memory))
      return ss_cli_usage_error(
          "sweep", "--max-memory: expected a size such as 8G, 500M or 2.5G, not '%s'",
          optarg);
    break;
  case O_PROGRESS:
    o->progress = 1;
    break;
  case 'q':
    o->quiet = 1;
    break;
  case O_FORMAT:
    if (ss_cli_format_option("sweep", optarg, &o->json)) return SS_EXIT_USAGE;
    break;
  case 'h':
    fputs(sweep_usage, stdout);
    fputs(sweep_usage_end, stdout);
    fputs(sweep_usage_mpi, stdout);
    return SS_EXIT_OK;
  default:
    return ss_cli_option_error("sweep", c, argv);
  }
  return -1;
}

int ss_sweep_parse(int argc, char **argv, ss_sweep_opts *o) {
  *o = (ss_sweep_opts){.db = "subspectra.db",
                       .vb = -1,
                       .eb = -1,
                       .jobs = omp_get_num_procs(),
                       .nparts = 1,
                       .depth = SS_JAC_DEPTH,
                       .tol = 1e-6,
                       .diag = SS_DIAG_BFS};
  optind = 1;
  opterr = 0;
  int c;
  while ((c = getopt_long(argc, argv, ":hs:j:q", sweep_options, NULL)) != -1) {
    const int rc = parse_option(c, argv, o);
    if (rc >= 0) return rc;
  }
  if (optind < argc)
    return ss_cli_usage_error("sweep", "unexpected argument '%s'", argv[optind]);
  if (o->psi_tubes && (!o->certify || !o->psi_depth))
    return ss_cli_usage_error("sweep", "--psi-tubes needs --certify and a --psi-depth "
                                       "of at least 1");
  if (o->progress && o->quiet)
    return ss_cli_usage_error("sweep", "--progress and --quiet: give one of them");
  if (ss_cli_opt_scheme_source("sweep", o->scheme, o->stencil)) return SS_EXIT_USAGE;
  if (!o->vtext && o->eb < o->ea && !o->face && !o->links)
    return ss_cli_usage_error("sweep",
                              "no cases: give --vertices, --edges, --face or --links");
  return -1;
}

const char *ss_sweep_check_cases(const ss_sweep_opts *o, const ss_scheme *s, int volume,
                                 int reads, char *msg, size_t n) {
  if (o->vtext && volume && (o->va < 4 || o->vb > SS_ENUM_MAXK)) {
    snprintf(msg, n, "--vertices '%s': links have 4..%d vertices", o->vtext,
             SS_ENUM_MAXK);
    return msg;
  }
  if (o->vtext && !volume && (o->va < 3 || o->vb > 1000)) {
    snprintf(msg, n, "--vertices '%s': surface valences are 3..1000", o->vtext);
    return msg;
  }
  if (!volume && (o->eb >= o->ea || o->face || o->links))
    return "--edges, --face and --links need a volumetric scheme";
  if (o->face && ss_scheme_split_kind(s) != SS_SPLIT_TETOCT)
    return "--face: the scheme does not split tets (tetoct split)";
  if (o->diag_given && !reads) return "--diagonals: the scheme reads no major diagonals";
  if ((o->diag == SS_DIAG_SKEW || o->diag == SS_DIAG_CENTER) &&
      (o->vtext || o->face || o->links))
    return "--diagonals skew and center are defined around an edge: --edges only";
  return NULL;
}
