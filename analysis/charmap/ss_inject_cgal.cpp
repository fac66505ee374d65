// ss_inject_cgal.cpp — the CGAL shim of the injectivity test
// (ss_inject_cgal.h): a winding number by signed crossings, and overlaps of
// cell images by a box filter and exact do_intersect.
//
// Exactness.  Every decision is a CGAL predicate of the Exact_predicates_
// inexact_constructions_kernel on the given doubles: orientation, collinear,
// equality, and do_intersect, which that kernel filters like any predicate
// (interval arithmetic, then exact arithmetic when the intervals cannot
// decide), so no rounding enters a yes/no answer.  Before do_intersect, two
// full simplices go through quick_meet (orientation predicates only: a
// separating facet, or a point of one strictly inside the other), which
// answers most pairs far more cheaply and leaves the rest to do_intersect;
// tests/analysis/test_inject.c checks that it never contradicts
// do_intersect, touching grid simplices included.  The only doubles computed
// here are the far end of the crossing segment, which is then a given point
// like the others, and box bounds, which are the points' own coordinates.
//
// Degenerate simplices.  CGAL's do_intersect requires non-degenerate
// triangles and tets.  A flat piece is replaced by the non-degenerate
// simplices of its points of its own dimension (Caratheodory: a set of
// affine dimension d is the union of the d-simplices its points span), so the
// union, and the answer, is unchanged.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <exception>
#include <new>
#include <utility>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Intersections_2/Point_2_Segment_2.h>
#include <CGAL/Intersections_2/Point_2_Triangle_2.h>
#include <CGAL/Intersections_2/Segment_2_Segment_2.h>
#include <CGAL/Intersections_2/Segment_2_Triangle_2.h>
#include <CGAL/Intersections_2/Triangle_2_Triangle_2.h>
#include <CGAL/Intersections_3/Point_3_Segment_3.h>
#include <CGAL/Intersections_3/Point_3_Tetrahedron_3.h>
#include <CGAL/Intersections_3/Point_3_Triangle_3.h>
#include <CGAL/Intersections_3/Segment_3_Segment_3.h>
#include <CGAL/Intersections_3/Segment_3_Tetrahedron_3.h>
#include <CGAL/Intersections_3/Segment_3_Triangle_3.h>
#include <CGAL/Intersections_3/Tetrahedron_3_Tetrahedron_3.h>
#include <CGAL/Intersections_3/Tetrahedron_3_Triangle_3.h>
#include <CGAL/Intersections_3/Triangle_3_Triangle_3.h>
#include <CGAL/box_intersection_d.h>

extern "C" {
#include "ss_error.h"
}
#include "ss_inject_cgal.h"

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using P2 = K::Point_2;
using P3 = K::Point_3;

// ---- dimension traits ----

// The cheap exact answers for two full-dimensional simplices a and b (D + 1
// points each, neither flat), before CGAL's do_intersect: 0 when a facet's
// hyperplane of one has every point of the other strictly on its outer side
// (a separating hyperplane: the closed simplices are disjoint), 1 when a
// point of one lies strictly inside the other (they meet), -1 when neither
// shows (do_intersect decides).  Only orientation predicates, which the
// kernel answers exactly (a static floating-point filter, exact arithmetic
// behind it) and far more cheaply than do_intersect, which runs whole in
// interval arithmetic; so no answer differs from do_intersect's.  Most
// pairs of pieces of non-neighbouring cells whose boxes meet are told apart
// by a facet; two pieces that cross only edge through edge are left to
// CGAL.
//
// oa, ob: the orientations of a and b (G::orient of their first D points
// and the last).  The inner side of facet i (s without s[i]) is then that
// orientation times (-1)^(D - i): s[i] moved from the end to place i is
// D - i transpositions, which flip an exact sign exactly.  A point of t is
// not tested against a facet when no answer there can matter (the facet
// already shown not to separate, the point already outside some facet):
// the same answer with fewer predicates.
//
// ab(i, j): the orientation of b's point j against facet i of a (G::orient
// of a's points but the i-th, in order, and b[j]); ba(i, j) the same with a
// and b swapped.  Computed here (quick_meet) or looked up where the pieces of
// two cells meet many times over (overlaps).
template <int D, class AB, class BA>
int quick_meet_by(CGAL::Orientation oa, CGAL::Orientation ob, AB ab, BA ba) {
  constexpr int m = D + 1;
  for (int pass = 0; pass < 2; pass++) {
    const CGAL::Orientation os = pass ? ob : oa;
    int inside[m]; // t's point j strictly on the inner side of every facet so far
    for (int j = 0; j < m; j++)
      inside[j] = 1;
    for (int i = 0; i < m; i++) {
      // facet i of s: its points but the i-th, in order; inner side: s[i]'s
      const CGAL::Orientation in = (D - i) % 2 ? -os : os;
      bool apart = true;
      for (int j = 0; j < m; j++) {
        if (!apart && !inside[j]) continue;
        const CGAL::Orientation o = pass ? ba(i, j) : ab(i, j);
        if (o != -in) apart = false;
        if (o != in) inside[j] = 0;
      }
      if (apart) return 0;
    }
    for (int j = 0; j < m; j++)
      if (inside[j]) return 1;
  }
  return -1;
}

