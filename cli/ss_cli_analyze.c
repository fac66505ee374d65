/* ss_cli_analyze.c — `subspectra analyze` (local matrix, eigenstructure,
 * eigenvalue condition and characteristic-map regularity for one case or one
 * case per input line), `subspectra matrix` (the local matrix in Matrix Market
 * format) and `subspectra draw` (a picture of the characteristic map): their
 * options and one case through the pipeline (ss_pipeline); the writers are in
 * ss_cli_analyze_print.c, ss_cli_matrix.c and ss_cli_draw.c. */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "ss_cli.h"
#include "ss_cli_analyze.h"
#include "ss_link.h"
#include "ss_outfile.h"
#include "ss_stencil.h"

typedef ss_cli_analyze_opts opts;

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
           "analyze reports them; see docs/draw.md).\n\n");
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
      "  --surface-vertex N     a 2D vertex of valence N (3..1000; quasi48: its\n"
      "                         patch's cap of 6e6 cells holds class 8 to N = 688,\n"
      "                         class 4 to N = 326 (odd N: 343); beyond, exit 2)\n\n"
      "options:\n"
      "  -s, --scheme S         mlca, tetoct, boxspline, boxspline-avg, catmull-clark,\n"
      "                         loop, ccsolid, ccsolid-tensor, quasi48 (surface\n"
      "                         vertices only; S maps two binary steps, a full 4-8\n"
      "                         cycle)\n"
      "  --class 4|8            quasi48: the 4-8 class of the surface vertex: 4 (all\n"
      "                         spokes legs, the outer edges split first; N >= 3),\n"
      "                         8 (spokes alternate, N even >= 6).  Default: 8 for\n"
      "                         even N >= 6, else 4.  Class 4 with N is class 8\n"
      "                         with 2N after one step: the same matrix\n"
      "  --diagonals D          major diagonals of tet stars (boxspline): bfs\n"
      "                         (Algorithm 2, default), or around the edge of\n"
      "                         --edge: skew (the same turn all round) or center\n"
      "                         (all toward the edge); other rules read none\n"
      "                         and refuse all but bfs\n",
      m || d
          ? "the\n                         link from standard input (exactly one)"
          : "one link per\n                         line on standard input (one result "
            "per line)");
  if (m)
    printf("  --ring 1|2             the one-ring block A or the whole two-ring (default "
           "2)\n"
           "  --format mtx           Matrix Market (the only format)\n"
           "  -o, --output FILE      write to FILE instead of standard output (whole or\n"
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
        "                         undecided (\"not certified: ...\"); algebraic\n"
        "                         weights (a stencil's cos): eigenvalue balls, ties\n"
        "                         by the case's symmetry (Fourier blocks, or Schur's\n"
        "                         lemma under the link's automorphisms)\n"
        "  --psi-depth N          judge psi itself, not only its control net (1..8,\n"
        "                         default %d; 0: not): mlca and ccsolid vertices on\n"
        "                         its polynomial pieces (where psi is a tricubic\n"
        "                         B-spline, the Bernstein form of det Dpsi; the ring\n"
        "                         cut in boxes down to side 2^-N) and the spokes'\n"
        "                         tubes; tetoct vertices at the ring's regular\n"
        "                         vertices (tangent masks) and on the spokes,\n"
        "                         boxspline at the regular vertices only; a fold\n"
        "                         of psi fails regularity and injectivity judged on\n"
        "                         psi; the spokes decide by evidence only; with\n"
        "                         --certify only what is proven about psi decides\n"
        "  --psi-tubes            with --certify (mlca): prove the tubes round the\n"
        "                         spokes too (the edge's layered structure, its\n"
        "                         smaller modes bounded), so a ring of one sign on\n"
        "                         its pieces is a proven pass on psi (seconds per\n"
        "                         case)\n",
        SS_JAC_DEPTH, SS_LOCAL_MAXRING, ss_charmap_defaults().ring_levels,
        SS_PSI_BOX_DEPTH);
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
        "  -o, --output FILE      the picture: FILE.png, FILE.svg, FILE.pdf or FILE.vtk\n"
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
           "  --format F             text (default), json (one object per case), tsv\n"
           "  -o, --output FILE      write to FILE instead of standard output (whole or\n"
           "                         not at all: an old FILE stays if writing fails)\n");
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
         "improper diagonals (Definition 3.2 as read in docs/schemes.md).\n"
         "Exit status: 0 all conditions hold, 1 a condition fails or is undecided (or\n"
         "the extraction failed a check), 2 bad usage or input, a case beyond the\n"
         "memory budget, or out of memory.\n");
}

