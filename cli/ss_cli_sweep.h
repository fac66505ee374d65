/* ss_cli_sweep.h — the interface of `subspectra sweep`'s files, private to
 * the command-line tool.  Each file uses only those after it:
 *  - ss_cli_sweep.c: the command's entry, the threaded sweep or MPI;
 *  - ss_cli_sweep_mpi.c: the MPI driver (built only with MPI);
 *  - ss_cli_sweep_run.c: the sweep's life and the steps of a case;
 *  - ss_cli_sweep_opts.c: the options, parsed once (ss_sweep_opts).
 *
 * A sweep is opened from the command line (options, scheme, --links, the
 * store, the count of cases), run (its cases enumerated in order and queued;
 * each full queue handed to the sweep's flush), and closed (the summary and
 * the exit status).  One case goes through three steps that the drivers
 * share: ss_sweep_prepare (canonical link, already stored?), ss_sweep_compute
 * (the analysis; any thread or process) and ss_sweep_record (store it, count
 * it, progress).  The threaded flush does the three in each thread; under MPI
 * rank 0 prepares and records, and the other ranks compute.
 *
 * What the command line says (ss_sweep_opts) is parsed once and then only
 * read; what the run changes (the store, the queue, the counts, the threads
 * in use) is the rest of ss_sweep. */
#ifndef SS_CLI_SWEEP_H
#define SS_CLI_SWEEP_H

#include <stddef.h>
#include <stdint.h>

#include "ss_diag.h"
#include "ss_link.h"
#include "ss_result.h"
#include "ss_store.h"

enum { SS_SWEEP_CHUNK = 512 }; /* cases queued before a flush */

/* The command line of sweep, as given (ss_sweep_parse). */
typedef struct {
  const char *scheme, *stencil; /* --scheme or --stencil */
  const char *links;            /* --links FILE, or NULL */
  const char *db;               /* --db: the store's file name */
  const char *vtext;            /* --vertices as given, or NULL */
  long va, vb;                  /* --vertices A..B */
  long ea, eb;                  /* --edges A..B (eb < ea: none) */
  long jobs;                    /* --jobs (default: the processors) */
  long part, nparts;            /* --part I/N */
  long depth;                   /* --depth */
  int face;                     /* --face */
  double tol;                   /* --tol */
  double max_memory;            /* --max-memory, 0: the default budget */
  ss_diag_mode diag;            /* --diagonals */
  int diag_given;               /* --diagonals was given */
  int json;                     /* --format json */
  int certify;                  /* --certify */
  long psi_depth;               /* --psi-depth (0: psi not judged) */
  int psi_tubes;                /* --psi-tubes */
  int jobs_given;               /* --jobs was given */
  int progress;                 /* --progress: progress lines even when stderr
                                   is not a terminal (one a second) */
  int quiet;                    /* --quiet: no progress lines (the summary and
                                   the failed cases' messages stay) */
} ss_sweep_opts;

/* argv (`sweep` and its options) into *o (ss_cli_sweep_opts.c): -1 to go
 * on, else the exit status (0 after --help, which prints the usage; 2 with
 * the message printed). */
int ss_sweep_parse(int argc, char **argv, ss_sweep_opts *o);

/* Whether the cases o asks for exist for scheme s (volume: volumetric;
 * reads: reads major diagonals): NULL, or why not (in msg, n bytes, or a
 * constant). */
const char *ss_sweep_check_cases(const ss_sweep_opts *o, const ss_scheme *s, int volume,
                                 int reads, char *msg, size_t n);

/* One case to run. */
typedef struct {
  ss_case_kind kind; /* the case */
  int n;             /* edge or surface valence */
  ss_link *link;     /* vertex case: the link (owned) */
} ss_sweep_job;

/* What a process of the sweep does (ss_sweep_open). */
typedef enum {
  SS_SWEEP_WHOLE = 0, /* everything: the threaded sweep, or MPI rank 0 */
  SS_SWEEP_WORKER     /* an MPI rank > 0: options and scheme only (no
                         --links, no store, no count: rank 0 has them) */
} ss_sweep_role;

typedef struct ss_sweep ss_sweep;

/* The threads' workspaces: thread t analyses every case of the sweep in
 * slot[t] (ss_result_compute_ws), made at its first case. */
typedef struct {
  ss_pipeline_workspace **slot; /* n workspaces (NULL until used) */
  int n;                        /* slots (grown to the highest thread number) */
} ss_sweep_wspool;