// The orientation of p against facet i of the simplex s (D + 1 points).
template <class G>
CGAL::Orientation facet_orient(const typename G::Point *s, int i,
                               const typename G::Point &p) {
  typename G::Point f[G::D];
  for (int j = 0, q = 0; j <= G::D; j++)
    if (j != i) f[q++] = s[j];
  return G::orient(f, p);
}

template <class G>
int quick_meet(const typename G::Point *a, const typename G::Point *b,
               CGAL::Orientation oa, CGAL::Orientation ob) {
  return quick_meet_by<G::D>(
      oa, ob, [&](int i, int j) { return facet_orient<G>(a, i, b[j]); },
      [&](int i, int j) { return facet_orient<G>(b, i, a[j]); });
}

template <int D> struct Geo;

template <> struct Geo<2> {
  static constexpr int D = 2;
  using Point = P2;
  static Point make(const double *p) {
    return Point(p[0], p[1]);
  }
  static double coord(const Point &p, int i) {
    return i == 0 ? p.x() : p.y();
  }
  // Are the k + 1 points v[0..k] affinely independent?
  static bool full(const Point *v, int k) {
    if (k == 0) return true;
    if (k == 1) return v[0] != v[1];
    return CGAL::orientation(v[0], v[1], v[2]) != CGAL::COLLINEAR;
  }
  static CGAL::Orientation orient(const Point *f, const Point &p) {
    return CGAL::orientation(f[0], f[1], p);
  }
  // Do the closed non-degenerate simplices a (ka + 1 points) and b meet?
  // oa, ob: their orientations when full (quick_meet), else unused.
  static bool meet(const Point *a, int ka, const Point *b, int kb, CGAL::Orientation oa,
                   CGAL::Orientation ob, bool filter = true) {
    if (ka < kb) return meet(b, kb, a, ka, ob, oa, filter);
    if (filter && ka == 2 && kb == 2) {
      const int quick = quick_meet<Geo<2>>(a, b, oa, ob);
      if (quick >= 0) return quick != 0;
    }
    if (ka == 2) {
      const K::Triangle_2 t(a[0], a[1], a[2]);
      if (kb == 2) return CGAL::do_intersect(t, K::Triangle_2(b[0], b[1], b[2]));
      if (kb == 1) return CGAL::do_intersect(t, K::Segment_2(b[0], b[1]));
      return CGAL::do_intersect(t, b[0]);
    }
    if (ka == 1) {
      const K::Segment_2 s(a[0], a[1]);
      if (kb == 1) return CGAL::do_intersect(s, K::Segment_2(b[0], b[1]));
      return CGAL::do_intersect(s, b[0]);
    }
    return a[0] == b[0];
  }
};

