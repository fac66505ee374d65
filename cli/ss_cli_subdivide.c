/* ss_cli_subdivide.c — `subspectra subdivide`: refine a whole mesh. */
#include <getopt.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <json-c/json.h>

#include "ss_cli.h"
#include "ss_diag.h"
#include "ss_mesh.h"
#include "ss_scheme.h"

static const char *const usage_text =
    "usage: subspectra subdivide --scheme S [--levels L] IN -o OUT [options]\n"
    "\n"
    "Refine the mesh IN L times with scheme S and write the result to OUT.\n"
    "Formats follow the file extensions: .mesh (Medit), .obj (surfaces), .vtk\n"
    "(legacy VTK), .vtu (VTK XML; read through libxml2), .msh (gmsh: versions 2\n"
    "and 4 read, 4.1 binary written, through gmsh's API), all read and written;\n"
    ".node/.ele (TetGen or Triangle: X.node with X.ele and X.face; read only).\n"
    "\n"
    "Fields: coordinates past the third are refined like the position and kept\n"
    "with their names: VTK point data (a 3-vector NAME is NAME_x, _y, _z), gmsh\n"
    "$NodeData views (by name), a Medit 4th coordinate (w; then x5, x6, ...),\n"
    "at most 13 (docs/command-line.md, \"Meshes in and out\").\n"
    "\n";

/* The usage text's second part (one literal would exceed the 4095
 * characters C11 compilers must support). */
static const char *const usage_options =
    "  -s, --scheme S        mlca | tetoct | boxspline | boxspline-avg |\n"
    "                        catmull-clark | loop | ccsolid | ccsolid-tensor |\n"
    "                        quasi48\n"
    "  -l, --levels L        number of refinement levels, 0..12 (default 1)\n"
    "  -o, --output OUT      output file (written whole or not at all: an old\n"
    "                        OUT stays if writing fails); when OUT is standard\n"
    "                        output (-o /dev/stdout) the summary goes to stderr\n"
    "      --output-format F OUT's format whatever its name: medit, vtk, vtu,\n"
    "                        gmsh or obj (for a name without extension:\n"
    "                        /dev/stdout)\n"
    "      --drop-unsupported  drop the cells below the mesh's top dimension that\n"
    "                        the scheme does not take (TetGen's .face triangles,\n"
    "                        gmsh's geometry points and curves) instead of\n"
    "                        refusing the mesh; stderr says how many\n"
    "      --hexify          first split triangles into 3 quads, tets into 4 hexes\n"
    "                        at their corners, the rest alike (MLCA paper, 3.3)\n"
    "      --octahedra-keyword  .mesh: keep octahedra under this project's\n"
    "                        Octahedra keyword (not Medit's: meshio refuses the\n"
    "                        file, gmsh drops the cells); by default each one is\n"
    "                        written as 4 positive tetrahedra about its 0-3\n"
    "                        diagonal, and stderr says how many were split\n"
    "      --split-octahedra the default (kept for old scripts)\n"
    "      --diagonals D     boxspline: the tets' major diagonals, bfs (Algorithm 2\n"
    "                        of the box-spline paper, default), proper (its search\n"
    "                        made to match neighbours' diagonals) or given (the pair\n"
    "                        (0,1),(2,3) of each tet's vertex order in IN, as\n"
    "                        subdivide writes them); octahedra keep theirs, the\n"
    "                        pair (0,3).  The summary counts improper pairs\n"
    "                        (Definition 3.2; see docs/schemes.md)\n"
    "      --boundary-c C    boxspline, boxspline-avg: the weight c of a smooth\n"
    "                        boundary vertex of valence k, (1 - k c) x + c each\n"
    "                        neighbour (box-spline paper, figure 14(b)): loop\n"
    "                        (Loop's beta(k), default) or 3/8k (c = 3/(8k))\n"
    "      --adapt-box X0,Y0,Z0,X1,Y1,Z1  quasi48: refine only the triangles\n"
    "                        whose bounding box meets this box (and their closure:\n"
    "                        the neighbours a wanted triangle needs refined first);\n"
    "                        the mesh stays conforming, points away stay put\n"
    "      --adapt-edge-length H  quasi48: refine only triangles with an edge\n"
    "                        longer than H\n"
    "      --adapt-curvature T  quasi48: refine only triangles whose normal and a\n"
    "                        neighbour's across an edge make an angle above T\n"
    "                        degrees (0..180; the adapt criteria given must all\n"
    "                        hold)\n"
    "      --boundary B      quasi48's boundary (paper, 4.3): normal (default:\n"
    "                        the boundary curve smoothed, cubic B-spline where\n"
    "                        every edge splits, each old vertex's move projected\n"
    "                        on its surface normal, so a planar boundary stays),\n"
    "                        smooth (the curve rule unprojected) or fixed (the\n"
    "                        boundary polygon never moves); tagged boundary\n"
    "                        vertices and edges are kept in every mode\n"
    "      --format F        summary as text (default) or json, on stdout\n"
    "  -h, --help            this text\n"
    "\n";

