/* ss_cli_sweep_mpi.c — `subspectra sweep` as one MPI job (mpirun, srun):
 * built only when Meson finds MPI (option mpi, define SS_HAVE_MPI).
 *
 * Rank 0 writes the one store; the other ranks only compute.  Why not a
 * store per rank, merged at the end: SQLite's locking is unreliable on the
 * network file systems that ranks on several machines share (the SQLite
 * FAQ), a store per rank left behind by a killed job would have to be found
 * and merged before a rerun could skip its cases, and rank 0 has the time:
 * measured (README), rank 0 spent a tenth of the CPU time of one computing
 * rank on a sweep with two, polling included, and the canonical form of a
 * k = 12 link (to skip stored cases) costs about 20 us against about 30 ms
 * for its analysis.  So the result is exactly the store of the threaded
 * sweep, resumed exactly as it is.
 *
 * Work is handed out dynamically: rank 0 enumerates the cases as the
 * threaded sweep does (ss_sweep_run: same order, same --part), drops those
 * already stored (ss_sweep_prepare), and gives the rest out in small pieces
 * (PIECE cases per thread of the asking rank) to whichever rank asks next:
 * a rank asks by sending back the results of its last piece, so a slow rank
 * takes fewer pieces and never holds the others.  A rank killed mid-run
 * loses only its piece in flight (mpirun then ends the job); everything
 * received before is committed, and the same command resumes.  A rank that
 * a signal stops alone gives back the cases of its piece it did not start,
 * and rank 0 hands them to the others.  Rank 0
 * prints the progress, the messages of failed cases and the summary.
 *
 * Messages are raw bytes: every rank runs the same binary (an ss_result is
 * sent as its struct, its link text after it), as mpirun starts it.
 *
 * One rank (mpirun -n 1, or srun of a single task) is the threaded sweep,
 * unchanged. */
#include <mpi.h>
#include <omp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "ss_cli.h"
#include "ss_cli_sweep.h"

enum {
  PIECE = 4,    /* cases handed out per thread of a rank */
  TAG_WORK = 1, /* rank 0 -> rank: a piece of cases */
  TAG_STOP,     /* rank 0 -> rank: no more work */
  TAG_DONE,     /* rank -> rank 0: results of a piece (the first: none) */
  NOT_RUN = -1  /* a case's status when a signal stopped it before it ran */
};

int ss_sweep_mpi_launched(void) {
  /* OpenMPI's mpirun sets OMPI_COMM_WORLD_SIZE, PMIx launchers (mpirun,
   * srun --mpi=pmix) PMIX_RANK */
  return getenv("OMPI_COMM_WORLD_SIZE") != NULL || getenv("PMIX_RANK") != NULL;
}

/* A growing byte buffer for messages. */
typedef struct {
  unsigned char *p; /* the bytes (owned) */
  size_t n;         /* bytes used */
  size_t cap;       /* bytes allocated */
  size_t at;        /* read position */
  int bad;          /* out of memory, or a read past the end */
} buf;

static void put(buf *b, const void *x, size_t n) {
  if (b->bad) return;
  if (b->n + n > b->cap) {
    size_t cap = b->cap ? 2 * b->cap : 4096;
    while (cap < b->n + n)
      cap *= 2;
    unsigned char *q = realloc(b->p, cap);
    if (!q) {
      b->bad = 1;
      return;
    }
    b->p = q;
    b->cap = cap;
  }
  if (x && n) memcpy(b->p + b->n, x, n); /* (x NULL: room only) */
  b->n += n;
}

static void put_i(buf *b, int32_t x) {
  put(b, &x, sizeof x);
}

static void put_s(buf *b, const char *s) {
  const uint32_t n = s ? (uint32_t)strlen(s) : 0;
  put(b, &n, sizeof n);
  put(b, s, n);
}

static void get(buf *b, void *x, size_t n) {
  if (b->bad || b->n - b->at < n) {
    b->bad = 1;
    memset(x, 0, n);
    return;
  }
  memcpy(x, b->p + b->at, n);
  b->at += n;
}

