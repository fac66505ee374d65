/* ss_cli_enumerate_mesh.c — `subspectra enumerate mesh FILE`: the distinct
 * vertex links of a tetrahedral or hexahedral mesh with multiplicities, its
 * edge valences and the valence statistics of the box-spline paper's Table 1. */
#include <getopt.h>
#include <stdio.h>
#include <string.h>

#include <json-c/json.h>

#include "ss_cli.h"
#include "ss_mesh.h"
#include "ss_meshlinks.h"

static const char usage_text[] =
    "usage: subspectra enumerate mesh FILE [--format text|json]\n"
    "\n"
    "The vertex links (one-rings) of a tetrahedral or hexahedral mesh: how many\n"
    "vertices have each distinct link (canonical plantri ASCII, mirror images\n"
    "identified), the valences of its edges, and the statistics of the box-spline\n"
    "paper's Table 1: mean and largest vertex valence (edges at an interior vertex)\n"
    "and edge valence (cells around an interior edge).\n"
    "\n"
    "FILE is a volume mesh: Medit .mesh, gmsh .msh or TetGen .node/.ele\n"
    "(tetrahedra or hexahedra, not both; triangles, edges and corners in it are\n"
    "ignored).  A vertex is interior when its link is a\n"
    "triangulated sphere, boundary when its link has a boundary, non-manifold\n"
    "otherwise; an edge is interior when its cells close up around it.\n"
    "\n"
    "      --format F   text (default): a summary, the valence histograms and the\n"
    "                   links by multiplicity (count, k, link); or json: one object\n"
    "                   with keys cells, interior_vertices, boundary_vertices,\n"
    "                   vertex_valence {mean, max, histogram}, edge_valence {...},\n"
    "                   links [{count, vertices, link, example_vertex}], ...\n"
    "  -h, --help       this text\n"
    "\n"
    "Vertex numbers are 1-based, as in the file.  Malformed files, mixed or\n"
    "cell-less meshes and flat, folded or inverted cells are errors (exit status 2).\n";

/* Histogram entries h[0..len) that are nonzero, as {"n": count}. */
static json_object *hist_json(const size_t *h, int len) {
  json_object *o = json_object_new_object();
  for (int i = 0; i < len; i++)
    if (h[i]) {
      char key[16];
      snprintf(key, sizeof key, "%d", i);
      json_object_object_add(o, key, json_object_new_int64((int64_t)h[i]));
    }
  return o;
}

static json_object *valence_json(double mean, int max, const size_t *h) {
  json_object *o = json_object_new_object();
  json_object_object_add(o, "mean", json_object_new_double(mean));
  json_object_object_add(o, "max", json_object_new_int(max));
  json_object_object_add(o, "histogram", hist_json(h, max + 1));
  return o;
}

static void print_json(const char *path, const ss_meshlinks *ml) {
  json_object *r = json_object_new_object();
  json_object_object_add(r, "file", json_object_new_string(path));
  json_object_object_add(r, "cell_type",
                         json_object_new_string(ss_cell_name(ml->cell_type)));
  json_object_object_add(r, "vertices", json_object_new_int64((int64_t)ml->nv));
  json_object_object_add(r, "edges", json_object_new_int64((int64_t)ml->ne));
  json_object_object_add(r, "cells", json_object_new_int64((int64_t)ml->nc));
  static const char *const vkeys[] = {
      "interior_vertices", "boundary_vertices", "nonmanifold_vertices", "unused_vertices",
      "interior_edges",    "boundary_edges",    "nonmanifold_edges"};
  const size_t vals[] = {ml->nv_interior,   ml->nv_boundary, ml->nv_nonmanifold,
                         ml->nv_unused,     ml->ne_interior, ml->ne_boundary,
                         ml->ne_nonmanifold};
  for (size_t i = 0; i < sizeof vals / sizeof vals[0]; i++)
    json_object_object_add(r, vkeys[i], json_object_new_int64((int64_t)vals[i]));
  json_object_object_add(r, "vertex_valence",
                         valence_json(ml->vval_mean, ml->vval_max, ml->vval_hist));
  json_object_object_add(r, "edge_valence",
                         valence_json(ml->eval_mean, ml->eval_max, ml->eval_hist));
  json_object_object_add(r, "distinct_links", json_object_new_int64((int64_t)ml->nlinks));
  json_object *links = json_object_new_array();
  for (size_t i = 0; i < ml->nlinks; i++) {
    const ss_meshlink_class *c = &ml->links[i];
    json_object *o = json_object_new_object();
    json_object_object_add(o, "count", json_object_new_int64((int64_t)c->count));
    json_object_object_add(o, "vertices", json_object_new_int(c->k));
    json_object_object_add(o, "link", json_object_new_string(c->link));
    json_object_object_add(o, "example_vertex",
                           json_object_new_int64((int64_t)c->first_vertex + 1));
    json_object_array_add(links, o);
  }
  json_object_object_add(r, "links", links);
  json_object *nm = json_object_new_array();
  for (size_t i = 0; i < ml->nv_nonmanifold; i++)
    json_object_array_add(nm, json_object_new_int64((int64_t)ml->nonmanifold[i] + 1));
  json_object_object_add(r, "nonmanifold_vertex_list", nm);
  printf("%s\n", json_object_to_json_string_ext(r, SS_CLI_JSON_FLAGS));
  json_object_put(r);
}

