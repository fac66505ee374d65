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
#include "ss_limit.h"
#include "ss_mesh.h"
#include "ss_outfile.h"
#include "ss_scheme.h"

static const char *const usage_text =
    "usage: subspectra limit --scheme S MESH (--at \"CELL U V W\" | --samples N |\n"
    "                        --gauss Q) [--derivatives] [--format text|json|vtk]\n"
    "                        [-o FILE]\n"
    "\n"
    "The limit volume of the hexahedral mesh MESH under scheme S: the limit point\n"
    "at parameters (U, V, W) in [0,1]^3 of a cell (U along the cell's corners\n"
    "1 -> 2, V along 1 -> 4, W along 1 -> 5 in the file's order), and with\n"
    "--derivatives the 3x3 Jacobian (rows d/dU, d/dV, d/dW).  Cells are numbered\n"
    "from 1 as in the file.\n"
    "\n"
    "Fields: coordinates past the third (a Medit 4th coordinate, the field w)\n"
    "are scalar values per control point; they are subdivided like the\n"
    "coordinates (the same weights), and their limit values are written with\n"
    "each point, with --derivatives also their gradients in the cell's\n"
    "parameters (d/dU, d/dV, d/dW).  A mesh without them is evaluated as before.\n"
    "\n"
    "  -s, --scheme S     mlca or ccsolid (any scheme that splits hexahedra\n"
    "                     multilinearly with a one-ring rule and is the\n"
    "                     tricubic B-spline on regular grids)\n"
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
    "                     sampled volume as hexahedra, otherwise points; point\n"
    "                     data: cell, jacobian_det, each field NAME and its\n"
    "                     NAME_gradient, 3 components)\n"
    "  -o, --output FILE  write there (whole or not at all) instead of stdout\n"
    "  -h, --help         this text\n"
    "\n";

/* The usage text's second half (one literal would exceed the 4095 characters
 * C11 compilers must support). */
static const char *const usage_how =
    "How (README, \"Limit evaluation\"): the cell's patch is refined in the\n"
    "scheme's own global rule, following the child that holds the point, until\n"
    "the sub-cell is regular (then the tricubic B-spline).  Each patch topology\n"
    "and step is computed once and cached; a stationary run of steps (towards an\n"
    "extraordinary vertex, along an extraordinary edge, towards the boundary) is\n"
    "one eigen-decomposition W^m = V L^m V^-1 (Stam), or binary powers of W where\n"
    "W is defective.  Cost per point: constant for regular cells, near\n"
    "extraordinary vertices, and near extraordinary edges whose refinement is a\n"
    "tensor product (checked on the patch: MLCA's are; the paper's eq. (1));\n"
    "near other edges (Joy-MacCracken's are no tensor product) and the boundary,\n"
    "bounded by the changes among the point's binary digits (at most ~53 per\n"
    "coordinate in double precision), not constant.\n"
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
    "Exit status: 0 all points evaluated; 1 a numerical failure (a Jacobian asked\n"
    "at a fixed point with an eigenvalue of modulus >= 1/2 other than 1/2 or 1,\n"
    "where it is unbounded, e.g. at an extraordinary vertex; a run whose limit\n"
    "is not defined; a result beyond the range of doubles; a Jacobian row that\n"
    "cannot be trusted, e.g. along an extraordinary edge on the boundary very\n"
    "near it); 2 bad usage or input (unknown cell, parameter outside [0,1], a\n"
    "mesh with cells other than hexahedra, not manifold, or with flat, folded or\n"
    "inverted hexahedra, a scheme that does not split hexahedra or is no\n"
    "tricubic B-spline on grids, a field value that is not a finite number).\n";

/* One point to evaluate and its result. */
typedef struct {
  size_t cell;      /* 0-based */
  double x[3];      /* parameters */
  double weight;    /* Gauss weight on [0,1]^3, or 0 */
  ss_limit_point r; /* result */
  double *f;        /* the fields' values (nf; in fields.val), or NULL */
  double (*df)[3];  /* their derivatives d/dU, d/dV, d/dW (nf rows), or NULL */
} point;

