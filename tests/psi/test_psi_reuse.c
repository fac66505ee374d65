/* test_psi_reuse.c — psi's pieces and the spokes' transitions from one
 * refinement per patch (ss_lim_refine + ss_lim_cut) and the canonical frame
 * found with walks stopped early are what the full computation gives
 * (issue 37: psi's traversal refined a box's patch again for each child, the
 * spokes' transitions refined a state's patch again per child and walked all
 * 48 frames in full).
 *
 * On MLCA vertex cases (a k = 13 link whose psi passes on its pieces, the
 * octahedron, a k = 7 link), their two-ring as a limit evaluator:
 *   - every child (0..7, inherited and canonical frame) of the patches of the
 *     cells around p and of their irregular children, cut from one shared
 *     refinement, equals ss_lim_step's (a fresh refinement per child): cells,
 *     points, keys, crease keys, sources, regularity, frame, rows W, bit for
 *     bit;
 *   - the canonical frame (ss_lim_patch_canonical, walks stopped once their
 *     key is above the best) equals a full scan done here: all 48 frames
 *     walked in full by ss_lim_patch_build, the smallest key then crease key,
 *     the first among equals;
 *   - the pieces ss_limit_pieces visits on the ring (box depth 2) equal the
 *     boxes reached here the old way, each child by ss_lim_step from its
 *     parent: the same boxes in the same order, the same 64 points.
 * Mutations this catches (tried by hand, 2026-12-06): the early stop at c >= 0
 * instead of c > 0 (a tie stops the walk: 134 of 2585 checks fail); a walk
 * stopped early that leaves its scratch loc numbered (the next child cut
 * from the same refinement numbered wrong: 1036 fail).  About 2 s. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "psi_case.h"
#include "ss_limit_impl.h"
#include "ss_limit_pieces.h"
#include "ss_test.h"

/* Whether two patches are the same, field by field. */
static int same_patch(const ss_lim_patch *a, const ss_lim_patch *b) {
  if (a->ncells != b->ncells || a->nv != b->nv || a->ncrease != b->ncrease ||
      a->regular != b->regular || a->posbad != b->posbad)
    return 0;
  if (memcmp(a->key, b->key, a->ncells * 8 * sizeof *a->key) ||
      memcmp(a->src, b->src, a->nv * sizeof *a->src) ||
      memcmp(a->pos, b->pos, a->nv * sizeof *a->pos))
    return 0;
  if (a->ncrease &&
      memcmp(a->ckey, b->ckey, a->ncrease * SS_LIM_CREASE_W * sizeof *a->ckey))
    return 0;
  return !a->regular || !memcmp(a->net, b->net, sizeof a->net);
}

static int same_frame(const ss_lim_frame *g, const ss_lim_frame *h) {
  return !memcmp(g->perm, h->perm, sizeof g->perm) &&
         !memcmp(g->flip, h->flip, sizeof g->flip);
}

/* The canonical frame by a full scan: every frame walked in full. */
static int full_canonical(const ss_lim_adj *a, size_t t, int64_t *loc, ss_lim_patch *out,
                          ss_lim_frame *g) {
  static const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2},
                                  {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  ss_error err = {0};
  memset(out, 0, sizeof *out);
  for (int p = 0; p < 6; p++)
    for (int f = 0; f < 8; f++) {
      ss_lim_frame h;
      for (int d = 0; d < 3; d++) {
        h.perm[d] = perms[p][d];
        h.flip[d] = (f >> d) & 1;
      }
      ss_lim_patch c;
      if (ss_lim_patch_build(a, t, &h, loc, &c, &err)) return -1;
      int better = out->key == NULL;
      if (!better) {
        int cmp = memcmp(c.key, out->key, c.ncells * 8 * sizeof *c.key);
        if (!cmp && c.ncrease)
          cmp = memcmp(c.ckey, out->ckey, c.ncrease * SS_LIM_CREASE_W * sizeof *c.ckey);
        better = cmp < 0;
      }
      if (better) {
        ss_lim_patch_free(out);
        *out = c;
        *g = h;
      } else {
        ss_lim_patch_free(&c);
      }
    }
  return 0;
}