static int32_t get_i(buf *b) {
  int32_t x;
  get(b, &x, sizeof x);
  return x;
}

/* A string of the message (malloc'd, NUL-terminated), or NULL. */
static char *get_s(buf *b) {
  uint32_t n;
  get(b, &n, sizeof n);
  if (b->bad || b->n - b->at < n) {
    b->bad = 1;
    return NULL;
  }
  char *s = malloc((size_t)n + 1);
  if (!s) {
    b->bad = 1;
    return NULL;
  }
  memcpy(s, b->p + b->at, n);
  s[n] = '\0';
  b->at += n;
  return s;
}

static void nap(void) {
  const struct timespec ts = {0, 500000}; /* 0.5 ms */
  nanosleep(&ts, NULL);
}

/* Wait for a message (from src, any tag) without spinning: OpenMPI's
 * blocking receive polls at full speed, which would take a core from the
 * computing ranks of an oversubscribed machine. */
static void wait_msg(int src, MPI_Status *stat) {
  int flag = 0;
  for (;;) {
    MPI_Iprobe(src, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, stat);
    if (flag) return;
    nap();
  }
}

static void wait_req(MPI_Request *req) {
  int flag = 0;
  for (;;) {
    MPI_Test(req, &flag, MPI_STATUS_IGNORE);
    if (flag) return;
    nap();
  }
}

/* Post the receive of the message stat announces into b (emptied first),
 * without waiting for it: *rq completes when it is all there. */
static void post_recv(buf *b, const MPI_Status *stat, MPI_Request *rq) {
  int n = 0;
  MPI_Get_count(stat, MPI_BYTE, &n);
  b->n = b->at = 0;
  b->bad = 0;
  put(b, NULL, (size_t)n);
  MPI_Irecv(b->bad ? NULL : b->p, b->bad ? 0 : n, MPI_BYTE, stat->MPI_SOURCE,
            stat->MPI_TAG, MPI_COMM_WORLD, rq);
}

/* Receive the message stat announces into b (emptied first). */
static void recv_into(buf *b, const MPI_Status *stat) {
  MPI_Request rq;
  post_recv(b, stat, &rq);
  wait_req(&rq);
}

/* A case handed out, as rank 0 remembers it until its result comes. */
typedef struct {
  ss_case_kind kind; /* the case */
  int n;             /* edge or surface valence */
  char *canon;       /* vertex: canonical link text (owned); else NULL */
} sent;

/* Rank 0's state. */
typedef struct {
  int size;        /* ranks */
  int *alive;      /* per rank: still takes work */
  int *idle;       /* per rank: has no piece (its last message was received) */
  int *threads;    /* per rank: its threads */
  sent **fly;      /* per rank: the cases it computes now (owned) */
  size_t *nfly;    /* per rank: how many */
  int nalive;      /* ranks > 0 still alive */
  sent *pending;   /* prepared cases not yet handed out: pending[head..npend) */
  size_t head;     /* the next to hand out */
  size_t npend;    /* end of the queue */
  size_t cap;      /* room in pending */
  buf *in;         /* per rank: its message being received */
  MPI_Request *rq; /* per rank: the receive posted for it, or
                      MPI_REQUEST_NULL */
  buf out;         /* the message being sent */
  int oom;         /* out of memory */
} coord;

/* Queue case j (taking its canon) to be handed out; 0, or -1 out of memory. */
static int push(coord *c, sent *j) {
  if (c->npend == c->cap) {
    sent *p = realloc(c->pending, 2 * c->cap * sizeof *p);
    if (!p) return -1;
    c->pending = p;
    c->cap *= 2;
  }
  c->pending[c->npend++] = *j;
  j->canon = NULL;
  return 0;
}

/* Take in the results of rank r's message (in c->in[r]) and record them.  The
 * cases a leaving rank did not run go back in the queue for the others. */
