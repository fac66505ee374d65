/* ss_cli_limit.c — `subspectra limit`: points (and Jacobians) of the limit
 * volume of a hex mesh at given parameters, regular samples or Gauss points. */
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <json-c/json.h>

#include "ss_cli.h"
#include "ss_cli_limit.h"
#include "ss_limit.h"
#include "ss_mesh.h"
#include "ss_outfile.h"
#include "ss_scheme.h"

static const char *const usage_text =
    "usage: subspectra limit --scheme S MESH (--at \"CELL U V W\" | --samples N |\n"
    "                        --gauss Q) [--derivatives]\n"
    "                        [--format text|json|vtk|vtu] [-o FILE] [--progress]\n"
    "\n"
    "The limit volume of the hexahedral mesh MESH under scheme S: the limit point\n"
    "at parameters (U, V, W) in [0,1]^3 of a cell (U along the cell's corners\n"
    "1 -> 2, V along 1 -> 4, W along 1 -> 5 in the file's order), and with\n"
    "--derivatives the 3x3 Jacobian (rows d/dU, d/dV, d/dW).  Cells are numbered\n"
    "from 1 as in the file.\n"
    "\n"
    "Boundaries and creases: corners (vertex cells), segments and quadrilaterals\n"
    "on the hexahedra are creases, refined by the scheme's own crease rules (as\n"
    "subdivide refines them); the limit on boundary and creased cells comes from\n"
    "those rules, with one-sided derivatives on the boundary and on a crease\n"
    "surface, where they exist (docs/limit.md).\n"
    "\n"
    "Fields: coordinates past the third are scalar values per control point,\n"
    "named by the file: VTK/VTU point data (a 3-vector NAME as NAME_x, _y, _z),\n"
    "gmsh $NodeData views, a Medit 4th coordinate (w; then x5, x6, ...).  They\n"
    "are subdivided like the coordinates (the same weights), and their limit\n"
    "values are written with each point, with --derivatives also their\n"
    "gradients in the cell's parameters (d/dU, d/dV, d/dW).  A mesh without\n"
    "them is evaluated as before.\n"
    "\n"
    "  -s, --scheme S     mlca, ccsolid or ccsolid-tensor (any scheme that splits\n"
    "                     hexahedra multilinearly with a one-ring rule and is\n"
    "                     the tricubic B-spline on regular grids)\n"
    "  -a, --at \"C U V W\" one point (repeatable)\n"
    "  -n, --samples N    N^3 regular samples per cell (parameters i/(N-1); N = 1:\n"
    "                     the centre), N in 1..100\n"
    "  -g, --gauss Q      Q^3 Gauss-Legendre points per cell, Q in 1..20 (json\n"
    "                     adds each point's weight on [0,1]^3)\n"
    "  -d, --derivatives  also the Jacobian\n"
    "      --reference    evaluate by repeated local subdivision instead (slow;\n"
    "                     for checking), at most 60 steps\n"
    "  -f, --format F     text (default: CELL U V W X Y Z [9 Jacobian entries]\n"
    "                     [each field's value] [each field's 3 derivatives]),\n"
    "                     json (one object per line with cell, u, v, w, point,\n"
    "                     jacobian, and with fields \"fields\": {NAME: value} and\n"
    "                     \"field_gradients\": {NAME: [d/dU, d/dV, d/dW]}) or vtk\n"
    "                     (legacy VTK for ParaView: with --samples N >= 2 the\n"
    "                     sampled volume as hexahedra, every cell with its own\n"
    "                     points, otherwise points; point data: cell,\n"
    "                     jacobian_det, each field NAME and its NAME_gradient,\n"
    "                     3 components) or vtu (VTK XML: the same, but a sample\n"
    "                     that neighbouring cells share is one point, and the\n"
    "                     point data hold status and the Jacobian as the\n"
    "                     9-component tensor jacobian, component 3a+d =\n"
    "                     jacobian[a][d]; a shared point's data are those of\n"
    "                     its first cell with the best status, named by cell)\n"
    "  -o, --output FILE  write there (whole or not at all) instead of stdout\n"
    "      --progress     the points evaluated of all on stderr (at most a line a\n"
    "                     second, and after the last)\n"
    "  -h, --help         this text\n"
    "\n";

