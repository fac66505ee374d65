/* ss_cli_sweep_run.c — the life of a sweep (open, run, close) and the
 * three steps of a case (prepare, compute, record), shared by the threaded
 * sweep and the MPI driver (ss_cli_sweep_mpi.c), both above this file.
 *
 * Work is cut into chunks of cases; by default (the threaded flush) each
 * chunk is analysed by an OpenMP parallel loop whose threads share the
 * read-only scheme and write through one store handle inside a critical
 * section.  A case already in the store (same scheme identity, kind, k and
 * canonical link) is skipped, so a rerun after any interruption computes
 * only what is missing, and every stored row is its own committed
 * transaction (ss_store.h), so a kill loses only the cases being computed at
 * that moment.  The options come parsed from ss_cli_sweep_opts.c. */
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <json-c/json.h>
#include <omp.h>

#include "ss_cli.h"
#include "ss_cli_sweep.h"
#include "ss_enum.h"
#include "ss_link.h"
#include "ss_result.h"
#include "ss_stencil.h"
#include "ss_store.h"

/* The signal that asked the sweep to stop (SIGINT, SIGTERM), or 0.  The one
 * piece of process-wide state: a signal handler can reach nothing else.  The
 * cases being computed finish and are stored; the rest is left for a rerun. */
static volatile sig_atomic_t interrupted;

static void on_signal(int sig) {
  interrupted = sig;
}

/* SIGINT and SIGTERM set `interrupted` from now on. */
static void catch_signals(void) {
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, NULL);
  sigaction(SIGTERM, &sa, NULL);
}

int ss_sweep_interrupted(void) {
  return interrupted;
}

void ss_sweep_raise(void) {
  if (!interrupted) return;
  fflush(stdout);
  const int sig = interrupted;
  signal(sig, SIG_DFL);
  raise(sig);
}

static void fmt_time(double s, char *buf, size_t n) {
  if (!isfinite(s) || s < 0) {
    snprintf(buf, n, "?");
    return;
  }
  long t = lround(s);
  if (t >= 3600)
    snprintf(buf, n, "%ldh%02ldm", t / 3600, t / 60 % 60);
  else if (t >= 60)
    snprintf(buf, n, "%ldm%02lds", t / 60, t % 60);
  else
    snprintf(buf, n, "%lds", t);
}

/* The progress line (on a terminal: one live line; for a log: a line every
 * log_every seconds); call inside the critical section. */
static void progress(ss_sweep *w, int force) {
  if (!w->tty && !(w->log_every > 0)) return;
  const double t = ss_cli_now();
  if (!force && t - w->last < (w->tty ? 0.25 : w->log_every)) return;
  w->last = t;
  const size_t done = w->computed + w->skipped + w->errors;
  const double rate = w->computed / (t - w->t0 > 1e-9 ? t - w->t0 : 1e-9);
  char eta[32];
  fmt_time(rate > 0 ? (double)(w->total - done) / rate : (double)NAN, eta, sizeof eta);
  char proven[64] = ""; /* a certified sweep: how many it proved so far */
  if (w->opt.certify)
    snprintf(proven, sizeof proven, "; %zu of %zu computed proven", w->proven,
             w->computed);
  fprintf(
      stderr,
      "%ssubspectra sweep: %zu/%zu cases (%.1f%%), %.1f cases/s, ETA %s; %zu fail, %zu "
      "undecided, %zu errors%s%s",
      w->tty ? "\r" : "", done, w->total,
      w->total ? 100.0 * (double)done / (double)w->total : 100.0, rate, eta, w->fail,
      w->undecided, w->errors, proven, w->tty ? "\033[K" : "\n");
}

static int job_k(const ss_sweep_job *j) {
  return j->kind == SS_CASE_VERTEX ? j->link->k : j->kind == SS_CASE_FACE ? 0 : j->n;
}