static void take_results(ss_sweep *w, coord *c, int r) {
  buf *b = &c->in[r];
  c->threads[r] = get_i(b);
  const int leaving = get_i(b);
  const int32_t count = get_i(b);
  for (int32_t i = 0; i < count && !b->bad && (size_t)i < c->nfly[r]; i++) {
    sent *j = &c->fly[r][i];
    const int32_t st = get_i(b);
    if (st == NOT_RUN) {
      if (leaving && !ss_sweep_interrupted() && push(c, j)) c->oom = 1;
      continue;
    }
    ss_result res;
    ss_error err = {0};
    memset(&res, 0, sizeof res);
    if (st == SS_OK) {
      get(b, &res, sizeof res);
      res.link = get_s(b);
    } else {
      char *msg = get_s(b);
      err.status = (ss_status)st;
      snprintf(err.msg, sizeof err.msg, "%s", msg ? msg : "?");
      free(msg);
    }
    if (b->bad) break;
    ss_sweep_record(w, j->kind, j->n, j->canon, (ss_status)st, &res, &err);
    free(res.link);
  }
  if (b->bad && !w->stop) {
    w->stop = 1;
    snprintf(w->fatal.msg, sizeof w->fatal.msg,
             "a malformed or unreadable message from MPI rank %d (out of memory?)", r);
  }
  for (size_t i = 0; i < c->nfly[r]; i++)
    free(c->fly[r][i].canon);
  c->nfly[r] = 0;
  c->idle[r] = 1;
  if (leaving && c->alive[r]) {
    c->alive[r] = 0;
    c->nalive--;
  }
}

/* Receive one whole message from a rank with a piece, record its results.
 * Each rank's message is received into its own buffer without blocking: a
 * message over the eager limit (a piece's results: about 2 kB per case)
 * comes in fragments that only its sender can push, so a blocking receive
 * would let one stopped or descheduled sender hold every other rank's
 * results, and their next pieces, until it runs again (test_sweep_mpi
 * stops a rank with SIGSTOP and found exactly that). */
static void receive_one(ss_sweep *w, coord *c) {
  for (;;) {
    for (int q = 1; q < c->size; q++) {
      int done = 0;
      if (c->rq[q] == MPI_REQUEST_NULL) continue;
      MPI_Test(&c->rq[q], &done, MPI_STATUS_IGNORE); /* done: rq[q] = NULL */
      if (done) {
        take_results(w, c, q);
        return;
      }
    }
    /* a rank sends one message per piece and waits for the answer, so a
     * message probed here is never one whose receive is posted already */
    MPI_Status stat;
    int flag = 0;
    MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &stat);
    if (flag)
      post_recv(&c->in[stat.MPI_SOURCE], &stat, &c->rq[stat.MPI_SOURCE]);
    else
      nap();
  }
}

/* Hand the pending cases out, a piece to each rank that asks. */
static void hand_out(ss_sweep *w, coord *c) {
  while (c->head < c->npend && !ss_sweep_interrupted() && !w->stop && !c->oom &&
         c->nalive > 0) {
    int r = 0;
    for (int q = 1; q < c->size && !r; q++)
      if (c->alive[q] && c->idle[q]) r = q;
    if (!r) {
      receive_one(w, c);
      continue;
    }
    size_t m = (size_t)PIECE * (size_t)(c->threads[r] > 0 ? c->threads[r] : 1);
    if (m > c->npend - c->head) m = c->npend - c->head;
    sent *f = realloc(c->fly[r], m * sizeof *f);
    if (!f) {
      c->oom = 1;
      break;
    }
    c->fly[r] = f;
    buf *b = &c->out;
    b->n = 0;
    put_i(b, (int32_t)m);
    for (size_t i = 0; i < m; i++) {
      const sent *j = &c->pending[c->head + i];
      put_i(b, (int32_t)j->kind);
      put_i(b, j->n);
      put_s(b, j->canon);
    }
    if (b->bad) {
      c->oom = 1;
      break;
    }
    MPI_Send(b->p, (int)b->n, MPI_BYTE, r, TAG_WORK, MPI_COMM_WORLD);
    memcpy(f, c->pending + c->head, m * sizeof *f);
    c->nfly[r] = m;
    c->idle[r] = 0;
    c->head += m;
  }
  /* what was not handed out (a stop) stays for a rerun */
  for (size_t i = c->head; i < c->npend; i++)
    free(c->pending[i].canon);
  c->head = c->npend = 0;
  if (c->oom && !w->stop) {
    w->stop = 1;
    snprintf(w->fatal.msg, sizeof w->fatal.msg, "out of memory handing out cases");
  }
}