/* The second half of the help (one literal stays within C's 4095 bytes). */
static const char *const usage_schemes =
    "Schemes and the cells they take:\n"
    "  mlca           segments, quadrilaterals, hexahedra (+ corners); lower-\n"
    "                 dimensional cells are creases (MLCA paper, section 3.2)\n"
    "  tetoct         tetrahedra, octahedra (+ triangle/segment/corner creases)\n"
    "  boxspline      tetrahedra, octahedra, triangles: the boundary and the\n"
    "                 triangles (surface parts) refine as one Loop surface\n"
    "  boxspline-avg  the same, averaged over the three diagonal directions\n"
    "                 (Appendix A): reads no diagonals\n"
    "  catmull-clark  quadrilateral surfaces; boundaries and segments are creases\n"
    "  loop           triangle surfaces; boundaries and segments are creases\n"
    "  ccsolid        Catmull-Clark solids (Joy-MacCracken): hexahedra; boundary\n"
    "                 faces and given quadrilaterals refine as Catmull-Clark\n"
    "                 surfaces, segments are creases, corners are kept; non-\n"
    "                 manifold hex meshes are refused\n"
    "  ccsolid-tensor the same, but a vertex on an extraordinary edge takes the\n"
    "                 tensor product of the cubic curve along the edge and\n"
    "                 Catmull-Clark across it (docs/schemes.md)\n"
    "  quasi48        quasi 4-8 surfaces (Velho-Gomes): triangles; one level is\n"
    "                 one longest-edge bisection pass (two make a 4-8 step);\n"
    "                 corners and segments (tags) stay fixed, the boundary\n"
    "                 follows --boundary;\n"
    "                 non-manifold, zero-length edges and doubled triangles\n"
    "                 are refused\n"
    "\n"
    "The input is checked: malformed files, cells a scheme does not take, and\n"
    "flat, folded or inverted cells are errors (exit status 2), and so is a\n"
    "result with a non-finite coordinate (input coordinates near 1.8e308\n"
    "overflow when averaged): the message names the input vertices it derives\n"
    "from, and OUT is not written.\n";

/* Cells after one more level, per type: exact for the splits with fixed child
 * counts; for a bisection split (quasi48: each triangle copied or halved) the
 * bound 2 per triangle. */
static void next_counts(const double *in, double *out, int bisect) {
  out[SS_VERTEX] = in[SS_VERTEX];
  out[SS_SEGMENT] = 2 * in[SS_SEGMENT];
  out[SS_TRIANGLE] = (bisect ? 2 : 4) * in[SS_TRIANGLE];
  out[SS_QUAD] = 4 * in[SS_QUAD];
  out[SS_HEX] = 8 * in[SS_HEX];
  out[SS_TET] = 4 * in[SS_TET] + 8 * in[SS_OCT];
  out[SS_OCT] = in[SS_TET] + 6 * in[SS_OCT];
}

static json_object *level_json(int level, const ss_cx *cx, double seconds) {
  json_object *o = json_object_new_object();
  json_object_object_add(o, "level", json_object_new_int(level));
  json_object_object_add(o, "vertices", json_object_new_int64((int64_t)cx->nv));
  json_object *cells = json_object_new_object();
  for (int t = 0; t < SS_NCELLTYPES; t++)
    if (cx->nc[t])
      json_object_object_add(cells, ss_cell_plural((ss_cell_type)t),
                             json_object_new_int64((int64_t)cx->nc[t]));
  json_object_object_add(o, "cells", cells);
  json_object_object_add(o, "seconds", json_object_new_double(seconds));
  return o;
}

