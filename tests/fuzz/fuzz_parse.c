/* fuzz_parse.c — in-process mutation fuzzer of the library's parsers.
 *
 *   fuzz_parse [--seed S] [--iterations N] [--first I | --only I] [--dump]
 *              [--max-seconds T] [--target link|mesh|stencil|all]
 *              [--known-raw LIST] [--known-slow] [--mutant-timeout T]
 *              [--summary] [--src DIR] [--write DIR]
 *
 * Seeds: the sample meshes (data/meshes, and the malformed ones of
 * tests/mesh/bad), the stencil files (data/stencils) and a set of links
 * (fuzz_mutate.c).  Iteration i mutates one seed with a generator seeded by
 * (S, i) alone, feeds the mutant to its parser (ss_link_parse, the Medit and
 * OBJ readers, ss_stencil_parse) and, when it parses, to the next stages:
 *   link     format and parse again (equal), canonical form (idempotent,
 *            isomorphic to the link), hex and tet stars (positive cells), for
 *            small links the local subdivision matrix of tetoct at the vertex;
 *   mesh     ss_cx_validate, the degenerate/inverted-cell check, a Medit
 *            round trip (bitwise equal), one level of subdivision by a scheme
 *            that takes the cells;
 *   stencil  one level of subdivision of a sample mesh and the local matrix
 *            at the tetrahedron link's vertex.
 * Every call must return SS_OK, or an error status (never SS_EINTERNAL from a
 * parser) whose message is non-empty, is the status's own and holds no raw
 * byte (< 0x20 or >= 0x7f: such input must be escaped, not echoed); mesh and
 * stencil messages start "FILE:LINE: " (DESIGN section 7).  A crash,
 * a sanitizer report or a mutant running longer than --mutant-timeout prints
 * the seed, iteration and the mutant (escaped) and kills the run.
 *
 * --write DIR writes the mutants to DIR (see write_mutant) instead of running
 * them, for fuzz_cli.sh.
 *
 * --known-raw link,mesh,stencil: raw bytes in those parsers' messages are a
 * known bug: counted and shown once, not failures.  --known-slow skips links
 * named bipyramid:N with N > 2000, known to take seconds to parse (counted).
 * --only I replays iteration I (with --dump: prints the mutant).
 * --max-seconds stops the run early (a time budget); --mutant-timeout
 * (default 20 s times SS_TIMEOUT_MULTIPLIER) bounds one mutant.  --summary
 * adds the messages grouped by shape.  Exit 0 if every check held, 1
 * otherwise, 2 on bad usage. */
#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include <gsl/gsl_rng.h>

#include "fuzz_mutate.h"
#include "ss_link.h"
#include "ss_local.h"
#include "ss_mesh.h"
#include "ss_scheme.h"
#include "ss_star.h"
#include "ss_stencil.h"

#ifndef SS_FUZZ_SRC
#define SS_FUZZ_SRC "."
#endif

#define MAXSEEDS   64 /* seed files of one kind at most */
#define MAXSHAPES  512
#define MAXREPORTS 20 /* failures printed in full */
/* --known-slow: links of more vertices take seconds to parse (validation is
 * quadratic in the largest degree; bipyramid:99998 ~ 7 s per parse). */
#define SLOW_BIPYRAMID 2000

/* ---- what the crash handler needs: the mutant under test ---- */

static unsigned long cur_seed, cur_iter;
static const char *volatile cur_kind = "-";
static const char *volatile cur_stage = "-";
static const char *volatile cur_data;
static volatile size_t cur_len;

static void put(const char *s) {
  size_t n = strlen(s);
  while (n) {
    ssize_t w = write(2, s, n);
    if (w <= 0) return;
    s += w;
    n -= (size_t)w;
  }
}

static void put_ulong(unsigned long x) {
  char b[24];
  int i = 23;
  b[i] = '\0';
  do {
    b[--i] = (char)('0' + x % 10);
    x /= 10;
  } while (x && i > 0);
  put(b + i);
}

/* Async-signal-safe: the mutant in the escapes of fz_escape. */
static void put_escaped(const char *p, size_t n) {
  static const char hex[] = "0123456789abcdef";
  char out[512];
  size_t k = 0;
  for (size_t i = 0; i < n; i++) {
    unsigned char c = (unsigned char)p[i];
    if (k > sizeof out - 8) {
      out[k] = '\0';
      put(out);
      k = 0;
    }
    if (c == '\\' || c == '\n' || c == '\r' || c == '\t') {
      out[k++] = '\\';
      out[k++] = c == '\\' ? '\\' : c == '\n' ? 'n' : c == '\r' ? 'r' : 't';
    } else if (c < 0x20 || c >= 0x7f) {
      out[k++] = '\\';
      out[k++] = 'x';
      out[k++] = hex[c >> 4];
      out[k++] = hex[c & 15];
    } else
      out[k++] = (char)c;
  }
  out[k] = '\0';
  put(out);
}