/* The mesh's fields: its coordinates past the third. */
typedef struct {
  size_t nf;                /* how many (0..SS_MAXDIM - 3) */
  char name[SS_MAXDIM][16]; /* their names: the 4th coordinate is "w" */
  double *val;              /* npts * nf values (owned) */
  double (*grad)[3];        /* npts * nf derivatives (owned) */
} fields;

/* Name of field i, the coordinate 4 + i of the mesh file. */
static void field_name(size_t i, char name[16]) {
  if (i == 0)
    snprintf(name, 16, "w");
  else
    snprintf(name, 16, "x%zu", i + 4);
}

/* The mesh's positions (*pos, a 3-coordinate copy) and its coordinates past
 * the third as fields (*val, nv * nf, vertex-major); mesh->dim >= 3.
 * SS_ENOMEM. */
static ss_status split_fields(const ss_cx *mesh, ss_cx **pos, double **val, fields *fl,
                              ss_error *err) {
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
    field_name(i, fl->name[i]);
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
static int parse_at(const char *s, point *p) {
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

static void write_text(FILE *f, const point *p, size_t n, int derivs, const fields *fl) {
  for (size_t i = 0; i < n; i++) {
    fprintf(f, "%zu %.17g %.17g %.17g %.17g %.17g %.17g", p[i].cell + 1, p[i].x[0],
            p[i].x[1], p[i].x[2], p[i].r.p[0], p[i].r.p[1], p[i].r.p[2]);
    if (derivs)
      for (int a = 0; a < 3; a++)
        for (int d = 0; d < 3; d++)
          fprintf(f, " %.17g", p[i].r.jac[a][d]);
    for (size_t k = 0; k < fl->nf; k++)
      fprintf(f, " %.17g", p[i].f[k]);
    for (size_t k = 0; k < fl->nf && derivs; k++)
      for (int a = 0; a < 3; a++)
        fprintf(f, " %.17g", p[i].df[k][a]);
    fputc('\n', f);
  }
}

/* JSON "fields": {NAME: value} and with derivs "field_gradients": {NAME:
 * [3]} of point p into o. */
static void json_fields(json_object *o, const point *p, int derivs, const fields *fl) {
  if (!fl->nf) return;
  json_object *v = json_object_new_object(),
              *g = derivs ? json_object_new_object() : NULL;
  for (size_t k = 0; k < fl->nf; k++) {
    json_object_object_add(v, fl->name[k], json_object_new_double(p->f[k]));
    if (!g) continue;
    json_object *row = json_object_new_array();
    for (int a = 0; a < 3; a++)
      json_object_array_add(row, json_object_new_double(p->df[k][a]));
    json_object_object_add(g, fl->name[k], row);
  }
  json_object_object_add(o, "fields", v);
  if (g) json_object_object_add(o, "field_gradients", g);
}

static void write_json(FILE *f, const point *p, size_t n, int derivs, const fields *fl) {
  for (size_t i = 0; i < n; i++) {
    json_object *o = json_object_new_object();
    json_object_object_add(o, "cell", json_object_new_int64((int64_t)p[i].cell + 1));
    static const char *const key[3] = {"u", "v", "w"};
    for (int a = 0; a < 3; a++)
      json_object_object_add(o, key[a], json_object_new_double(p[i].x[a]));
    if (p[i].weight > 0)
      json_object_object_add(o, "weight", json_object_new_double(p[i].weight));
    json_object *pt = json_object_new_array();
    for (int d = 0; d < 3; d++)
      json_object_array_add(pt, json_object_new_double(p[i].r.p[d]));
    json_object_object_add(o, "point", pt);
    if (derivs) {
      json_object *J = json_object_new_array();
      for (int a = 0; a < 3; a++) {
        json_object *row = json_object_new_array();
        for (int d = 0; d < 3; d++)
          json_object_array_add(row, json_object_new_double(p[i].r.jac[a][d]));
        json_object_array_add(J, row);
      }
      json_object_object_add(o, "jacobian", J);
    }
    json_fields(o, p + i, derivs, fl);
    fprintf(f, "%s\n", json_object_to_json_string_ext(o, JSON_C_TO_STRING_PLAIN));
    json_object_put(o);
  }
}

/* Legacy VTK: points; with samples >= 2 (points cell by cell, i fastest) the
 * (N-1)^3 sample hexes of every cell, else one vertex cell per point.  Point
 * data: the cell number and, with derivatives, det J; each field and with
 * derivatives its gradient NAME_gradient (3 components: d/dU, d/dV, d/dW). */
static void write_vtk(FILE *f, const point *p, size_t n, int samples, int derivs,
                      const fields *fl) {
  fprintf(f,
          "# vtk DataFile Version 3.0\nsubspectra limit\nASCII\nDATASET "
          "UNSTRUCTURED_GRID\nPOINTS %zu double\n",
          n);
  for (size_t i = 0; i < n; i++)
    fprintf(f, "%.17g %.17g %.17g\n", p[i].r.p[0], p[i].r.p[1], p[i].r.p[2]);
  if (samples >= 2) {
    size_t N = (size_t)samples, per = N * N * N, m = N - 1, ncell = n / per * m * m * m;
    fprintf(f, "CELLS %zu %zu\n", ncell, ncell * 9);
    for (size_t c = 0; c < n / per; c++)
      for (size_t k = 0; k < m; k++)
        for (size_t j = 0; j < m; j++)
          for (size_t i = 0; i < m; i++) {
#define ID(a, b, d) (c * per + (i + (a)) + N * ((j + (b)) + N * (k + (d))))
            fprintf(f, "8 %zu %zu %zu %zu %zu %zu %zu %zu\n", ID(0, 0, 0), ID(1, 0, 0),
                    ID(1, 1, 0), ID(0, 1, 0), ID(0, 0, 1), ID(1, 0, 1), ID(1, 1, 1),
                    ID(0, 1, 1));
#undef ID
          }
    fprintf(f, "CELL_TYPES %zu\n", ncell);
    for (size_t c = 0; c < ncell; c++)
      fprintf(f, "12\n");
  } else {
    fprintf(f, "CELLS %zu %zu\n", n, 2 * n);
    for (size_t i = 0; i < n; i++)
      fprintf(f, "1 %zu\n", i);
    fprintf(f, "CELL_TYPES %zu\n", n);
    for (size_t i = 0; i < n; i++)
      fprintf(f, "1\n");
  }
  fprintf(f, "POINT_DATA %zu\nSCALARS cell int 1\nLOOKUP_TABLE default\n", n);
  for (size_t i = 0; i < n; i++)
    fprintf(f, "%zu\n", p[i].cell + 1);
  if (derivs) {
    fprintf(f, "SCALARS jacobian_det double 1\nLOOKUP_TABLE default\n");
    for (size_t i = 0; i < n; i++) {
      const double(*J)[3] = p[i].r.jac;
      double det = J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) -
                   J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) +
                   J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
      fprintf(f, "%.17g\n", det);
    }
  }
  for (size_t k = 0; k < fl->nf; k++) {
    fprintf(f, "SCALARS %s double 1\nLOOKUP_TABLE default\n", fl->name[k]);
    for (size_t i = 0; i < n; i++)
      fprintf(f, "%.17g\n", p[i].f[k]);
    if (!derivs) continue;
    fprintf(f, "SCALARS %s_gradient double 3\nLOOKUP_TABLE default\n", fl->name[k]);
    for (size_t i = 0; i < n; i++)
      fprintf(f, "%.17g %.17g %.17g\n", p[i].df[k][0], p[i].df[k][1], p[i].df[k][2]);
  }
}

