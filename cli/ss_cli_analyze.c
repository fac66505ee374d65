/* ss_cli_analyze.c — `subspectra analyze` (local matrix, eigenstructure,
 * eigenvalue condition and characteristic-map regularity for one case or one
 * case per input line), `subspectra matrix` (the local matrix in Matrix Market
 * format) and `subspectra draw` (a picture of the characteristic map). */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <json-c/json.h>

#include "ss_certify.h"
#include "ss_charmap.h"
#include "ss_cli.h"
#include "ss_cli_eigvec.h"
#include "ss_eig.h"
#include "ss_link.h"
#include "ss_local.h"
#include "ss_outfile.h"
#include "ss_report_case.h"
#include "ss_report_draw.h"
#include "ss_report_table.h"
#include "ss_stencil.h"

enum { FMT_TEXT = 0, FMT_JSON, FMT_TSV, FMT_MTX };

/* Options shared by analyze and matrix. */
typedef struct {
  const char *cmd;          /* "analyze" or "matrix" */
  const char *scheme;       /* --scheme */
  const char *stencil;      /* --stencil FILE (instead of --scheme) */
  ss_case_kind kind;        /* which case option was given */
  int ncase;                /* how many case options were given */
  const char *link;         /* --vertex argument ("-" = standard input) */
  int n;                    /* --edge / --surface-vertex valence */
  double tol;               /* --tol */
  int neig;                 /* --eigenvalues: how many to print */
  int format;               /* FMT_* */
  int ring;                 /* matrix --ring 1|2 */
  const char *out;          /* matrix, draw: -o FILE */
  int depth;                /* --depth: hex subdivision limit of the Jacobian test */
  int ring_levels;          /* --ring-levels: ring levels judged at most */
  int certify;              /* --certify: the exact path too (ss_certify) */
  ss_report_draw_opts draw; /* draw: picture options */
  ss_diag_mode diag;        /* --diagonals: major diagonals of tet stars */
  int force;                /* draw --force: a map even when the condition fails */
  double max_memory;        /* --max-memory in bytes, 0: the default budget */
  int progress;             /* --progress: progress lines on stderr */
  int nvec;                 /* --eigenvectors K: export the K leading eigenpairs
                               (analyze: JSON; matrix: Matrix Market); 0: none */
  int left;                 /* matrix --left: the left eigenvectors */
  int nocaption;            /* draw --no-caption */
  int cls;                  /* --class 4|8: 4-8 class of a quasi48 surface
                               vertex; 0: ss_case_class48's default */
  int cls48;                /* the class analysed (quasi48 surface vertex),
                               else 0 */
} opts;

