/* ss_inject.c — injectivity of a control net's piecewise-linear image
 * (ss_inject.h): the checks of the input, the boundary (facets of one cell
 * only), the PL pieces of every cell and the verdict.  The exact geometry
 * (winding number, overlaps) is the CGAL shim's (ss_inject_cgal.h). */
#include "ss_inject.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_inject_cgal.h"

/* Facets of each cell type as local corner indices, each oriented as the
 * boundary of a positive cell (ss_cx.h): triangles and quads counter-
 * clockwise seen from outside, segments with the cell on their left. */
static const int tri_facets[] = {0, 1, 1, 2, 2, 0};
static const int quad_facets[] = {0, 1, 1, 2, 2, 3, 3, 0};
static const int tet_facets[] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2};
/* one corner of each opposite pair (0,3), (1,4), (2,5); reversed when an odd
 * number of them is the second of its pair */
static const int oct_facets[] = {0, 1, 2, 3, 2, 1, 0, 2, 4, 0, 5, 1,
                                 3, 4, 2, 3, 1, 5, 0, 4, 5, 3, 5, 4};
/* bottom, top, then the sides y = 0, y = 1, x = 0, x = 1 of the unit cube
 * with corner k at ss_cube_corner_bits(3, k) */
static const int hex_facets[] = {0, 3, 2, 1, 4, 5, 6, 7, 0, 1, 5, 4,
                                 3, 7, 6, 2, 0, 4, 7, 3, 1, 2, 6, 5};

/* The facets of cell type t: count, corners per facet, the table. */
typedef struct {
  int n;        /* facets */
  int nv;       /* corners per facet: 2, 3 or 4 */
  const int *v; /* n * nv local corner indices */
} facet_table;

static facet_table facets_of(ss_cell_type t) {
  switch (t) {
  case SS_TRIANGLE:
    return (facet_table){3, 2, tri_facets};
  case SS_QUAD:
    return (facet_table){4, 2, quad_facets};
  case SS_TET:
    return (facet_table){4, 3, tet_facets};
  case SS_OCT:
    return (facet_table){8, 3, oct_facets};
  case SS_HEX:
    return (facet_table){6, 4, hex_facets};
  default:
    return (facet_table){0, 0, NULL};
  }
}

/* Centre points a cell adds to the PL image: hex 6 face centres and the
 * cell centre, octahedron and quad their centre, simplices none. */
static size_t extra_points(ss_cell_type t) {
  return t == SS_HEX ? 7 : (t == SS_OCT || t == SS_QUAD) ? 1 : 0;
}

/* PL pieces (tets in 3D, triangles in 2D) of a cell of type t. */
static size_t pieces_of(ss_cell_type t) {
  switch (t) {
  case SS_HEX:
    return 24;
  case SS_OCT:
    return 8;
  case SS_QUAD:
    return 4;
  default:
    return 1;
  }
}

/* One facet of one cell, named canonically: two cells hold the same facet iff
 * their keys are equal; sign tells the two orientations apart. */
typedef struct {
  size_t key[4]; /* triangle (m, s, t), m the smallest, s < t; quad (m, s, o,
                    t) the cycle from m with s < t; segment (a < b); unused
                    SIZE_MAX */
  int sign;      /* +1 if the cell runs through the facet in the key's order
                    (cyclically), -1 if against it */
  size_t cell;   /* the cell */
  int local;     /* the facet's index in the cell's table */
} facet_rec;

static int facet_cmp(const void *pa, const void *pb) {
  const facet_rec *a = pa, *b = pb;
  for (int i = 0; i < 4; i++)
    if (a->key[i] != b->key[i]) return a->key[i] < b->key[i] ? -1 : 1;
  return a->cell < b->cell ? -1 : a->cell > b->cell;
}