int ss_sweep_prepare(ss_sweep *w, const ss_sweep_job *j, char **canon) {
  *canon = NULL;
  if (interrupted) return 0;
  ss_error err = {0};
  int found = 0, stop = 0;
  ss_verdict_kind v = SS_PASS;
  ss_link *cl = NULL;
  ss_status s = SS_OK;
  if (j->kind == SS_CASE_VERTEX) {
    s = ss_link_canonical(j->link, &cl, NULL, &err);
    if (!s) s = ss_link_format(cl, canon, &err);
  }
  ss_link_free(cl);
#pragma omp critical(ss_sweep_store)
  {
    stop = w->stop;
    if (!stop && !s &&
        ss_store_has(w->st, w->id, j->kind, job_k(j), *canon, &found, &v, &w->fatal))
      w->stop = stop = 1;
    if (found) {
      w->skipped++;
      ++*(v == SS_PASS ? &w->pass : v == SS_FAIL ? &w->fail : &w->undecided);
      progress(w, 0);
    }
    if (s) {
      w->errors++;
      fprintf(stderr, "%ssubspectra sweep: %s: %s\n", w->tty ? "\r\033[K" : "",
              ss_case_name(j->kind), err.msg);
    }
  }
  if (stop || found || s) {
    free(*canon);
    *canon = NULL;
    return 0;
  }
  return 1;
}

/* The calling thread's workspace, made at its first case; NULL when out of
 * memory (the case then allocates its own, with the same result). */
static ss_pipeline_workspace *thread_ws(ss_sweep_wspool *p) {
  if (!p) return NULL;
  const int t = omp_get_thread_num();
  ss_pipeline_workspace *ws = NULL;
#pragma omp critical(ss_sweep_ws)
  {
    if (t >= p->n) {
      ss_pipeline_workspace **g = realloc(p->slot, (size_t)(t + 1) * sizeof *g);
      if (g) {
        for (int i = p->n; i <= t; i++)
          g[i] = NULL;
        p->slot = g;
        p->n = t + 1;
      }
    }
    if (t < p->n) {
      if (!p->slot[t]) p->slot[t] = ss_pipeline_workspace_new();
      ws = p->slot[t];
    }
  }
  return ws;
}

ss_status ss_sweep_compute(const ss_sweep *w, const ss_sweep_job *j, ss_result *r,
                           ss_error *err) {
  const ss_case c = {j->kind, j->link, j->n, w->opt.diag, 0};
  return ss_result_compute_ws(w->s, &c, &w->ro, thread_ws(w->pool), r, err);
}

void ss_sweep_record(ss_sweep *w, ss_case_kind kind, int n, const char *canon,
                     ss_status s, const ss_result *r, const ss_error *err) {
#pragma omp critical(ss_sweep_store)
  {
    if (s) {
      w->errors++;
      w->nomem += s == SS_ENOMEM;
      if (canon)
        fprintf(stderr, "%ssubspectra sweep: vertex %s: %s\n", w->tty ? "\r\033[K" : "",
                canon, err->msg);
      else
        fprintf(stderr, "%ssubspectra sweep: %s %d: %s\n", w->tty ? "\r\033[K" : "",
                ss_case_name(kind), n, err->msg);
    } else if (!w->stop) {
      int added = 0;
      if (ss_store_put(w->st, w->id, r, &added, &w->fatal))
        w->stop = 1;
      else {
        /* a case given twice (isomorphic links) is stored once */
        ++*(added ? &w->computed : &w->skipped);
        w->proven += added && ss_result_certified(r);
        const ss_verdict_kind v = ss_result_verdict(r);
        ++*(v == SS_PASS ? &w->pass : v == SS_FAIL ? &w->fail : &w->undecided);
      }
    }
    progress(w, 0);
  }
}

/* Run one case (in a worker thread). */
static void run_job(ss_sweep *w, const ss_sweep_job *j) {
  char *canon = NULL;
  if (!ss_sweep_prepare(w, j, &canon)) return;
  ss_error err = {0};
  ss_result r;
  const ss_status s = ss_sweep_compute(w, j, &r, &err);
  ss_sweep_record(w, j->kind, j->n, canon, s, &r, &err);
  ss_result_clear(&r);
  free(canon);
}

void ss_sweep_clear_chunk(ss_sweep *w) {
  for (size_t i = 0; i < w->nchunk; i++)
    ss_link_free(w->chunk[i].link);
  w->nchunk = 0;
}

/* The threaded flush: run the waiting cases in parallel and free them. */
static void flush_threads(ss_sweep *w) {
  const long n = (long)w->nchunk;
#pragma omp parallel for schedule(dynamic, 1) num_threads(w->jobs)
  for (long i = 0; i < n; i++)
    run_job(w, &w->chunk[i]);
  ss_sweep_clear_chunk(w);
}