static void level_text(FILE *f, const char *what, const ss_cx *cx, double seconds) {
  fprintf(f, "%s: %zu vertices", what, cx->nv);
  for (int t = 0; t < SS_NCELLTYPES; t++)
    if (cx->nc[t])
      fprintf(f, ", %zu %s", cx->nc[t],
              cx->nc[t] == 1 ? ss_cell_name((ss_cell_type)t)
                             : ss_cell_plural((ss_cell_type)t));
  if (seconds >= 0) fprintf(f, " (%.3f s)", seconds);
  fprintf(f, "\n");
}

/* Whether path names the file or device standard output is on. */
static int is_stdout(const char *path) {
  struct stat a, b;
  return stat(path, &a) == 0 && fstat(STDOUT_FILENO, &b) == 0 && a.st_dev == b.st_dev &&
         a.st_ino == b.st_ino;
}

/* The command line of subdivide. */
typedef struct {
  const char *scheme;       /* --scheme */
  const char *out;          /* -o OUT */
  const char *in;           /* IN */
  long levels;              /* --levels */
  int json;                 /* --format json */
  const char *diag;         /* --diagonals as given; NULL: the default, bfs */
  ss_diag_mode dmode;       /* its mode, unless given */
  int given;                /* --diagonals given: keep the file's */
  ss_mesh_write_opts wopts; /* --octahedra-keyword; the field names */
  ss_mesh_fields names;     /* IN's field names, written with OUT's */
  int split_given;          /* --split-octahedra: the default, said explicitly */
  ss_mesh_format ofmt;      /* OUT's format: --output-format, else its name's */
  int drop;                 /* --drop-unsupported */
  int hexify;               /* --hexify */
  const char *bc;           /* --boundary-c as given; NULL: not given */
  ss_adapt adapt;           /* --adapt-box, --adapt-edge-length,
                               --adapt-curvature */
  const char *bnd;          /* --boundary as given; NULL: not given */
  ss_boundary boundary;     /* its rule */
  int adaptive;             /* either given */
  ss_loop_c loop_c;         /* its choice */
  FILE *sum;                /* the summary's stream: stdout, or stderr when
                               OUT is standard output */
} sub_opts;

/* "X0,Y0,Z0,X1,Y1,Z1" into b: 0, or -1 if not six finite numbers with each
 * lower bound at most its upper one. */
static int parse_box(const char *s, double b[6]) {
  const char *p = s;
  for (int i = 0; i < 6; i++) {
    char *end = NULL;
    b[i] = strtod(p, &end);
    if (end == p || !isfinite(b[i]) || *end != (i < 5 ? ',' : '\0')) return -1;
    p = end + 1;
  }
  return b[0] > b[3] || b[1] > b[4] || b[2] > b[5] ? -1 : 0;
}

/* quasi48's options (--adapt-box 'A', --adapt-edge-length 'E',
 * --adapt-curvature 'C', --boundary 'b') into o: 0, or the exit status 2
 * with the message printed. */
static int quasi48_option(int c, const char *arg, sub_opts *o) {
  switch (c) {
  case 'A':
    if (parse_box(arg, o->adapt.box))
      return ss_cli_usage_error("subdivide",
                                "--adapt-box: expected six numbers X0,Y0,Z0,X1,Y1,Z1 "
                                "with X0 <= X1, Y0 <= Y1, Z0 <= Z1, not '%s'",
                                arg);
    o->adapt.use_box = o->adaptive = 1;
    break;
  case 'E': {
    char *end = NULL;
    o->adapt.max_edge = strtod(arg, &end);
    if (end == arg || *end || !isfinite(o->adapt.max_edge) || !(o->adapt.max_edge > 0.0))
      return ss_cli_usage_error(
          "subdivide", "--adapt-edge-length: expected a length > 0, not '%s'", arg);
    o->adaptive = 1;
    break;
  }
  case 'C': {
    char *end = NULL;
    const double deg = strtod(arg, &end);
    if (end == arg || *end || !(deg >= 0.0 && deg <= 180.0))
      return ss_cli_usage_error(
          "subdivide",
          "--adapt-curvature: expected an angle in degrees, 0..180, not '%s'", arg);
    o->adapt.use_angle = o->adaptive = 1;
    o->adapt.max_angle = deg * (M_PI / 180.0);
    break;
  }
  case 'b':
    if (!strcmp(arg, "normal"))
      o->boundary = SS_BOUNDARY_NORMAL;
    else if (!strcmp(arg, "smooth"))
      o->boundary = SS_BOUNDARY_SMOOTH;
    else if (!strcmp(arg, "fixed"))
      o->boundary = SS_BOUNDARY_FIXED;
    else
      return ss_cli_usage_error(
          "subdivide", "--boundary: expected normal, smooth or fixed, not '%s'", arg);
    o->bnd = arg;
    break;
  }
  return 0;
}