static void help(const char *cmd) {
  const int m = !strcmp(cmd, "matrix"), d = !strcmp(cmd, "draw");
  printf("usage: subspectra %s --scheme S CASE [options]%s\n\n", cmd,
         d ? " -o FILE" : "");
  if (d)
    printf("Draw the characteristic map of one case: its control net on the two-ring\n"
           "(the subdominant eigenvectors, or a basis of their invariant subspace),\n"
           "cells in 3D projection with depth cues beside the cross-section through\n"
           "psi(p) by the plane z3 = 0; cells that are not regular in red\n"
           "(undecided ones orange), a colour legend, axes.  The net is drawn in a\n"
           "frame fixed by the case, not by the eigenvector basis: psi(p) at the\n"
           "origin, z1 toward the first two-ring point, z2 toward the next one not\n"
           "parallel to it (a tie's arbitrary basis gives the same picture).  Surface\n"
           "cases are drawn flat.  FILE's extension picks the format: .png, .svg,\n"
           ".pdf (in both, text is text) or .vtk (for ParaView: the normalised net,\n"
           "the two-ring's cells and the deciding ring level's, with per-cell\n"
           "Jacobian sign and minimum scaled Jacobian in the map's orientation, as\n"
           "analyze reports them; see the README).\n\n");
  else if (m)
    printf("Write the local subdivision matrix S of one case in Matrix Market format,\n"
           "rows and columns labelled (in comments) by their exact coordinates relative\n"
           "to the centre.  S maps the two-ring on level j to the two-ring on level\n"
           "j+1; the one-ring comes first, so S = [A 0; B C].\n\n");
  else
    printf("Derive the local subdivision matrix of one case from the scheme's global\n"
           "rule, compute its eigenstructure with LAPACK and test the eigenvalue\n"
           "condition: lambda0 = 1 simple; lambda1..3 (surfaces: 1..2) real, positive;\n"
           "lambda3 > |lambda4| (surfaces: lambda2 > |lambda3|).  Equal eigenvalues are\n"
           "grouped by a relative tolerance, printed with the verdict.  Then test the\n"
           "characteristic map for regularity on the two-ring: every cell, mapped by\n"
           "its multilinear interpolant, must have a Jacobian determinant of one\n"
           "strict sign, the same for all cells (hexes: Bernstein coefficients with\n"
           "adaptive subdivision; quads: corners; tets: determinant; octahedra: eight\n"
           "tets), and report the minimum scaled Jacobian.  The map is self-similar,\n"
           "so it is judged on its ring: the cells that do not touch the centre, as S\n"
           "maps them (ring level 0), refined by the scheme's rule while a fold is\n"
           "seen (levels 1, 2, ...); a fold that persists fails, one that shrinks\n"
           "(its share of the cells falls below half per level) is undecided.  Folds\n"
           "of the cells around the centre decide nothing and are only counted.  The\n"
           "map is normalised (the ring's points isotropic) so that scaled Jacobians\n"
           "do not depend on the eigenvector basis.\n\n");
  printf(
      "cases (exactly one):\n"
      "  --vertex LINK          a 3D vertex whose link is LINK: plantri ASCII\n"
      "                         ('4 bcd,adc,abd,acb') or a name (tetrahedron,\n"
      "                         octahedron, icosahedron, bipyramid:N); '-' reads %s\n"
      "  --edge N               a point on an edge of valence N (3..1000)\n"
      "  --face                 a point inside the face of two tets (tet/oct split)\n"
      "  --surface-vertex N     a 2D vertex of valence N (3..1000)\n\n"
      "options:\n"
      "  --scheme S             mlca, tetoct, boxspline, boxspline-avg, catmull-clark,\n"
      "                         loop, ccsolid, quasi48 (surface vertices only; S\n"
      "                         maps two binary steps, a full 4-8 cycle)\n"
      "  --class 4|8            quasi48: the 4-8 class of the surface vertex: 4 (all\n"
      "                         spokes legs, the outer edges split first; N >= 3),\n"
      "                         8 (spokes alternate, N even >= 6).  Default: 8 for\n"
      "                         even N >= 6, else 4.  Class 4 with N is class 8\n"
      "                         with 2N after one step: the same matrix\n"
      "  --diagonals D          major diagonals of tet stars (boxspline): bfs\n"
      "                         (Algorithm 2, default), or around the edge of\n"
      "                         --edge: skew (the same turn all round) or center\n"
      "                         (all toward the edge)\n",
      m || d
          ? "the\n                         link from standard input (exactly one)"
          : "one link per\n                         line on standard input (one result "
            "per line)");
  if (m)
    printf("  --ring 1|2             the one-ring block A or the whole two-ring (default "
           "2)\n"
           "  --format mtx           Matrix Market (the only format)\n"
           "  -o FILE                write to FILE instead of standard output (whole or\n"
           "                         not at all: an old FILE stays if writing fails)\n"
           "  --eigenvectors K       instead of S (or A with --ring 1): the right\n"
           "                         eigenvectors of its K leading eigenvalues, a dense\n"
           "                         Matrix Market array, one column each (a conjugate\n"
           "                         pair or a tie cut by K is kept whole; maximum\n"
           "                         modulus 1, that entry positive)\n"
           "  --left                 with --eigenvectors: the left eigenvectors instead\n"
           "                         (l^T S = lambda l^T, L^T R = I within a tie): the\n"
           "                         first is the limit-position mask, the next the\n"
           "                         tangent masks\n");
  else
    printf(
        "  --tol T                relative tolerance for equal eigenvalues (default "
        "1e-6);\n"
        "                         raised to the eigenvalues' rounding error bound when\n"
        "                         below it (printed; a verdict only that bound decides\n"
        "                         is undecided)\n"
        "  --depth D              subdivision depth limit of the hex Jacobian test "
        "(0..12,\n"
        "                         default %d)\n"
        "  --ring-levels L        ring levels judged at most (1..%d, default %d)\n"
        "  --certify              prove the verdicts too: the exact spectrum of the\n"
        "                         rational matrix (FLINT), the subdominant basis in\n"
        "                         ball arithmetic (arb) and the ring's Jacobians in\n"
        "                         interval arithmetic; what cannot be proven becomes\n"
        "                         undecided (\"not certified: ...\")\n",
        SS_JAC_DEPTH, SS_LOCAL_MAXRING, ss_charmap_defaults().ring_levels);
  if (!m && !d)
    printf(
        "  --eigenvectors K       with --format json: the right and left eigenvectors\n"
        "                         of the K leading eigenvalues of S (key\n"
        "                         \"eigenvectors\"; ties and conjugate pairs cut by K\n"
        "                         kept whole) and, when the eigenvalue condition\n"
        "                         holds, the limit masks: the limit-position mask\n"
        "                         (left eigenvector of lambda0 = 1, summing to 1) and\n"
        "                         the tangent masks (left eigenvectors of the\n"
        "                         subdominant eigenvalues, L^T R = I within a tie)\n");
  if (d)
    printf(
        "  -o FILE                the picture: FILE.png, FILE.svg, FILE.pdf or FILE.vtk\n"
        "                         (whole or not at all: an old FILE stays if writing\n"
        "                         fails)\n"
        "  --no-caption           no caption under the picture (the case, lambdas,\n"
        "                         verdict), for a document that captions it\n"
        "  --size WxH             picture size (default 1200x600)\n"
        "  --view AZ,EL           view direction in degrees (default 30,25)\n"
        "  --force                draw the map of the three leading subdominant\n"
        "                         eigenvectors even when the eigenvalue condition\n"
        "                         fails (they must be real and positive); with a\n"
        "                         tie lambda3 = lambda4 the third is an arbitrary\n"
        "                         vector of the tied eigenspace.  Such a picture is\n"
        "                         not a characteristic map; the caption says so\n");
  else if (!m)
    printf("  --eigenvalues K        how many leading eigenvalues to print (default 16)\n"
           "  --format F             text (default), json (one object per case), tsv\n");
  printf("  --max-memory SIZE      memory budget of the case, SIZE with K, M, G or T\n"
         "                         (powers of 1000; default half the physical memory,\n"
         "                         3/4 of ulimit -v and -d when set): a case whose\n"
         "                         estimate (rows of S, dense blocks, workspaces)\n"
         "                         exceeds it is refused before anything is built,\n"
         "                         with the estimate (exit 2)\n"
         "  --progress             progress lines on standard error (phases: star,\n"
         "                         S, eigen-solve blocks); by default only when\n"
         "                         standard error is a terminal and the case is\n"
         "                         estimated to take more than a few seconds\n"
         "  -h, --help             this help\n\n"
         "Schemes use the star their split calls for: mlca and ccsolid hexes (quads\n"
         "on surfaces),\n"
         "tetoct, boxspline and boxspline-avg tets, catmull-clark quads, loop\n"
         "triangles.  boxspline reports how many face-adjacent pairs of the star have\n"
         "improper diagonals (Definition 3.2 as read in the README).\n"
         "Exit status: 0 all conditions hold, 1 a condition fails or is undecided (or\n"
         "the extraction failed a check), 2 bad usage or input, a case beyond the\n"
         "memory budget, or out of memory.\n");
}

enum {
  O_SCHEME = 256,
  O_VERTEX,
  O_EDGE,
  O_FACE,
  O_SURF,
  O_TOL,
  O_NEIG,
  O_FORMAT,
  O_RING,
  O_DEPTH,
  O_SIZE,
  O_VIEW,
  O_DIAG,
  O_FORCE,
  O_STENCIL,
  O_RINGS,
  O_CERTIFY,
  O_MAXMEM,
  O_PROGRESS,
  O_EIGVEC,
  O_LEFT,
  O_NOCAPTION,
  O_CLASS
};

static int is_matrix(const opts *o) {
  return !strcmp(o->cmd, "matrix");
}

static int is_draw(const opts *o) {
  return !strcmp(o->cmd, "draw");
}

/* --vertex, --edge, --surface-vertex, --face: which case (counted, so that
 * check_options can ask for exactly one).  0 or the exit status 2. */
static int case_option(opts *o, int c, const char *arg) {
  long v;
  switch (c) {
  case O_VERTEX:
    o->kind = SS_CASE_VERTEX;
    o->link = arg;
    break;
  case O_EDGE:
  case O_SURF:
    if (ss_cli_parse_int(arg, 3, 1000, &v))
      return ss_cli_usage_error(o->cmd,
                                "%s: valence must be an integer in 3..1000, not '%s'",
                                c == O_EDGE ? "--edge" : "--surface-vertex", arg);
    o->kind = c == O_EDGE ? SS_CASE_EDGE : SS_CASE_SURFACE_VERTEX;
    o->n = (int)v;
    break;
  default: /* O_FACE */
    o->kind = SS_CASE_FACE;
    break;
  }
  o->ncase++;
  return 0;
}

