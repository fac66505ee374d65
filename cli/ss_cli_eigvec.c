/* ss_cli_eigvec.c — eigenvectors and limit masks as JSON and Matrix Market
 * (ss_cli_eigvec.h). */
#include "ss_cli_eigvec.h"

#include <stdint.h>
#include <stdio.h>
#include <string.h>

void ss_cli_label_text(const ss_star_coord *c, char *buf, size_t n) {
  size_t used = 0;
  int w = snprintf(buf, n, "(");
  for (int i = 0; i < c->n && w >= 0 && (used += (size_t)w) < n; i++)
    w = snprintf(buf + used, n - used, "%s%d:%d", i ? " " : "", c->idx[i], c->val[i]);
  if (w >= 0 && (used += (size_t)w) < n) snprintf(buf + used, n - used, ")");
}

/* column j of an n x k column-major array as a JSON array */
static json_object *column(const double *X, size_t n, int j) {
  json_object *a = json_object_new_array();
  for (size_t i = 0; i < n; i++)
    json_object_array_add(a, json_object_new_double(X[i + (size_t)j * n]));
  return a;
}

static json_object *columns(const double *X, size_t n, int j0, int j1) {
  json_object *a = json_object_new_array();
  for (int j = j0; j < j1; j++)
    json_object_array_add(a, column(X, n, j));
  return a;
}

json_object *ss_cli_eigvec_json(const ss_eigvec *v, const ss_local *M, int dim,
                                int masks_ok, const char *why_not) {
  json_object *r = json_object_new_object();
  if (!r) return NULL;
  json_object_object_add(r, "k", json_object_new_int(v->k));
  json_object_object_add(
      r, "normalisation",
      json_object_new_string("right: maximum modulus 1, that entry real and positive; "
                             "left: L^T R = I within each group of equal eigenvalues "
                             "(l^T S = lambda l^T, no conjugation)"));
  json_object *pts = json_object_new_array();
  char buf[256];
  for (size_t i = 0; i < v->n; i++) {
    ss_cli_label_text(M->label + i, buf, sizeof buf);
    json_object_array_add(pts, json_object_new_string(buf));
  }
  json_object_object_add(r, "points", pts);
  json_object *vals = json_object_new_array();
  for (int j = 0; j < v->k; j++) {
    json_object *x = json_object_new_object();
    json_object_object_add(x, "re", json_object_new_double(v->re[j]));
    json_object_object_add(x, "im", json_object_new_double(v->im[j]));
    json_object_object_add(x, "group", json_object_new_int(v->group[j]));
    json_object_object_add(x, "biorthonormal", json_object_new_boolean(v->biorth[j]));
    json_object_array_add(vals, x);
  }
  json_object_object_add(r, "eigenvalues", vals);
  json_object_object_add(r, "right", columns(v->right_re, v->n, 0, v->k));
  json_object_object_add(r, "left", columns(v->left_re, v->n, 0, v->k));
  if (v->complex_any) {
    json_object_object_add(r, "right_im", columns(v->right_im, v->n, 0, v->k));
    json_object_object_add(r, "left_im", columns(v->left_im, v->n, 0, v->k));
  }
  if (masks_ok && v->k > dim) {
    json_object *m = json_object_new_object();
    json_object_object_add(m, "position", column(v->left_re, v->n, 0));
    json_object_object_add(m, "tangent", columns(v->left_re, v->n, 1, dim + 1));
    json_object_object_add(r, "limit_masks", m);
  } else {
    json_object_object_add(r, "limit_masks", NULL);
    char need[64];
    snprintf(need, sizeof need, "the masks need --eigenvectors %d or more", dim + 1);
    json_object_object_add(r, "limit_masks_reason",
                           json_object_new_string(masks_ok ? need : why_not));
  }
  return r;
}