static void report_context(const char *what) {
  put("\nfuzz_parse: ");
  put(what);
  put(" at seed ");
  put_ulong(cur_seed);
  put(" iteration ");
  put_ulong(cur_iter);
  put(" (");
  put(cur_kind);
  put(", stage ");
  put(cur_stage);
  put(")\n  replay: fuzz_parse --seed ");
  put_ulong(cur_seed);
  put(" --only ");
  put_ulong(cur_iter);
  put(" --dump\n  input: \"");
  if (cur_data) put_escaped(cur_data, cur_len);
  put("\"\n");
}

static void on_signal(int sig) {
  report_context(sig == SIGALRM ? "mutant timed out (a hang?)" : "crash (signal)");
  if (sig == SIGALRM) _exit(1);
  signal(sig, SIG_DFL);
  raise(sig);
}

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_UNDEFINED__)
#define FUZZ_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(undefined_behavior_sanitizer)
#define FUZZ_SANITIZED 1
#endif
#endif
#ifdef FUZZ_SANITIZED
void __sanitizer_set_death_callback(void (*callback)(void));
static void on_sanitizer_death(void) {
  report_context("sanitizer report");
}
#endif

/* ---- the run's state and statistics ---- */

typedef struct {
  char *path;  /* file name (for messages and the reader by extension) */
  fz_buf text; /* contents */
} seed_file;

typedef struct {
  const char *shape; /* message with numbers and quoted text blanked (owned) */
  long n;            /* how many messages had it */
} shape;

typedef struct {
  /* options */
  unsigned long seed;       /* --seed */
  unsigned long first;      /* first iteration */
  unsigned long n;          /* --iterations */
  double max_seconds;       /* --max-seconds, 0 = no limit */
  int target;               /* fz_kind, or -1 for all */
  int known_raw[FZ_NKINDS]; /* --known-raw */
  int known_slow;           /* --known-slow: skip bipyramid:N, N > SLOW_BIPYRAMID */
  int dump;                 /* --dump: print every mutant */
  const char *write_dir;    /* --write DIR: write the mutants there, run none */
  int summary;              /* --summary: message shapes too */
  unsigned mutant_timeout;  /* seconds a mutant may take */
  /* inputs */
  seed_file seeds[FZ_NKINDS][MAXSEEDS];
  int nseeds[FZ_NKINDS];
  ss_cx *tet_sample, *hex_sample; /* cube-6tets, cube-creased: stencils refine them */
  ss_scheme *schemes[4];          /* mlca, tetoct, loop, catmull-clark */
  ss_link *tetra;                 /* the tetrahedron link */
  /* statistics */
  long tried[FZ_NKINDS], accepted[FZ_NKINDS];
  long rejected[FZ_NKINDS][SS_NSTATUS];
  long raw_known[FZ_NKINDS];
  long stage_ok, stage_err; /* next stages after a successful parse */
  long nonfinite;           /* refinements with non-finite positions (issue 16 item 3) */
  unsigned long nonfinite_it; /* the first of them */
  long failures;
  long skipped_slow; /* links skipped by --known-slow */
  shape shapes[MAXSHAPES];
  int nshapes;
  double slowest[3];           /* seconds of the three slowest mutants */
  unsigned long slowest_it[3]; /* and their iterations */
  const char *slowest_kind[3];
  fz_buf *mutant; /* the mutant under test */
} fuzz;

static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void failure(fuzz *F, const char *what, const ss_error *err) {
  F->failures++;
  if (F->failures > MAXREPORTS) return;
  fprintf(stderr,
          "FAILED: seed %lu iteration %lu (%s, stage %s): %s\n"
          "  replay: fuzz_parse --seed %lu --only %lu --dump\n  input: \"",
          cur_seed, cur_iter, cur_kind, cur_stage, what, cur_seed, cur_iter);
  fz_escape(stderr, F->mutant->data, F->mutant->len, 4096);
  fputs("\"\n", stderr);
  if (err) {
    fputs("  message: \"", stderr);
    fz_escape(stderr, err->msg, strnlen(err->msg, sizeof err->msg), 0);
    fputs("\"\n", stderr);
  }
}