/* Rank 0's flush: prepare the queued cases (drop the stored ones) and hand
 * them out. */
static void flush_mpi(ss_sweep *w) {
  coord *c = w->flush_ctx;
  for (size_t i = 0; i < w->nchunk; i++) {
    char *canon = NULL;
    if (!ss_sweep_prepare(w, &w->chunk[i], &canon)) continue;
    sent j = {w->chunk[i].kind, w->chunk[i].n, canon};
    if (push(c, &j)) {
      free(canon);
      c->oom = 1;
    }
  }
  ss_sweep_clear_chunk(w);
  hand_out(w, c);
}

/* Rank 0 after the last case: wait for every piece out (handing out again
 * what a leaving rank gave back), then stop the ranks. */
static void finish(ss_sweep *w, coord *c) {
  for (;;) {
    hand_out(w, c);
    int busy = 0;
    for (int q = 1; q < c->size; q++)
      busy |= c->alive[q] && !c->idle[q];
    if (!busy) break;
    receive_one(w, c);
  }
  for (int q = 1; q < c->size; q++)
    if (c->alive[q]) MPI_Send(NULL, 0, MPI_BYTE, q, TAG_STOP, MPI_COMM_WORLD);
}

static void coord_free(coord *c) {
  for (int q = 0; c->fly && q < c->size; q++) {
    for (size_t i = 0; i < c->nfly[q]; i++)
      free(c->fly[q][i].canon);
    free(c->fly[q]);
  }
  free(c->fly);
  free(c->nfly);
  free(c->alive);
  free(c->idle);
  free(c->threads);
  free(c->pending);
  for (int q = 0; c->in && q < c->size; q++)
    free(c->in[q].p);
  free(c->in);
  free(c->rq);
  free(c->out.p);
}

static int coord_init(coord *c, int size) {
  *c = (coord){.size = size, .nalive = size - 1};
  c->alive = calloc((size_t)size, sizeof *c->alive);
  c->idle = calloc((size_t)size, sizeof *c->idle);
  c->threads = calloc((size_t)size, sizeof *c->threads);
  c->fly = calloc((size_t)size, sizeof *c->fly);
  c->nfly = calloc((size_t)size, sizeof *c->nfly);
  c->in = calloc((size_t)size, sizeof *c->in);
  c->rq = malloc((size_t)size * sizeof *c->rq);
  c->cap = SS_SWEEP_CHUNK;
  c->pending = calloc(c->cap, sizeof *c->pending);
  if (!c->alive || !c->idle || !c->threads || !c->fly || !c->nfly || !c->in || !c->rq ||
      !c->pending)
    return -1;
  for (int q = 0; q < size; q++)
    c->rq[q] = MPI_REQUEST_NULL;
  for (int q = 1; q < size; q++)
    c->alive[q] = 1; /* busy until its first (empty) message says it is ready */
  return 0;
}

/* A computing rank: ask for pieces, compute them with the threads, send the
 * results back, until rank 0 says stop (or a signal came). */
