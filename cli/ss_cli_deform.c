/* ss_cli_deform.c — `subspectra deform`: a point set or a test pattern
 * embedded in a base mesh, deformed by moving the control points, through the
 * scheme's limit (tet/oct paper, figures 7-8). */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_cli.h"
#include "ss_cli_deform.h"
#include "ss_deform.h"
#include "ss_mesh.h"
#include "ss_outfile.h"
#include "ss_scheme.h"

static const char *const usage_text =
    "usage: subspectra deform --scheme S MESH (--points FILE | --pattern grid|checker)\n"
    "                         [--displace FILE | --target MESH2] [--n N] [--samples K]\n"
    "                         [--levels L] [--method auto|exact|levels] [--embed-level "
    "E]\n"
    "                         [--format text|json|vtk|vtu|png] [-o FILE] [--progress]\n"
    "\n"
    "Embeds points in the volume of the base mesh MESH (each point's cell and\n"
    "parameters there: hexahedra by Newton's method on the trilinear map,\n"
    "tetrahedra by barycentric coordinates, octahedra by their four tets about\n"
    "the diagonal 1-4), moves the control points, and writes every point's\n"
    "image under the scheme's limit of the moved mesh, with its image under the\n"
    "limit of the unmoved one (docs/deform.md).\n"
    "\n"
    "  -s, --scheme S     the scheme (mlca, ccsolid, tetoct, boxspline, ...: any\n"
    "                     with the multilinear or the tet/oct split)\n"
    "  -p, --points FILE  the points, \"X Y Z\" per line ('#' comments); a point\n"
    "                     outside every cell is an error (exit 2)\n"
    "  -P, --pattern P    grid: the lines of an N x N x N grid of lines over the\n"
    "                     mesh's bounding box (cell-centred), K samples per line;\n"
    "                     checker: K^3 volume samples, each with the label 0/1 of\n"
    "                     its square of an N x N x N checkerboard.  Pattern points\n"
    "                     outside every cell are reported (status outside) and\n"
    "                     counted on stderr, not dropped silently\n"
    "  -N, --n N          pattern size N (2..64; default 6)\n"
    "  -k, --samples K    pattern samples K (2..400; default 64 for grid, 24 for\n"
    "                     checker)\n"
    "  -D, --displace FILE  one displacement \"DX DY DZ\" per control point, in\n"
    "                     the mesh's vertex order (exactly as many as vertices)\n"
    "  -t, --target MESH2 the moved control points: a mesh with the same vertices\n"
    "                     count and the same cells (checked); without --displace\n"
    "                     and --target nothing moves\n"
    "  -L, --levels L     levels of subdivision on the levels path (1..8; default\n"
    "                     3); memory grows by 8^L\n"
    "  -E, --embed-level E  embed in the base mesh refined E times by the scheme\n"
    "                     (0..4; default 0: the control net itself).  The\n"
    "                     tet/oct paper's way (section 3): a point's cell and\n"
    "                     parameters in the refined rest mesh, so that without\n"
    "                     a move the pattern stays (nearly) where it is and the\n"
    "                     picture shows the deformation, not the parametrisation;\n"
    "                     cells are then those of the refined mesh\n"
    "  -m, --method M     auto (default: exact where the limit evaluator covers\n"
    "                     the scheme and mesh, else levels), exact or levels\n"
    "  -f, --format F     text (default; the columns are named in a '#' line),\n"
    "                     json (one object per point: index, status, input,\n"
    "                     cell, params, base, point, with error_estimate and rate\n"
    "                     on the levels path, label or line), vtk or vtu (points;\n"
    "                     grid lines as polylines, checker labels as point data\n"
    "                     label; status point data) or png (a picture: a fixed\n"
    "                     oblique view of the deformed pattern over the moved\n"
    "                     control net).  Default from -o's extension\n"
    "  -o, --output FILE  write there (whole or not at all) instead of stdout\n"
    "      --progress     the phases on stderr as they start (reading, embedding,\n"
    "                     evaluating, writing)\n"
    "  -h, --help         this text\n"
    "\n";

/* The usage text's second half (one literal would exceed the 4095 characters
 * C11 compilers must support). */