/* argv into o: 0, -1 after --help (printed), or the exit status 2 with the
 * message printed. */
static int parse(int argc, char **argv, sub_opts *o) {
  static const struct option opts[] = {
      {"scheme", required_argument, NULL, 's'},
      {"levels", required_argument, NULL, 'l'},
      {"output", required_argument, NULL, 'o'},
      {"split-octahedra", no_argument, NULL, 'S'},
      {"octahedra-keyword", no_argument, NULL, 'K'},
      {"format", required_argument, NULL, 'F'},
      {"diagonals", required_argument, NULL, 'D'},
      {"output-format", required_argument, NULL, 'O'},
      {"drop-unsupported", no_argument, NULL, 'U'},
      {"hexify", no_argument, NULL, 'X'},
      {"boundary-c", required_argument, NULL, 'B'},
      {"adapt-box", required_argument, NULL, 'A'},
      {"adapt-edge-length", required_argument, NULL, 'E'},
      {"adapt-curvature", required_argument, NULL, 'C'},
      {"boundary", required_argument, NULL, 'b'},
      {"help", no_argument, NULL, 'h'},
      {NULL, 0, NULL, 0}};
  memset(o, 0, sizeof *o);
  o->levels = 1;
  o->dmode = SS_DIAG_BFS;
  optind = 1;
  opterr = 0;
  int c;
  while ((c = getopt_long(argc, argv, ":s:l:o:h", opts, NULL)) != -1) {
    switch (c) {
    case 's':
      o->scheme = optarg;
      break;
    case 'l':
      if (ss_cli_parse_int(optarg, 0, 12, &o->levels))
        return ss_cli_usage_error("subdivide", "--levels '%s' is not an integer in 0..12",
                                  optarg);
      break;
    case 'o':
      o->out = optarg;
      break;
    case 'S':
      o->split_given = 1;
      break;
    case 'K':
      o->wopts.octahedra_keyword = 1;
      break;
    case 'O':
      o->ofmt = ss_mesh_format_from_name(optarg);
      if (!ss_mesh_format_writable(o->ofmt))
        return ss_cli_usage_error(
            "subdivide",
            "--output-format: expected medit, vtk, vtu, gmsh or obj, not '%s'", optarg);
      break;
    case 'U':
      o->drop = 1;
      break;
    case 'X':
      o->hexify = 1;
      break;
    case 'A':
    case 'E':
    case 'C':
    case 'b':
      if (quasi48_option(c, optarg, o)) return SS_EXIT_USAGE;
      break;
    case 'B':
      if (strcmp(optarg, "loop") && strcmp(optarg, "3/8k"))
        return ss_cli_usage_error(
            "subdivide", "--boundary-c: expected loop or 3/8k, not '%s'", optarg);
      o->bc = optarg;
      o->loop_c = strcmp(optarg, "loop") ? SS_LOOP_C_3_8K : SS_LOOP_C_BETA;
      break;
    case 'F':
      if (ss_cli_format_option("subdivide", optarg, &o->json)) return SS_EXIT_USAGE;
      break;
    case 'D':
      o->given = !strcmp(optarg, "given");
      if (!o->given && (ss_diag_parse(optarg, &o->dmode) ||
                        (o->dmode != SS_DIAG_BFS && o->dmode != SS_DIAG_PROPER)))
        return ss_cli_usage_error(
            "subdivide", "--diagonals: expected bfs, proper or given, not '%s'", optarg);
      o->diag = optarg;
      break;
    case 'h':
      fputs(usage_text, stdout);
      fputs(usage_options, stdout);
      fputs(usage_schemes, stdout);
      return -1;
    default:
      return ss_cli_option_error("subdivide", c, argv);
    }
  }
  if (optind + 1 != argc)
    return ss_cli_usage_error("subdivide", optind == argc ? "no input mesh given"
                                                          : "more than one input mesh");
  o->in = argv[optind];
  if (o->split_given && o->wopts.octahedra_keyword)
    return ss_cli_usage_error("subdivide",
                              "--split-octahedra and --octahedra-keyword contradict");
  if (!o->scheme) return ss_cli_usage_error("subdivide", "--scheme is required");
  if (!o->out) return ss_cli_usage_error("subdivide", "-o OUT is required");
  o->sum = is_stdout(o->out) ? stderr : stdout;
  if (o->ofmt) return 0;
  o->ofmt = ss_mesh_format_from_path(o->out);
  if (!ss_mesh_format_writable(o->ofmt))
    return ss_cli_usage_error("subdivide", "%s '%s' (write: %s)",
                              ss_mesh_format_from_path(o->out) == SS_MESH_AUTO
                                  ? "cannot tell the format of"
                                  : "cannot write the read-only format of",
                              o->out, ss_mesh_writable_list());
  return 0;
}