template <> struct Geo<3> {
  static constexpr int D = 3;
  using Point = P3;
  static Point make(const double *p) {
    return Point(p[0], p[1], p[2]);
  }
  static double coord(const Point &p, int i) {
    return i == 0 ? p.x() : i == 1 ? p.y() : p.z();
  }
  static bool full(const Point *v, int k) {
    if (k == 0) return true;
    if (k == 1) return v[0] != v[1];
    if (k == 2) return !CGAL::collinear(v[0], v[1], v[2]);
    return CGAL::orientation(v[0], v[1], v[2], v[3]) != CGAL::COPLANAR;
  }
  static CGAL::Orientation orient(const Point *f, const Point &p) {
    return CGAL::orientation(f[0], f[1], f[2], p);
  }
  static bool meet(const Point *a, int ka, const Point *b, int kb, CGAL::Orientation oa,
                   CGAL::Orientation ob, bool filter = true) {
    if (ka < kb) return meet(b, kb, a, ka, ob, oa, filter);
    if (filter && ka == 3 && kb == 3) {
      const int quick = quick_meet<Geo<3>>(a, b, oa, ob);
      if (quick >= 0) return quick != 0;
    }
    if (ka == 3) {
      const K::Tetrahedron_3 t(a[0], a[1], a[2], a[3]);
      if (kb == 3) return CGAL::do_intersect(t, K::Tetrahedron_3(b[0], b[1], b[2], b[3]));
      if (kb == 2) return CGAL::do_intersect(t, K::Triangle_3(b[0], b[1], b[2]));
      if (kb == 1) return CGAL::do_intersect(t, K::Segment_3(b[0], b[1]));
      return CGAL::do_intersect(t, b[0]);
    }
    if (ka == 2) {
      const K::Triangle_3 t(a[0], a[1], a[2]);
      if (kb == 2) return CGAL::do_intersect(t, K::Triangle_3(b[0], b[1], b[2]));
      if (kb == 1) return CGAL::do_intersect(t, K::Segment_3(b[0], b[1]));
      return CGAL::do_intersect(t, b[0]);
    }
    if (ka == 1) {
      const K::Segment_3 s(a[0], a[1]);
      if (kb == 1) return CGAL::do_intersect(s, K::Segment_3(b[0], b[1]));
      return CGAL::do_intersect(s, b[0]);
    }
    return a[0] == b[0];
  }
};

// p on the closed segment ab (a may equal b): collinear, and between a and b
// in every coordinate.
template <int D>
bool on_segment(const typename Geo<D>::Point &a, const typename Geo<D>::Point &b,
                const typename Geo<D>::Point &p) {
  bool col;
  if constexpr (D == 2)
    col = CGAL::orientation(a, b, p) == CGAL::COLLINEAR;
  else
    col = CGAL::collinear(a, b, p);
  if (!col) return false;
  for (int i = 0; i < D; i++) {
    const double u = Geo<D>::coord(a, i), v = Geo<D>::coord(b, i),
                 w = Geo<D>::coord(p, i);
    if (w < std::min(u, v) || w > std::max(u, v)) return false;
  }
  return true;
}

// ---- winding number ----