/* The canonical name of the facet with corner points v[0..nv). */
static void facet_key(const size_t *v, int nv, facet_rec *r) {
  int m = 0;
  for (int i = 1; i < nv; i++)
    if (v[i] < v[m]) m = i;
  for (int i = 0; i < 4; i++)
    r->key[i] = SIZE_MAX;
  if (nv == 2) {
    r->key[0] = v[m];
    r->key[1] = v[1 - m];
    r->sign = m == 0 ? 1 : -1;
    return;
  }
  const size_t s = v[(m + 1) % nv], t = v[(m + nv - 1) % nv];
  r->sign = s < t ? 1 : -1;
  r->key[0] = v[m];
  r->key[1] = s < t ? s : t;
  if (nv == 3) {
    r->key[2] = s < t ? t : s;
  } else {
    r->key[2] = v[(m + 2) % 4];
    r->key[3] = s < t ? t : s;
  }
}

/* The mean of points v[0..nv) of x, summed in increasing index order so that
 * every cell holding the same points gets the same doubles. */
static void mean_point(const double *x, int dim, const size_t *v, int nv, double *out) {
  size_t s[SS_MAXCELLVERTS];
  for (int i = 0; i < nv; i++) {
    size_t a = v[i];
    int j = i;
    for (; j > 0 && s[j - 1] > a; j--)
      s[j] = s[j - 1];
    s[j] = a;
  }
  for (int d = 0; d < dim; d++) {
    double sum = 0.0;
    for (int i = 0; i < nv; i++)
      sum += x[s[i] * (size_t)dim + (size_t)d];
    out[d] = sum / nv;
  }
}

/* Check the input; SS_EINPUT naming the first defect. */
static ss_status check_input(const double *x, int dim, size_t n,
                             const ss_cell_type *ctype, const size_t *corner,
                             size_t ncells, size_t centre, ss_error *err) {
  if (dim != 2 && dim != 3)
    return ss_error_set(err, SS_EINPUT,
                        "injectivity: the net has %d coordinates per point, not 2 or 3",
                        dim);
  if (!x || n == 0)
    return ss_error_set(err, SS_EINPUT, "injectivity: the net has no points");
  if (!ctype || !corner || ncells == 0)
    return ss_error_set(err, SS_EINPUT, "injectivity: the net has no cells");
  if (centre >= n)
    return ss_error_set(err, SS_EINPUT,
                        "injectivity: the centre is point %zu, out of range (%zu points)",
                        centre, n);
  int hex = 0, simplicial = 0;
  for (size_t c = 0; c < ncells; c++) {
    const ss_cell_type t = ctype[c];
    if ((int)t < 0 || t >= SS_NCELLTYPES)
      return ss_error_set(err, SS_EINPUT, "injectivity: cell %zu has no valid type (%d)",
                          c, (int)t);
    if (ss_cell_dim(t) != dim)
      return ss_error_set(err, SS_EINPUT,
                          "injectivity: cell %zu is a %s, a %d-dimensional cell in a net "
                          "of %d coordinates (cells of mixed dimension)",
                          c, ss_cell_name(t), ss_cell_dim(t), dim);
    hex |= t == SS_HEX;
    simplicial |= t == SS_TET || t == SS_OCT;
    if (hex && simplicial)
      return ss_error_set(
          err, SS_EINPUT,
          "injectivity: hexahedra mixed with tetrahedra or octahedra (cell "
          "%zu): a hexahedron's quad faces cannot match their triangles",
          c);
    const size_t *v = corner + c * SS_MAXCELLVERTS;
    for (int j = 0; j < ss_cell_nverts(t); j++) {
      if (v[j] >= n)
        return ss_error_set(
            err, SS_EINPUT,
            "injectivity: corner %d of cell %zu (a %s) is point %zu, out of "
            "range (%zu points)",
            j, c, ss_cell_name(t), v[j], n);
      for (int i = 0; i < j; i++)
        if (v[i] == v[j])
          return ss_error_set(
              err, SS_EINPUT,
              "injectivity: corners %d and %d of cell %zu are both point %zu", i, j, c,
              v[j]);
      for (int d = 0; d < dim; d++)
        if (!isfinite(x[v[j] * (size_t)dim + (size_t)d]))
          return ss_error_set(
              err, SS_EINPUT,
              "injectivity: point %zu has a coordinate that is not finite", v[j]);
    }
  }
  for (int d = 0; d < dim; d++)
    if (!isfinite(x[centre * (size_t)dim + (size_t)d]))
      return ss_error_set(
          err, SS_EINPUT,
          "injectivity: the centre, point %zu, has a coordinate that is not "
          "finite",
          centre);
  return SS_OK;
}