/* Refuse, before any work, a refinement of cx by levels levels with scheme s
 * that would make more than 2e9 cells (counted exactly from the split's child
 * counts, or bounded by 2 per triangle and level for a bisection split):
 * 0, or the exit status 2 with the message printed. */
static int check_size(const ss_scheme *s, const ss_cx *cx, long levels) {
  const ss_split_kind k = ss_scheme_split_kind(s);
  const int bisect = k == SS_SPLIT_BISECT || k == SS_SPLIT_NVB;
  double n[SS_NCELLTYPES], m[SS_NCELLTYPES], total = 0;
  for (int t = 0; t < SS_NCELLTYPES; t++)
    n[t] = (double)cx->nc[t];
  for (long l = 0; l < levels; l++) {
    next_counts(n, m, bisect);
    memcpy(n, m, sizeof n);
  }
  for (int t = 0; t < SS_NCELLTYPES; t++)
    total += n[t];
  if (total <= 2e9) return 0;
  fprintf(stderr,
          "subspectra subdivide: %ld levels would make %s%.3g cells (the limit is 2e9); "
          "use fewer levels\n",
          levels, bisect ? "up to " : "", total);
  return SS_EXIT_USAGE;
}

/* The summary of the input: its level-0 counts and diagonals (dpairs pairs,
 * dbad improper, when the scheme reads them), as text on stdout, or as the
 * start of the JSON report *report (levels array *lv) with --format json. */
static void summary_start(const sub_opts *o, const ss_cx *cx, int reads_diag,
                          size_t dpairs, size_t dbad, json_object **report,
                          json_object **lv) {
  if (o->json) {
    *report = json_object_new_object();
    json_object_object_add(*report, "scheme", json_object_new_string(o->scheme));
    json_object_object_add(*report, "input", json_object_new_string(o->in));
    if (reads_diag) {
      json_object *d = json_object_new_object();
      json_object_object_add(d, "choice", json_object_new_string(o->diag));
      json_object_object_add(d, "pairs", json_object_new_int64((int64_t)dpairs));
      json_object_object_add(d, "improper", json_object_new_int64((int64_t)dbad));
      json_object_object_add(*report, "diagonals", d);
    }
    *lv = json_object_new_array();
    json_object_object_add(*report, "levels", *lv);
    json_object_array_add(*lv, level_json(0, cx, 0.0));
  } else {
    char what[64];
    snprintf(what, sizeof what, "read %s", o->in);
    level_text(o->sum, what, cx, -1);
    if (reads_diag)
      fprintf(
          o->sum,
          "major diagonals: %s; %zu of %zu adjacent pairs improper (Definition 3.2 as "
          "read in docs/schemes.md)\n",
          o->diag, dbad, dpairs);
  }
}

/* Refine *cx o->levels times with scheme, a summary line (or JSON entry in
 * lv) per level.  *cx is replaced by each finer level (the levels between are
 * freed, input never: it names the input vertices a non-finite coordinate
 * derives from).  0, or the exit status with the message printed. */