static void work(ss_sweep *w) {
  buf in = {0}, out = {0};
  ss_sweep_job *jobs = NULL;
  ss_result *res = NULL;
  int *st = NULL; /* per case: an ss_status, or NOT_RUN */
  ss_error *errs = NULL;
  int32_t count = 0;
  for (;;) {
    /* the results of the last piece (none the first time): also the request
     * for the next */
    int leaving = ss_sweep_interrupted() != 0;
    out.n = 0;
    out.bad = 0;
    put_i(&out, w->jobs);
    put_i(&out, leaving);
    put_i(&out, count);
    for (int32_t i = 0; i < count; i++) {
      put_i(&out, st[i]);
      if (st[i] == SS_OK) {
        ss_result r = res[i];
        r.link = NULL;
        put(&out, &r, sizeof r);
        put_s(&out, res[i].link);
      } else if (st[i] != NOT_RUN)
        put_s(&out, errs[i].msg);
    }
    for (int32_t i = 0; i < count; i++) {
      ss_result_clear(&res[i]);
      ss_link_free(jobs[i].link);
    }
    count = 0;
    if (out.bad) {
      /* out of memory for the message: leave with no results (the piece
       * stays for a rerun); three integers fit in what was there */
      leaving = 1;
      out.n = 0;
      out.bad = 0;
      put_i(&out, w->jobs);
      put_i(&out, leaving);
      put_i(&out, 0);
      if (out.bad) break;
    }
    MPI_Send(out.p, (int)out.n, MPI_BYTE, 0, TAG_DONE, MPI_COMM_WORLD);
    if (leaving) break;
    MPI_Status stat;
    wait_msg(0, &stat);
    recv_into(&in, &stat);
    if (stat.MPI_TAG == TAG_STOP) break;
    const int32_t m = get_i(&in);
    free(jobs);
    free(res);
    free(st);
    free(errs);
    jobs = calloc(m > 0 ? (size_t)m : 1, sizeof *jobs);
    res = calloc(m > 0 ? (size_t)m : 1, sizeof *res);
    st = calloc(m > 0 ? (size_t)m : 1, sizeof *st);
    errs = calloc(m > 0 ? (size_t)m : 1, sizeof *errs);
    for (int32_t i = 0; i < m && jobs && res && st && errs && !in.bad; i++) {
      jobs[i].kind = (ss_case_kind)get_i(&in);
      jobs[i].n = get_i(&in);
      char *text = get_s(&in);
      if (text && *text)
        st[i] = ss_link_parse(text, &jobs[i].link, &errs[i]);
      else if (jobs[i].kind == SS_CASE_VERTEX && !in.bad) {
        st[i] = SS_EINTERNAL;
        snprintf(errs[i].msg, sizeof errs[i].msg, "no link received");
      }
      free(text);
      count = i + 1;
    }
    if (!jobs || !res || !st || !errs || in.bad) {
      /* what was read is answered (as errors where nothing could be read);
       * the rest of the piece stays for a rerun */
      for (int32_t i = 0; st && errs && i < count; i++)
        if (!st[i]) {
          st[i] = SS_ENOMEM;
          snprintf(errs[i].msg, sizeof errs[i].msg, "out of memory reading the case");
        }
      if (!jobs || !res || !st || !errs) count = 0;
      continue;
    }
#pragma omp parallel for schedule(dynamic, 1) num_threads(w->jobs)
    for (int32_t i = 0; i < count; i++) {
      if (st[i]) continue;
      if (ss_sweep_interrupted())
        st[i] = NOT_RUN;
      else
        st[i] = ss_sweep_compute(w, &jobs[i], &res[i], &errs[i]);
    }
  }
  for (int32_t i = 0; i < count; i++) {
    ss_result_clear(&res[i]);
    ss_link_free(jobs[i].link);
  }
  free(jobs);
  free(res);
  free(st);
  free(errs);
  free(in.p);
  free(out.p);
}

/* Threads of this rank by default: the processors here shared by the
 * computing ranks on this machine; and the memory budget of one case: the
 * machine's budget shared by all their threads.  Collective. */
static void share_machine(ss_sweep *w, int rank) {
  MPI_Comm local;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank, MPI_INFO_NULL, &local);
  int mine = rank != 0, here = 0;
  MPI_Allreduce(&mine, &here, 1, MPI_INT, MPI_SUM, local);
  MPI_Comm_free(&local);
  if (here < 1) here = 1;
  if (!w->opt.jobs_given) {
    w->jobs = omp_get_num_procs() / here;
    if (w->jobs < 1) w->jobs = 1;
  }
  w->ro.max_bytes = ss_cli_budget(w->opt.max_memory) / ((double)w->jobs * here);
}