/* Match the facets of all cells: *bnd (malloc'd) receives the facets held by
 * one cell only, *nbnd their number.  SS_EINPUT for a facet of three or more
 * cells, or of two cells that run through it the same way. */
static ss_status boundary_facets(int dim, const ss_cell_type *ctype, const size_t *corner,
                                 size_t ncells, facet_rec **bnd, size_t *nbnd,
                                 ss_error *err) {
  ss_status st = SS_OK;
  size_t nf = 0, nb = 0;
  for (size_t c = 0; c < ncells; c++)
    nf += (size_t)facets_of(ctype[c]).n;
  facet_rec *f = malloc(nf * sizeof *f);
  facet_rec *b = NULL;
  if (!f) {
    st = ss_error_nomem(err, "injectivity: facets");
    goto done;
  }
  size_t k = 0;
  for (size_t c = 0; c < ncells; c++) {
    const facet_table ft = facets_of(ctype[c]);
    const size_t *v = corner + c * SS_MAXCELLVERTS;
    for (int i = 0; i < ft.n; i++, k++) {
      size_t w[4];
      for (int j = 0; j < ft.nv; j++)
        w[j] = v[ft.v[i * ft.nv + j]];
      facet_key(w, ft.nv, &f[k]);
      f[k].cell = c;
      f[k].local = i;
    }
  }
  qsort(f, nf, sizeof *f, facet_cmp);
  b = malloc((nf ? nf : 1) * sizeof *b);
  if (!b) {
    st = ss_error_nomem(err, "injectivity: boundary facets");
    goto done;
  }
  const char *what = dim == 3 ? "face" : "edge";
  for (size_t i = 0, j; i < nf; i = j) {
    for (j = i + 1; j < nf && !memcmp(f[j].key, f[i].key, sizeof f[i].key); j++)
      ;
    if (j - i == 1) {
      b[nb++] = f[i];
    } else if (j - i > 2) {
      st =
          ss_error_set(err, SS_EINPUT,
                       "injectivity: a %s of cell %zu (through point %zu) belongs to %zu "
                       "cells; at most two may share one",
                       what, f[i].cell, f[i].key[0], j - i);
      goto done;
    } else if (f[i].sign == f[i + 1].sign) {
      st = ss_error_set(
          err, SS_EINPUT,
          "injectivity: cells %zu and %zu run through their common %s (through "
          "point %zu) the same way: the cells are not consistently ordered",
          f[i].cell, f[i + 1].cell, what, f[i].key[0]);
      goto done;
    }
  }
done:
  free(f);
  if (st != SS_OK) {
    free(b);
    b = NULL;
    nb = 0;
  }
  *bnd = b;
  *nbnd = nb;
  return st;
}

/* The PL image: xe gets the n points of x, then each cell's centre points
 * (extra[c] the first of cell c); cell c's pieces are piece[(dim + 1) s ..]
 * for s in [first[c], first[c + 1]). */
