/* ss_star_embed.c — a geodesic embedding of a link on the unit sphere.
 *
 * Remove a vertex w of maximum degree: what is left is a triangulated disk
 * whose boundary is the cycle of w's neighbours.  Put that cycle on a regular
 * polygon and every other vertex at the mean of its neighbours (Tutte's
 * barycentric embedding; a sparse symmetric positive definite system, solved
 * by conjugate gradients).  For a disk with a strictly convex boundary this
 * map is one-to-one (Floater 2003), so every triangle keeps one orientation.
 * Lifting the plane to z = 1 (scaled by R) and projecting centrally onto the
 * sphere keeps the sign of each triangle's determinant, and w at the south
 * pole closes the sphere: its triangles (w, n_i, n_i+1) get the same sign as
 * the disk's.  R is chosen so the points' mean height is near 0. */
#include "ss_star.h"

#include <math.h>
#include <stdlib.h>

#include "ss_dense.h"

#define PI 3.14159265358979323846

/* y = A x for the Tutte system restricted to interior vertices: row of
 * interior vertex a is deg(a) x_a - sum of its interior neighbours. */
static void tutte_apply(const ss_link *l, const int *in, const int *ivert, int m,
                        const double *x, double *y) {
  for (int i = 0; i < m; i++) {
    int a = ivert[i];
    double s = (double)ss_link_deg(l, a) * x[i];
    for (int j = l->off[a]; j < l->off[a + 1]; j++)
      if (in[l->nbr[j]] >= 0) s -= x[in[l->nbr[j]]];
    y[i] = s;
  }
}

/* Solve A x = b by conjugate gradients from x = 0; r, p, q are scratch of
 * size m.  Returns the number of iterations used. */
static int tutte_cg(const ss_link *l, const int *in, const int *ivert, int m,
                    const double *b, double *x, double *r, double *p, double *q) {
  double bb = 0.0;
  for (int i = 0; i < m; i++) {
    x[i] = 0.0;
    r[i] = p[i] = b[i];
    bb += b[i] * b[i];
  }
  double rr = bb;
  const double tol = 1e-30 * (bb > 0.0 ? bb : 1.0);
  int it = 0;
  for (const int maxit = 10 * m + 100; it < maxit && rr > tol; it++) {
    tutte_apply(l, in, ivert, m, p, q);
    double pq = 0.0;
    for (int i = 0; i < m; i++)
      pq += p[i] * q[i];
    if (!(pq > 0.0)) break;
    double alpha = rr / pq, rr2 = 0.0;
    for (int i = 0; i < m; i++) {
      x[i] += alpha * p[i];
      r[i] -= alpha * q[i];
      rr2 += r[i] * r[i];
    }
    double beta = rr2 / rr;
    rr = rr2;
    for (int i = 0; i < m; i++)
      p[i] = r[i] + beta * p[i];
  }
  return it;
}

ss_status ss_star_link_embed(const ss_link *l, double *x, ss_error *err) {
  const int k = l->k;
  ss_status st = SS_OK;
  int *in = malloc((size_t)k * sizeof *in); /* interior index of a vertex, or -1 */
  int *ivert = malloc((size_t)k * sizeof *ivert);
  double *pl = malloc((size_t)k * 2 * sizeof *pl); /* planar positions */
  double *work = malloc((size_t)k * 6 * sizeof *work);
  int *tri = NULL, ntri = 0;
  if (!in || !ivert || !pl || !work) {
    st = ss_error_nomem(err, "link embedding");
    goto done;
  }
  /* w: the lowest-numbered vertex of maximum degree; its neighbours, in
   * rotation order, go on the polygon clockwise (see the sign check below) */
  int w = 0;
  for (int a = 1; a < k; a++)
    if (ss_link_deg(l, a) > ss_link_deg(l, w)) w = a;
  const int d = ss_link_deg(l, w);
  for (int a = 0; a < k; a++)
    in[a] = 0;
  in[w] = -1;
  for (int i = 0; i < d; i++) {
    int b = l->nbr[l->off[w] + i];
    in[b] = -1;
    pl[2 * b] = cos(2.0 * PI * i / d);
    pl[2 * b + 1] = -sin(2.0 * PI * i / d);
  }
  pl[2 * w] = pl[2 * w + 1] = 0.0;
  int m = 0;
  for (int a = 0; a < k; a++)
    if (in[a] == 0) {
      in[a] = m;
      ivert[m++] = a;
    }
  /* right-hand sides: the fixed (boundary) neighbours of each interior vertex */
  double *bx = work, *by = work + k, *sol = work + 2 * k, *r = work + 3 * k,
         *p = work + 4 * k, *q = work + 5 * k;
  for (int i = 0; i < m; i++) {
    int a = ivert[i];
    bx[i] = by[i] = 0.0;
    for (int j = l->off[a]; j < l->off[a + 1]; j++)
      if (in[l->nbr[j]] < 0) {
        bx[i] += pl[2 * l->nbr[j]];
        by[i] += pl[2 * l->nbr[j] + 1];
      }
  }
  for (int c = 0; c < 2; c++) {
    tutte_cg(l, in, ivert, m, c ? by : bx, sol, r, p, q);
    for (int i = 0; i < m; i++)
      pl[2 * ivert[i] + c] = sol[i];
  }
  /* lift: R chosen by bisection so that the mean height is about 0 (the
   * height falls as R grows), within [1/2, 8] to keep triangles well shaped */
  double lo = 0.5, hi = 8.0;
  for (int it = 0; it < 40; it++) {
    double R = 0.5 * (lo + hi), zsum = -1.0;
    for (int a = 0; a < k; a++)
      if (a != w) {
        double rx = R * pl[2 * a], ry = R * pl[2 * a + 1];
        zsum += 1.0 / sqrt(rx * rx + ry * ry + 1.0);
      }
    if (zsum > 0.0)
      lo = R;
    else
      hi = R;
  }
  const double R = 0.5 * (lo + hi);
  for (int a = 0; a < k; a++) {
    double *xa = x + 3 * a;
    if (a == w) {
      xa[0] = xa[1] = 0.0;
      xa[2] = -1.0;
      continue;
    }
    xa[0] = R * pl[2 * a];
    xa[1] = R * pl[2 * a + 1];
    xa[2] = 1.0;
    double n = sqrt(xa[0] * xa[0] + xa[1] * xa[1] + 1.0);
    for (int c = 0; c < 3; c++)
      xa[c] /= n;
  }
  /* every triangle as ss_link_triangles orients it must be positive; all share
   * one sign in exact arithmetic, so mirror if the first is negative */
  if ((st = ss_link_triangles(l, &tri, &ntri, err))) goto done;
  for (int pass = 0; pass < 2; pass++) {
    int npos = 0;
    for (int t = 0; t < ntri; t++)
      npos += ss_dense_det3(x + 3 * tri[3 * t], x + 3 * tri[3 * t + 1],
                            x + 3 * tri[3 * t + 2]) > 0.0;
    if (npos == ntri) break;
    if (pass == 0 && npos == 0) {
      for (int a = 0; a < k; a++)
        x[3 * a + 1] = -x[3 * a + 1];
      continue;
    }
    st = ss_error_set(err, SS_ENUMERIC,
                      "link embedding: %d of %d triangles not positively oriented "
                      "(rounding in the Tutte embedding)",
                      ntri - npos, ntri);
    goto done;
  }
done:
  free(tri);
  free(in);
  free(ivert);
  free(pl);
  free(work);
  return st;
}