/* The usage text's second half (one literal would exceed the 4095 characters
 * C11 compilers must support). */
static const char *const usage_how =
    "How (docs/methods.md, \"Limit evaluation\"): the cell's patch is refined in the\n"
    "scheme's own global rule, following the child that holds the point, until\n"
    "the sub-cell is regular (then the tricubic B-spline).  Each patch topology\n"
    "and step is computed once and cached; a stationary run of steps (towards an\n"
    "extraordinary vertex, along an extraordinary edge, towards the boundary) is\n"
    "one eigen-decomposition W^m = V L^m V^-1 (Stam), or binary powers of W where\n"
    "W is defective.  Cost per point: constant for regular cells, near\n"
    "extraordinary vertices, and near extraordinary edges whose refinement is a\n"
    "tensor product (checked on the patch: MLCA's and ccsolid-tensor's are; the\n"
    "paper's eq. (1)); near other edges (Joy-MacCracken's ccsolid: no tensor\n"
    "product) and the boundary, bounded by the changes among the point's binary\n"
    "digits (at most ~53 per coordinate in double precision), not constant.\n"
    "\n"
    "Points exactly on an extraordinary vertex or edge or on the boundary are\n"
    "fixed points of a run; their Jacobian is read from the run's eigenvalue-1/2\n"
    "part (eigenvalues below 1/2 contribute 0: MLCA's limit of a pure hex mesh\n"
    "has a zero normal derivative on the boundary).\n"
    "\n"
    "Every double parameter is walked exactly, down to 2^-1074; the Jacobian is\n"
    "accurate to about 1e-13 of its largest entry, and the row along an\n"
    "extraordinary edge very near it, which grows far slower than the others,\n"
    "is computed apart (README: \"Jacobians ... and precision\"); a row whose\n"
    "estimated rounding still exceeds 1e-9 of its size is refused.\n"
    "\n"
    "Exit status: 0 all points evaluated; 1 some point not evaluated in full\n"
    "(below; every point is written all the same); 2 bad usage or input,\n"
    "before anything is evaluated (bad options, an --at that is not \"CELL U V\n"
    "W\", an unreadable mesh, a mesh with cells other than hexahedra and the\n"
    "creases on them, not manifold across a face, or with flat, folded or\n"
    "inverted hexahedra, a scheme that does not split hexahedra or is no\n"
    "tricubic B-spline on grids, a field value that is not a finite number).\n";

/* The usage text's third part: batches. */
static const char *const usage_batch =
    "\n"
    "Batches: a point that cannot be evaluated does not stop the others.  Every\n"
    "point is written, with its status:\n"
    "  0 ok              evaluated\n"
    "  1 no_derivatives  the point and field values, but with --derivatives\n"
    "                    no Jacobian or field gradients: at a fixed point with\n"
    "                    an eigenvalue of modulus >= 1/2 other than 1/2 or 1\n"
    "                    (e.g. an extraordinary vertex) or a Jordan block at\n"
    "                    1/2 they are unbounded or undefined, or a row whose\n"
    "                    rounding estimate exceeds 1e-9 of its size\n"
    "  2 failed          a numerical failure of the point itself (a run whose\n"
    "                    limit is not defined, a result beyond the range of\n"
    "                    doubles, --reference beyond 60 steps): no value\n"
    "  3 refused         not a point the evaluator takes (unknown cell, a\n"
    "                    parameter outside [0,1] or not a number, a cell whose\n"
    "                    patch is not manifold at a vertex): no value\n"
    "Values a point does not have are nan in text and VTK and null in JSON.\n"
    "When some point is not ok the text gets a last column (the status name),\n"
    "each JSON object \"status\" (the name) and, unless ok, \"reason\" (the\n"
    "evaluator's message), VTK the point data status (the code); the first ten\n"
    "such points and their count go to stderr, and the exit status is 1.  When\n"
    "every point is ok the output has no status (VTU always has its array).\n";

/* The mesh's positions (*pos, a 3-coordinate copy) and its coordinates past
 * the third as fields (*val, nv * nf, vertex-major) named by names (the
 * mesh file's, ss_mesh_read_fields); mesh->dim >= 3.  SS_ENOMEM. */