// A reproducible stream of doubles in [0, 1) (splitmix64; local state).
struct Stream {
  std::uint64_t s;
  double next() {
    std::uint64_t z = (s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * 0x1.0p-53;
  }
};

// A double drawn from a little beyond [lo, hi].
double draw(double lo, double hi, Stream &r) {
  double w = (hi - lo) + 1.0, a = lo - w, b = hi + w;
  if (!std::isfinite(a) || !std::isfinite(b)) a = lo, b = hi;
  const double u = r.next();
  return (1.0 - u) * a + u * b;
}

constexpr int kTries = 64;

int sgn(CGAL::Orientation o) {
  return o == CGAL::POSITIVE ? 1 : o == CGAL::NEGATIVE ? -1 : 0;
}

// The crossing test of the segment p q with facet f, for a facet that does
// not hold p and is not flat; sp is the side of p.  Returns the signed
// crossing (-1, 0, +1) or sets *bad when the segment meets the facet's
// boundary or lies in its plane.  q lies beyond every facet, so it is on no
// facet: q on the facet's plane (line) means the segment meets it only at q.
int crossing(const P3 *t, int sp, const P3 &p, const P3 &q, bool *bad) {
  const int sq = sgn(CGAL::orientation(t[0], t[1], t[2], q));
  if (sp == 0 || sq == 0) {
    if (sp == 0 && sq == 0) *bad = true;
    return 0;
  }
  if (sq == sp) return 0;
  const int s1 = sgn(CGAL::orientation(p, q, t[0], t[1]));
  const int s2 = sgn(CGAL::orientation(p, q, t[1], t[2]));
  const int s3 = sgn(CGAL::orientation(p, q, t[2], t[0]));
  const bool pos = s1 > 0 || s2 > 0 || s3 > 0, neg = s1 < 0 || s2 < 0 || s3 < 0;
  if (pos && neg) return 0;
  if (s1 == 0 || s2 == 0 || s3 == 0) {
    *bad = true;
    return 0;
  }
  // p inside a positive cell is on the negative side of its outward facets.
  return -sp;
}

int crossing(const P2 *s, int sp, const P2 &p, const P2 &q, bool *bad) {
  const int sq = sgn(CGAL::orientation(s[0], s[1], q));
  if (sp == 0 || sq == 0) {
    if (sp == 0 && sq == 0) *bad = true;
    return 0;
  }
  if (sq == sp) return 0;
  const int s1 = sgn(CGAL::orientation(p, q, s[0]));
  const int s2 = sgn(CGAL::orientation(p, q, s[1]));
  if (s1 == 0 || s2 == 0) {
    *bad = true;
    return 0;
  }
  if (s1 == s2) return 0;
  // p inside a positive cell is on the left of its boundary segments.
  return sp;
}

// The facet (D points) holds p: the closed triangle or segment, flat or not.
bool holds(const P3 *t, const P3 &p) {
  if (CGAL::collinear(t[0], t[1], t[2]))
    return on_segment<3>(t[0], t[1], p) || on_segment<3>(t[1], t[2], p) ||
           on_segment<3>(t[2], t[0], p);
  return CGAL::do_intersect(K::Triangle_3(t[0], t[1], t[2]), p);
}
bool holds(const P2 *s, const P2 &p) {
  return on_segment<2>(s[0], s[1], p);
}

bool flat(const P3 *t) {
  return CGAL::collinear(t[0], t[1], t[2]);
}
bool flat(const P2 *s) {
  return s[0] == s[1];
}
int side(const P3 *t, const P3 &p) {
  return sgn(CGAL::orientation(t[0], t[1], t[2], p));
}
int side(const P2 *s, const P2 &p) {
  return sgn(CGAL::orientation(s[0], s[1], p));
}

template <int D>
void winding(const double *x, size_t nfacet, const size_t *facet, size_t centre,
             ss_wind_kind *kind, int *w) {
  using G = Geo<D>;
  using Point = typename G::Point;
  const Point p = G::make(x + D * centre);
  // Facets that can be crossed (not flat), with the side of p.
  std::vector<std::array<Point, D>> live;
  std::vector<int> sp;
  std::array<double, D> lo, hi;
  for (int i = 0; i < D; i++)
    lo[i] = hi[i] = G::coord(p, i);
  for (size_t f = 0; f < nfacet; f++) {
    std::array<Point, D> t;
    for (int j = 0; j < D; j++) {
      t[j] = G::make(x + D * facet[D * f + j]);
      for (int i = 0; i < D; i++) {
        lo[i] = std::min(lo[i], G::coord(t[j], i));
        hi[i] = std::max(hi[i], G::coord(t[j], i));
      }
    }
    if (holds(t.data(), p)) {
      *kind = SS_WIND_ON_BOUNDARY;
      return;
    }
    // A flat facet holds no crossing a generic segment can count: zero area
    // (length), so it adds nothing to the winding number.
    if (flat(t.data())) continue;
    live.push_back(t);
    sp.push_back(side(t.data(), p));
  }
  // q beyond the largest x: no facet reaches there, so q winds 0 times.
  double qx = hi[0] + (1.0 + std::fabs(hi[0]));
  if (!std::isfinite(qx)) qx = std::nextafter(hi[0], HUGE_VAL);
  *kind = SS_WIND_NO_RAY;
  if (!std::isfinite(qx) || !(qx > hi[0])) return;
  Stream r{0x5eed1234abcdull};
  for (int attempt = 0; attempt < kTries; attempt++) {
    double c[D];
    c[0] = qx;
    for (int i = 1; i < D; i++)
      c[i] = draw(lo[i], hi[i], r);
    const Point q = G::make(c);
    bool bad = false;
    int sum = 0;
    for (size_t f = 0; f < live.size() && !bad; f++)
      sum += crossing(live[f].data(), sp[f], p, q, &bad);
    if (!bad) {
      *kind = SS_WIND_OK;
      *w = sum;
      return;
    }
  }
}

// ---- overlaps ----

template <int D> struct Simplex {
  int k;                                       // dimension: k + 1 points
  CGAL::Orientation o;                         // orientation when k = D (quick_meet)
  std::array<typename Geo<D>::Point, D + 1> v; // its points
  std::array<double, D> lo, hi;                // its box
  std::array<int, D + 1> pt;                   // v's numbers among its cell's points
};

int bits(unsigned mask) {
  int n = 0;
  for (; mask; mask &= mask - 1)
    n++;
  return n;
}

// Append the non-degenerate simplices of top dimension spanned by the
// D + 1 points v: v itself when it is not flat.
// id[i]: the number of v[i] among the cell's points (Simplex::pt).
template <int D>
void decompose(const std::array<typename Geo<D>::Point, D + 1> &v,
               const std::array<int, D + 1> &id, std::vector<Simplex<D>> &out) {
  using G = Geo<D>;
  const int m = D + 1;
  for (int k = D; k >= 0; k--) {
    bool any = false;
    for (unsigned mask = 0; mask < (1u << m); mask++) {
      if (bits(mask) != k + 1) continue;
      Simplex<D> s;
      s.k = k;
      int j = 0;
      for (int i = 0; i < m; i++)
        if (mask & (1u << i)) {
          s.pt[static_cast<size_t>(j)] = id[static_cast<size_t>(i)];
          s.v[static_cast<size_t>(j++)] = v[static_cast<size_t>(i)];
        }
      // full: for k = D its orientation, kept for quick_meet, is not zero
      s.o = k == D ? G::orient(s.v.data(), s.v[D]) : CGAL::ZERO;
      if (k == D ? s.o == CGAL::ZERO : !G::full(s.v.data(), k)) continue;
      for (int i = 0; i < D; i++) {
        s.lo[i] = s.hi[i] = G::coord(s.v[0], i);
        for (int a = 1; a <= k; a++) {
          s.lo[i] = std::min(s.lo[i], G::coord(s.v[static_cast<size_t>(a)], i));
          s.hi[i] = std::max(s.hi[i], G::coord(s.v[static_cast<size_t>(a)], i));
        }
      }
      out.push_back(s);
      any = true;
      if (k == D) return; // the whole simplex
    }
    if (any) return;
  }
}

template <int D> bool boxes_meet(const Simplex<D> &a, const Simplex<D> &b) {
  for (int i = 0; i < D; i++)
    if (a.hi[i] < b.lo[i] || b.hi[i] < a.lo[i]) return false;
  return true;
}

bool share_corner(const size_t *a, const size_t *b, int m) {
  for (int i = 0; i < m; i++) {
    if (a[i] == SIZE_MAX) continue;
    for (int j = 0; j < m; j++)
      if (a[i] == b[j]) return true;
  }
  return false;
}

template <int D>
void overlaps(const double *x, size_t ncells, const size_t *corner, int maxcorner,
              const size_t *first_piece, const size_t *piece, size_t *count,
              size_t pair[2]) {
  using G = Geo<D>;
  using Point = typename G::Point;
  // The simplices of every cell, and the cell's box.
  std::vector<Simplex<D>> simp;
  std::vector<size_t> begin(ncells + 1);
  using Box = CGAL::Box_intersection_d::Box_with_handle_d<
      double, D, const size_t *, CGAL::Box_intersection_d::ID_FROM_HANDLE>;
  std::vector<size_t> ids(ncells);
  std::vector<Box> boxes; // reordered by box_self_intersection_d
  boxes.reserve(ncells);
  std::vector<std::array<double, 2 * D>> cbox(ncells); // cell c's lo, then hi
  std::vector<int> npts(ncells); // the number of distinct points of cell c's pieces
  std::vector<size_t> seen;      // those points, while numbering them
  for (size_t c = 0; c < ncells; c++) {
    begin[c] = simp.size();
    seen.clear();
    for (size_t s = first_piece[c]; s < first_piece[c + 1]; s++) {
      std::array<Point, D + 1> v;
      std::array<int, D + 1> id;
      for (int j = 0; j <= D; j++) {
        const size_t q = piece[(D + 1) * s + static_cast<size_t>(j)];
        v[static_cast<size_t>(j)] = G::make(x + D * q);
        const auto at = std::find(seen.begin(), seen.end(), q);
        id[static_cast<size_t>(j)] = static_cast<int>(at - seen.begin());
        if (at == seen.end()) seen.push_back(q);
      }
      decompose<D>(v, id, simp);
    }
    npts[c] = static_cast<int>(seen.size());
    double lo[D], hi[D];
    for (int i = 0; i < D; i++)
      lo[i] = HUGE_VAL, hi[i] = -HUGE_VAL;
    for (size_t s = begin[c]; s < simp.size(); s++)
      for (int i = 0; i < D; i++) {
        lo[i] = std::min(lo[i], simp[s].lo[i]);
        hi[i] = std::max(hi[i], simp[s].hi[i]);
      }
    ids[c] = c;
    boxes.emplace_back(lo, hi, &ids[c]);
    for (int i = 0; i < D; i++)
      cbox[c][static_cast<size_t>(i)] = lo[i],
      cbox[c][static_cast<size_t>(D + i)] = hi[i];
  }
  begin[ncells] = simp.size();
  // Candidate pairs: closed boxes that meet, cells that share no corner.
  std::vector<std::pair<size_t, size_t>> cand;
  const size_t m = static_cast<size_t>(maxcorner);
  CGAL::box_self_intersection_d(
      boxes.begin(), boxes.end(), [&](const Box &a, const Box &b) {
        size_t i = *a.handle(), j = *b.handle();
        if (i > j) std::swap(i, j);
        if (!share_corner(corner + i * m, corner + j * m, maxcorner))
          cand.emplace_back(i, j);
      });
  std::sort(cand.begin(), cand.end());
  cand.erase(std::unique(cand.begin(), cand.end()), cand.end());
  *count = 0;
  pair[0] = pair[1] = SIZE_MAX;
  // The pieces of two cells share points (a hex's 24 tets have 15), so the
  // orientations of quick_meet recur: each (piece, facet, point of the other
  // cell) is computed once per pair of cells and looked up after (memo,
  // kUnknown until then); the same predicates, the same answers.
  constexpr signed char kUnknown = 2;
  constexpr size_t F = static_cast<size_t>(D + 1); // facets of a piece
  std::vector<signed char> memo_a, memo_b;
  // the orientation of T's point j against facet i of S, memo[i n + point]
  auto cached = [](signed char *memo, size_t n, const Simplex<D> &S,
                   const Simplex<D> &T) {
    return [=, &S, &T](int i, int j) {
      const size_t u = static_cast<size_t>(j);
      signed char &r = memo[static_cast<size_t>(i) * n + static_cast<size_t>(T.pt[u])];
      if (r == kUnknown)
        r = static_cast<signed char>(facet_orient<G>(S.v.data(), i, T.v[u]));
      return static_cast<CGAL::Orientation>(r);
    };
  };
  for (const auto &c : cand) {
    bool hit = false;
    const size_t a0 = begin[c.first], b0 = begin[c.second];
    const size_t na = npts[c.first], nb = npts[c.second];
    memo_a.assign((begin[c.first + 1] - a0) * F * nb, kUnknown);
    memo_b.assign((begin[c.second + 1] - b0) * F * na, kUnknown);
    // a piece of one cell outside the other cell's box meets none of its
    // pieces (their boxes are inside it): skipped before the inner loop
    const std::array<double, 2 *D> &bb = cbox[c.second];
    for (size_t s = a0; s < begin[c.first + 1] && !hit; s++) {
      bool near = true;
      for (int i = 0; i < D; i++)
        near &= !(simp[s].hi[i] < bb[static_cast<size_t>(i)] ||
                  bb[static_cast<size_t>(D + i)] < simp[s].lo[i]);
      if (!near) continue;
      const Simplex<D> &A = simp[s];
      for (size_t t = b0; t < begin[c.second + 1] && !hit; t++) {
        const Simplex<D> &B = simp[t];
        if (!boxes_meet<D>(A, B)) continue;
        if (A.k < D || B.k < D) {
          hit = G::meet(A.v.data(), A.k, B.v.data(), B.k, A.o, B.o);
          continue;
        }
        const int quick = quick_meet_by<D>(
            A.o, B.o, cached(memo_a.data() + (s - a0) * F * nb, nb, A, B),
            cached(memo_b.data() + (t - b0) * F * na, na, B, A));
        hit = quick >= 0 ? quick != 0
                         : G::meet(A.v.data(), A.k, B.v.data(), B.k, A.o, B.o, false);
      }
    }
    if (!hit) continue;
    if (*count == 0) pair[0] = c.first, pair[1] = c.second;
    ++*count;
  }
}

// Run f, turning every exception into a status.
template <class F> ss_status guarded(const char *what, ss_error *err, F f) {
  try {
    f();
    return SS_OK;
  } catch (const std::bad_alloc &) {
    return ss_error_nomem(err, what);
  } catch (const std::exception &e) {
    return ss_error_set(err, SS_EINTERNAL, "%s: %s", what, e.what());
  } catch (...) {
    return ss_error_set(err, SS_EINTERNAL, "%s: unknown exception", what);
  }
}

} // namespace