enum {
  O_VERTEX = 256,
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
  O_PSI,
  O_TUBES,
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
  case O_PSI:
    if (m || d || ss_cli_parse_int(arg, 0, 8, &v))
      return ss_cli_usage_error(o->cmd,
                                "--psi-depth: an option of analyze, expects an integer "
                                "in 0..8, not '%s'",
                                arg);
    o->psi_depth = (int)v;
    break;
  case O_TUBES:
    if (m || d) return ss_cli_usage_error(o->cmd, "--psi-tubes is an option of analyze");
    o->psi_tubes = 1;
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
  if (o->psi_tubes && (!o->certify || !o->psi_depth))
    return ss_cli_usage_error(o->cmd, "--psi-tubes needs --certify and a --psi-depth "
                                      "above 0 (the tubes are proven, never judged in "
                                      "doubles)");
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
  static const struct option lo[] = {{"scheme", required_argument, 0, 's'},
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
                                     {"psi-depth", required_argument, 0, O_PSI},
                                     {"psi-tubes", no_argument, 0, O_TUBES},
                                     {"max-memory", required_argument, 0, O_MAXMEM},
                                     {"progress", no_argument, 0, O_PROGRESS},
                                     {"eigenvectors", required_argument, 0, O_EIGVEC},
                                     {"left", no_argument, 0, O_LEFT},
                                     {"no-caption", no_argument, 0, O_NOCAPTION},
                                     {"class", required_argument, 0, O_CLASS},
                                     {"output", required_argument, 0, 'o'},
                                     {"help", no_argument, 0, 'h'},
                                     {0, 0, 0, 0}};
  optind = 1;
  opterr = 0;
  int c, rc = 0;
  while (!rc && (c = getopt_long(argc, argv, ":hs:o:", lo, NULL)) != -1) {
    switch (c) {
    case 'h':
      help(o->cmd);
      return -1;
    case 'o':
      o->out = optarg;
      break;
    case 's':
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
    case O_PSI:
    case O_TUBES:
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

/* ---- one case ---- */

#define SLOW 3.0 /* estimated seconds above which a terminal sees progress */

/* The case as the command line named it, for messages: "--edge 1000"; num
 * is k for a vertex, n for an edge point, edge or surface vertex. */
static void case_text(const opts *o, ss_case_kind kind, int num, char *buf, size_t n) {
  switch (kind) {
  case SS_CASE_VERTEX:
    snprintf(buf, n, "--vertex (a link with k = %d vertices)", num);
    break;
  case SS_CASE_EDGE_POINT:
    snprintf(buf, n, "--vertex (the bipyramid over %d, as --edge %d)", num, num);
    break;
  case SS_CASE_EDGE:
    snprintf(buf, n, "--edge %d", num);
    break;
  case SS_CASE_SURFACE_VERTEX:
    snprintf(buf, n, "--surface-vertex %d", num);
    if (o->cls) snprintf(buf + strlen(buf), n - strlen(buf), " --class %d", o->cls);
    break;
  default:
    snprintf(buf, n, "--face");
  }
}

/* Whether case c fits the memory budget: 0, or the exit status after saying
 * why not (the estimate against the budget, ss_local_check_budget, or the
 * estimator's error).  *cost receives the estimate. */
static int check_budget(const opts *o, const ss_scheme *s, const ss_case *c,
                        ss_case_kind kind, int num, const char *where,
                        ss_local_cost *cost) {
  ss_error err = {0};
  ss_status st = ss_local_estimate(s, c, cost, &err);
  if (st) {
    fprintf(stderr, "subspectra %s: %s%s\n", o->cmd, where, err.msg);
    return ss_cli_exit_status(st);
  }
  if ((st = ss_local_check_budget(cost, ss_cli_budget(o->max_memory), &err))) {
    char what[96];
    case_text(o, kind, num, what, sizeof what);
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

/* Analyse one case; link_text is the link's text for the vertex case and
 * where is a prefix for messages ("" or "stdin:LINE: "). */
static int one_case(const opts *o, const ss_scheme *s, const char *link_text,
                    const char *where, int *header) {
  ss_error err = {0};
  ss_link *l = NULL;
  ss_pipeline *p = NULL;
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
    if ((rc = check_budget(o, s, &cv, SS_CASE_VERTEX, l->k, where, &cost))) goto done;
  }
  ss_pipeline_opts po = ss_pipeline_defaults();
  po.tol = o->tol;
  po.depth = o->depth;
  po.ring_levels = o->ring_levels;
  po.certify = o->certify;
  po.psi_depth = o->psi_depth;
  po.psi_tubes = o->psi_tubes;
  po.force = o->force;
  /* the case as analysed: the canonical labelling, as sweep and reproduce
   * analyse it (isomorphic links give the same numbers to the last bit), a
   * point on an extraordinary edge as that edge (ss_case.h) */
  const ss_case c = {o->kind, l, o->n, o->diag, o->cls};
  if (ss_pipeline_new(s, &c, &po, NULL, &p, &err)) {
    rc = case_fail(o, where, &err);
    goto done;
  }
  /* what the case will cost, before anything is built */
  if ((rc = check_budget(o, s, &p->c.judged, p->c.kind,
                         p->c.kind == SS_CASE_EDGE_POINT ? p->c.valence : p->c.k, where,
                         &cost)))
    goto done;
  ss_cli_progress pr = {o->cmd, ss_cli_now(), 0.0, NULL, 0};
  p->opts.progress = (ss_progress){
      o->progress || (isatty(STDERR_FILENO) && cost.seconds > SLOW) ? ss_cli_progress_fn
                                                                    : NULL,
      &pr};
  const ss_pipeline_stage until =
      o->format == FMT_MTX ? SS_PIPE_MATRIX : SS_PIPE_VERDICTS;
  if (ss_pipeline_run(p, until, NULL, &err)) {
    rc = case_fail(o, where, &err);
    goto done;
  }
  if (o->format == FMT_MTX) {
    rc = o->nvec ? ss_cli_write_eigvec_mtx(o, p) : ss_cli_write_mtx(o, p);
    goto done;
  }
  if (!strcmp(o->cmd, "draw")) {
    /* a failure, or a forced map: its status, not the verdicts' */
    if ((rc = ss_cli_draw_case(o, p, where))) goto done;
  } else if (o->format == FMT_JSON) {
    json_object *evj = NULL;
    if (o->nvec && (rc = ss_cli_eigvec_json_of(o, p, where, &evj))) goto done;
    if ((rc = ss_cli_print_json(o, p, evj))) goto done;
  } else if (o->format == FMT_TSV)
    ss_cli_print_tsv(o, p, (*header)++ == 0);
  else
    ss_cli_print_text(o, p);
  if (ss_verdicts_combined(&p->v) != SS_PASS) rc = SS_EXIT_FAIL;
done:
  ss_pipeline_free(p);
  ss_link_free(l);
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

/* The cases of o (one, or a stream of links on standard input), printed on
 * standard output; the exit status. */
static int run_cases(const opts *o, const ss_scheme *s) {
  int rc = SS_EXIT_OK, header = 0;
  if (o->kind == SS_CASE_VERTEX && !strcmp(o->link, "-") && strcmp(o->cmd, "analyze"))
    rc = one_case_stdin(o, s, &header);
  else if (o->kind == SS_CASE_VERTEX && !strcmp(o->link, "-")) {
    char *line = NULL;
    size_t cap = 0;
    long lineno = 0, nread = 0;
    char *p;
    while ((p = ss_cli_next_item(stdin, &line, &cap, &lineno))) {
      char where[48];
      snprintf(where, sizeof where, "stdin:%ld: ", lineno);
      int one = one_case(o, s, p, where, &header);
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
      fprintf(stderr, "subspectra %s: stdin: no links read\n", o->cmd);
      rc = SS_EXIT_USAGE;
    }
  } else {
    rc = one_case(o, s, o->link, "", &header);
  }
  return rc;
}

static int run(int argc, char **argv, const char *cmd) {
  opts o = {.cmd = cmd,
            .kind = SS_CASE_VERTEX,
            .tol = 1e-6,
            .neig = 16,
            .format = FMT_TEXT,
            .ring = 2,
            .depth = SS_JAC_DEPTH,
            .ring_levels = ss_charmap_defaults().ring_levels,
            .psi_depth = strcmp(cmd, "analyze") ? 0 : SS_PSI_BOX_DEPTH,
            .draw = ss_report_draw_defaults(),
            .diag = SS_DIAG_BFS};
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
  ss_outfile *of = NULL;
  FILE *const out = stdout;
  int rc = SS_EXIT_OK;
  if (o.out && !strcmp(cmd, "analyze")) {
    /* analyze -o FILE: what analyze prints goes to FILE, written whole or
     * not at all.  The printers write to stdout, so stdout is pointed at the
     * file for the run (as main points it at its own stream) and restored */
    if (ss_outfile_open(o.out, &of, &err)) {
      ss_scheme_free(s);
      return ss_cli_fail(cmd, &err);
    }
    stdout = ss_outfile_file(of);
  }
  rc = run_cases(&o, s);
  if (of) {
    stdout = out;
    if (rc == SS_EXIT_USAGE)
      ss_outfile_abort(of); /* a bad link or input: the old FILE stays */
    else if (ss_outfile_commit(of, &err))
      rc = ss_cli_fail(cmd, &err);
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