static void count_shape(fuzz *F, const char *msg) {
  char s[sizeof((ss_error *)0)->msg];
  size_t k = 0;
  int quoted = 0;
  for (const char *p = msg; *p && k + 4 < sizeof s; p++) {
    if (*p == '\'') {
      quoted = !quoted;
      s[k++] = '\'';
      if (quoted) s[k++] = '*';
    } else if (quoted)
      continue;
    else if (*p >= '0' && *p <= '9') {
      if (!k || s[k - 1] != 'N') s[k++] = 'N';
    } else
      s[k++] = *p;
  }
  s[k] = '\0';
  for (int i = 0; i < F->nshapes; i++)
    if (!strcmp(F->shapes[i].shape, s)) {
      F->shapes[i].n++;
      return;
    }
  if (F->nshapes == MAXSHAPES) return;
  char *c = strdup(s);
  if (!c) return;
  F->shapes[F->nshapes].shape = c;
  F->shapes[F->nshapes++].n = 1;
}

/* 1 if msg starts "mutant.EXT:LINE: " (the readers name the file and line). */
static int names_line(const char *msg) {
  if (strncmp(msg, "mutant.", 7)) return 0;
  const char *p = strchr(msg, ':');
  if (!p || p[1] < '0' || p[1] > '9') return 0;
  p += 1 + strspn(p + 1, "0123456789");
  return p[0] == ':' && p[1] == ' ';
}

/* The contract of a failed call.  `parser`: SS_EINTERNAL is a bug there. */
static void check_error(fuzz *F, fz_kind kind, ss_status st, const ss_error *err,
                        int parser) {
  if (parser) F->rejected[kind][st < SS_NSTATUS ? st : 0]++;
  if (st <= SS_OK || st >= SS_NSTATUS) {
    failure(F, "status out of range", err);
    return;
  }
  if (strnlen(err->msg, sizeof err->msg) == sizeof err->msg) {
    failure(F, "message not NUL-terminated", NULL);
    return;
  }
  count_shape(F, err->msg);
  if (!err->msg[0]) failure(F, "error without a message", err);
  if (err->status != st) failure(F, "the message belongs to another status", err);
  if (parser && st == SS_EINTERNAL) failure(F, "internal error from a parser", err);
  if (parser && kind != FZ_LINK && st == SS_EINPUT && !names_line(err->msg))
    failure(F, "the message does not name the file and line (\"FILE:LINE: ...\")", err);
  if (fz_has_raw(err->msg)) {
    if (F->known_raw[kind]) {
      if (!F->raw_known[kind]++) {
        fprintf(stderr, "known failure (--known-raw %s): raw bytes in a message: \"",
                fz_kind_name(kind));
        fz_escape(stderr, err->msg, strlen(err->msg), 0);
        fputs("\"\n", stderr);
      }
    } else
      failure(F, "raw bytes in the message (escape them)", err);
  }
}

/* A later stage: OK, or an error that keeps the contract. */
static void stage_result(fuzz *F, fz_kind kind, ss_status st, const ss_error *err) {
  if (st == SS_OK) {
    F->stage_ok++;
    return;
  }
  F->stage_err++;
  check_error(F, kind, st, err, 0);
}

#define ERR0 ((ss_error){SS_OK, {0}})

/* ---- links ---- */

/* 1 if text names a bipyramid over more than SLOW_BIPYRAMID vertices. */
static int slow_link(const char *text) {
  while (*text == ' ' || *text == '\t' || *text == '\n' || *text == '\r')
    text++;
  if (strncmp(text, "bipyramid:", 10)) return 0;
  text += 10;
  size_t digits = strspn(text, "0123456789");
  return digits > 9 || (digits && strtol(text, NULL, 10) > SLOW_BIPYRAMID);
}