static const char *const usage_paths =
    "Paths.  exact: the limit evaluator of `subspectra limit` (hexahedral meshes\n"
    "under mlca, ccsolid and the averaging family, creases on the hexahedra\n"
    "included).  levels: L\n"
    "levels of the scheme's refinement, each point followed into its child cell\n"
    "through the linear split, evaluated by its level-L cell's interpolant; the\n"
    "error estimate is g_L lambda / (1 - lambda) with g_L the change from level\n"
    "L-1 and lambda = max(1/2, g_L / g_(L-1)) -- an estimate, not a bound (the\n"
    "gaps shrink by the largest eigenvalue below 1 that the point sees once its\n"
    "cell is stationary; docs/deform.md).  The largest estimate is on stderr.\n"
    "\n"
    "Exit status: 0 every point evaluated; 1 a point the evaluator refused (all\n"
    "points written, missing values NaN / null); 2 bad usage or input (an\n"
    "unknown pattern, a displacement count that is not the vertex count, a\n"
    "target of other topology, a --points point outside the mesh).\n";

/* The command line. */
typedef struct {
  const char *scheme, *mesh; /* --scheme, MESH */
  const char *points;        /* --points FILE, or NULL */
  const char *pattern;       /* --pattern, or NULL */
  const char *displace;      /* --displace FILE, or NULL */
  const char *target;        /* --target MESH2, or NULL */
  const char *out;           /* -o FILE, or NULL: stdout */
  long n, samples, levels;   /* --n, --samples (0: default), --levels */
  long embed;                /* --embed-level E */
  int method;                /* 0 auto, 1 exact, 2 levels */
  int format;                /* SS_DEFORM_FMT_*, or -1: from -o */
  int want_progress;         /* --progress was given */
  ss_cli_progress *progress; /* the phases' lines on stderr (--progress); NULL: none */
} deform_opts;

/* A phase starts: its line on stderr with --progress. */
static void phase(const deform_opts *o, const char *what) {
  if (o->progress) ss_cli_progress_fn(o->progress, what, 0, 0);
}

static int parse_format(const char *s) {
  static const char *const names[] = {"text", "json", "vtk", "vtu", "png"};
  for (int i = 0; i < 5; i++)
    if (!strcmp(s, names[i])) return i;
  return -1;
}