static int refine_levels(const sub_opts *o, const ss_scheme *scheme, const ss_cx *input,
                         ss_cx **cx, json_object *lv) {
  ss_error err = {0};
  for (long l = 1; l <= o->levels; l++) {
    double t0 = ss_cli_now();
    ss_cx *fine = NULL;
    size_t bad;
    if (ss_scheme_refine_at(scheme, *cx, &fine, &bad, &err)) {
      if (bad == SIZE_MAX) return ss_cli_fail("subdivide", &err);
      ss_scheme_explain_nonfinite(scheme, input, (int)l, bad, &err);
      fprintf(stderr, "subspectra subdivide: %s: %s; nothing written\n", o->in, err.msg);
      return SS_EXIT_USAGE;
    }
    if (*cx != input) ss_cx_free(*cx);
    *cx = fine;
    double dt = ss_cli_now() - t0;
    if (o->json) {
      json_object_array_add(lv, level_json((int)l, *cx, dt));
    } else {
      char what[32];
      snprintf(what, sizeof what, "%s level %ld", o->scheme, l);
      level_text(o->sum, what, *cx, dt);
    }
  }
  return SS_EXIT_OK;
}

/* The end of the summary, once OUT is written: the output file and its
 * format, as text or closing the JSON report. */
static void summary_end(const sub_opts *o, json_object *report) {
  const char *format = ss_mesh_format_name(o->ofmt);
  if (o->json) {
    json_object_object_add(report, "output", json_object_new_string(o->out));
    json_object_object_add(report, "format", json_object_new_string(format));
    fprintf(o->sum, "%s\n", json_object_to_json_string_ext(report, SS_CLI_JSON_FLAGS));
  } else {
    fprintf(o->sum, "wrote %s (%s)\n", o->out, format);
  }
}

/* --drop-unsupported: drop from cx the lower-dimensional cells the scheme
 * does not take, saying on stderr how many of which type. */
static void drop_unsupported(const sub_opts *o, const ss_scheme *scheme, ss_cx *cx) {
  size_t n[SS_NCELLTYPES];
  if (!ss_scheme_drop_lower(scheme, cx, n)) return;
  fprintf(stderr, "subspectra subdivide: %s: dropped", o->in);
  for (int t = 0, first = 1; t < SS_NCELLTYPES; t++)
    if (n[t]) {
      fprintf(stderr, "%s %zu %s", first ? "" : ",", n[t],
              n[t] == 1 ? ss_cell_name((ss_cell_type)t)
                        : ss_cell_plural((ss_cell_type)t));
      first = 0;
    }
  fprintf(stderr, " that scheme %s does not take (--drop-unsupported)\n", o->scheme);
}

/* --hexify: *cx made hexahedral by the hexify split (section 3.3), saying
 * on stderr what was split; 0 or the exit status with the message printed. */
static int hexify(const sub_opts *o, const ss_scheme *scheme, ss_cx **cx) {
  ss_error err = {0};
  if (ss_scheme_split_kind(scheme) != SS_SPLIT_MULTILINEAR)
    return ss_cli_usage_error(
        "subdivide",
        "--hexify: scheme %s is not hexahedral (it refines with the "
        "%s split)",
        o->scheme, ss_split_name(ss_scheme_split_kind(scheme)));
  if ((*cx)->nc[SS_OCT]) {
    fprintf(stderr,
            "subspectra subdivide: %s: --hexify: the mesh has %zu octahedra, whose "
            "vertices have valence 4: no split into hexahedra at the corners (MLCA "
            "paper, section 3.3); split them into tetrahedra first\n",
            o->in, (*cx)->nc[SS_OCT]);
    return SS_EXIT_USAGE;
  }
  ss_cx *h = NULL;
  ss_split *L = NULL;
  if (ss_split_refine(SS_SPLIT_HEXIFY, *cx, &h, &L, &err))
    return ss_cli_fail("subdivide", &err);
  ss_split_free(L);
  fprintf(stderr, "subspectra subdivide: %s: hexified (MLCA paper, section 3.3):", o->in);
  static const int each[SS_NCELLTYPES] = {1, 2, 3, 4, 4, 8, 0}; /* children per cell */
  for (int t = SS_SEGMENT, first = 1; t < SS_NCELLTYPES; t++) {
    const size_t n = (*cx)->nc[t];
    if (!n) continue;
    const ss_cell_type to = t == SS_TRIANGLE ? SS_QUAD : t == SS_TET ? SS_HEX : t;
    const size_t m = n * (size_t)each[t];
    fprintf(stderr, "%s %zu %s into %zu %s", first ? "" : ",", n,
            n == 1 ? ss_cell_name((ss_cell_type)t) : ss_cell_plural((ss_cell_type)t), m,
            m == 1 ? ss_cell_name(to) : ss_cell_plural(to));
    first = 0;
  }
  fputc('\n', stderr);
  ss_cx_free(*cx);
  *cx = h;
  return 0;
}