int ss_sweep_mpi(int argc, char **argv) {
  int provided = 0, rank = 0, size = 1;
  /* only the main thread calls MPI; the analysis threads never do */
  if (MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS) {
    fprintf(stderr, "subspectra sweep: MPI could not be initialised\n");
    return SS_EXIT_USAGE;
  }
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  ss_sweep *w = NULL;
  int rc = SS_EXIT_OK;
  if (size == 1) {
    rc = ss_sweep_open(argc, argv, SS_SWEEP_WHOLE, &w);
    if (rc < 0) {
      ss_sweep_run(w);
      rc = ss_sweep_close(w);
    }
    MPI_Finalize();
    ss_sweep_raise();
    return rc;
  }
  /* rank 0 opens the sweep and says whether to go on (and with what scheme
   * identity); the others stay silent about the options rank 0 judged */
  struct {
    int32_t go, rc;
    char ident[256];
  } hdr = {0, 0, ""};
  if (rank == 0) {
    rc = ss_sweep_open(argc, argv, SS_SWEEP_WHOLE, &w);
    hdr.go = rc < 0;
    hdr.rc = rc;
    if (w) memcpy(hdr.ident, w->ident, sizeof hdr.ident);
  }
  MPI_Request req;
  MPI_Ibcast(&hdr, (int)sizeof hdr, MPI_BYTE, 0, MPI_COMM_WORLD, &req);
  wait_req(&req);
  if (!hdr.go) {
    MPI_Finalize();
    if (rank == 0) ss_sweep_raise();
    return hdr.rc;
  }
  /* the other ranks load the scheme themselves (a --stencil file must be
   * there on every machine) and check it is rank 0's */
  int ok = 1;
  if (rank != 0) {
    rc = ss_sweep_open(argc, argv, SS_SWEEP_WORKER, &w);
    if (rc >= 0) {
      fprintf(stderr, "subspectra sweep: (MPI rank %d could not load the scheme)\n",
              rank);
      ok = 0;
    } else if (strcmp(w->ident, hdr.ident)) {
      fprintf(stderr,
              "subspectra sweep: MPI rank %d has the scheme %s, rank 0 has %s: give "
              "every machine the same --stencil file\n",
              rank, w->ident, hdr.ident);
      ok = 0;
    }
  }
  int all = 0;
  MPI_Allreduce(&ok, &all, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  if (all) share_machine(w, rank);
  int threads = rank ? w->jobs : 0, maxthreads = 1;
  if (all) MPI_Allreduce(&threads, &maxthreads, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  if (!all) {
    if (rank == 0)
      fprintf(stderr, "subspectra sweep: not every MPI rank could start; nothing run\n");
    ss_sweep_free(w);
    MPI_Finalize();
    return SS_EXIT_USAGE;
  }
  if (rank == 0) {
    coord c;
    if (coord_init(&c, size)) {
      w->stop = 1;
      snprintf(w->fatal.msg, sizeof w->fatal.msg, "out of memory");
      for (int q = 1; q < size; q++)
        MPI_Send(NULL, 0, MPI_BYTE, q, TAG_STOP, MPI_COMM_WORLD);
    } else {
      w->ranks = size - 1;
      w->jobs = maxthreads;
      w->flush = flush_mpi;
      w->flush_ctx = &c;
      /* mpirun passes standard error on through a pipe, whatever it is
       * itself: no live line, but a line a minute in the job's log */
      if (!w->tty && !w->opt.quiet && !w->opt.progress) w->log_every = 60;
      ss_sweep_run(w);
      finish(w, &c);
    }
    coord_free(&c);
    rc = ss_sweep_close(w);
  } else {
    work(w);
    ss_sweep_free(w);
  }
  /* every rank exits with rank 0's status, so mpirun's is the sweep's */
  hdr.rc = rank == 0 ? rc : 0;
  MPI_Ibcast(&hdr.rc, 1, MPI_INT, 0, MPI_COMM_WORLD, &req);
  wait_req(&req);
  MPI_Finalize();
  ss_sweep_raise();
  return hdr.rc;
}