/* argv into o: -1 to go on, else the exit status. */
static int parse(int argc, char **argv, deform_opts *o) {
  static const struct option opts[] = {{"scheme", required_argument, NULL, 's'},
                                       {"points", required_argument, NULL, 'p'},
                                       {"pattern", required_argument, NULL, 'P'},
                                       {"n", required_argument, NULL, 'N'},
                                       {"samples", required_argument, NULL, 'k'},
                                       {"displace", required_argument, NULL, 'D'},
                                       {"target", required_argument, NULL, 't'},
                                       {"levels", required_argument, NULL, 'L'},
                                       {"method", required_argument, NULL, 'm'},
                                       {"format", required_argument, NULL, 'f'},
                                       {"output", required_argument, NULL, 'o'},
                                       {"help", no_argument, NULL, 'h'},
                                       {"embed-level", required_argument, NULL, 'E'},
                                       {"progress", no_argument, NULL, 'G'},
                                       {NULL, 0, NULL, 0}};
  optind = 1;
  opterr = 0;
  int c;
  while ((c = getopt_long(argc, argv, ":s:p:P:N:k:D:t:L:m:f:o:hE:", opts, NULL)) != -1) {
    switch (c) {
    case 's':
      o->scheme = optarg;
      break;
    case 'p':
      o->points = optarg;
      break;
    case 'P':
      if (strcmp(optarg, "grid") && strcmp(optarg, "checker"))
        return ss_cli_usage_error(
            "deform", "unknown pattern '%s': expected grid or checker", optarg);
      o->pattern = optarg;
      break;
    case 'N':
      if (ss_cli_parse_int(optarg, 2, 64, &o->n))
        return ss_cli_usage_error("deform", "--n '%s' is not an integer in 2..64",
                                  optarg);
      break;
    case 'k':
      if (ss_cli_parse_int(optarg, 2, 400, &o->samples))
        return ss_cli_usage_error("deform", "--samples '%s' is not an integer in 2..400",
                                  optarg);
      break;
    case 'E':
      if (ss_cli_parse_int(optarg, 0, 4, &o->embed))
        return ss_cli_usage_error("deform",
                                  "--embed-level '%s' is not an integer in 0..4", optarg);
      break;
    case 'D':
      o->displace = optarg;
      break;
    case 't':
      o->target = optarg;
      break;
    case 'L':
      if (ss_cli_parse_int(optarg, 1, 8, &o->levels))
        return ss_cli_usage_error("deform", "--levels '%s' is not an integer in 1..8",
                                  optarg);
      break;
    case 'm':
      if (!strcmp(optarg, "auto"))
        o->method = 0;
      else if (!strcmp(optarg, "exact"))
        o->method = 1;
      else if (!strcmp(optarg, "levels"))
        o->method = 2;
      else
        return ss_cli_usage_error(
            "deform", "--method: expected auto, exact or levels, not '%s'", optarg);
      break;
    case 'f':
      if ((o->format = parse_format(optarg)) < 0)
        return ss_cli_usage_error(
            "deform", "--format: expected text, json, vtk, vtu or png, not '%s'", optarg);
      break;
    case 'o':
      o->out = optarg;
      break;
    case 'G':
      o->want_progress = 1;
      break;
    case 'h':
      fputs(usage_text, stdout);
      fputs(usage_paths, stdout);
      return SS_EXIT_OK;
    default:
      return ss_cli_option_error("deform", c, argv);
    }
  }
  if (optind + 1 != argc)
    return ss_cli_usage_error("deform",
                              optind == argc ? "no mesh given" : "more than one mesh");
  o->mesh = argv[optind];
  if (!o->scheme) return ss_cli_usage_error("deform", "--scheme is required");
  if (!o->points == !o->pattern)
    return ss_cli_usage_error("deform", "give exactly one of --points and --pattern");
  if (o->displace && o->target)
    return ss_cli_usage_error("deform", "give at most one of --displace and --target");
  if (o->format < 0) {
    const char *dot = o->out ? strrchr(o->out, '.') : NULL;
    o->format = dot ? parse_format(dot + 1) : SS_DEFORM_FMT_TEXT;
    if (o->format < 0) o->format = SS_DEFORM_FMT_TEXT;
  }
  if (o->format == SS_DEFORM_FMT_PNG && !o->out)
    return ss_cli_usage_error("deform", "--format png needs -o FILE");
  return -1;
}

/* Append point x (label, line) to *pt: 0 or -1 (out of memory). */
static int push(ss_deform_cli_point **pt, size_t *n, size_t *cap, const double x[3],
                int label, long line) {
  if (*n == *cap) {
    const size_t c2 = *cap ? 2 * *cap : 1024;
    ss_deform_cli_point *q = realloc(*pt, c2 * sizeof *q);
    if (!q) return -1;
    *pt = q;
    *cap = c2;
  }
  ss_deform_cli_point *p = &(*pt)[(*n)++];
  memset(p, 0, sizeof *p);
  memcpy(p->x, x, sizeof p->x);
  p->label = label;
  p->line = line;
  return 0;
}

/* The pattern's points over the bounding box of mesh: 0 or -1 (memory). */
static int make_pattern(const deform_opts *o, const ss_cx *mesh, ss_deform_cli_point **pt,
                        size_t *n) {
  double lo[3] = {INFINITY, INFINITY, INFINITY},
         hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (size_t v = 0; v < mesh->nv; v++)
    for (int a = 0; a < 3; a++) {
      lo[a] = fmin(lo[a], mesh->x[v * 3 + (size_t)a]);
      hi[a] = fmax(hi[a], mesh->x[v * 3 + (size_t)a]);
    }
  const long N = o->n ? o->n : 6;
  const int grid = !strcmp(o->pattern, "grid");
  const long K = o->samples ? o->samples : (grid ? 64 : 24);
  size_t cap = 0;
  double x[3];
  if (grid) { /* lines along axis a through the cell centres of the other two */
    long line = 0;
    for (int a = 0; a < 3; a++)
      for (long i = 0; i < N; i++)
        for (long j = 0; j < N; j++, line++) {
          const int b = (a + 1) % 3, c = (a + 2) % 3;
          x[b] = lo[b] + (hi[b] - lo[b]) * ((double)i + 0.5) / (double)N;
          x[c] = lo[c] + (hi[c] - lo[c]) * ((double)j + 0.5) / (double)N;
          for (long s = 0; s < K; s++) {
            const double t =
                (0.5 + (double)(N - 1) * (double)s / (double)(K - 1)) / (double)N;
            x[a] = lo[a] + (hi[a] - lo[a]) * t;
            if (push(pt, n, &cap, x, -1, line)) return -1;
          }
        }
    return 0;
  }
  for (long k = 0; k < K; k++)
    for (long j = 0; j < K; j++)
      for (long i = 0; i < K; i++) {
        const long ijk[3] = {i, j, k};
        long sum = 0;
        for (int a = 0; a < 3; a++) {
          x[a] = lo[a] + (hi[a] - lo[a]) * ((double)ijk[a] + 0.5) / (double)K;
          sum += ijk[a] * N / K;
        }
        if (push(pt, n, &cap, x, (int)(sum % 2), -1)) return -1;
      }
  return 0;
}