static void pl_pieces(const double *x, int dim, size_t n, const ss_cell_type *ctype,
                      const size_t *corner, size_t ncells, double *xe, size_t *first,
                      size_t *piece, size_t *extra) {
  const size_t D = (size_t)dim;
  memcpy(xe, x, n * D * sizeof *xe);
  size_t e = n, s = 0;
  for (size_t c = 0; c < ncells; c++) {
    const ss_cell_type t = ctype[c];
    const size_t *v = corner + c * SS_MAXCELLVERTS;
    const facet_table ft = facets_of(t);
    size_t *p = piece + s * (D + 1);
    extra[c] = e;
    first[c] = s;
    if (t == SS_HEX) {
      /* face centres e + f, cell centre e + 6; 4 tets per face */
      for (int f = 0; f < 6; f++) {
        size_t w[4];
        for (int j = 0; j < 4; j++)
          w[j] = v[ft.v[4 * f + j]];
        mean_point(x, dim, w, 4, xe + (e + (size_t)f) * D);
        for (int j = 0; j < 4; j++, p += 4) {
          p[0] = w[j], p[1] = w[(j + 1) % 4];
          p[2] = e + (size_t)f, p[3] = e + 6;
        }
      }
      mean_point(x, dim, v, 8, xe + (e + 6) * D);
    } else if (t == SS_OCT) {
      mean_point(x, dim, v, 6, xe + e * D);
      for (int f = 0; f < 8; f++, p += 4) {
        for (int j = 0; j < 3; j++)
          p[j] = v[ft.v[3 * f + j]];
        p[3] = e;
      }
    } else if (t == SS_QUAD) {
      mean_point(x, dim, v, 4, xe + e * D);
      for (int j = 0; j < 4; j++, p += 3) {
        p[0] = v[j], p[1] = v[(j + 1) % 4], p[2] = e;
      }
    } else {
      for (int j = 0; j <= dim; j++)
        p[j] = v[j];
    }
    e += extra_points(t);
    s += pieces_of(t);
  }
  first[ncells] = s;
}

/* The boundary as PL facets bf[dim f ..] (a hex face as 4 triangles at its
 * centre point), oriented as their cells run through them; returns their
 * number. */
static size_t pl_boundary(int dim, const ss_cell_type *ctype, const size_t *corner,
                          const facet_rec *bnd, size_t nbnd, const size_t *extra,
                          size_t *bf) {
  const size_t D = (size_t)dim;
  size_t nbf = 0;
  for (size_t i = 0; i < nbnd; i++) {
    const size_t c = bnd[i].cell;
    const facet_table ft = facets_of(ctype[c]);
    const size_t *v = corner + c * SS_MAXCELLVERTS;
    const int *lv = ft.v + bnd[i].local * ft.nv;
    if (ft.nv == 4) {
      const size_t m = extra[c] + (size_t)bnd[i].local;
      for (int j = 0; j < 4; j++, nbf++) {
        bf[3 * nbf] = v[lv[j]];
        bf[3 * nbf + 1] = v[lv[(j + 1) % 4]];
        bf[3 * nbf + 2] = m;
      }
    } else {
      for (int j = 0; j < ft.nv; j++)
        bf[D * nbf + (size_t)j] = v[lv[j]];
      nbf++;
    }
  }
  return nbf;
}

/* The verdict from the degree and the overlaps. */
static void judge(ss_wind_kind kind, ss_injectivity *out) {
  char *r = out->verdict.reason;
  const size_t len = sizeof out->verdict.reason;
  const int deg_bad = kind == SS_WIND_OK && out->degree != 1 && out->degree != -1;
  r[0] = '\0';
  if (deg_bad || out->overlaps > 0) {
    out->verdict.verdict = SS_FAIL;
    size_t k = 0;
    if (deg_bad)
      k += (size_t)snprintf(r, len,
                            "the boundary image winds %d times about the centre's image "
                            "(degree %d, not +-1)",
                            out->degree, out->degree);
    if (out->overlaps > 0 && k < len)
      snprintf(
          r + k, len - k,
          "%s%zu pair%s of cells sharing no corner overlap%s (e.g. cells %zu and %zu)",
          k ? "; " : "", out->overlaps, out->overlaps == 1 ? "" : "s",
          out->overlaps == 1 ? "s" : "", out->first[0], out->first[1]);
  } else if (kind == SS_WIND_ON_BOUNDARY) {
    out->verdict.verdict = SS_UNDECIDED;
    snprintf(r, len, "the centre's image lies on the boundary image: no degree");
  } else if (kind == SS_WIND_NO_RAY) {
    out->verdict.verdict = SS_UNDECIDED;
    snprintf(r, len,
             "every ray tried from the centre's image met an edge or vertex of the "
             "boundary image");
  } else {
    out->verdict.verdict = SS_PASS;
  }
}