/* Queue a case (the link is copied); runs the chunk when it is full. */
static int add(ss_sweep *w, ss_case_kind kind, int n, const ss_link *l) {
  if (w->stop || interrupted) return 1;
  ss_sweep_job *j = &w->chunk[w->nchunk];
  *j = (ss_sweep_job){kind, n, NULL};
  if (l && ss_link_copy(l, &j->link, &w->fatal)) {
    w->stop = 1;
    return 1;
  }
  if (++w->nchunk == SS_SWEEP_CHUNK) w->flush(w);
  return w->stop;
}

static int visit(const ss_link *l, void *ctx) {
  return add(ctx, SS_CASE_VERTEX, 0, l);
}

/* The links of --links, all read and checked before anything runs. */
typedef struct {
  ss_link **l;  /* the links */
  size_t n;     /* how many */
  size_t alloc; /* room for */
} linklist;

/* One link of --links appended (ss_cli_read_links: l is ours). */
static int take_link(ss_link *l, void *ctx) {
  linklist *ll = ctx;
  if (ll->n == ll->alloc) {
    const size_t alloc = ll->alloc ? 2 * ll->alloc : 64;
    ss_link **q = realloc(ll->l, alloc * sizeof *q);
    if (!q) {
      ss_link_free(l);
      return 1;
    }
    ll->l = q;
    ll->alloc = alloc;
  }
  ll->l[ll->n++] = l;
  return 0;
}

/* A link of --links by its canonical form, for finding repeats. */
typedef struct {
  char *canon; /* canonical plantri text (owned) */
  size_t i;    /* index in the list */
} canon_item;

static int canon_cmp(const void *pa, const void *pb) {
  const canon_item *a = pa, *b = pb;
  const int c = strcmp(a->canon, b->canon);
  return c ? c : (a->i > b->i) - (a->i < b->i);
}

/* Drop the links of ll that repeat an earlier one up to isomorphism (or, when
 * skip_hi >= skip_lo, have skip_lo..skip_hi vertices: --vertices enumerates
 * them); the first of each stays, in order.  *dropped counts the others.
 * Done before anything runs, so a repeat is neither computed twice nor
 * reported as found in the store. */
static int dedupe_links(linklist *ll, long skip_lo, long skip_hi, size_t *dropped) {
  *dropped = 0;
  const size_t n0 = ll->n;
  canon_item *c = calloc(n0 ? n0 : 1, sizeof *c);
  char *drop = calloc(ll->n ? ll->n : 1, 1);
  int rc = SS_EXIT_OK;
  if (!c || !drop) {
    fprintf(stderr, "subspectra sweep: out of memory\n");
    rc = SS_EXIT_FAIL;
    goto done;
  }
  for (size_t i = 0; i < ll->n; i++) {
    ss_error err = {0};
    ss_link *cl = NULL;
    c[i].i = i;
    if (ss_link_canonical(ll->l[i], &cl, NULL, &err) ||
        ss_link_format(cl, &c[i].canon, &err)) {
      ss_link_free(cl);
      fprintf(stderr, "subspectra sweep: --links: %s\n", err.msg);
      rc = err.status == SS_ENOMEM ? SS_EXIT_FAIL : SS_EXIT_USAGE;
      goto done;
    }
    ss_link_free(cl);
  }
  qsort(c, ll->n, sizeof *c, canon_cmp);
  for (size_t i = 0; i < ll->n; i++) {
    const int k = ll->l[c[i].i]->k;
    drop[c[i].i] =
        (i > 0 && !strcmp(c[i].canon, c[i - 1].canon)) || (k >= skip_lo && k <= skip_hi);
  }
  size_t n = 0;
  for (size_t i = 0; i < ll->n; i++) {
    if (drop[i])
      ss_link_free(ll->l[i]);
    else
      ll->l[n++] = ll->l[i];
  }
  *dropped = ll->n - n;
  ll->n = n;
done:
  for (size_t i = 0; c && i < n0; i++)
    free(c[i].canon);
  free(c);
  free(drop);
  return rc;
}

/* The counting pass's visitor: nothing to do but stop on a signal. */
static int count_visit(const ss_link *l, void *ctx) {
  (void)l;
  (void)ctx;
  return interrupted != 0;
}