/* A sweep in progress. */
struct ss_sweep {
  ss_sweep_opts opt;          /* the command line (only read once opened) */
  ss_scheme *s;               /* the scheme (owned; read-only, shared by the threads) */
  int volume;                 /* the scheme is volumetric (--vertices enumerates links) */
  char ident[256];            /* the scheme's identity in the store */
  ss_result_opts ro;          /* analysis options, with this process's memory
                                 budget of one case */
  int jobs;                   /* threads in use (of each rank under MPI) */
  int ranks;                  /* MPI processes computing (1 without MPI) */
  ss_store *st;               /* the store (owned; NULL on a worker) */
  int64_t id;                 /* the scheme's id in the store */
  ss_link **links;            /* --links, repeats dropped (owned) */
  size_t nlinks;              /* how many */
  size_t dups;                /* --links dropped as repeats */
  void (*flush)(ss_sweep *w); /* runs (or hands out) the queued cases and
                                 empties the queue; threads by default */
  void *flush_ctx;            /* the flush's own state (MPI) */
  ss_sweep_job chunk[SS_SWEEP_CHUNK];   /* cases waiting to be run */
  size_t nchunk;                        /* how many */
  size_t total;                         /* cases in this sweep (this part) */
  int counting_stopped;                 /* a signal came while counting */
  size_t computed;                      /* cases analysed and stored now */
  size_t skipped;                       /* cases found in the store */
  size_t pass, fail, undecided, errors; /* verdicts (stored cases included) */
  size_t proven;         /* of the computed cases, those whose verdict is proven
                            (--certify) */
  size_t nomem;          /* of the errors, cases out of memory or beyond the budget */
  double t0, last;       /* start, last progress line (seconds) */
  int tty;               /* stderr is a terminal: show progress */
  double log_every;      /* > 0 (not tty): a progress line this often (seconds),
                            for a log (MPI: rank 0's stderr is never a terminal) */
  int stop;              /* a store error happened: run nothing more */
  ss_error fatal;        /* that error */
  ss_sweep_wspool *pool; /* the threads' workspaces (owned; NULL when out of
                            memory: each case allocates its own) */
};

/* Parse argv (ss_sweep_parse), load the scheme, check the options
 * against it and, for SS_SWEEP_WHOLE, read --links, open the store, install
 * the SIGINT/SIGTERM handler and count the cases.  Returns -1 with *out
 * (owned: ss_sweep_close) when the sweep is to run, otherwise the exit status
 * (--help: 0; a message was printed). */
int ss_sweep_open(int argc, char **argv, ss_sweep_role role, ss_sweep **out);

/* Queue every case of this part in order, flushing each full queue and the
 * last; stops early on a signal or a store error. */
void ss_sweep_run(ss_sweep *w);

/* Print the summary (and the JSON object), free w and return the exit
 * status.  Does not raise the signal that interrupted the sweep: the caller
 * does (ss_sweep_interrupted), after anything it must still close. */
int ss_sweep_close(ss_sweep *w);

/* Close a worker's sweep (no summary). */
void ss_sweep_free(ss_sweep *w);

/* The signal (SIGINT, SIGTERM) that asked the sweep to stop, or 0. */
int ss_sweep_interrupted(void);

/* Die of the signal that interrupted the sweep, if any, as the shell
 * expects of an interrupted program. */
void ss_sweep_raise(void);

/* Step 1 of a case: its canonical link (vertex cases) and whether the store
 * already has it (then it is counted).  Returns 1 if the case is to be
 * computed, with *canon its canonical link (owned by the caller; NULL for
 * other cases); 0 if it is done with (stored, an error already counted, a
 * stop or a signal).  Thread-safe (the store is used in a critical
 * section). */
int ss_sweep_prepare(ss_sweep *w, const ss_sweep_job *j, char **canon);

/* Step 2: analyse the case exactly as `analyze` does.  Needs only w's
 * scheme and options, so it runs on any thread or rank. */
ss_status ss_sweep_compute(const ss_sweep *w, const ss_sweep_job *j, ss_result *r,
                           ss_error *err);

/* Step 3: store r (s == SS_OK) or report the error err (s != SS_OK: the case
 * kind, valence n and canonical link canon name it), count it and update the
 * progress line.  Thread-safe.  r is not freed. */
void ss_sweep_record(ss_sweep *w, ss_case_kind kind, int n, const char *canon,
                     ss_status s, const ss_result *r, const ss_error *err);

/* Free the queued cases' links and empty the queue. */
void ss_sweep_clear_chunk(ss_sweep *w);

#if SS_HAVE_MPI
/* Whether this process was started by an MPI launcher (mpirun, mpiexec,
 * srun with PMI/PMIx): only then is MPI initialised. */
int ss_sweep_mpi_launched(void);
/* `sweep` under an MPI launcher (ss_cli_sweep_mpi.c): one rank behaves as
 * the threaded sweep; with more, rank 0 hands out the cases and writes the
 * store, the others compute. */
int ss_sweep_mpi(int argc, char **argv);
#endif

#endif