static ss_status split_fields(const ss_cx *mesh, const ss_mesh_fields *names, ss_cx **pos,
                              double **val, ss_limit_cli_fields *fl, ss_error *err) {
  const size_t dim = (size_t)mesh->dim, nf = dim - 3;
  ss_status st = ss_cx_copy(mesh, pos, err);
  *val = NULL;
  fl->nf = nf;
  if (st || !nf) return st;
  if (!(*val = malloc((mesh->nv * nf + 1) * sizeof **val))) {
    ss_cx_free(*pos);
    *pos = NULL;
    return ss_error_nomem(err, "fields");
  }
  double *x = (*pos)->x; /* compacted in place to 3 per vertex */
  for (size_t v = 0; v < mesh->nv; v++) {
    for (size_t d = 0; d < 3; d++)
      x[v * 3 + d] = mesh->x[v * dim + d];
    for (size_t i = 0; i < nf; i++)
      (*val)[v * nf + i] = mesh->x[v * dim + 3 + i];
  }
  (*pos)->dim = 3;
  for (size_t i = 0; i < nf; i++)
    memcpy(fl->name[i], names->name[i], sizeof fl->name[i]);
  return SS_OK;
}

/* Gauss-Legendre nodes and weights on [0,1] (Newton on P_q from the
 * Chebyshev guesses; weights 2 / ((1 - t^2) P_q'(t)^2), halved for [0,1]). */