/* The cases of this sweep (this part) into w->total, so that progress can
 * show an ETA: the links counted by enumerating them (a signal stops the
 * count, and then the sweep before its first case), the other cases dealt
 * round the parts as the run deals them.  0, or the exit status with the
 * message printed. */
static int count_total(ss_sweep *w) {
  ss_error err = {0};
  const long part = w->opt.part, nparts = w->opt.nparts;
  if (w->opt.vtext && w->volume) {
    ss_enum_opts eo = {(int)w->opt.va, (int)w->opt.vb, (int)part, (int)nparts};
    uint64_t counts[SS_ENUM_MAXK + 1];
    if (w->tty && w->opt.vb >= 15)
      fprintf(stderr, "subspectra sweep: counting the links with %ld..%ld vertices...\n",
              w->opt.va, w->opt.vb);
    if (ss_enum_links(&eo, count_visit, NULL, counts, &err)) {
      fprintf(stderr, "subspectra sweep: %s\n", err.msg);
      return ss_cli_exit_status(err.status);
    }
    for (long k = w->opt.va; k <= w->opt.vb; k++)
      w->total += counts[k];
    w->counting_stopped = interrupted != 0;
  }
  size_t idx = 0; /* index of the non-enumerated cases, for --part */
  for (long n = w->opt.vtext && !w->volume ? w->opt.va : 1;
       n <= (w->opt.vtext && !w->volume ? w->opt.vb : 0); n++)
    w->total += idx++ % (size_t)nparts == (size_t)part;
  for (long n = w->opt.ea; n <= w->opt.eb; n++)
    w->total += idx++ % (size_t)nparts == (size_t)part;
  if (w->opt.face) w->total += idx++ % (size_t)nparts == (size_t)part;
  for (size_t i = 0; i < w->nlinks; i++)
    w->total += idx++ % (size_t)nparts == (size_t)part;
  return SS_EXIT_OK;
}

int ss_sweep_open(int argc, char **argv, ss_sweep_role role, ss_sweep **out) {
  *out = NULL;
  ss_sweep_opts a;
  int rc = ss_sweep_parse(argc, argv, &a);
  if (rc >= 0) return rc;
  ss_error err = {0};
  ss_scheme *s = NULL;
  uint64_t hash = 0;
  if (a.stencil ? ss_stencil_load(a.stencil, &s, &hash, &err)
                : ss_scheme_new(a.scheme, &s, &err)) {
    fprintf(stderr, "subspectra sweep: %s%s\n",
            a.stencil ? "--stencil " : "--scheme: ", err.msg);
    return SS_EXIT_USAGE; /* bad scheme or stencil, or out of memory */
  }
  if (ss_cli_refuse_local("sweep", s)) {
    ss_scheme_free(s);
    return SS_EXIT_USAGE;
  }
  const int volume = ss_scheme_accepts(s, SS_HEX) || ss_scheme_accepts(s, SS_TET);
  const int reads = ss_scheme_reads_diagonals(s);
  char msg[160];
  const char *bad = ss_sweep_check_cases(&a, s, volume, reads, msg, sizeof msg);
  if (bad) {
    ss_scheme_free(s);
    return ss_cli_usage_error("sweep", "%s", bad);
  }
  ss_sweep *w = calloc(1, sizeof *w);
  if (!w) {
    ss_scheme_free(s);
    fprintf(stderr, "subspectra sweep: out of memory\n");
    return SS_EXIT_USAGE;
  }
  ss_result_opts ro = ss_result_defaults();
  ro.tol = a.tol;
  ro.depth = (int)a.depth;
  ro.certify = a.certify;
  ro.psi_depth = (int)a.psi_depth;
  ro.psi_tubes = a.psi_tubes;
  /* the budget is shared by the threads, one case each */
  ro.max_bytes = ss_cli_budget(a.max_memory) / (double)a.jobs;
  *w = (ss_sweep){.opt = a,
                  .s = s,
                  .volume = volume,
                  .ro = ro,
                  .jobs = (int)a.jobs,
                  .ranks = 1,
                  .flush = flush_threads,
                  .tty = role == SS_SWEEP_WHOLE && !a.quiet && isatty(STDERR_FILENO),
                  /* --progress to a file or a pipe: a line a second */
                  .log_every = a.progress && role != SS_SWEEP_WORKER ? 1.0 : 0.0,
                  .pool = calloc(1, sizeof(ss_sweep_wspool))};
  ss_store_scheme sc = {ss_scheme_name(s), a.stencil, hash, reads, a.diag, ro};
  ss_store_identity(&sc, w->ident, sizeof w->ident);
  if (role == SS_SWEEP_WORKER) {
    /* an MPI rank that computes: a signal finishes the cases in flight */
    catch_signals();
    *out = w;
    return -1;
  }
  linklist ll = {NULL, 0, 0};
  rc = a.links ? ss_cli_read_links("sweep", a.links, take_link, &ll) : SS_EXIT_OK;
  if (!rc && a.links)
    rc = dedupe_links(&ll, a.vtext && volume ? a.va : 1, a.vtext && volume ? a.vb : 0,
                      &w->dups);
  w->links = ll.l;
  w->nlinks = ll.n;
  if (rc) goto fail;
  if (ss_store_open(a.db, SS_STORE_WRITE, &w->st, &err) ||
      ss_store_scheme_id(w->st, &sc, &w->id, &err)) {
    fprintf(stderr, "subspectra sweep: %s\n", err.msg);
    rc = SS_EXIT_USAGE; /* a bad store, or out of memory */
    goto fail;
  }
  /* SIGINT, SIGTERM from here on: the store is open */
  catch_signals();
  if ((rc = count_total(w))) goto fail;
  *out = w;
  return -1;
fail:
  ss_sweep_free(w);
  return rc;
}