/* --format: text, json or tsv for analyze, mtx for matrix, none for draw
 * (its format is -o FILE's).  0 or the exit status 2. */
static int format_option(opts *o, const char *arg) {
  const int m = is_matrix(o);
  if (is_draw(o))
    return ss_cli_usage_error(o->cmd, "--format: draw takes the format from -o FILE");
  else if (!m && !strcmp(arg, "text"))
    o->format = FMT_TEXT;
  else if (!m && !strcmp(arg, "json"))
    o->format = FMT_JSON;
  else if (!m && !strcmp(arg, "tsv"))
    o->format = FMT_TSV;
  else if (m && !strcmp(arg, "mtx"))
    o->format = FMT_MTX;
  else
    return ss_cli_usage_error(o->cmd, "--format: expected %s, not '%s'",
                              m ? "mtx" : "text, json or tsv", arg);
  return 0;
}

/* How the case is analysed and what of it is printed: --tol, --eigenvalues,
 * --diagonals, --depth, --ring-levels, --certify, --max-memory, --class,
 * --ring, --eigenvectors, --left; each refused by the commands it does not
 * belong to.  0 or the exit status 2. */
static int analysis_option(opts *o, int c, const char *arg) {
  const int m = is_matrix(o), d = is_draw(o);
  long v;
  switch (c) {
  case O_TOL:
    if (ss_cli_opt_tol(o->cmd, arg, &o->tol)) return SS_EXIT_USAGE;
    break;
  case O_NEIG:
    if (m || ss_cli_parse_int(arg, 1, 1000000, &v))
      return ss_cli_usage_error(o->cmd,
                                "--eigenvalues: expected a positive integer, not "
                                "'%s'",
                                arg);
    o->neig = (int)v;
    break;
  case O_RING:
    if (!m || ss_cli_parse_int(arg, 1, 2, &v))
      return ss_cli_usage_error(o->cmd, "--ring: expected 1 or 2, not '%s'", arg);
    o->ring = (int)v;
    break;
  case O_DIAG:
    if (ss_diag_parse(arg, &o->diag))
      return ss_cli_usage_error(
          o->cmd, "--diagonals: expected bfs, proper, skew or center, not '%s'", arg);
    break;
  case O_DEPTH:
    if (m) return ss_cli_usage_error(o->cmd, "--depth is not an option of matrix");
    if (ss_cli_opt_depth(o->cmd, arg, &v)) return SS_EXIT_USAGE;
    o->depth = (int)v;
    break;
  case O_EIGVEC:
    if (d || ss_cli_parse_int(arg, 1, 1000000, &v))
      return ss_cli_usage_error(o->cmd,
                                d ? "--eigenvectors is an option of analyze and matrix"
                                  : "--eigenvectors: expected a positive integer, not "
                                    "'%s'",
                                arg);
    o->nvec = (int)v;
    break;
  case O_LEFT:
    if (!m) return ss_cli_usage_error(o->cmd, "--left is an option of matrix");
    o->left = 1;
    break;
  case O_CERTIFY:
    if (m || d) return ss_cli_usage_error(o->cmd, "--certify is an option of analyze");
    o->certify = 1;
    break;
  case O_RINGS:
    if (m || ss_cli_parse_int(arg, 1, SS_LOCAL_MAXRING, &v))
      return ss_cli_usage_error(o->cmd,
                                "--ring-levels: expected an integer in 1..%d, not '%s'",
                                SS_LOCAL_MAXRING, arg);
    o->ring_levels = (int)v;
    break;
  case O_MAXMEM:
    if (ss_cli_parse_bytes(arg, &o->max_memory))
      return ss_cli_usage_error(
          o->cmd, "--max-memory: expected a size such as 8G, 500M or 2.5G, not '%s'",
          arg);
    break;
  default: /* O_CLASS */
    if (strcmp(arg, "4") && strcmp(arg, "8"))
      return ss_cli_usage_error(o->cmd, "--class: expected 4 or 8, not '%s'", arg);
    o->cls = arg[0] - '0';
    break;
  }
  return 0;
}

/* The picture of draw: --size, --view, --force, --no-caption (refused by
 * analyze and matrix).  0 or the exit status 2. */
static int draw_option(opts *o, int c, const char *arg) {
  const int d = is_draw(o);
  switch (c) {
  case O_SIZE: {
    int w = 0, h = 0;
    char tail;
    if (!d || sscanf(arg, "%dx%d%c", &w, &h, &tail) != 2 || w < 100 || h < 100 ||
        w > 10000 || h > 10000)
      return ss_cli_usage_error(
          o->cmd, "--size: expected WxH with 100 <= W, H <= 10000, not '%s'", arg);
    o->draw.width = w;
    o->draw.height = h;
    break;
  }
  case O_VIEW: {
    double az = 0.0, el = 0.0;
    char tail;
    if (!d || sscanf(arg, "%lf,%lf%c", &az, &el, &tail) != 2 || !(fabs(az) <= 360.0) ||
        !(fabs(el) <= 90.0))
      return ss_cli_usage_error(
          o->cmd, "--view: expected AZ,EL in degrees (|AZ| <= 360, |EL| <= 90), not '%s'",
          arg);
    o->draw.azimuth = az;
    o->draw.elevation = el;
    break;
  }
  case O_FORCE:
    if (!d) return ss_cli_usage_error(o->cmd, "--force is an option of draw only");
    o->force = 1;
    break;
  default: /* O_NOCAPTION */
    if (!d) return ss_cli_usage_error(o->cmd, "--no-caption is an option of draw only");
    o->nocaption = 1;
    break;
  }
  return 0;
}

/* The rules between options, once all are read.  0 or the exit status 2. */
static int check_options(const opts *o) {
  const int m = is_matrix(o), d = is_draw(o);
  if (ss_cli_opt_scheme_source(o->cmd, o->scheme, o->stencil)) return SS_EXIT_USAGE;
  if (o->ncase != 1)
    return ss_cli_usage_error(o->cmd, "give exactly one of --vertex, --edge, --face, "
                                      "--surface-vertex");
  if (d && !o->out) return ss_cli_usage_error(o->cmd, "-o FILE is required");
  if (o->left && !o->nvec)
    return ss_cli_usage_error(o->cmd, "--left needs --eigenvectors K");
  if (o->nvec && !m && !d && o->format != FMT_JSON)
    return ss_cli_usage_error(o->cmd,
                              "--eigenvectors: analyze writes them with --format "
                              "json (matrix --eigenvectors writes Matrix Market)");
  if (o->cls && o->kind != SS_CASE_SURFACE_VERTEX)
    return ss_cli_usage_error(o->cmd, "--class is the 4-8 class of a quasi48 "
                                      "--surface-vertex; no other case has one");
  return 0;
}