static void run_link(fuzz *F, const char *text) {
  ss_error err = ERR0;
  ss_link *l = NULL, *l2 = NULL, *c = NULL, *cc = NULL;
  ss_star *star = NULL;
  ss_local *M = NULL;
  char *fmt = NULL;
  if (F->known_slow && slow_link(text)) {
    F->skipped_slow++;
    return;
  }
  cur_stage = "ss_link_parse";
  ss_status st = ss_link_parse(text, &l, &err);
  if (st) {
    check_error(F, FZ_LINK, st, &err, 1);
    goto done;
  }
  F->accepted[FZ_LINK]++;
  cur_stage = "ss_link_format";
  if ((st = ss_link_format(l, &fmt, &err))) {
    failure(F, "a parsed link cannot be formatted", &err);
    goto done;
  }
  cur_stage = "parse the formatted link";
  if ((st = ss_link_parse(fmt, &l2, &err)) || !ss_link_equal(l, l2)) {
    failure(F, "format and parse do not give the link back", st ? &err : NULL);
    goto done;
  }
  if (l->k <= 64) {
    cur_stage = "ss_link_canonical";
    if ((st = ss_link_canonical(l, &c, NULL, &err)) ||
        (st = ss_link_canonical(c, &cc, NULL, &err))) {
      failure(F, "no canonical form", &err);
      goto done;
    }
    if (!ss_link_equal(c, cc)) failure(F, "the canonical form is not idempotent", NULL);
    if (ss_link_isomorphic(l, c) != 1)
      failure(F, "the canonical form is not isomorphic to the link", NULL);
  }
  if (l->k <= 12) {
    cur_stage = "stars";
    for (int hex = 0; hex < 2; hex++) {
      st = hex ? ss_star_hex_vertex(l, &star, &err) : ss_star_tet_vertex(l, &star, &err);
      if (st) {
        failure(F, "no star for a valid link", &err);
        goto done;
      }
      if ((st = ss_cx_check_orientation(star->cx, &err)))
        failure(F, "the star of a valid link has a bad cell", &err);
      ss_star_free(star);
      star = NULL;
    }
  }
  if (l->k <= 7) {
    cur_stage = "ss_local_new (tetoct)";
    ss_case cs = {.kind = SS_CASE_VERTEX, .link = l};
    stage_result(F, FZ_LINK, ss_local_new(F->schemes[1], &cs, &M, &err), &err);
  }
done:
  ss_local_free(M);
  ss_star_free(star);
  ss_link_free(l);
  ss_link_free(l2);
  ss_link_free(c);
  ss_link_free(cc);
  free(fmt);
}

/* ---- meshes ---- */

static int all_finite(const ss_cx *cx) {
  for (size_t i = 0; i < cx->nv * (size_t)cx->dim; i++)
    if (!isfinite(cx->x[i])) return 0;
  return 1;
}

static int same_mesh(const ss_cx *a, const ss_cx *b) {
  if (a->dim != b->dim || a->nv != b->nv) return 0;
  if (a->nv && memcmp(a->x, b->x, a->nv * (size_t)a->dim * sizeof *a->x)) return 0;
  for (int t = 0; t < SS_NCELLTYPES; t++) {
    if (a->nc[t] != b->nc[t]) return 0;
    size_t n = a->nc[t] * (size_t)ss_cell_nverts((ss_cell_type)t);
    if (n && memcmp(a->cells[t], b->cells[t], n * sizeof(ss_idx))) return 0;
  }
  return 1;
}

/* Refine once by the first scheme that takes every cell type of cx. */
static void refine_once(fuzz *F, fz_kind kind, const ss_scheme *only, const ss_cx *cx) {
  const ss_scheme *s = only;
  for (int k = 0; !s && k < 4; k++) {
    int ok = 1;
    for (int t = 0; t < SS_NCELLTYPES; t++)
      if (cx->nc[t] && !ss_scheme_accepts(F->schemes[k], (ss_cell_type)t)) ok = 0;
    if (ok) s = F->schemes[k];
  }
  if (!s) s = F->schemes[0]; /* none takes them all: the refusal is checked */
  ss_error err = ERR0;
  ss_cx *fine = NULL;
  cur_stage = "ss_scheme_refine";
  ss_status st = ss_scheme_refine(s, cx, &fine, NULL, &err);
  stage_result(F, kind, st, &err);
  if (!st && !all_finite(fine) && !F->nonfinite++) F->nonfinite_it = cur_iter;
  ss_cx_free(fine);
}

static void run_mesh(fuzz *F, const fz_buf *b, int obj) {
  ss_error err = ERR0;
  ss_cx *cx = NULL, *back = NULL;
  char *mem = NULL;
  size_t memlen = 0;
  FILE *f = b->len ? fmemopen(b->data, b->len, "r") : tmpfile();
  if (!f) {
    fprintf(stderr, "fuzz_parse: cannot open a memory stream: %s\n", strerror(errno));
    exit(2);
  }
  const char *name = obj ? "mutant.obj" : "mutant.mesh";
  cur_stage = obj ? "ss_mesh_read_obj" : "ss_mesh_read_medit";
  ss_status st =
      obj ? ss_mesh_read_obj(f, name, &cx, &err) : ss_mesh_read_medit(f, name, &cx, &err);
  fclose(f);
  if (st) {
    check_error(F, FZ_MESH, st, &err, 1);
    goto done;
  }
  F->accepted[FZ_MESH]++;
  cur_stage = "ss_cx_validate";
  if ((st = ss_cx_validate(cx, &err))) {
    failure(F, "the reader accepted a malformed cell", &err);
    goto done;
  }
  cur_stage = "ss_cx_check_orientation";
  ss_status ost = ss_cx_check_orientation(cx, &err);
  stage_result(F, FZ_MESH, ost, &err);
  cur_stage = "Medit round trip";
  f = open_memstream(&mem, &memlen);
  if (!f) exit(2);
  err = ERR0;
  /* the extension keyword keeps octahedra, so the mesh reads back the same */
  st = ss_mesh_write_medit(f, cx, &(ss_mesh_write_opts){.octahedra_keyword = 1}, &err);
  if (fclose(f) || st) {
    failure(F, "the mesh cannot be written", &err);
    goto done;
  }
  f = fmemopen(mem, memlen, "r");
  if (!f) exit(2);
  st = ss_mesh_read_medit(f, "round-trip.mesh", &back, &err);
  fclose(f);
  if (st || !same_mesh(cx, back)) {
    failure(F, "a mesh written and read back is not the same", st ? &err : NULL);
    goto done;
  }
  if (!ost && cx->nv <= 4096 && ss_cx_ncells(cx) <= 2048)
    refine_once(F, FZ_MESH, NULL, cx);
done:
  ss_cx_free(cx);
  ss_cx_free(back);
  free(mem);
}