/* The children of patch complex pcx cut from one refinement against
 * ss_lim_step's; recursing into irregular children down to `levels`. */
static void check_children(const ss_scheme *s, const ss_cx *pcx, int levels,
                           const char *what, size_t *ncut) {
  ss_error err = {0};
  ss_lim_refined r;
  REQUIRE_OK_VOID(ss_lim_refine(s, pcx, 1, &r, &err), &err);
  for (int k = 0; k < 8; k++)
    for (int canonical = 0; canonical < 2; canonical++) {
      ss_lim_patch a, b;
      ss_lim_frame ga, gb;
      ss_cx *ca = NULL, *cb = NULL;
      double *Wa = NULL, *Wb = NULL;
      REQUIRE_OK_VOID(ss_lim_cut(&r, k, canonical, &a, &ga, &ca, &Wa, &err), &err);
      REQUIRE_OK_VOID(ss_lim_step(s, pcx, k, canonical, &b, &gb, &cb, &Wb, &err), &err);
      ++*ncut;
      CHECK(same_patch(&a, &b) && same_frame(&ga, &gb),
            "%s: child %d (%s frame) cut from the shared refinement differs from "
            "ss_lim_step's",
            what, k, canonical ? "canonical" : "inherited");
      CHECK(a.nv == b.nv && !memcmp(Wa, Wb, a.nv * pcx->nv * sizeof *Wa),
            "%s: child %d's rows differ", what, k);
      if (canonical) {
        ss_lim_patch f;
        ss_lim_frame gf;
        CHECK(!full_canonical(&r.fa, (size_t)k, r.loc, &f, &gf), "%s: full scan", what);
        CHECK(same_patch(&a, &f) && same_frame(&ga, &gf),
              "%s: child %d's canonical frame differs from the full scan's", what, k);
        ss_lim_patch_free(&f);
      } else if (levels > 1 && !a.regular) {
        check_children(s, ca, levels - 1, what, ncut);
      }
      ss_lim_patch_free(&a);
      ss_lim_patch_free(&b);
      ss_cx_free(ca);
      ss_cx_free(cb);
      free(Wa);
      free(Wb);
    }
  ss_lim_refined_free(&r);
}

/* A box reached by either traversal. */
typedef struct {
  size_t n, cap;
  size_t *cell;
  int *depth;
  double (*origin)[3];
  double (*net)[64][3]; /* zero for a box left uncovered */
} boxes;

static int add_box(boxes *b, size_t cell, int depth, const double o[3],
                   const double (*net)[3]) {
  if (b->n == b->cap) {
    b->cap = b->cap ? 2 * b->cap : 64;
    b->cell = realloc(b->cell, b->cap * sizeof *b->cell);
    b->depth = realloc(b->depth, b->cap * sizeof *b->depth);
    b->origin = realloc(b->origin, b->cap * sizeof *b->origin);
    b->net = realloc(b->net, b->cap * sizeof *b->net);
    if (!b->cell || !b->depth || !b->origin || !b->net) return 1;
  }
  b->cell[b->n] = cell;
  b->depth[b->n] = depth;
  memcpy(b->origin[b->n], o, sizeof b->origin[b->n]);
  if (net)
    memcpy(b->net[b->n], net, sizeof b->net[b->n]);
  else
    memset(b->net[b->n], 0, sizeof b->net[b->n]);
  b->n++;
  return 0;
}

static int visit(const ss_limit_piece *pc, void *arg) {
  return add_box(arg, pc->cell, pc->depth, pc->origin, pc->net);
}