extern "C" ss_status ss_inject_cgal_winding(int dim, const double *x, size_t nfacet,
                                            const size_t *facet, size_t centre,
                                            ss_wind_kind *kind, int *winding_out,
                                            ss_error *err) {
  *kind = SS_WIND_NO_RAY;
  *winding_out = 0;
  return guarded("winding number", err, [&] {
    if (dim == 3)
      winding<3>(x, nfacet, facet, centre, kind, winding_out);
    else
      winding<2>(x, nfacet, facet, centre, kind, winding_out);
  });
}

extern "C" ss_status ss_inject_cgal_overlaps(int dim, const double *x, size_t ncells,
                                             const size_t *corner, int maxcorner,
                                             const size_t *first_piece,
                                             const size_t *piece, size_t *noverlaps,
                                             size_t pair[2], ss_error *err) {
  *noverlaps = 0;
  pair[0] = pair[1] = SIZE_MAX;
  return guarded("cell overlaps", err, [&] {
    if (dim == 3)
      overlaps<3>(x, ncells, corner, maxcorner, first_piece, piece, noverlaps, pair);
    else
      overlaps<2>(x, ncells, corner, maxcorner, first_piece, piece, noverlaps, pair);
  });
}

extern "C" ss_status ss_inject_cgal_meet(int dim, const double *a, const double *b,
                                         int *quick, int *exact, ss_error *err) {
  *quick = -2;
  *exact = 0;
  return guarded("simplex meet", err, [&] {
    auto run = [&](auto g) {
      using G = decltype(g);
      typename G::Point pa[G::D + 1], pb[G::D + 1];
      for (int j = 0; j <= G::D; j++)
        pa[j] = G::make(a + G::D * j), pb[j] = G::make(b + G::D * j);
      const CGAL::Orientation oa = G::orient(pa, pa[G::D]), ob = G::orient(pb, pb[G::D]);
      if (oa != CGAL::ZERO && ob != CGAL::ZERO) *quick = quick_meet<G>(pa, pb, oa, ob);
      // the exact answer without the cheap test: the do_intersect of meet
      *exact = G::meet(pa, G::D, pb, G::D, oa, ob, false);
    };
    if (dim == 3)
      run(Geo<3>{});
    else
      run(Geo<2>{});
  });
}