/* ---- stencils ---- */

static void run_stencil(fuzz *F, const char *text) {
  ss_error err = ERR0;
  ss_scheme *s = NULL;
  ss_local *M = NULL;
  cur_stage = "ss_stencil_parse";
  ss_status st = ss_stencil_parse(text, "mutant.ini", &s, &err);
  if (st) {
    check_error(F, FZ_STENCIL, st, &err, 1);
    return;
  }
  F->accepted[FZ_STENCIL]++;
  const int multi = ss_scheme_split_kind(s) == SS_SPLIT_MULTILINEAR;
  refine_once(F, FZ_STENCIL, s, multi ? F->hex_sample : F->tet_sample);
  cur_stage = "ss_local_new (stencil)";
  ss_case cs = {.kind = SS_CASE_VERTEX, .link = F->tetra};
  err = ERR0;
  stage_result(F, FZ_STENCIL, ss_local_new(s, &cs, &M, &err), &err);
  ss_local_free(M);
  ss_scheme_free(s);
}

/* ---- seeds ---- */

static int read_file(const char *path, fz_buf *b) {
  FILE *f = fopen(path, "rb");
  if (!f) return -1;
  char chunk[4096];
  size_t n;
  int rc = fz_buf_set(b, "", 0);
  while (!rc && (n = fread(chunk, 1, sizeof chunk, f)) > 0) {
    size_t old = b->len;
    char *tmp = malloc(old + n);
    if (!tmp) rc = -1;
    if (tmp) {
      memcpy(tmp, b->data, old);
      memcpy(tmp + old, chunk, n);
      rc = fz_buf_set(b, tmp, old + n);
      free(tmp);
    }
  }
  if (ferror(f)) rc = -1;
  fclose(f);
  return rc;
}

/* Add every file of dir whose name ends in one of the extensions, in
 * alphabetical order (so a seed and iteration name the same mutant on every
 * machine). */
static int add_seeds(fuzz *F, fz_kind kind, const char *dir, const char *const *ext) {
  struct dirent **list = NULL;
  int n = scandir(dir, &list, NULL, alphasort), rc = 0;
  for (int i = 0; i < n; i++) {
    const char *name = list[i]->d_name;
    int ok = 0;
    for (const char *const *e = ext; *e; e++) {
      size_t ln = strlen(name), le = strlen(*e);
      if (ln > le && !strcmp(name + ln - le, *e)) ok = 1;
    }
    if (rc || !ok || F->nseeds[kind] == MAXSEEDS) continue;
    seed_file *s = &F->seeds[kind][F->nseeds[kind]];
    size_t len = strlen(dir) + strlen(name) + 2;
    s->path = malloc(len);
    if (!s->path) {
      rc = -1;
      continue;
    }
    snprintf(s->path, len, "%s/%s", dir, name);
    F->nseeds[kind]++;
    if (read_file(s->path, &s->text)) {
      fprintf(stderr, "fuzz_parse: cannot read %s\n", s->path);
      rc = -1;
    }
  }
  for (int i = 0; i < n; i++)
    free(list[i]);
  free(list);
  return rc;
}