/* The command line of analyze, matrix or draw into o (whose defaults the
 * caller set): 0, -1 after --help, or the exit status 2 with the message
 * printed. */
static int parse(int argc, char **argv, opts *o) {
  static const struct option lo[] = {{"scheme", required_argument, 0, O_SCHEME},
                                     {"vertex", required_argument, 0, O_VERTEX},
                                     {"edge", required_argument, 0, O_EDGE},
                                     {"face", no_argument, 0, O_FACE},
                                     {"surface-vertex", required_argument, 0, O_SURF},
                                     {"tol", required_argument, 0, O_TOL},
                                     {"eigenvalues", required_argument, 0, O_NEIG},
                                     {"format", required_argument, 0, O_FORMAT},
                                     {"ring", required_argument, 0, O_RING},
                                     {"depth", required_argument, 0, O_DEPTH},
                                     {"size", required_argument, 0, O_SIZE},
                                     {"view", required_argument, 0, O_VIEW},
                                     {"diagonals", required_argument, 0, O_DIAG},
                                     {"force", no_argument, 0, O_FORCE},
                                     {"stencil", required_argument, 0, O_STENCIL},
                                     {"ring-levels", required_argument, 0, O_RINGS},
                                     {"certify", no_argument, 0, O_CERTIFY},
                                     {"max-memory", required_argument, 0, O_MAXMEM},
                                     {"progress", no_argument, 0, O_PROGRESS},
                                     {"eigenvectors", required_argument, 0, O_EIGVEC},
                                     {"left", no_argument, 0, O_LEFT},
                                     {"no-caption", no_argument, 0, O_NOCAPTION},
                                     {"class", required_argument, 0, O_CLASS},
                                     {"help", no_argument, 0, 'h'},
                                     {0, 0, 0, 0}};
  optind = 1;
  opterr = 0;
  int c, rc = 0;
  while (!rc && (c = getopt_long(argc, argv, is_matrix(o) || is_draw(o) ? ":ho:" : ":h",
                                 lo, NULL)) != -1) {
    switch (c) {
    case 'h':
      help(o->cmd);
      return -1;
    case 'o':
      o->out = optarg;
      break;
    case O_SCHEME:
      o->scheme = optarg;
      break;
    case O_STENCIL:
      o->stencil = optarg;
      break;
    case O_PROGRESS:
      o->progress = 1;
      break;
    case O_VERTEX:
    case O_EDGE:
    case O_SURF:
    case O_FACE:
      rc = case_option(o, c, optarg);
      break;
    case O_FORMAT:
      rc = format_option(o, optarg);
      break;
    case O_TOL:
    case O_NEIG:
    case O_RING:
    case O_DIAG:
    case O_DEPTH:
    case O_EIGVEC:
    case O_LEFT:
    case O_CERTIFY:
    case O_RINGS:
    case O_MAXMEM:
    case O_CLASS:
      rc = analysis_option(o, c, optarg);
      break;
    case O_SIZE:
    case O_VIEW:
    case O_FORCE:
    case O_NOCAPTION:
      rc = draw_option(o, c, optarg);
      break;
    default:
      return ss_cli_option_error(o->cmd, c, argv);
    }
  }
  if (rc) return rc;
  if (optind < argc)
    return ss_cli_usage_error(o->cmd, "unexpected argument '%s'", argv[optind]);
  return check_options(o);
}

/* ---- output ---- */

static const char *param_text(const opts *o, const char *canon, char *buf, size_t n) {
  if (o->kind == SS_CASE_VERTEX || o->kind == SS_CASE_EDGE_POINT) return canon;
  if (o->kind == SS_CASE_FACE) return "";
  if (o->cls48 && o->format != FMT_TSV) /* TSV: the valence column stays a number */
    snprintf(buf, n, "%d, 4-8 class %d", o->n, o->cls48);
  else
    snprintf(buf, n, "%d", o->n);
  return buf;
}

/* What --certify adds (ss_certify). */
typedef struct {
  int on;                /* --certify given */
  ss_certified c;        /* the proven eigenvalue condition, timing */
  const ss_exact *exact; /* the exact spectrum, or NULL */
} cert_info;

/* Major diagonals of a tet star, for schemes that read them. */
typedef struct {
  int shown;       /* 1 if the scheme reads diagonals */
  size_t pairs;    /* adjacent cell pairs they concern (ss_diag_improper) */
  size_t improper; /* of which improper */
} diag_info;

/* The JSON object of DESIGN section 7 (ss_report_case_json), on one line. */
static int print_json(const opts *o, const char *scheme, const char *canon, int k,
                      const ss_local *M, const ss_eig *e, const ss_regularity *reg,
                      const ss_charmap_inj *inj, const diag_info *di, const cert_info *ci,
                      json_object *eigvec) {
  const ss_report_case c = {scheme,
                            o->kind,
                            canon,
                            k,
                            o->n,
                            o->neig,
                            M,
                            e,
                            reg,
                            inj,
                            di->shown,
                            o->diag,
                            di->pairs,
                            di->improper,
                            ci->on ? &ci->c : NULL,
                            ci->exact,
                            eigvec,
                            o->cls48};
  ss_error err = {0};
  json_object *r = NULL;
  if (ss_report_case_json(&c, &r, &err)) {
    fprintf(stderr, "subspectra %s: %s\n", o->cmd, err.msg);
    return ss_cli_exit_status(err.status);
  }
  printf("%s\n", json_object_to_json_string_ext(r, JSON_C_TO_STRING_PLAIN |
                                                       JSON_C_TO_STRING_NOSLASHESCAPE));
  json_object_put(r);
  return SS_EXIT_OK;
}

static void print_value(FILE *f, const ss_eigval *v) {
  if (v->im == 0.0)
    fprintf(f, "%.12g", v->re);
  else
    fprintf(f, "%.12g%+.12gi", v->re, v->im);
}

static void print_tsv(const opts *o, const char *scheme, const char *canon,
                      const ss_local *M, const ss_eig *e, const ss_regularity *reg,
                      const ss_charmap_inj *inj, const cert_info *ci, int header) {
  if (header) {
    printf("scheme\tcase\tlink_or_valence\ttwo_ring\tone_ring");
    for (int i = 0; i < o->neig; i++)
      printf("\tlambda%d", i);
    printf("\teigen_condition\treason\ttolerance\tregularity\tregularity_reason\t"
           "min_scaled_jacobian\tinjectivity\tinjectivity_reason\teigen_certified\t"
           "regularity_certified\n");
  }
  char buf[32];
  printf("%s\t%s\t%s\t%zu\t%zu", scheme, ss_case_name(o->kind),
         param_text(o, canon, buf, sizeof buf), M->n2, M->n1);
  for (int i = 0; i < o->neig; i++) {
    putchar('\t');
    if ((size_t)i < e->n) print_value(stdout, e->val + i);
  }
  const ss_verdict *cond = ci->on ? &ci->c.cond : &e->cond;
  printf("\t%s\t%s\t%g\t%s\t%s\t", ss_verdict_name(cond->verdict), cond->reason, e->tol,
         ss_verdict_name(reg->verdict.verdict), reg->verdict.reason);
  if (isfinite(reg->min_scaled_jacobian)) printf("%.6g", reg->min_scaled_jacobian);
  printf("\t%s\t%s\t%d\t%d\n", ss_verdict_name(inj->verdict.verdict), inj->verdict.reason,
         ci->on && ci->c.cond_certified, reg->certified);
}

