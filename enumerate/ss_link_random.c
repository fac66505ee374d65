/* ss_link_random.c — random links from convex hulls of random sphere points. */
#include <stdlib.h>

#include <gsl/gsl_randist.h>

#include "ss_hull.h"
#include "ss_link_random.h"

ss_status ss_link_random(int k, gsl_rng *r, ss_link **out, ss_error *err) {
  *out = NULL;
  if (k < 4 || k > SS_LINK_MAXK)
    return ss_error_set(err, SS_EINPUT, "a random link needs 4..%d vertices, not %d",
                        SS_LINK_MAXK, k);
  if (!r) return ss_error_set(err, SS_EINPUT, "ss_link_random: no random generator");
  ss_status st = SS_OK;
  int *tri = NULL, ntri = 0;
  double *xyz = malloc((size_t)k * 3 * sizeof *xyz);
  if (!xyz) {
    st = ss_error_nomem(err, "random points");
    goto done;
  }
  for (int attempt = 1;; attempt++) {
    for (int i = 0; i < k; i++)
      gsl_ran_dir_3d(r, &xyz[3 * i], &xyz[3 * i + 1], &xyz[3 * i + 2]);
    ss_error herr = {0};
    st = ss_hull_sphere_triangles(k, xyz, &tri, &ntri, &herr);
    if (st == SS_OK) break;
    if (st != SS_EINPUT) {
      if (err) *err = herr;
      goto done;
    }
    if (attempt == SS_LINK_RANDOM_TRIES) {
      st = ss_error_set(err, SS_ENUMERIC,
                        "no simplicial hull of %d random sphere points in %d tries "
                        "(last: %s)",
                        k, attempt, herr.msg);
      goto done;
    }
  }
  ss_error lerr = {0};
  st = ss_link_from_triangles(k, ntri, tri, out, &lerr);
  if (st == SS_EINPUT) /* the hull was checked, so this is a bug */
    st = ss_error_set(err, SS_EINTERNAL, "random link: the hull is not a sphere: %s",
                      lerr.msg);
  else if (st != SS_OK && err)
    *err = lerr;
done:
  free(xyz);
  free(tri);
  return st;
}
