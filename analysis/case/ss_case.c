/* ss_case.c — cases: names, the 4-8 class, edge points, the star's cell
 * type and the star (ss_case.h). */
#include "ss_case.h"

#include <string.h>

#include <stdio.h>

const char *ss_case_name(ss_case_kind kind) {
  switch (kind) {
  case SS_CASE_VERTEX:
    return "vertex";
  case SS_CASE_EDGE:
    return "edge";
  case SS_CASE_FACE:
    return "face";
  case SS_CASE_SURFACE_VERTEX:
    return "surface-vertex";
  case SS_CASE_EDGE_POINT:
    return "edge-point";
  }
  return "?";
}

int ss_case_kind_parse(const char *name, ss_case_kind *out) {
  for (int i = 0; i < SS_NCASEKINDS; i++)
    if (!strcmp(name, ss_case_name((ss_case_kind)i))) {
      *out = (ss_case_kind)i;
      return 0;
    }
  return -1;
}

int ss_case_edge_point(const ss_scheme *s, const ss_link *l) {
  const int n = l->k - 2;
  if (ss_scheme_split_kind(s) != SS_SPLIT_MULTILINEAR || n < 3 || n == 4) return 0;
  for (int v = 0, poles = 0; v < l->k; v++) { /* cheap filter: degrees n, n, 4 ... */
    const int d = ss_link_deg(l, v);
    poles += d == n && n != 4;
    if (d != 4 && d != n) return 0;
    if (v == l->k - 1 && poles != 2) return 0;
  }
  char name[32];
  snprintf(name, sizeof name, "bipyramid:%d", n);
  ss_link *b = NULL;
  ss_error err = {0};
  if (ss_link_named(name, &b, &err)) return -1;
  const int iso = ss_link_isomorphic(l, b);
  ss_link_free(b);
  return iso < 0 ? -1 : iso ? n : 0;
}

int ss_case_class48(int n, int cls) {
  if (cls) return cls;
  return n >= 6 && n % 2 == 0 ? 8 : 4;
}

int ss_case_centre_level(ss_case_kind kind) {
  return kind == SS_CASE_EDGE ? 1 : kind == SS_CASE_FACE ? 2 : 0;
}

ss_status ss_case_cell(const ss_scheme *s, ss_case_kind kind, ss_cell_type *t,
                       ss_error *err) {
  const int ml = ss_scheme_split_kind(s) == SS_SPLIT_MULTILINEAR;
  switch (kind) {
  case SS_CASE_VERTEX:
  case SS_CASE_EDGE:
    *t = ml ? SS_HEX : SS_TET;
    break;
  case SS_CASE_FACE:
    if (ml)
      return ss_error_set(err, SS_EINPUT,
                          "scheme %s: the face case exists only for schemes with the "
                          "tet/oct split (two tets sharing a face)",
                          ss_scheme_name(s));
    *t = SS_TET;
    break;
  case SS_CASE_SURFACE_VERTEX:
    *t = ml ? SS_QUAD : SS_TRIANGLE;
    break;
  default:
    return ss_error_set(err, SS_EINPUT, "unknown case");
  }
  if (!ss_scheme_accepts(s, *t))
    return ss_error_set(
        err, SS_EINPUT,
        "scheme %s does not support the %s case: its star would be made of "
        "%s, which the scheme does not take",
        ss_scheme_name(s), ss_case_name(kind), ss_cell_plural(*t));
  return SS_OK;
}

ss_status ss_case_star(const ss_scheme *s, const ss_case *c, ss_star **out,
                       ss_error *err) {
  *out = NULL;
  ss_cell_type t =
      SS_HEX; /* set by ss_case_cell; initialised for -Wmaybe-uninitialized */
  ss_status st0 = ss_case_cell(s, c->kind, &t, err);
  if (st0) return st0;
  if (c->kind == SS_CASE_VERTEX && !c->link)
    return ss_error_set(err, SS_EINPUT, "the vertex case needs a link");
  /* a choice other than the default for a rule that reads none is refused:
   * on a tet star it would only relabel the star (its rcond, orientation and
   * the inf-norm profiles change, nothing the rule computes) */
  if (c->diag != SS_DIAG_BFS && !ss_scheme_reads_diagonals(s))
    return ss_error_set(err, SS_EINPUT,
                        "scheme %s does not read major diagonals: diagonals '%s' do not "
                        "apply to it",
                        ss_scheme_name(s), ss_diag_name(c->diag));
  if ((c->diag == SS_DIAG_SKEW || c->diag == SS_DIAG_CENTER) &&
      (c->kind != SS_CASE_EDGE || t != SS_TET))
    return ss_error_set(err, SS_EINPUT,
                        "major diagonals '%s' are defined around an edge: only for the "
                        "edge case of a tet star",
                        ss_diag_name(c->diag));
  ss_status st;
  switch (c->kind) {
  case SS_CASE_VERTEX:
    st = t == SS_HEX ? ss_star_hex_vertex(c->link, out, err)
                     : ss_star_tet_vertex(c->link, out, err);
    break;
  case SS_CASE_EDGE:
    st =
        t == SS_HEX ? ss_star_hex_edge(c->n, out, err) : ss_star_tet_edge(c->n, out, err);
    break;
  case SS_CASE_FACE:
    st = ss_star_tet_face(out, err);
    break;
  default:
    if (c->cls && ss_scheme_split_kind(s) != SS_SPLIT_BISECT)
      return ss_error_set(err, SS_EINPUT,
                          "scheme %s: a 4-8 vertex class exists only for quasi48",
                          ss_scheme_name(s));
    if (ss_scheme_split_kind(s) == SS_SPLIT_BISECT)
      return ss_star_tri48_vertex(c->n, ss_case_class48(c->n, c->cls), out, err);
    return t == SS_QUAD ? ss_star_quad_vertex(c->n, out, err)
                        : ss_star_tri_vertex(c->n, out, err);
  }
  /* tet stars carry their major diagonals in the tets' vertex order (the edge
   * star's edge is star vertices 0 and 1) */
  if (!st && t == SS_TET) st = ss_diag_choose((*out)->cx, c->diag, 0, 1, err);
  if (st) {
    ss_star_free(*out);
    *out = NULL;
  }
  return st;
}