/* Read "X Y Z" rows of path into *rows (n rows): 0, or 2 with the message. */
static int read_rows(const char *path, const char *what, double (**rows)[3], size_t *n) {
  FILE *f = fopen(path, "r");
  if (!f) {
    fprintf(stderr, "subspectra deform: cannot open %s file '%s'\n", what, path);
    return SS_EXIT_USAGE;
  }
  char *line = NULL, *item;
  size_t lcap = 0, cap = 0;
  long lineno = 0;
  int rc = 0;
  *rows = NULL;
  *n = 0;
  while ((item = ss_cli_next_item(f, &line, &lcap, &lineno))) {
    double x[3];
    char *end = item;
    for (int a = 0; a < 3; a++) {
      const char *b = end;
      x[a] = strtod(b, &end);
      if (end == b || !isfinite(x[a])) end = NULL;
      if (!end) break;
    }
    while (end && (*end == ' ' || *end == '\t'))
      end++;
    if (!end || *end) {
      fprintf(stderr, "subspectra deform: %s:%ld: expected three finite numbers\n", path,
              lineno);
      rc = SS_EXIT_USAGE;
      break;
    }
    if (*n == cap) {
      cap = cap ? 2 * cap : 256;
      double(*q)[3] = realloc(*rows, cap * sizeof *q);
      if (!q) {
        fprintf(stderr, "subspectra deform: out of memory\n");
        rc = SS_EXIT_USAGE;
        break;
      }
      *rows = q;
    }
    memcpy((*rows)[(*n)++], x, sizeof x);
  }
  free(line);
  fclose(f);
  return rc;
}

/* The moved control net: a copy of base, moved by --displace or replaced by
 * --target's positions after the topology check.  0 or 2 with the message. */
static int moved_net(const deform_opts *o, const ss_cx *base, ss_cx **moved) {
  ss_error err = {0};
  if (ss_cx_copy(base, moved, &err)) return ss_cli_fail("deform", &err);
  if (o->displace) {
    double(*d)[3] = NULL;
    size_t n = 0;
    int rc = read_rows(o->displace, "displacement", &d, &n);
    if (!rc && n != base->nv) {
      fprintf(stderr,
              "subspectra deform: %s has %zu displacements; %s has %zu control points "
              "(one displacement per control point)\n",
              o->displace, n, o->mesh, base->nv);
      rc = SS_EXIT_USAGE;
    }
    for (size_t v = 0; !rc && v < n; v++)
      for (int a = 0; a < 3; a++)
        (*moved)->x[v * 3 + (size_t)a] += d[v][a];
    free(d);
    return rc;
  }
  if (!o->target) return 0;
  ss_cx *t = NULL;
  if (ss_mesh_read(o->target, SS_MESH_AUTO, &t, &err)) return ss_cli_fail("deform", &err);
  const char *why = NULL;
  char buf[160];
  if (t->dim != 3)
    why = "it has not 3 coordinates";
  else if (t->nv != base->nv) {
    snprintf(buf, sizeof buf, "%zu vertices, not %zu", t->nv, base->nv);
    why = buf;
  }
  for (int ty = 0; !why && ty < SS_NCELLTYPES; ty++) {
    const size_t m = base->nc[ty] * (size_t)ss_cell_nverts((ss_cell_type)ty);
    if (t->nc[ty] != base->nc[ty]) {
      snprintf(buf, sizeof buf, "%zu %s, not %zu", t->nc[ty],
               ss_cell_plural((ss_cell_type)ty), base->nc[ty]);
      why = buf;
    } else if (m && memcmp(t->cells[ty], base->cells[ty], m * sizeof(ss_idx))) {
      snprintf(buf, sizeof buf, "its %s have other vertices",
               ss_cell_plural((ss_cell_type)ty));
      why = buf;
    }
  }
  if (why) {
    fprintf(stderr, "subspectra deform: target %s does not have the topology of %s: %s\n",
            o->target, o->mesh, why);
    ss_cx_free(t);
    return SS_EXIT_USAGE;
  }
  memcpy((*moved)->x, t->x, base->nv * 3 * sizeof *t->x);
  ss_cx_free(t);
  return 0;
}