static int load_inputs(fuzz *F, const char *src) {
  static const char *const mesh_ext[] = {".mesh", ".obj", NULL};
  static const char *const ini_ext[] = {".ini", NULL};
  char dir[4096];
  snprintf(dir, sizeof dir, "%s/data/meshes", src);
  if (add_seeds(F, FZ_MESH, dir, mesh_ext)) return -1;
  snprintf(dir, sizeof dir, "%s/tests/mesh/bad", src);
  if (add_seeds(F, FZ_MESH, dir, mesh_ext)) return -1;
  snprintf(dir, sizeof dir, "%s/data/stencils", src);
  if (add_seeds(F, FZ_STENCIL, dir, ini_ext)) return -1;
  for (int i = 0; fz_link_seeds[i] && F->nseeds[FZ_LINK] < MAXSEEDS; i++) {
    seed_file *s = &F->seeds[FZ_LINK][F->nseeds[FZ_LINK]++];
    s->path = strdup("link");
    if (!s->path || fz_buf_set(&s->text, fz_link_seeds[i], strlen(fz_link_seeds[i])))
      return -1;
  }
  if (F->nseeds[FZ_MESH] < 2 || F->nseeds[FZ_STENCIL] < 1) {
    fprintf(stderr, "fuzz_parse: no seed meshes or stencils under %s (use --src)\n", src);
    return -1;
  }
  ss_error err = ERR0;
  static const char *const names[4] = {"mlca", "tetoct", "loop", "catmull-clark"};
  for (int k = 0; k < 4; k++)
    if (ss_scheme_new(names[k], &F->schemes[k], &err)) goto fail;
  char path[4096];
  snprintf(path, sizeof path, "%s/data/meshes/cube-6tets.mesh", src);
  if (ss_mesh_read(path, SS_MESH_AUTO, &F->tet_sample, &err)) goto fail;
  snprintf(path, sizeof path, "%s/data/meshes/cube-creased.mesh", src);
  if (ss_mesh_read(path, SS_MESH_AUTO, &F->hex_sample, &err)) goto fail;
  if (ss_link_named("tetrahedron", &F->tetra, &err)) goto fail;
  return 0;
fail:
  fprintf(stderr, "fuzz_parse: %s\n", err.msg);
  return -1;
}

/* ---- mutants as files, for the process-level fuzzer (fuzz_cli.sh) ---- */

/* DIR/ITER.EXT: .mesh, .obj, .ini; links .link when they are invalid or have
 * at most 7 vertices (cheap to analyse), .link64 for valid links of 8..64
 * vertices (cheap to put in canonical form); larger links are not written. */
static int write_mutant(const fuzz *F, unsigned long it, fz_kind kind, int obj,
                        const fz_buf *b) {
  const char *ext = kind == FZ_MESH      ? (obj ? "obj" : "mesh")
                    : kind == FZ_STENCIL ? "ini"
                                         : "link";
  if (kind == FZ_LINK) {
    if (slow_link(b->data)) return 0;
    ss_error err = ERR0;
    ss_link *l = NULL;
    if (!ss_link_parse(b->data, &l, &err)) {
      ext = l->k <= 7 ? "link" : l->k <= 64 ? "link64" : NULL;
      ss_link_free(l);
    }
    if (!ext) return 0;
  }
  char path[4096];
  snprintf(path, sizeof path, "%s/%06lu.%s", F->write_dir, it, ext);
  FILE *f = fopen(path, "wb");
  if (!f || fwrite(b->data, 1, b->len, f) != b->len || fclose(f)) {
    fprintf(stderr, "fuzz_parse: cannot write %s: %s\n", path, strerror(errno));
    return -1;
  }
  return 0;
}

/* ---- main ---- */

static int usage(const char *msg) {
  fprintf(stderr,
          "fuzz_parse: %s\nusage: fuzz_parse [--seed S] [--iterations N] "
          "[--first I | --only I] [--dump] [--max-seconds T] "
          "[--target link|mesh|stencil|all] [--known-raw LIST] "
          "[--known-slow] [--mutant-timeout T] [--summary] [--src DIR] [--write DIR]\n",
          msg);
  return 2;
}

static int parse_ulong(const char *s, unsigned long *out) {
  char *end;
  errno = 0;
  unsigned long v = strtoul(s, &end, 10);
  if (end == s || *end || errno || *s == '-') return -1;
  *out = v;
  return 0;
}

static void note_time(fuzz *F, double dt, unsigned long it, const char *kind) {
  for (int i = 0; i < 3; i++)
    if (dt > F->slowest[i]) {
      for (int j = 2; j > i; j--) {
        F->slowest[j] = F->slowest[j - 1];
        F->slowest_it[j] = F->slowest_it[j - 1];
        F->slowest_kind[j] = F->slowest_kind[j - 1];
      }
      F->slowest[i] = dt;
      F->slowest_it[i] = it;
      F->slowest_kind[i] = kind;
      return;
    }
}

static int cmp_shape(const void *a, const void *b) {
  const shape *x = a, *y = b;
  return x->n < y->n ? 1 : x->n > y->n ? -1 : strcmp(x->shape, y->shape);
}