void ss_sweep_free(ss_sweep *w) {
  if (!w) return;
  ss_sweep_clear_chunk(w);
  for (size_t i = 0; i < w->nlinks; i++)
    ss_link_free(w->links[i]);
  free(w->links);
  ss_store_close(w->st);
  ss_scheme_free(w->s);
  for (int i = 0; w->pool && i < w->pool->n; i++)
    ss_pipeline_workspace_free(w->pool->slot[i]);
  if (w->pool) free(w->pool->slot);
  free(w->pool);
  free(w);
}

void ss_sweep_run(ss_sweep *w) {
  const long part = w->opt.part, nparts = w->opt.nparts;
  const int volume = w->volume;
  if ((w->tty || w->log_every > 0) && !w->counting_stopped) {
    char ranks[48] = "";
    if (w->ranks > 1) snprintf(ranks, sizeof ranks, "%d ranks of ", w->ranks);
    fprintf(stderr, "subspectra sweep: %zu cases of %s into %s with %s%d thread%s%s\n",
            w->total, w->ident, w->opt.db, ranks, w->jobs, w->jobs == 1 ? "" : "s",
            nparts > 1 ? " (this part)" : "");
  }
  w->t0 = w->last = ss_cli_now();
  ss_error err = {0};
  ss_enum_opts eo = {(int)w->opt.va, (int)w->opt.vb, (int)part, (int)nparts};
  if (w->opt.vtext && volume && ss_enum_links(&eo, visit, w, NULL, &err) && !w->stop) {
    w->stop = 1;
    w->fatal = err;
  }
  size_t idx = 0;
  for (long n = w->opt.vtext && !volume ? w->opt.va : 1;
       n <= (w->opt.vtext && !volume ? w->opt.vb : 0); n++)
    if (idx++ % (size_t)nparts == (size_t)part)
      add(w, SS_CASE_SURFACE_VERTEX, (int)n, NULL);
  for (long n = w->opt.ea; n <= w->opt.eb; n++)
    if (idx++ % (size_t)nparts == (size_t)part) add(w, SS_CASE_EDGE, (int)n, NULL);
  if (w->opt.face && idx++ % (size_t)nparts == (size_t)part)
    add(w, SS_CASE_FACE, 0, NULL);
  for (size_t i = 0; i < w->nlinks; i++)
    if (idx++ % (size_t)nparts == (size_t)part) add(w, SS_CASE_VERTEX, 0, w->links[i]);
  w->flush(w);
}