static void print_hist(const char *title, const char *unit, const size_t *h, int len) {
  size_t total = 0;
  for (int i = 0; i < len; i++)
    total += h[i];
  printf("\n%s\n", title);
  if (!total) {
    printf("  (none)\n");
    return;
  }
  printf("  valence  %s\n", unit);
  for (int i = 0; i < len; i++)
    if (h[i]) printf("  %7d  %zu\n", i, h[i]);
}

/* "mean 13.95, max 23", or "none" when nothing was counted. */
static void print_valence(const char *what, size_t n, double mean, int max) {
  if (n)
    printf("%-46s mean %.2f, max %d\n", what, mean, max);
  else
    printf("%-46s none\n", what);
}

static void print_text(const char *path, const ss_meshlinks *ml) {
  printf("%s: %zu vertices, %zu edges, %zu %s\n", path, ml->nv, ml->ne, ml->nc,
         ml->nc == 1 ? ss_cell_name(ml->cell_type) : ss_cell_plural(ml->cell_type));
  printf("vertices: %zu interior, %zu boundary, %zu non-manifold, %zu unused\n",
         ml->nv_interior, ml->nv_boundary, ml->nv_nonmanifold, ml->nv_unused);
  printf("edges:    %zu interior, %zu boundary, %zu non-manifold\n", ml->ne_interior,
         ml->ne_boundary, ml->ne_nonmanifold);
  print_valence("vertex valence (edges at an interior vertex):", ml->nv_interior,
                ml->vval_mean, ml->vval_max);
  print_valence("edge valence (cells around an interior edge):", ml->ne_interior,
                ml->eval_mean, ml->eval_max);
  if (ml->nv_nonmanifold) {
    printf("non-manifold vertices:");
    for (size_t i = 0; i < ml->nv_nonmanifold && i < 20; i++)
      printf(" %zu", ml->nonmanifold[i] + 1);
    printf("%s\n", ml->nv_nonmanifold > 20 ? " ..." : "");
  }
  print_hist("edge valence histogram (interior edges)", "edges", ml->eval_hist,
             ml->eval_max + 1);
  print_hist("vertex valence histogram (interior vertices)", "vertices", ml->vval_hist,
             ml->vval_max + 1);
  printf("\n%zu distinct link%s of interior vertices, by multiplicity\n", ml->nlinks,
         ml->nlinks == 1 ? "" : "s");
  if (ml->nlinks) printf("  %8s  %4s  %s\n", "count", "k", "link");
  for (size_t i = 0; i < ml->nlinks; i++)
    printf("  %8zu  %4d  %s\n", ml->links[i].count, ml->links[i].k, ml->links[i].link);
}

int ss_cli_enumerate_mesh(int argc, char **argv) {
  static const struct option opts[] = {{"format", required_argument, NULL, 'F'},
                                       {"help", no_argument, NULL, 'h'},
                                       {NULL, 0, NULL, 0}};
  const char *cmd = "enumerate mesh";
  int json = 0;
  optind = 1;
  opterr = 0;
  int c;
  while ((c = getopt_long(argc, argv, ":h", opts, NULL)) != -1) {
    switch (c) {
    case 'F':
      if (ss_cli_format_option(cmd, optarg, &json)) return SS_EXIT_USAGE;
      break;
    case 'h':
      fputs(usage_text, stdout);
      return SS_EXIT_OK;
    default:
      return ss_cli_option_error(cmd, c, argv);
    }
  }
  if (optind + 1 != argc)
    return ss_cli_usage_error(cmd, optind == argc ? "no mesh file given"
                                                  : "more than one mesh file given");
  const char *path = argv[optind];

  ss_error err = {0};
  ss_cx *cx = NULL;
  ss_meshlinks *ml = NULL;
  int rc = SS_EXIT_OK;
  if (ss_mesh_read(path, SS_MESH_AUTO, &cx, &err)) {
    rc = ss_cli_fail(cmd, &err);
    goto done;
  }
  if (ss_cx_check_orientation(cx, &err) || ss_meshlinks_compute(cx, &ml, &err)) {
    fprintf(stderr, "subspectra %s: %s: %s\n", cmd, path, err.msg);
    rc =
        err.status == SS_ENOMEM || err.status == SS_EINPUT ? SS_EXIT_USAGE : SS_EXIT_FAIL;
    goto done;
  }
  if (json)
    print_json(path, ml);
  else
    print_text(path, ml);
done:
  ss_meshlinks_free(ml);
  ss_cx_free(cx);
  return rc;
}