static void print_summary(fuzz *F, unsigned long ran, double secs, int stopped) {
  printf("fuzz_parse: seed %lu, iterations %lu..%lu: %lu mutants in %.2f s%s\n", F->seed,
         F->first, F->first + (ran ? ran - 1 : 0), ran, secs,
         stopped ? " (stopped by --max-seconds)" : "");
  for (int k = 0; k < FZ_NKINDS; k++) {
    if (!F->tried[k]) continue;
    long rej = 0;
    for (int s = 0; s < SS_NSTATUS; s++)
      rej += F->rejected[k][s];
    printf("  %-8s %7ld tried, %6ld accepted, %7ld rejected (", fz_kind_name((fz_kind)k),
           F->tried[k], F->accepted[k], rej);
    int first = 1;
    for (int s = 0; s < SS_NSTATUS; s++)
      if (F->rejected[k][s]) {
        printf("%s%s %ld", first ? "" : ", ", ss_status_name((ss_status)s),
               F->rejected[k][s]);
        first = 0;
      }
    printf(")");
    if (F->raw_known[k]) printf("; %ld messages with raw bytes (known)", F->raw_known[k]);
    printf("\n");
  }
  if (F->skipped_slow)
    printf("  %ld links skipped as known to be slow (--known-slow)\n", F->skipped_slow);
  printf("  next stages: %ld ok, %ld refused with a message; %ld refinements with "
         "non-finite points\n",
         F->stage_ok, F->stage_err, F->nonfinite);
  if (F->nonfinite)
    printf(
        "  (the first non-finite refinement: iteration %lu; a known bug, issue 16 item "
        "3)\n",
        F->nonfinite_it);
  for (int i = 0; i < 3 && F->slowest[i] > 0; i++)
    printf("  slowest %d: %.3f s (%s, iteration %lu)\n", i + 1, F->slowest[i],
           F->slowest_kind[i], F->slowest_it[i]);
  if (F->summary && F->nshapes) {
    qsort(F->shapes, (size_t)F->nshapes, sizeof *F->shapes, cmp_shape);
    printf("  messages by shape (%d shapes; N = a number, '*' = quoted input):\n",
           F->nshapes);
    for (int i = 0; i < F->nshapes && i < 40; i++) {
      printf("    %6ld  ", F->shapes[i].n);
      fz_escape(stdout, F->shapes[i].shape, strlen(F->shapes[i].shape), 160);
      printf("\n");
    }
  }
  printf("  failures: %ld\n", F->failures);
}