/* The command line of limit. */
typedef struct {
  const char *scheme; /* --scheme */
  const char *out;    /* -o FILE, or NULL: stdout */
  const char *mesh;   /* MESH */
  long samples;       /* --samples N per direction, or 0 */
  long gq;            /* --gauss Q points per direction, or 0 */
  int derivs;         /* --derivatives */
  int reference;      /* --reference: the slow reference evaluation */
  int format;         /* 0 text, 1 json, 2 vtk */
  point *pts;         /* --at points (owned) */
  size_t npts, cap;   /* how many, allocated */
  fields fl;          /* the mesh's fields and their results */
} limit_opts;

/* --at TEXT appended to o->pts: 0, or the exit status 2 with the message
 * printed. */
static int add_at(limit_opts *o, const char *text) {
  if (o->npts == o->cap) {
    const size_t cap = o->cap ? 2 * o->cap : 8;
    point *q = realloc(o->pts, cap * sizeof *q);
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
  static const struct option opts[] = {
      {"scheme", required_argument, NULL, 's'},  {"at", required_argument, NULL, 'a'},
      {"samples", required_argument, NULL, 'n'}, {"gauss", required_argument, NULL, 'g'},
      {"derivatives", no_argument, NULL, 'd'},   {"reference", no_argument, NULL, 'R'},
      {"format", required_argument, NULL, 'f'},  {"output", required_argument, NULL, 'o'},
      {"help", no_argument, NULL, 'h'},          {NULL, 0, NULL, 0}};
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
    case 'f':
      if (!strcmp(optarg, "text"))
        o->format = 0;
      else if (!strcmp(optarg, "json"))
        o->format = 1;
      else if (!strcmp(optarg, "vtk"))
        o->format = 2;
      else
        return ss_cli_usage_error(
            "limit", "--format: expected text, json or vtk, not '%s'", optarg);
      break;
    case 'o':
      o->out = optarg;
      break;
    case 'h':
      fputs(usage_text, stdout);
      fputs(usage_how, stdout);
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

/* The limit (and derivatives) at every point of o, in place (L caches what
 * the evaluation builds: not const). */
static ss_status eval_points(limit_opts *o, ss_limit *L, ss_error *err) {
  const size_t nf = o->fl.nf;
  if (nf) {
    o->fl.val = calloc(o->npts * nf + 1, sizeof *o->fl.val);
    o->fl.grad = calloc(o->npts * nf + 1, sizeof *o->fl.grad);
    if (!o->fl.val || !o->fl.grad) return ss_error_nomem(err, "field values");
  }
  for (size_t i = 0; i < o->npts; i++) {
    point *p = o->pts + i;
    p->f = nf ? o->fl.val + i * nf : NULL;
    p->df = nf ? o->fl.grad + i * nf : NULL;
    ss_status st =
        o->reference
            ? ss_limit_eval_reference_fields(L, p->cell, p->x[0], p->x[1], p->x[2],
                                             o->derivs, 60, &p->r, p->f, p->df, err)
            : ss_limit_eval_fields(L, p->cell, p->x[0], p->x[1], p->x[2], o->derivs,
                                   &p->r, p->f, p->df, err);
    if (st) return st;
  }
  return SS_OK;
}

/* The points of o, as text, JSON or VTK, to -o FILE (whole or not at all)
 * or stdout. */
static ss_status write_points(const limit_opts *o, ss_error *err) {
  ss_outfile *out = NULL;
  if (o->out) {
    const ss_status st = ss_outfile_open(o->out, &out, err);
    if (st) return st;
  }
  FILE *f = out ? ss_outfile_file(out) : stdout;
  if (o->format == 0)
    write_text(f, o->pts, o->npts, o->derivs, &o->fl);
  else if (o->format == 1)
    write_json(f, o->pts, o->npts, o->derivs, &o->fl);
  else
    write_vtk(f, o->pts, o->npts, o->samples > 0 ? (int)o->samples : 0, o->derivs,
              &o->fl);
  return out ? ss_outfile_commit(out, err) : SS_OK;
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
  if (ss_scheme_new(o.scheme, &s, &err) ||
      ss_mesh_read(o.mesh, SS_MESH_AUTO, &mesh, &err) ||
      (mesh->dim > 3 && split_fields(mesh, &pos, &fv, &o.fl, &err)) ||
      ss_limit_new_fields(s, pos ? pos : mesh, o.fl.nf, fv, &L, &err))
    rc = ss_cli_fail(&err);
  else if (ss_cx_check_orientation(pos ? pos : mesh, &err)) {
    /* flat, folded or inverted hexes, refused as subdivide and enumerate
     * mesh refuse them: the parametrisation has no consistent sign there */
    fprintf(stderr, "subspectra: %s: %s\n", o.mesh, err.msg);
    rc = SS_EXIT_USAGE;
  } else if ((!o.npts && grid_points(&o, L, &err)) || eval_points(&o, L, &err) ||
             write_points(&o, &err))
    rc = ss_cli_fail(&err);
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