ss_status ss_inject_test(const double *x, int dim, size_t n, const ss_cell_type *ctype,
                         const size_t *corner, size_t ncells, size_t centre,
                         ss_injectivity *out, ss_error *err) {
  return ss_inject_test_parts(x, dim, n, ctype, corner, ncells, centre,
                              SS_INJECT_DEGREE | SS_INJECT_OVERLAPS, out, err);
}

ss_status ss_inject_test_parts(const double *x, int dim, size_t n,
                               const ss_cell_type *ctype, const size_t *corner,
                               size_t ncells, size_t centre, int parts,
                               ss_injectivity *out, ss_error *err) {
  facet_rec *bnd = NULL; /* the boundary facets */
  double *xe = NULL;     /* the points of the PL image */
  size_t *first = NULL, *piece = NULL, *bf = NULL, *extra = NULL;
  size_t nbnd = 0;
  if (!out) return ss_error_set(err, SS_EINPUT, "injectivity: no result to fill");
  memset(out, 0, sizeof *out);
  out->first[0] = out->first[1] = SIZE_MAX;
  out->verdict.verdict = SS_UNDECIDED;
  ss_status st = (parts & (SS_INJECT_DEGREE | SS_INJECT_OVERLAPS))
                     ? check_input(x, dim, n, ctype, corner, ncells, centre, err)
                     : ss_error_set(err, SS_EINPUT, "injectivity: no part asked for");
  if (st != SS_OK) goto done;
  st = boundary_facets(dim, ctype, corner, ncells, &bnd, &nbnd, err);
  if (st != SS_OK) goto done;

  /* The points of the PL image: the net, then each cell's centre points. */
  const size_t D = (size_t)dim;
  size_t ne = n, npiece = 0;
  for (size_t c = 0; c < ncells; c++) {
    ne += extra_points(ctype[c]);
    npiece += pieces_of(ctype[c]);
  }
  xe = malloc(ne * D * sizeof *xe);
  first = malloc((ncells + 1) * sizeof *first);
  piece = malloc(npiece * (D + 1) * sizeof *piece);
  /* each boundary facet gives at most 4 PL triangles (a hex face) */
  bf = malloc((nbnd ? 4 * nbnd : 1) * D * sizeof *bf);
  extra = malloc(ncells * sizeof *extra); /* the first centre point of each cell */
  if (!xe || !first || !piece || !bf || !extra) {
    st = ss_error_nomem(err, "injectivity: the PL image");
    goto done;
  }
  pl_pieces(x, dim, n, ctype, corner, ncells, xe, first, piece, extra);
  const size_t nbf = pl_boundary(dim, ctype, corner, bnd, nbnd, extra, bf);
  out->boundary = nbnd;

  ss_wind_kind kind = SS_WIND_NO_RAY; /* a degree not asked for is undecided */
  int w = 0;
  if (parts & SS_INJECT_DEGREE) {
    st = ss_inject_cgal_winding(dim, xe, nbf, bf, centre, &kind, &w, err);
    if (st != SS_OK) goto done;
  }
  out->degree = kind == SS_WIND_OK ? w : 0;
  if (parts & SS_INJECT_OVERLAPS) {
    st = ss_inject_cgal_overlaps(dim, xe, ncells, corner, SS_MAXCELLVERTS, first, piece,
                                 &out->overlaps, out->first, err);
    if (st != SS_OK) goto done;
  }
  judge(kind, out);
done:
  if (st != SS_OK) {
    memset(out, 0, sizeof *out);
    out->first[0] = out->first[1] = SIZE_MAX;
    out->verdict.verdict = SS_UNDECIDED;
  }
  free(bnd);
  free(xe);
  free(first);
  free(piece);
  free(bf);
  free(extra);
  return st;
}