/* The old traversal: every child by ss_lim_step from its parent's patch. */
static void old_box(const ss_scheme *s, size_t cell, ss_lim_patch *p, ss_cx *pcx,
                    int depth, const double o[3], int maxdepth, boxes *out) {
  ss_error err = {0};
  if (p->regular) {
    double net[64][3];
    const double *x0 = pcx->x + 3 * (size_t)p->net[21];
    for (int q = 0; q < 64; q++)
      for (int d = 0; d < 3; d++)
        net[q][d] = pcx->x[3 * (size_t)p->net[q] + (size_t)d] - x0[d];
    add_box(out, cell, depth, o, (const double(*)[3])net);
  } else if (depth >= maxdepth) {
    add_box(out, cell, depth, o, NULL);
  } else {
    const double h = ldexp(1.0, -depth - 1);
    for (int k = 0; k < 8; k++) {
      const unsigned b = ss_cube_corner_bits(3, k);
      const double c[3] = {o[0] + ((b & 1u) ? h : 0.0), o[1] + ((b & 2u) ? h : 0.0),
                           o[2] + ((b & 4u) ? h : 0.0)};
      ss_lim_patch child;
      ss_lim_frame g;
      ss_cx *ccx = NULL;
      REQUIRE_OK_VOID(ss_lim_step(s, pcx, k, 0, &child, &g, &ccx, NULL, &err), &err);
      old_box(s, cell, &child, ccx, depth + 1, c, maxdepth, out);
    }
  }
  ss_lim_patch_free(p);
  ss_cx_free(pcx);
}

static void boxes_free(boxes *b) {
  free(b->cell);
  free(b->depth);
  free(b->origin);
  free(b->net);
}

static void check_case(const ss_scheme *s, const char *link, int levels) {
  ss_pipeline *p = psi_run(s, link, 0, 0);
  CHECK(p && p->cm, "%s: no characteristic map", link);
  if (!p || !p->cm) {
    ss_pipeline_free(p);
    return;
  }
  ss_limit *L = psi_limit(s, p, p->cm->x);
  CHECK(L != NULL, "%s: no limit evaluator", link);
  size_t ncut = 0, ncentre = 0, nbox = 0;
  ss_error err = {0};
  for (size_t c = 0; L && c < p->M->ncells; c++) {
    if (ss_local_centre_corner(p->M, c) < 0) continue;
    ncentre++;
    ss_lim_frame g = ss_lim_frame_id();
    ss_lim_patch root;
    ss_cx *pcx = NULL;
    if (ss_lim_patch_build(&L->adj, c, &g, L->loc, &root, &err) ||
        ss_lim_patch_complex(L->mesh, &root, &pcx, &err)) {
      CHECK(0, "%s: cell %zu's patch: %s", link, c, err.msg);
      break;
    }
    char what[96];
    snprintf(what, sizeof what, "%s, cell %zu", link, c);
    /* the cells after the first few: their children only (time) */
    check_children(s, pcx, ncentre <= 3 ? levels : 1, what, &ncut);
    /* psi's traversal against the old one, box depth 2 */
    boxes nw = {0}, od = {0};
    const double o[3] = {0, 0, 0};
    CHECK(!ss_limit_pieces(L, c, 2, NULL, visit, &nw, &err), "%s: %s", what, err.msg);
    old_box(s, c, &root, pcx, 0, o, 2, &od);
    int same = nw.n == od.n;
    for (size_t i = 0; same && i < nw.n; i++)
      same = nw.cell[i] == od.cell[i] && nw.depth[i] == od.depth[i] &&
             !memcmp(nw.origin[i], od.origin[i], sizeof nw.origin[i]) &&
             !memcmp(nw.net[i], od.net[i], sizeof nw.net[i]);
    CHECK(same, "%s: the pieces (%zu) differ from the old traversal's (%zu)", what, nw.n,
          od.n);
    nbox += nw.n;
    boxes_free(&nw);
    boxes_free(&od);
  }
  CHECK(ncut >= 16 * ncentre, "%s: %zu children compared", link, ncut);
  printf("%s: %zu cells around p, %zu children cut and compared, %zu boxes\n", link,
         ncentre, ncut, nbox);
  ss_limit_free(L);
  ss_pipeline_free(p);
}

int main(void) {
  ss_scheme *s = NULL;
  ss_error err = {0};
  REQUIRE_OK(ss_scheme_new("mlca", &s, &err), &err);
  check_case(s, "octahedron", 2);
  check_case(s, "7 becgdf,afdce,aebdg,agcbf,abc,adb,acd", 2);
  check_case(s,
             "13 begcmdjkilf,afhdce,agebdm,amcbhfij,abcg,alidhb,aec,bfd,akjdfl,adik,"
             "aji,aif,acd",
             1);
  ss_scheme_free(s);
  return ss_test_done("psi_reuse");
}