static void print_text(const opts *o, const char *scheme, const char *canon, int k,
                       const ss_local *M, const ss_eig *e, const ss_regularity *reg,
                       const ss_charmap_inj *inj, const diag_info *di,
                       const cert_info *ci) {
  printf("scheme %s, %s case", scheme, ss_case_name(o->kind));
  if (o->kind == SS_CASE_EDGE_POINT)
    printf(", link %s (k = %d): the bipyramid over %d, a point on an edge of valence %d, "
           "analysed as --edge %d\n",
           canon, k, o->n, o->n, o->n);
  else if (o->kind == SS_CASE_VERTEX)
    printf(", link %s (k = %d, %d %s)\n", canon, k, 2 * k - 4, ss_cell_plural(M->cell));
  else if (o->kind == SS_CASE_FACE)
    printf(" (two tets sharing a face)\n");
  else if (M->cell == SS_TRIANGLE && o->cls48)
    printf(", valence %d, 4-8 class %d%s\n", o->n, o->cls48,
           o->cls48 == 4 ? " (S is class 8's with twice the valence: after one step "
                           "the vertex is of class 8)"
                         : "");
  else
    printf(", valence %d\n", o->n);
  printf(
      "two-ring %zu points, one-ring %zu (read on level %d); outer part in %zu blocks, "
      "the largest %zu\n",
      M->n2, M->n1, M->level, e->nblocks, e->largest_block);
  if (di->shown)
    printf("major diagonals: %s; %zu of %zu face-adjacent pairs improper (Definition 3.2 "
           "as read in the README)\n",
           ss_diag_name(o->diag), di->improper, di->pairs);
  printf("\n    #  eigenvalue            mult  rcond     block\n");
  for (size_t i = 0; i < e->n && i < (size_t)o->neig; i++) {
    char v[64];
    if (e->val[i].im == 0.0)
      snprintf(v, sizeof v, "%.12g", e->val[i].re);
    else
      snprintf(v, sizeof v, "%.8g%+.8gi", e->val[i].re, e->val[i].im);
    printf("  %3zu  %-20s  %4d  %-8.2e  %s\n", i, v, e->val[i].mult, e->val[i].rcond,
           e->val[i].block ? "outer" : "one-ring");
  }
  printf("\neigenvalue condition: %s%s%s (equal within relative tolerance %.1e",
         ss_verdict_name(e->cond.verdict), e->cond.reason[0] ? ": " : "", e->cond.reason,
         e->tol);
  if (e->tol > e->tol_requested)
    printf(": the requested %.1e is below the eigenvalues' rounding error bound",
           e->tol_requested);
  printf(")\n");
  if (ci->on) {
    printf("eigenvalue condition, exact (%.2f s): %s%s%s%s\n", ci->c.seconds,
           ss_verdict_name(ci->c.cond.verdict), ci->c.cond_certified ? ", certified" : "",
           ci->c.cond.reason[0] ? ": " : "", ci->c.cond.reason);
    size_t nr = 0;
    const ss_exact_root *x = ci->exact ? ss_exact_roots(ci->exact, &nr) : NULL;
    for (size_t i = 0; i < nr && i < 6; i++) {
      char poly[160];
      printf("    %-20.12g %+.3gi  mult %d  radius %.1e  minimal polynomial %s\n",
             x[i].re, x[i].im, x[i].mult, x[i].rad,
             ss_exact_minpoly(ci->exact, i, poly, sizeof poly));
    }
  }
  if (e->basis_kind[0]) printf("subdominant basis: %s\n", e->basis_kind);
  printf("regularity: %s%s%s%s\n", ss_verdict_name(reg->verdict.verdict),
         reg->certified ? ", certified" : "", reg->verdict.reason[0] ? ": " : "",
         reg->verdict.reason);
  if (reg->nlevels > 0) {
    printf(
        "  judged on the ring (cells not touching the centre), levels 0..%d of at most "
        "%d; fold shrink ratio %.2f:\n",
        reg->nlevels - 1, o->ring_levels, reg->shrink);
    for (int l = 0; l < reg->nlevels; l++) {
      const ss_ring_level *L = reg->level + l;
      printf(
          "    level %d: %zu cells: %zu positive, %zu negative, %zu folded (%zu inverted "
          "whole), %zu undecided, %zu flat; minimum scaled Jacobian %.6g\n",
          l, L->cells, L->positive, L->negative, L->folded, L->inverted, L->undecided,
          L->degenerate, L->min_scaled_jacobian);
    }
    printf(
        "  minimum scaled Jacobian %.6g (level %d, ring cell %zu; hex subdivision depth "
        "limit %d)\n"
        "  cells around the centre: %zu of %zu not of the ring's sign "
        "(centre_corner_folds; they decide nothing)\n",
        reg->min_scaled_jacobian, reg->ring_level, reg->worst_cell, reg->depth,
        reg->centre_corner_folds, M->ncentre);
  }
  printf("injectivity: %s%s%s%s\n", ss_verdict_name(inj->verdict.verdict),
         inj->certified ? ", certified" : "", inj->verdict.reason[0] ? ": " : "",
         inj->verdict.reason);
  if (inj->verdict.verdict == SS_PASS)
    printf("  degree %d about psi(p); no two ring cells without a common vertex meet "
           "(piecewise-linear images, exact predicates)\n",
           inj->degree);
}

static void print_label(FILE *f, const ss_star_coord *c) {
  char buf[256];
  ss_cli_label_text(c, buf, sizeof buf);
  fputs(buf, f);
}