/* Embed every point: status OUTSIDE or its loc.  With --points an outside
 * point is an error (2, named); patterns count them.  0, or the exit status. */
static int embed(const deform_opts *o, const ss_cx *base, ss_deform_cli_point *pt,
                 size_t n, size_t *outside) {
  ss_deform_locator *P = NULL;
  ss_error err = {0};
  if (ss_deform_locator_new(base, &P, &err)) return ss_cli_fail("deform", &err);
  *outside = 0;
  size_t first = n;
  for (size_t i = 0; i < n; i++) {
    int found;
    ss_deform_locate(P, pt[i].x, &pt[i].loc, &found);
    pt[i].status = found ? SS_DEFORM_CLI_OK : SS_DEFORM_CLI_OUTSIDE;
    if (!found && !(*outside)++) first = i;
    for (int a = 0; a < 3; a++)
      pt[i].base[a] = pt[i].p[a] = NAN;
    pt[i].est = pt[i].rate = NAN;
  }
  ss_deform_locator_free(P);
  if (*outside && o->points) {
    fprintf(stderr,
            "subspectra deform: point %zu (%.17g %.17g %.17g) of %s lies outside every "
            "cell of %s (%zu of %zu points are outside)\n",
            first + 1, pt[first].x[0], pt[first].x[1], pt[first].x[2], o->points, o->mesh,
            *outside, n);
    return SS_EXIT_USAGE;
  }
  return 0;
}

/* The exact path for the embedded points: 0, 1 (a point refused), 2, or -1
 * when the evaluator does not take this scheme and mesh (why in *err). */
static int eval_exact(const ss_scheme *s, const ss_cx *base, const ss_cx *moved,
                      ss_deform_cli_point *pt, size_t n, ss_error *err) {
  size_t m = 0;
  ss_deform_loc *loc = malloc((n + 1) * sizeof *loc);
  double(*vb)[3] = malloc((n + 1) * sizeof *vb), (*vm)[3] = malloc((n + 1) * sizeof *vm);
  unsigned char *okb = malloc(n + 1), *okm = malloc(n + 1);
  int rc = 0;
  if (!loc || !vb || !vm || !okb || !okm) {
    rc = ss_cli_fail("deform", (ss_error_nomem(err, "points"), err));
    goto done;
  }
  for (size_t i = 0; i < n; i++)
    if (pt[i].status == SS_DEFORM_CLI_OK) loc[m++] = pt[i].loc;
  ss_status st = ss_deform_eval_exact(s, base, loc, m, vb, okb, err);
  if (!st) st = ss_deform_eval_exact(s, moved, loc, m, vm, okm, err);
  if (st) {
    rc = st == SS_EINPUT ? -1 : ss_cli_fail("deform", err);
    goto done;
  }
  for (size_t i = 0, j = 0; i < n; i++) {
    if (pt[i].status != SS_DEFORM_CLI_OK) continue;
    memcpy(pt[i].base, vb[j], sizeof vb[j]);
    memcpy(pt[i].p, vm[j], sizeof vm[j]);
    if (!okb[j] || !okm[j]) {
      pt[i].status = SS_DEFORM_CLI_FAILED;
      rc = SS_EXIT_FAIL;
    }
    j++;
  }
done:
  free(loc);
  free(vb);
  free(vm);
  free(okb);
  free(okm);
  return rc;
}