int main(int argc, char **argv) {
  static fuzz F;
  const char *src = SS_FUZZ_SRC;
  F.seed = 1;
  F.n = 1000;
  F.target = -1;
  F.mutant_timeout = 20;
  const char *mult = getenv("SS_TIMEOUT_MULTIPLIER");
  if (mult && atoi(mult) > 0) F.mutant_timeout *= (unsigned)atoi(mult);
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    unsigned long x;
    if (!strcmp(a, "--help")) {
      printf("usage: fuzz_parse [--seed S] [--iterations N] [--first I | --only I] "
             "[--dump] [--max-seconds T] [--target link|mesh|stencil|all] "
             "[--known-raw LIST] [--known-slow] [--mutant-timeout T] [--summary] "
             "[--src DIR] [--write DIR]\n(see the comment at the top of "
             "tests/fuzz/fuzz_parse.c)\n");
      return 0;
    } else if (!strcmp(a, "--dump"))
      F.dump = 1;
    else if (!strcmp(a, "--known-slow"))
      F.known_slow = 1;
    else if (!strcmp(a, "--summary"))
      F.summary = 1;
    else if (!v)
      return usage("unknown option or missing value");
    else if (!strcmp(a, "--seed") && !parse_ulong(v, &x))
      F.seed = x, i++;
    else if (!strcmp(a, "--iterations") && !parse_ulong(v, &x))
      F.n = x, i++;
    else if (!strcmp(a, "--first") && !parse_ulong(v, &x))
      F.first = x, i++;
    else if (!strcmp(a, "--only") && !parse_ulong(v, &x))
      F.first = x, F.n = 1, i++;
    else if (!strcmp(a, "--max-seconds") && !parse_ulong(v, &x))
      F.max_seconds = (double)x, i++;
    else if (!strcmp(a, "--mutant-timeout") && !parse_ulong(v, &x) && x > 0)
      F.mutant_timeout = (unsigned)x, i++;
    else if (!strcmp(a, "--src"))
      src = v, i++;
    else if (!strcmp(a, "--write"))
      F.write_dir = v, i++;
    else if (!strcmp(a, "--target")) {
      i++;
      F.target = -2;
      for (int k = 0; k < FZ_NKINDS; k++)
        if (!strcmp(v, fz_kind_name((fz_kind)k))) F.target = k;
      if (!strcmp(v, "all")) F.target = -1;
      if (F.target == -2) return usage("--target: link, mesh, stencil or all");
    } else if (!strcmp(a, "--known-raw")) {
      i++;
      char *list = strdup(v), *save = NULL;
      if (!list) return 2;
      for (char *t = strtok_r(list, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
        int found = 0;
        for (int k = 0; k < FZ_NKINDS; k++)
          if (!strcmp(t, fz_kind_name((fz_kind)k))) F.known_raw[k] = found = 1;
        if (!found) {
          free(list);
          return usage("--known-raw: a list of link, mesh, stencil");
        }
      }
      free(list);
    } else
      return usage("unknown option or bad value");
  }
  if (load_inputs(&F, src)) return 2;

  static const int sigs[] = {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGALRM};
  for (size_t i = 0; i < sizeof sigs / sizeof sigs[0]; i++) {
#ifdef FUZZ_SANITIZED
    if (sigs[i] != SIGALRM && sigs[i] != SIGABRT) continue; /* the sanitizer's */
#endif
    signal(sigs[i], on_signal);
  }
#ifdef FUZZ_SANITIZED
  __sanitizer_set_death_callback(on_sanitizer_death);
#endif

  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  fz_buf b = {0};
  if (!r) return 2;
  F.mutant = &b;
  cur_seed = F.seed;
  const double t0 = now();
  unsigned long ran = 0;
  int stopped = 0;
  for (unsigned long it = F.first; it - F.first < F.n; it++) {
    if (F.max_seconds > 0 && now() - t0 > F.max_seconds) {
      stopped = 1;
      break;
    }
    fz_rng_for(r, F.seed, it);
    /* links and meshes 2 : 2, stencils 1 */
    fz_kind kind =
        F.target >= 0
            ? (fz_kind)F.target
            : (fz_kind)((unsigned long[]){0, 0, 1, 1, 2})[gsl_rng_uniform_int(r, 5)];
    const seed_file *s =
        &F.seeds[kind][gsl_rng_uniform_int(r, (unsigned long)F.nseeds[kind])];
    const seed_file *o =
        &F.seeds[kind][gsl_rng_uniform_int(r, (unsigned long)F.nseeds[kind])];
    /* a mesh is sometimes fed to the other format's reader */
    int obj = kind == FZ_MESH && strstr(s->path, ".obj") != NULL;
    if (kind == FZ_MESH && gsl_rng_uniform(r) < 0.1) obj = !obj;
    if (fz_buf_set(&b, s->text.data, s->text.len) || fz_mutate(r, kind, &b, &o->text)) {
      fprintf(stderr, "fuzz_parse: out of memory\n");
      return 2;
    }
    cur_iter = it;
    cur_kind = fz_kind_name(kind);
    cur_stage = "-";
    cur_data = b.data;
    cur_len = b.len;
    if (F.dump) {
      printf("iteration %lu (%s%s, from %s): \"", it, fz_kind_name(kind),
             kind == FZ_MESH ? (obj ? " as OBJ" : " as Medit") : "", s->path);
      fz_escape(stdout, b.data, b.len, 0);
      printf("\"\n");
      fflush(stdout);
    }
    if (F.write_dir) {
      if (write_mutant(&F, it, kind, obj, &b)) return 2;
      ran++;
      continue;
    }
    F.tried[kind]++;
    const double t = now();
    alarm(F.mutant_timeout);
    switch (kind) {
    case FZ_LINK:
      run_link(&F, b.data);
      break;
    case FZ_MESH:
      run_mesh(&F, &b, obj);
      break;
    default:
      run_stencil(&F, b.data);
      break;
    }
    alarm(0);
    note_time(&F, now() - t, it, fz_kind_name(kind));
    cur_data = NULL;
    ran++;
  }
  print_summary(&F, ran, now() - t0, stopped);
  if (F.failures > MAXREPORTS)
    fprintf(stderr, "(%ld more failures not shown)\n", F.failures - MAXREPORTS);
  gsl_rng_free(r);
  fz_buf_free(&b);
  for (int k = 0; k < FZ_NKINDS; k++)
    for (int i = 0; i < F.nseeds[k]; i++) {
      free(F.seeds[k][i].path);
      fz_buf_free(&F.seeds[k][i].text);
    }
  for (int i = 0; i < F.nshapes; i++)
    free((char *)F.shapes[i].shape);
  for (int k = 0; k < 4; k++)
    ss_scheme_free(F.schemes[k]);
  ss_cx_free(F.tet_sample);
  ss_cx_free(F.hex_sample);
  ss_link_free(F.tetra);
  return F.failures || ran == 0 ? 1 : 0;
}