static int write_mtx(const opts *o, const char *scheme, const char *canon,
                     const ss_local *M, const diag_info *di) {
  /* -o: a temporary file renamed over the target, written whole or not at all;
   * standard output is checked by main */
  ss_outfile *out = NULL;
  ss_error err = {0};
  if (o->out && ss_outfile_open(o->out, &out, &err)) return ss_cli_fail(&err);
  FILE *f = out ? ss_outfile_file(out) : stdout;
  const size_t n = o->ring == 1 ? M->n1 : M->n2;
  size_t nnz = 0;
  for (size_t i = 0; i < n; i++)
    for (size_t j = 0; j < n; j++)
      nnz += M->S[i * M->n2 + j] != 0.0;
  char buf[32];
  fprintf(f, "%%%%MatrixMarket matrix coordinate real general\n");
  fprintf(f, "%% subspectra local subdivision matrix: scheme %s, %s case %s\n", scheme,
          ss_case_name(o->kind), param_text(o, canon, buf, sizeof buf));
  if (di->shown)
    fprintf(f, "%% major diagonals: %s; %zu of %zu face-adjacent pairs improper\n",
            ss_diag_name(o->diag), di->improper, di->pairs);
  fprintf(f,
          "%% %s: row i = point i on level j+1, column j = point j on level j (read on "
          "level %d)\n",
          o->ring == 1 ? "one-ring block A" : "whole two-ring S", M->level);
  fprintf(f,
          "%% points 1..%zu are the one-ring, %zu..%zu the rest of the two-ring; each\n"
          "%% point is named by its exact coordinates relative to the centre, as\n"
          "%% (chart-index:value ...) pairs in units of the level's grid\n",
          M->n1, M->n1 + 1, M->n2);
  for (size_t i = 0; i < n; i++) {
    fprintf(f, "%% %zu ", i + 1);
    print_label(f, M->label + i);
    fputc('\n', f);
  }
  fprintf(f, "%zu %zu %zu\n", n, n, nnz);
  for (size_t i = 0; i < n; i++)
    for (size_t j = 0; j < n; j++)
      if (M->S[i * M->n2 + j] != 0.0)
        fprintf(f, "%zu %zu %.17g\n", i + 1, j + 1, M->S[i * M->n2 + j]);
  if (ss_outfile_commit(out, &err)) return ss_cli_fail(&err);
  return SS_EXIT_OK;
}

/* The K leading eigenpairs of S, or of A with --ring 1 (ss_eigvec); NULL
 * after saying why. */
static ss_eigvec *eigvec_of(const opts *o, const ss_local *M, size_t n,
                            const char *where) {
  ss_error err = {0};
  ss_eigvec *v = NULL;
  double *A = NULL;
  if ((size_t)o->nvec > n) {
    fprintf(stderr, "subspectra %s: %s--eigenvectors %d: the matrix has only %zu rows\n",
            o->cmd, where, o->nvec, n);
    return NULL;
  }
  if (n != M->n2) { /* the one-ring block, contiguous */
    if (!(A = malloc(n * n * sizeof *A))) {
      fprintf(stderr, "subspectra %s: out of memory\n", o->cmd);
      return NULL;
    }
    for (size_t i = 0; i < n; i++)
      memcpy(A + i * n, M->S + i * M->n2, n * sizeof *A);
  }
  if (ss_eigvec_new(A ? A : M->S, n, o->nvec, o->tol, &v, &err))
    fprintf(stderr, "subspectra %s: %s%s\n", o->cmd, where, err.msg);
  free(A);
  return v;
}

static int write_eigvec_mtx(const opts *o, const char *scheme, const char *canon,
                            const ss_local *M) {
  const size_t n = o->ring == 1 ? M->n1 : M->n2;
  ss_eigvec *v = eigvec_of(o, M, n, "");
  if (!v) return SS_EXIT_USAGE;
  ss_outfile *out = NULL;
  ss_error err = {0};
  if (o->out && ss_outfile_open(o->out, &out, &err)) {
    ss_eigvec_free(v);
    return ss_cli_fail(&err);
  }
  char head[256], buf[32];
  snprintf(head, sizeof head,
           "%% subspectra local subdivision matrix: scheme %s, %s case %s, %s", scheme,
           ss_case_name(o->kind), param_text(o, canon, buf, sizeof buf),
           o->ring == 1 ? "one-ring block A" : "whole two-ring S");
  ss_cli_eigvec_mtx(out ? ss_outfile_file(out) : stdout, v, M, o->left, head);
  ss_eigvec_free(v);
  if (ss_outfile_commit(out, &err)) return ss_cli_fail(&err);
  return SS_EXIT_OK;
}

/* analyze's "eigenvectors" object: 0, or the exit status after saying why
 * not.  The limit masks need the eigenvalue condition (cond). */
static int eigvec_json(const opts *o, const ss_local *M, const ss_eig *e,
                       const ss_verdict *cond, const char *where, json_object **out) {
  ss_eigvec *v = eigvec_of(o, M, M->n2, where);
  if (!v) return SS_EXIT_USAGE;
  const int limit = ss_eigvec_has_limit(v, e->tol);
  const int ok = cond->verdict == SS_PASS && limit;
  *out = ss_cli_eigvec_json(v, M, M->dim, ok,
                            !limit ? "lambda0 = 1 is not simple with a constant "
                                     "eigenvector"
                                   : "the eigenvalue condition does not hold");
  ss_eigvec_free(v);
  if (!*out) {
    fprintf(stderr, "subspectra %s: out of memory\n", o->cmd);
    return SS_EXIT_USAGE;
  }
  return 0;
}

/* ---- one case ---- */

#define SLOW 3.0 /* estimated seconds above which a terminal sees progress */

/* The case as the command line named it, for messages: "--edge 1000". */
static void case_text(const opts *o, const ss_link *l, char *buf, size_t n) {
  switch (o->kind) {
  case SS_CASE_VERTEX:
    snprintf(buf, n, "--vertex (a link with k = %d vertices)", l ? l->k : 0);
    break;
  case SS_CASE_EDGE_POINT:
    snprintf(buf, n, "--vertex (the bipyramid over %d, as --edge %d)", o->n, o->n);
    break;
  case SS_CASE_EDGE:
    snprintf(buf, n, "--edge %d", o->n);
    break;
  case SS_CASE_SURFACE_VERTEX:
    snprintf(buf, n, "--surface-vertex %d", o->n);
    if (o->cls) snprintf(buf + strlen(buf), n - strlen(buf), " --class %d", o->cls);
    break;
  default:
    snprintf(buf, n, "--face");
  }
}

/* Analyse one case; link_text is the link's text for the vertex case and
 * where is a prefix for messages ("" or "stdin:LINE: "). */
/* Whether case c fits the memory budget: 0, or the exit status after saying
 * why not (the estimate against the budget, ss_local_check_budget, or the
 * estimator's error).  *cost receives the estimate. */
static int check_budget(const opts *o, const ss_scheme *s, const ss_case *c,
                        const ss_link *l, const char *where, ss_local_cost *cost) {
  ss_error err = {0};
  ss_status st = ss_local_estimate(s, c, cost, &err);
  if (st) {
    fprintf(stderr, "subspectra %s: %s%s\n", o->cmd, where, err.msg);
    return ss_cli_exit_status(st);
  }
  if ((st = ss_local_check_budget(cost, ss_cli_budget(o->max_memory), &err))) {
    char what[96];
    case_text(o, l, what, sizeof what);
    fprintf(stderr, "subspectra %s: %s%s %s: set --max-memory to override\n", o->cmd,
            where, what, err.msg);
    return ss_cli_exit_status(st);
  }
  return 0;
}