static void gauss(int q, double *node, double *weight) {
  for (int i = 0; i < q; i++) {
    double t = cos(M_PI * (i + 0.75) / (q + 0.5)), dp = 1.0;
    for (int it = 0; it < 100; it++) {
      double p0 = 1.0, p1 = t;
      for (int k = 2; k <= q; k++) {
        double p2 = ((2.0 * k - 1.0) * t * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = q * (t * p1 - p0) / (t * t - 1.0);
      double dt = p1 / dp;
      t -= dt;
      if (fabs(dt) < 1e-17) break;
    }
    node[q - 1 - i] = (1.0 + t) / 2.0;
    weight[q - 1 - i] = 1.0 / ((1.0 - t * t) * dp * dp);
  }
}

/* Parse "CELL U V W" strictly. */
static int parse_at(const char *s, ss_limit_cli_point *p) {
  char *end;
  errno = 0;
  long long c = strtoll(s, &end, 10);
  if (end == s || errno || c < 1) return -1;
  p->cell = (size_t)(c - 1);
  for (int a = 0; a < 3; a++) {
    const char *b = end;
    p->x[a] = strtod(b, &end);
    if (end == b) return -1;
  }
  while (*end == ' ' || *end == '\t')
    end++;
  return *end ? -1 : 0;
}

/* The command line of limit. */
typedef struct {
  const char *scheme;      /* --scheme */
  const char *out;         /* -o FILE, or NULL: stdout */
  const char *mesh;        /* MESH */
  long samples;            /* --samples N per direction, or 0 */
  long gq;                 /* --gauss Q points per direction, or 0 */
  int derivs;              /* --derivatives */
  int reference;           /* --reference: the slow reference evaluation */
  int format;              /* 0 text, 1 json, 2 vtk, 3 vtu */
  int progress;            /* --progress: points done on stderr */
  ss_limit_cli_point *pts; /* --at points (owned) */
  size_t npts, cap;        /* how many, allocated */
  ss_limit_cli_fields fl;  /* the mesh's fields and their results */
} limit_opts;

/* --at TEXT appended to o->pts: 0, or the exit status 2 with the message
 * printed. */
static int add_at(limit_opts *o, const char *text) {
  if (o->npts == o->cap) {
    const size_t cap = o->cap ? 2 * o->cap : 8;
    ss_limit_cli_point *q = realloc(o->pts, cap * sizeof *q);
    if (!q) {
      fprintf(stderr, "subspectra limit: out of memory\n");
      return SS_EXIT_USAGE;
    }
    o->pts = q;
    o->cap = cap;
  }
  memset(&o->pts[o->npts], 0, sizeof o->pts[o->npts]);
  if (parse_at(text, &o->pts[o->npts]))
    return ss_cli_usage_error("limit",
                              "--at '%s': expected \"CELL U V W\" (a cell number from "
                              "1 and three numbers)",
                              text);
  o->npts++;
  return 0;
}

/* argv into o (o->pts owned by the caller, also on failure): -1 to go on,
 * else the exit status (0 after --help, 2 with the message printed). */
static int parse(int argc, char **argv, limit_opts *o) {
  static const struct option opts[] = {{"scheme", required_argument, NULL, 's'},
                                       {"at", required_argument, NULL, 'a'},
                                       {"samples", required_argument, NULL, 'n'},
                                       {"gauss", required_argument, NULL, 'g'},
                                       {"derivatives", no_argument, NULL, 'd'},
                                       {"reference", no_argument, NULL, 'R'},
                                       {"format", required_argument, NULL, 'f'},
                                       {"output", required_argument, NULL, 'o'},
                                       {"progress", no_argument, NULL, 'P'},
                                       {"help", no_argument, NULL, 'h'},
                                       {NULL, 0, NULL, 0}};
  optind = 1;
  opterr = 0;
  int c, rc;
  while ((c = getopt_long(argc, argv, ":s:a:n:g:df:o:h", opts, NULL)) != -1) {
    switch (c) {
    case 's':
      o->scheme = optarg;
      break;
    case 'a':
      if ((rc = add_at(o, optarg))) return rc;
      break;
    case 'n':
      if (ss_cli_parse_int(optarg, 1, 100, &o->samples))
        return ss_cli_usage_error("limit", "--samples '%s' is not an integer in 1..100",
                                  optarg);
      break;
    case 'g':
      if (ss_cli_parse_int(optarg, 1, 20, &o->gq))
        return ss_cli_usage_error("limit", "--gauss '%s' is not an integer in 1..20",
                                  optarg);
      break;
    case 'd':
      o->derivs = 1;
      break;
    case 'R':
      o->reference = 1;
      break;
    case 'P':
      o->progress = 1;
      break;
    case 'f':
      if (!strcmp(optarg, "text"))
        o->format = 0;
      else if (!strcmp(optarg, "json"))
        o->format = 1;
      else if (!strcmp(optarg, "vtk"))
        o->format = 2;
      else if (!strcmp(optarg, "vtu"))
        o->format = 3;
      else
        return ss_cli_usage_error(
            "limit", "--format: expected text, json, vtk or vtu, not '%s'", optarg);
      break;
    case 'o':
      o->out = optarg;
      break;
    case 'h':
      fputs(usage_text, stdout);
      fputs(usage_how, stdout);
      fputs(usage_batch, stdout);
      return SS_EXIT_OK;
    default:
      return ss_cli_option_error("limit", c, argv);
    }
  }
  if (optind + 1 != argc)
    return ss_cli_usage_error("limit",
                              optind == argc ? "no mesh given" : "more than one mesh");
  o->mesh = argv[optind];
  if (!o->scheme) return ss_cli_usage_error("limit", "--scheme is required");
  if ((o->npts > 0) + (o->samples > 0) + (o->gq > 0) != 1)
    return ss_cli_usage_error("limit", "give exactly one of --at, --samples and --gauss");
  return -1;
}

/* --samples or --gauss: the q x q x q grid of points in every cell of L
 * (equally spaced with zero weights, or Gauss-Legendre nodes with their
 * weights) in place of o->pts. */
static ss_status grid_points(limit_opts *o, const ss_limit *L, ss_error *err) {
  size_t nc = ss_limit_ncells(L), q = o->samples > 0 ? (size_t)o->samples : (size_t)o->gq;
  double node[100], wt[100];
  if (o->samples > 0)
    for (size_t i = 0; i < q; i++) {
      node[i] = q == 1 ? 0.5 : (double)i / (double)(q - 1);
      wt[i] = 0.0;
    }
  else
    gauss((int)q, node, wt);
  free(o->pts);
  o->npts = nc * q * q * q;
  o->pts = calloc(o->npts + 1, sizeof *o->pts);
  if (!o->pts) {
    o->npts = 0;
    return ss_error_nomem(err, "points");
  }
  size_t m = 0;
  for (size_t cell = 0; cell < nc; cell++)
    for (size_t k = 0; k < q; k++)
      for (size_t j = 0; j < q; j++)
        for (size_t i = 0; i < q; i++, m++) {
          o->pts[m].cell = cell;
          o->pts[m].x[0] = node[i];
          o->pts[m].x[1] = node[j];
          o->pts[m].x[2] = node[k];
          o->pts[m].weight = wt[i] * wt[j] * wt[k];
        }
  return SS_OK;
}

/* Point p by the walk (or the reference), with derivatives or not. */
static ss_status eval_one(const limit_opts *o, ss_limit *L, ss_limit_cli_point *p,
                          int derivs, ss_error *err) {
  return o->reference
             ? ss_limit_eval_reference_fields(L, p->cell, p->x[0], p->x[1], p->x[2],
                                              derivs, 60, &p->r, p->f, p->df, err)
             : ss_limit_eval_fields(L, p->cell, p->x[0], p->x[1], p->x[2], derivs, &p->r,
                                    p->f, p->df, err);
}

/* NaN in p's values it does not have: all of them, or (values = 1) only the
 * Jacobian and the field gradients. */
static void no_values(ss_limit_cli_point *p, size_t nf, int values) {
  for (int a = 0; a < 3; a++) {
    if (!values) p->r.p[a] = NAN;
    for (int d = 0; d < 3; d++)
      p->r.jac[a][d] = NAN;
  }
  for (size_t k = 0; k < nf; k++) {
    if (!values) p->f[k] = NAN;
    for (int a = 0; a < 3; a++)
      p->df[k][a] = NAN;
  }
}

/* Point p evaluated, with its status: a Jacobian that fails numerically is
 * retried without derivatives (the point may still exist: no_derivatives);
 * the evaluator's refusals (SS_EINPUT: refused) and numerical failures
 * (SS_ENUMERIC: failed) are the point's, with the reason kept.  SS_OK, or a
 * failure that ends the batch (SS_ENOMEM, SS_EINTERNAL) in err. */
static ss_status eval_point(const limit_opts *o, ss_limit *L, ss_limit_cli_point *p,
                            ss_error *err) {
  ss_error e = {0}, e2 = {0};
  ss_status st = eval_one(o, L, p, o->derivs, &e);
  p->status = SS_LIMIT_CLI_OK;
  if (!st) return SS_OK;
  if (st == SS_ENUMERIC && o->derivs) {
    const ss_status st2 = eval_one(o, L, p, 0, &e2);
    if (!st2)
      p->status = SS_LIMIT_CLI_NO_DERIVATIVES;
    else { /* the point itself fails: its own reason */
      e = e2;
      st = st2;
    }
  }
  if (st != SS_OK && st != SS_ENUMERIC && st != SS_EINPUT) {
    *err = e;
    return st;
  }
  if (!p->status)
    p->status = st == SS_EINPUT ? SS_LIMIT_CLI_REFUSED : SS_LIMIT_CLI_FAILED;
  no_values(p, o->fl.nf, p->status == SS_LIMIT_CLI_NO_DERIVATIVES);
  if (!(p->why = strdup(e.msg[0] ? e.msg : ss_status_name(st))))
    return ss_error_nomem(err, "reasons");
  return SS_OK;
}

/* The limit (and derivatives) at every point of o, in place (L caches what
 * the evaluation builds: not const); *bad receives how many points failed
 * (they have their status and reason).  SS_ENOMEM, SS_EINTERNAL. */
static ss_status eval_points(limit_opts *o, ss_limit *L, size_t *bad, ss_error *err) {
  const size_t nf = o->fl.nf;
  *bad = 0;
  if (nf) {
    o->fl.val = calloc(o->npts * nf + 1, sizeof *o->fl.val);
    o->fl.grad = calloc(o->npts * nf + 1, sizeof *o->fl.grad);
    if (!o->fl.val || !o->fl.grad) return ss_error_nomem(err, "field values");
  }
  ss_cli_progress pr = {"limit", ss_cli_now(), 0, NULL, 0};
  for (size_t i = 0; i < o->npts; i++) {
    ss_limit_cli_point *p = o->pts + i;
    p->f = nf ? o->fl.val + i * nf : NULL;
    p->df = nf ? o->fl.grad + i * nf : NULL;
    const ss_status st = eval_point(o, L, p, err);
    if (st) return st;
    *bad += p->status != SS_LIMIT_CLI_OK;
    if (o->progress) ss_cli_progress_fn(&pr, "points evaluated", i + 1, o->npts);
  }
  return SS_OK;
}

/* The points of o, as text, JSON, VTK or VTU (statuses written when bad >
 * 0), to -o FILE (whole or not at all) or stdout. */
static ss_status write_points(const limit_opts *o, const ss_cx *mesh, size_t bad,
                              ss_error *err) {
  const ss_limit_cli_out w = {o->pts,    o->npts, o->samples > 0 ? (int)o->samples : 0,
                              o->derivs, bad > 0, &o->fl,
                              mesh};
  ss_outfile *out = NULL;
  ss_status st = SS_OK;
  if (o->out && (st = ss_outfile_open(o->out, &out, err))) return st;
  FILE *f = out ? ss_outfile_file(out) : stdout;
  if (o->format == 0)
    ss_cli_limit_write_text(f, &w);
  else if (o->format == 1)
    ss_cli_limit_write_json(f, &w);
  else if (o->format == 2)
    ss_cli_limit_write_vtk(f, &w);
  else
    st = ss_cli_limit_write_vtu(f, &w, err);
  if (st) {
    ss_outfile_abort(out);
    return st;
  }
  return out ? ss_outfile_commit(out, err) : SS_OK;
}

/* The failed points on stderr (the first ten, then a count) after writing:
 * the exit status 1. */
static int report_failed(const limit_opts *o, size_t bad) {
  size_t shown = 0;
  for (size_t i = 0; i < o->npts && shown < 10; i++) {
    const ss_limit_cli_point *p = o->pts + i;
    if (p->status == SS_LIMIT_CLI_OK) continue;
    /* the evaluator's reason names the cell too: not twice on one line */
    char own[48];
    snprintf(own, sizeof own, "cell %zu: ", p->cell + 1);
    const char *why = p->why ? p->why : "";
    if (!strncmp(why, own, strlen(own))) why += strlen(own);
    fprintf(stderr, "subspectra limit: cell %zu at (%.17g, %.17g, %.17g): %s: %s\n",
            p->cell + 1, p->x[0], p->x[1], p->x[2], ss_cli_limit_status_name(p->status),
            why);
    shown++;
  }
  fprintf(stderr,
          "subspectra limit: %zu of %zu points not evaluated in full%s (written with "
          "their status)\n",
          bad, o->npts, bad > shown ? ", the first ten shown above" : "");
  return SS_EXIT_FAIL;
}

int ss_cli_limit(int argc, char **argv) {
  limit_opts o = {0};
  int rc = parse(argc, argv, &o);
  if (rc >= 0) {
    free(o.pts);
    return rc;
  }
  rc = SS_EXIT_OK;
  ss_error err = {0};
  ss_scheme *s = NULL;
  ss_cx *mesh = NULL, *pos = NULL;
  ss_limit *L = NULL;
  double *fv = NULL;
  size_t bad = 0;
  ss_mesh_fields names;
  if (ss_scheme_new(o.scheme, &s, &err) ||
      ss_mesh_read_fields(o.mesh, SS_MESH_AUTO, &mesh, &names, &err) ||
      (mesh->dim > 3 && split_fields(mesh, &names, &pos, &fv, &o.fl, &err)) ||
      ss_limit_new_fields(s, pos ? pos : mesh, o.fl.nf, fv, &L, &err))
    rc = ss_cli_fail("limit", &err);
  else if (ss_cx_check_orientation(pos ? pos : mesh, &err)) {
    /* flat, folded or inverted hexes, refused as subdivide and enumerate
     * mesh refuse them: the parametrisation has no consistent sign there */
    fprintf(stderr, "subspectra limit: %s: %s\n", o.mesh, err.msg);
    rc = SS_EXIT_USAGE;
  } else if ((!o.npts && grid_points(&o, L, &err)) || eval_points(&o, L, &bad, &err) ||
             write_points(&o, pos ? pos : mesh, bad, &err))
    rc = ss_cli_fail("limit", &err);
  else if (bad)
    rc = report_failed(&o, bad);
  for (size_t i = 0; i < o.npts; i++)
    free(o.pts[i].why);
  free(o.pts);
  free(o.fl.val);
  free(o.fl.grad);
  free(fv);
  ss_limit_free(L);
  ss_cx_free(pos);
  ss_cx_free(mesh);
  ss_scheme_free(s);
  return rc;
}