int ss_sweep_close(ss_sweep *w) {
  const double dt = ss_cli_now() - w->t0;
  int rc;
  if (w->tty) fprintf(stderr, "\r\033[K");
  if (w->stop) {
    fprintf(stderr, "subspectra sweep: %s\n", w->fatal.msg);
    rc = SS_EXIT_USAGE; /* a store error, or out of memory */
    goto done;
  }
  char took[32];
  fmt_time(dt, took, sizeof took);
  const size_t done = w->computed + w->skipped + w->errors;
  char dupnote[64] = "", ranks[48] = "";
  if (w->dups)
    snprintf(dupnote, sizeof dupnote, ", %zu repeated link%s in --links skipped", w->dups,
             w->dups == 1 ? "" : "s");
  if (w->ranks > 1) snprintf(ranks, sizeof ranks, "%d ranks of ", w->ranks);
  if (w->counting_stopped)
    fprintf(stderr,
            "subspectra sweep: interrupted (%s) while counting the cases, before any was "
            "computed (store %s); the same command resumes\n",
            interrupted == SIGINT ? "SIGINT" : "SIGTERM", w->opt.db);
  else
    fprintf(stderr,
            "subspectra sweep: %zu cases of %s in %s (%zu computed, %.1f cases/s with "
            "%s%d thread%s; "
            "%zu already stored%s): %zu pass, %zu fail, %zu undecided, %zu errors; "
            "store %s\n",
            done, w->ident, took, w->computed, dt > 0 ? (double)w->computed / dt : 0.0,
            ranks, w->jobs, w->jobs == 1 ? "" : "s", w->skipped, dupnote, w->pass,
            w->fail, w->undecided, w->errors, w->opt.db);
  if (interrupted && !w->counting_stopped)
    fprintf(
        stderr,
        "subspectra sweep: interrupted (%s) with %zu of %zu cases done; the same command "
        "resumes\n",
        interrupted == SIGINT ? "SIGINT" : "SIGTERM", done, w->total);
  else if (w->ranks > 1 && done < w->total)
    /* every computing rank stopped (a signal) before the work did */
    fprintf(stderr,
            "subspectra sweep: stopped with %zu of %zu cases done; the same command "
            "resumes\n",
            done, w->total);
  if (w->opt.json) {
    json_object *o = json_object_new_object();
    json_object_object_add(o, "scheme", json_object_new_string(ss_scheme_name(w->s)));
    json_object_object_add(o, "identity", json_object_new_string(w->ident));
    json_object_object_add(o, "db", json_object_new_string(w->opt.db));
    json_object_object_add(o, "part", json_object_new_int64(w->opt.part));
    json_object_object_add(o, "parts", json_object_new_int64(w->opt.nparts));
    json_object_object_add(o, "threads", json_object_new_int64(w->jobs));
    /* computing MPI ranks (1 without MPI); threads is per rank */
    json_object_object_add(o, "ranks", json_object_new_int64(w->ranks));
    /* (null: the count was interrupted) */
    json_object_object_add(
        o, "cases",
        w->counting_stopped ? NULL : json_object_new_int64((int64_t)w->total));
    json_object_object_add(o, "done", json_object_new_int64((int64_t)done));
    json_object_object_add(o, "computed", json_object_new_int64((int64_t)w->computed));
    json_object_object_add(o, "already_stored",
                           json_object_new_int64((int64_t)w->skipped));
    json_object_object_add(o, "pass", json_object_new_int64((int64_t)w->pass));
    json_object_object_add(o, "fail", json_object_new_int64((int64_t)w->fail));
    json_object_object_add(o, "undecided", json_object_new_int64((int64_t)w->undecided));
    json_object_object_add(o, "errors", json_object_new_int64((int64_t)w->errors));
    json_object_object_add(o, "repeated_links", json_object_new_int64((int64_t)w->dups));
    json_object_object_add(o, "seconds", json_object_new_double(dt));
    json_object_object_add(o, "interrupted", json_object_new_boolean(interrupted != 0));
    printf("%s\n", json_object_to_json_string_ext(o, SS_CLI_JSON_FLAGS));
    json_object_put(o);
  }
  /* a case out of memory or beyond the budget was skipped (with its message):
   * exit 2, as for any case that could not be run for lack of memory */
  rc = w->nomem                               ? SS_EXIT_USAGE
       : w->fail || w->undecided || w->errors ? SS_EXIT_FAIL
                                              : SS_EXIT_OK;
done:
  ss_sweep_free(w);
  return rc;
}