/* The error of a case: "subspectra CMD: WHERE message" on stderr; its exit
 * status. */
static int case_fail(const opts *o, const char *where, const ss_error *err) {
  fprintf(stderr, "subspectra %s: %s%s\n", o->cmd, where, err->msg);
  return ss_cli_exit_status(err->status);
}

/* draw: the picture of the characteristic map *cm of case (M, e) into
 * o->out, captioned with the case (canon, diagonals di) unless --no-caption.
 * With --force and no map (the eigenvalue condition fails) the would-be map
 * is built into *cm, judged into *reg and drawn, labelled as such.  The exit
 * status: 0, 1 for a forced map or none to draw, 2 when writing fails. */
static int draw_case(const opts *o, const ss_scheme *s, const char *canon,
                     const ss_local *M, const ss_eig *e, const ss_charmap_opts *co,
                     const diag_info *di, const char *where, ss_charmap **cm,
                     ss_regularity *reg) {
  ss_error err = {0};
  int forced = 0;
  if (!*cm && o->force && e->basis) {
    if (ss_charmap_new(M, e, cm, &err) || ss_charmap_regularity(*cm, M, co, reg, &err))
      return case_fail(o, where, &err);
    forced = 1;
  }
  if (!*cm) {
    fprintf(stderr, "subspectra draw: %sno characteristic map to draw: %s\n", where,
            reg->verdict.reason);
    return SS_EXIT_FAIL;
  }
  char caption[600], buf[32];
  char dtext[128] = "";
  if (di->shown)
    snprintf(dtext, sizeof dtext, ", diagonals %s (%zu of %zu pairs improper)",
             ss_diag_name(o->diag), di->improper, di->pairs);
  snprintf(caption, sizeof caption, "%s, %s %s%s%s", ss_scheme_name(s),
           ss_case_name(o->kind),
           o->kind == SS_CASE_FACE ? "" : param_text(o, canon, buf, sizeof buf), dtext,
           forced ? "; forced: NOT a characteristic map (the eigenvalue condition fails)"
                  : "");
  ss_report_draw_opts dopt = o->draw;
  dopt.caption = o->nocaption ? NULL : caption;
  if (ss_report_draw(*cm, reg, &dopt, o->out, &err)) {
    fprintf(stderr, "subspectra draw: %s\n", err.msg);
    return SS_EXIT_USAGE; /* bad file, i/o or out of memory */
  }
  fprintf(stderr, "subspectra draw: wrote %s (%s %s%s%s)\n", o->out,
          forced ? "forced map, eigenvalue condition fails; its cells:" : "regularity",
          ss_verdict_name(reg->verdict.verdict), reg->verdict.reason[0] ? ": " : "",
          reg->verdict.reason);
  return forced ? SS_EXIT_FAIL : SS_EXIT_OK;
}

static int one_case(const opts *o, const ss_scheme *s, const char *link_text,
                    const char *where, int *header) {
  ss_error err = {0};
  ss_link *l = NULL, *cl = NULL;
  char *canon = NULL;
  ss_local *M = NULL;
  ss_eig *e = NULL;
  ss_charmap *cm = NULL;
  ss_exact *ex = NULL;
  int rc = SS_EXIT_OK;
  ss_local_cost cost;
  if (o->kind == SS_CASE_VERTEX) {
    if (ss_link_parse(link_text, &l, &err)) {
      rc = case_fail(o, where, &err);
      goto done;
    }
    /* the budget before the canonical form, which costs O(k^2) (bipyramid:99998
     * spent 35 s there).  A bipyramid becomes an edge point below, whose rows
     * are at least the vertex case's (MLCA 30k - 55 = 30n + 5 both, tet/oct
     * 5k - 5 < 15n + 5, ss_local_cost.c), so nothing refused here fits. */
    const ss_case cv = {SS_CASE_VERTEX, l, 0, o->diag, 0};
    if ((rc = check_budget(o, s, &cv, l, where, &cost))) goto done;
    if (ss_link_canonical(l, &cl, NULL, &err) || ss_link_format(cl, &canon, &err)) {
      rc = case_fail(o, where, &err);
      goto done;
    }
  }
  /* the canonical labelling, as sweep and reproduce analyse it (ss_result):
   * isomorphic links then give the same numbers to the last bit */
  ss_case c = {o->kind, cl ? cl : l, o->n, o->diag, o->cls};
  /* a point on an extraordinary edge: the edge case judges it (ss_local.h) */
  const int ep = cl ? ss_case_edge_point(s, cl) : 0;
  opts oe = *o;
  if (ss_scheme_split_kind(s) == SS_SPLIT_BISECT && o->kind == SS_CASE_SURFACE_VERTEX) {
    oe.cls48 = ss_case_class48(o->n, o->cls);
    o = &oe;
  }
  if (ep > 0) {
    c = (ss_case){SS_CASE_EDGE, NULL, ep, o->diag, 0};
    oe.kind = SS_CASE_EDGE_POINT;
    oe.n = ep;
    o = &oe;
  }
  /* what the case will cost, before anything is built */
  if ((rc = check_budget(o, s, &c, l, where, &cost))) goto done;
  ss_cli_progress pr = {o->cmd, ss_cli_now(), 0.0, NULL, 0};
  const ss_progress prog = {o->progress || (isatty(STDERR_FILENO) && cost.seconds > SLOW)
                                ? ss_cli_progress_fn
                                : NULL,
                            &pr};
  ss_local_opts lo = ss_local_defaults();
  lo.progress = prog;
  if (ss_local_new_opts(s, &c, &lo, &M, &err)) {
    rc = case_fail(o, where, &err);
    goto done;
  }
  diag_info di = {0, 0, 0};
  if (ss_scheme_reads_diagonals(s) && M->cell == SS_TET) {
    ss_star *star = NULL;
    if (ss_case_star(s, &c, &star, &err) ||
        ss_diag_improper(star->cx, &di.pairs, &di.improper, &err)) {
      ss_star_free(star);
      rc = case_fail(o, where, &err);
      goto done;
    }
    ss_star_free(star);
    di.shown = 1;
  }
  if (o->format == FMT_MTX && o->nvec) {
    rc = write_eigvec_mtx(o, ss_scheme_name(s), canon ? canon : "", M);
    goto done;
  }
  if (o->format == FMT_MTX) {
    rc = write_mtx(o, ss_scheme_name(s), canon ? canon : "", M, &di);
    goto done;
  }
  ss_eig_opts eo = ss_eig_defaults(M->dim);
  eo.tol = o->tol;
  eo.force = o->force;
  eo.progress = prog;
  if (ss_eig_new(M->S, M->n2, M->n1, &eo, &e, &err)) {
    rc = case_fail(o, where, &err);
    goto done;
  }
  ss_regularity reg;
  ss_charmap_opts co = ss_charmap_defaults();
  co.depth = o->depth;
  co.ring_levels = o->ring_levels;
  ss_charmap_inj inj;
  cert_info ci = {o->certify, {e->cond, 0, 0.0}, NULL};
  ss_progress_step(&prog,
                   o->certify ? "regularity, injectivity, exact path"
                              : "regularity and injectivity",
                   0, 0);
  if (ss_certify_verdicts(s, &c, M, e, &co, o->certify, &cm, &reg, &inj, &ci.c, &ex,
                          &err)) {
    rc = case_fail(o, where, &err);
    goto done;
  }
  ci.exact = ex;
  const int k = l ? l->k : 0;
  if (!strcmp(o->cmd, "draw")) {
    /* a failure, or a forced map: its status, not the verdicts' */
    if ((rc = draw_case(o, s, canon, M, e, &co, &di, where, &cm, &reg))) goto done;
  } else if (o->format == FMT_JSON) {
    json_object *evj = NULL;
    if (o->nvec && (rc = eigvec_json(o, M, e, &ci.c.cond, where, &evj))) goto done;
    if ((rc = print_json(o, ss_scheme_name(s), canon ? canon : "", k, M, e, &reg, &inj,
                         &di, &ci, evj)))
      goto done;
  } else if (o->format == FMT_TSV)
    print_tsv(o, ss_scheme_name(s), canon ? canon : "", M, e, &reg, &inj, &ci,
              (*header)++ == 0);
  else
    print_text(o, ss_scheme_name(s), canon ? canon : "", k, M, e, &reg, &inj, &di, &ci);
  if (ci.c.cond.verdict != SS_PASS || reg.verdict.verdict != SS_PASS ||
      inj.verdict.verdict != SS_PASS)
    rc = SS_EXIT_FAIL;
done:
  ss_charmap_free(cm);
  ss_exact_free(ex);
  ss_eig_free(e);
  ss_local_free(M);
  free(canon);
  ss_link_free(l);
  ss_link_free(cl);
  return rc;
}