/* The levels path: 0 or the exit status. */
static int eval_levels(const ss_scheme *s, const ss_cx *base, const ss_cx *moved, int L,
                       ss_deform_cli_point *pt, size_t n) {
  size_t m = 0;
  ss_error err = {0};
  ss_deform_loc *loc = malloc((n + 1) * sizeof *loc);
  double(*vb)[3] = malloc(((size_t)(L + 1) * n + 1) * sizeof *vb);
  double(*vm)[3] = malloc(((size_t)(L + 1) * n + 1) * sizeof *vm);
  int rc = 0;
  if (!loc || !vb || !vm) {
    rc = ss_cli_fail("deform", (ss_error_nomem(&err, "points"), &err));
    goto done;
  }
  for (size_t i = 0; i < n; i++)
    if (pt[i].status == SS_DEFORM_CLI_OK) loc[m++] = pt[i].loc;
  if (ss_deform_eval_levels(s, base, L, loc, m, vb, &err) ||
      ss_deform_eval_levels(s, moved, L, loc, m, vm, &err)) {
    rc = ss_cli_fail("deform", &err);
    goto done;
  }
  for (size_t i = 0, j = 0; i < n; i++) {
    if (pt[i].status != SS_DEFORM_CLI_OK) continue;
    memcpy(pt[i].base, vb[(size_t)L * m + j], sizeof vb[0]);
    memcpy(pt[i].p, vm[(size_t)L * m + j], sizeof vm[0]);
    pt[i].est = ss_deform_estimate((const double(*)[3])vm + j, m, L, &pt[i].rate);
    j++;
  }
done:
  free(loc);
  free(vb);
  free(vm);
  return rc;
}

/* Write out to o->out or stdout: 0 or the exit status. */
static int write_out(const deform_opts *o, const ss_deform_cli_out *out) {
  ss_error err = {0};
  if (!o->out)
    return ss_cli_deform_write_text(stdout, out, o->format, &err)
               ? ss_cli_fail("deform", &err)
               : 0;
  ss_outfile *of = NULL;
  if (ss_outfile_open(o->out, &of, &err)) return ss_cli_fail("deform", &err);
  ss_status st = SS_OK;
  if (o->format == SS_DEFORM_FMT_PNG)
    st = ss_cli_deform_write_png(ss_outfile_file(of), out, &err);
  else
    st = ss_cli_deform_write_text(ss_outfile_file(of), out, o->format, &err);
  if (st) {
    ss_outfile_abort(of);
    return ss_cli_fail("deform", &err);
  }
  return ss_outfile_commit(of, &err) ? ss_cli_fail("deform", &err) : 0;
}

/* --embed-level E: both nets refined E times by the scheme (in place).  0
 * or the exit status. */
static int refine_both(const ss_scheme *s, int E, ss_cx **base, ss_cx **moved) {
  ss_error err = {0};
  ss_cx *b = NULL, *m = NULL;
  if (ss_scheme_refine_levels(s, *base, E, &b, &err) ||
      ss_scheme_refine_levels(s, *moved, E, &m, &err)) {
    ss_cx_free(b);
    return ss_cli_fail("deform", &err);
  }
  ss_cx_free(*base);
  ss_cx_free(*moved);
  *base = b;
  *moved = m;
  return 0;
}

/* Evaluate by o->method (base and moved: the nets the points are embedded
 * in; net: the moved control net, drawn in the picture), write, and print the
 * summary; 0, 1 or 2. */