int ss_cli_subdivide(int argc, char **argv) {
  sub_opts o;
  int rc = parse(argc, argv, &o);
  if (rc) return rc < 0 ? SS_EXIT_OK : rc;

  ss_error err = {0};
  ss_scheme *scheme = NULL;
  ss_cx *cx = NULL, *input = NULL;
  json_object *report = NULL, *lv = NULL;
  if (ss_scheme_new(o.scheme, &scheme, &err) ||
      ss_mesh_read_fields(o.in, SS_MESH_AUTO, &cx, &o.names, &err)) {
    rc = ss_cli_fail("subdivide", &err);
    goto done;
  }
  if (o.bc && ss_scheme_set_loop_c(scheme, o.loop_c, &err)) {
    rc = ss_cli_usage_error("subdivide", "--boundary-c: %s", err.msg);
    goto done;
  }
  if (o.adaptive && ss_scheme_set_adapt(scheme, &o.adapt, &err)) {
    rc = ss_cli_usage_error(
        "subdivide", "--adapt-box/--adapt-edge-length/--adapt-curvature: %s", err.msg);
    goto done;
  }
  if (o.bnd && ss_scheme_set_boundary(scheme, o.boundary, &err)) {
    rc = ss_cli_usage_error("subdivide", "--boundary: %s", err.msg);
    goto done;
  }
  o.wopts.fields = &o.names;
  if (o.drop) drop_unsupported(&o, scheme, cx);
  if (ss_cx_check_orientation(cx, &err)) {
    fprintf(stderr, "subspectra subdivide: %s: %s\n", o.in, err.msg);
    rc = SS_EXIT_USAGE;
    goto done;
  }
  if (o.hexify && (rc = hexify(&o, scheme, &cx))) goto done;
  size_t dpairs = 0, dbad = 0;
  const int reads_diag = ss_scheme_reads_diagonals(scheme);
  if (o.diag && !reads_diag) {
    rc = ss_cli_usage_error("subdivide",
                            "--diagonals: scheme %s reads no major diagonals", o.scheme);
    goto done;
  }
  if (reads_diag) {
    if (!o.diag) o.diag = "bfs";
    if ((!o.given && ss_diag_choose(cx, o.dmode, 0, 0, &err)) ||
        ss_diag_improper(cx, &dpairs, &dbad, &err)) {
      rc = ss_cli_fail("subdivide", &err);
      goto done;
    }
  }
  if ((rc = check_size(scheme, cx, o.levels))) goto done;
  summary_start(&o, cx, reads_diag, dpairs, dbad, &report, &lv);
  input = cx; /* kept to name input vertices if a level overflows */
  if ((rc = refine_levels(&o, scheme, input, &cx, lv))) goto done;
  if (ss_mesh_write(o.out, o.ofmt, cx, &o.wopts, &err)) {
    rc = ss_cli_fail("subdivide", &err);
    goto done;
  }
  /* Medit has no octahedron: say that the file holds tets in their place */
  if (o.ofmt == SS_MESH_MEDIT && cx->nc[SS_OCT] && !o.wopts.octahedra_keyword)
    fprintf(stderr,
            "subspectra subdivide: %s: split %zu octahedra into %zu tetrahedra (Medit "
            "has no octahedron; --octahedra-keyword keeps them)\n",
            o.out, cx->nc[SS_OCT], 4 * cx->nc[SS_OCT]);
  summary_end(&o, report);
done:
  json_object_put(report);
  if (cx != input) ss_cx_free(input);
  ss_cx_free(cx);
  ss_scheme_free(scheme);
  return rc;
}