/* matrix and draw write one case: `--vertex -` reads exactly one link from
 * standard input, and refuses a second one before writing anything (a stream
 * of results belongs to analyze). */
static int one_case_stdin(const opts *o, const ss_scheme *s, int *header) {
  char *line = NULL, *first = NULL;
  size_t cap = 0;
  long lineno = 0, firstline = 0;
  int rc = SS_EXIT_USAGE;
  char *p = ss_cli_next_item(stdin, &line, &cap, &lineno);
  if (!p) {
    fprintf(stderr, "subspectra %s: stdin: no links read\n", o->cmd);
    goto done;
  }
  firstline = lineno;
  if (!(first = strdup(p))) {
    fprintf(stderr, "subspectra %s: out of memory\n", o->cmd);
    goto done;
  }
  if (ss_cli_next_item(stdin, &line, &cap, &lineno)) {
    fprintf(stderr,
            "subspectra %s: stdin:%ld: a second link: %s writes one case (analyze "
            "takes a stream of links)\n",
            o->cmd, lineno, o->cmd);
    goto done;
  }
  char where[48];
  snprintf(where, sizeof where, "stdin:%ld: ", firstline);
  rc = one_case(o, s, first, where, header);
done:
  free(first);
  free(line);
  return rc;
}

static int run(int argc, char **argv, const char *cmd) {
  opts o = {cmd,
            NULL,
            NULL,
            SS_CASE_VERTEX,
            0,
            NULL,
            0,
            1e-6,
            16,
            FMT_TEXT,
            2,
            NULL,
            SS_JAC_DEPTH,
            ss_charmap_defaults().ring_levels,
            0,
            ss_report_draw_defaults(),
            SS_DIAG_BFS,
            0,
            0.0,
            0,
            0,
            0,
            0,
            0,
            0};
  if (!strcmp(cmd, "matrix")) o.format = FMT_MTX;
  int r = parse(argc, argv, &o);
  if (r) return r < 0 ? SS_EXIT_OK : r;
  ss_error err = {0};
  ss_scheme *s = NULL;
  if (o.stencil ? ss_stencil_load(o.stencil, &s, NULL, &err)
                : ss_scheme_new(o.scheme, &s, &err)) {
    fprintf(stderr, "subspectra %s: %s%s\n", cmd,
            o.stencil ? "--stencil " : "--scheme: ", err.msg);
    return SS_EXIT_USAGE; /* bad scheme or stencil, or out of memory */
  }
  if (o.cls && ss_scheme_split_kind(s) != SS_SPLIT_BISECT) {
    ss_scheme_free(s);
    return ss_cli_usage_error(cmd,
                              "--class: scheme %s has no 4-8 vertex classes (only "
                              "quasi48 has)",
                              o.stencil ? o.stencil : o.scheme);
  }
  int rc = SS_EXIT_OK, header = 0;
  if (o.kind == SS_CASE_VERTEX && !strcmp(o.link, "-") && strcmp(cmd, "analyze"))
    rc = one_case_stdin(&o, s, &header);
  else if (o.kind == SS_CASE_VERTEX && !strcmp(o.link, "-")) {
    char *line = NULL;
    size_t cap = 0;
    long lineno = 0, nread = 0;
    char *p;
    while ((p = ss_cli_next_item(stdin, &line, &cap, &lineno))) {
      char where[48];
      snprintf(where, sizeof where, "stdin:%ld: ", lineno);
      int one = one_case(&o, s, p, where, &header);
      nread++;
      if (fflush(stdout) || ferror(stdout)) break; /* output lost: main reports it */
      if (one == SS_EXIT_USAGE) {
        rc = SS_EXIT_USAGE;
        break;
      }
      if (one == SS_EXIT_FAIL) rc = SS_EXIT_FAIL;
    }
    free(line);
    if (rc == SS_EXIT_OK && nread == 0) {
      fprintf(stderr, "subspectra %s: stdin: no links read\n", cmd);
      rc = SS_EXIT_USAGE;
    }
  } else {
    rc = one_case(&o, s, o.link, "", &header);
  }
  ss_scheme_free(s);
  return rc;
}

int ss_cli_analyze(int argc, char **argv) {
  return run(argc, argv, "analyze");
}

int ss_cli_matrix(int argc, char **argv) {
  return run(argc, argv, "matrix");
}

int ss_cli_draw(int argc, char **argv) {
  return run(argc, argv, "draw");
}