static int run(const deform_opts *o, const ss_scheme *s, const ss_cx *base,
               const ss_cx *moved, const ss_cx *net, ss_deform_cli_point *pt, size_t n,
               size_t outside) {
  ss_error err = {0};
  const int L = o->levels ? (int)o->levels : 3;
  int rc = -1, exact = 0;
  phase(o, "evaluating the limit");
  if (o->method != 2) {
    rc = eval_exact(s, base, moved, pt, n, &err);
    if (rc == -1 && o->method == 1) {
      fprintf(stderr, "subspectra deform: --method exact: %s\n", err.msg);
      return SS_EXIT_USAGE;
    }
    if (rc == -1)
      fprintf(stderr,
              "subspectra deform: no exact limit here (%s): %d levels of "
              "subdivision\n",
              err.msg, L);
    exact = rc != -1;
  }
  if (rc == -1) rc = eval_levels(s, base, moved, L, pt, n);
  if (rc == SS_EXIT_USAGE) return rc;
  double worst = 0.0, rate = 0.0;
  size_t failed = 0;
  for (size_t i = 0; i < n; i++) {
    failed += pt[i].status == SS_DEFORM_CLI_FAILED;
    if (pt[i].status == SS_DEFORM_CLI_OK && !exact && !(pt[i].est <= worst)) {
      worst = pt[i].est;
      rate = pt[i].rate;
    }
  }
  ss_deform_cli_out out = {pt, n, exact, exact ? 0 : L, o->scheme, net};
  phase(o, "writing");
  int wc = write_out(o, &out);
  if (wc) return wc;
  fprintf(stderr, "subspectra deform: %zu points, %zu outside the mesh, %zu refused; ", n,
          outside, failed);
  if (exact)
    fprintf(stderr, "the exact limit\n");
  else
    fprintf(stderr,
            "%d levels of %s, error estimate (not a bound) at most %.3g "
            "(rate %.3g there)\n",
            L, o->scheme, worst, rate);
  return rc;
}

int ss_cli_deform(int argc, char **argv) {
  deform_opts o = {0};
  o.format = -1;
  int rc = parse(argc, argv, &o);
  if (rc >= 0) return rc;
  ss_cli_progress pr = {"deform", ss_cli_now(), 0, NULL, 0};
  if (o.want_progress) o.progress = &pr;
  phase(&o, "reading the mesh");
  ss_error err = {0};
  ss_scheme *s = NULL;
  ss_cx *base = NULL, *moved = NULL, *net = NULL;
  ss_deform_cli_point *pt = NULL;
  size_t n = 0, outside = 0;
  ss_mesh_fields names;
  if (ss_scheme_new(o.scheme, &s, &err) ||
      ss_mesh_read_fields(o.mesh, SS_MESH_AUTO, &base, &names, &err)) {
    rc = ss_cli_fail("deform", &err);
    goto done;
  }
  if (base->dim > 3) { /* fields: named, and not evaluated here (yet) */
    fprintf(stderr,
            "subspectra deform: %s carries %d field%s (%s%s), which deform "
            "does not evaluate yet (`subspectra limit` does)\n",
            o.mesh, names.n, names.n == 1 ? "" : "s", names.name[0],
            names.n > 1 ? ", ..." : "");
    rc = SS_EXIT_USAGE;
    goto done;
  }
  if (base->dim != 3) {
    fprintf(stderr,
            "subspectra deform: %s has %d coordinates per vertex; deform needs 3\n",
            o.mesh, base->dim);
    rc = SS_EXIT_USAGE;
    goto done;
  }
  if (o.points) {
    double(*rows)[3] = NULL;
    if ((rc = read_rows(o.points, "points", &rows, &n))) goto done;
    size_t cap = 0, m = 0;
    for (size_t i = 0; i < n && !rc; i++)
      if (push(&pt, &m, &cap, rows[i], -1, -1)) rc = SS_EXIT_USAGE;
    free(rows);
    if (rc || !n) {
      fprintf(stderr, "subspectra deform: %s\n",
              rc ? "out of memory" : "no points given");
      rc = SS_EXIT_USAGE;
      goto done;
    }
  } else if (make_pattern(&o, base, &pt, &n)) {
    fprintf(stderr, "subspectra deform: out of memory\n");
    rc = SS_EXIT_USAGE;
    goto done;
  }
  if ((rc = moved_net(&o, base, &moved))) goto done;
  if (ss_cx_copy(moved, &net, &err)) { /* the moved control net, for the picture */
    rc = ss_cli_fail("deform", &err);
    goto done;
  }
  if (o.embed > 0 && (rc = refine_both(s, (int)o.embed, &base, &moved))) goto done;
  phase(&o, "embedding the points");
  if ((rc = embed(&o, base, pt, n, &outside))) goto done;
  rc = run(&o, s, base, moved, net, pt, n, outside);
done:
  free(pt);
  ss_cx_free(base);
  ss_cx_free(moved);
  ss_cx_free(net);
  ss_scheme_free(s);
  return rc;
}
