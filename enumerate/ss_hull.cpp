// ss_hull.cpp — the CGAL shim: convex hulls as triangle lists (ss_hull.h).
//
// CGAL::convex_hull_3 builds the hull in a Surface_mesh; the hull's vertices
// are mapped back to input indices by their exact coordinates (the kernel
// copies the doubles), degenerate configurations are detected with CGAL's
// exact predicates, and every exception becomes an ss_status.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <new>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

extern "C" {
#include "ss_error.h"
}
#include "ss_hull.h"

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Tri = std::array<int, 3>;

bool less_xyz(const Point &a, const Point &b) {
  if (a.x() != b.x()) return a.x() < b.x();
  if (a.y() != b.y()) return a.y() < b.y();
  return a.z() < b.z();
}

// The input index of hull point p: binary search in the indices sorted by
// coordinates; -1 if p is not an input point (cannot happen with this kernel).
int index_of(const std::vector<Point> &pts, const std::vector<int> &sorted,
             const Point &p) {
  auto it = std::lower_bound(sorted.begin(), sorted.end(), p,
                             [&](int i, const Point &q) { return less_xyz(pts[i], q); });
  if (it == sorted.end() || pts[*it] != p) return -1;
  return *it;
}

// Everything but the exception handling; fills out on success.
ss_status hull(int n, const double *xyz, std::vector<Tri> &out, ss_error *err) {
  if (n < 4)
    return ss_error_set(err, SS_EINPUT, "a hull needs at least 4 points, not %d", n);
  if (!xyz) return ss_error_set(err, SS_EINPUT, "hull: no coordinates");
  std::vector<Point> pts;
  pts.reserve(static_cast<size_t>(n));
  for (int i = 0; i < n; i++) {
    const double *p = xyz + 3 * static_cast<size_t>(i);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      return ss_error_set(err, SS_EINPUT, "point %d has a coordinate that is not finite",
                          i);
    pts.emplace_back(p[0], p[1], p[2]);
  }
  std::vector<int> sorted(static_cast<size_t>(n));
  for (int i = 0; i < n; i++)
    sorted[static_cast<size_t>(i)] = i;
  std::sort(sorted.begin(), sorted.end(), [&](int a, int b) {
    return less_xyz(pts[a], pts[b]) || (pts[a] == pts[b] && a < b);
  });
  for (size_t j = 1; j < sorted.size(); j++)
    if (pts[sorted[j - 1]] == pts[sorted[j]])
      return ss_error_set(err, SS_EINPUT, "points %d and %d coincide", sorted[j - 1],
                          sorted[j]);

  // Full dimension: three points not on a line and a fourth off their plane.
  int i2 = -1, i3 = -1;
  for (int i = 2; i < n && i2 < 0; i++)
    if (!CGAL::collinear(pts[0], pts[1], pts[i])) i2 = i;
  if (i2 < 0) return ss_error_set(err, SS_EINPUT, "all %d points lie on a line", n);
  for (int i = 2; i < n && i3 < 0; i++)
    if (CGAL::orientation(pts[0], pts[1], pts[i2], pts[i]) != CGAL::COPLANAR) i3 = i;
  if (i3 < 0) return ss_error_set(err, SS_EINPUT, "all %d points lie on a plane", n);

  Mesh mesh;
  CGAL::convex_hull_3(pts.begin(), pts.end(), mesh);

  // Every point a hull vertex.
  std::vector<int> vidx(mesh.number_of_vertices(), -1);
  std::vector<char> used(static_cast<size_t>(n), 0);
  for (Mesh::Vertex_index v : mesh.vertices()) {
    int i = index_of(pts, sorted, mesh.point(v));
    if (i < 0)
      return ss_error_set(err, SS_EINTERNAL, "hull: a hull vertex is not an input point");
    vidx[v.idx()] = i;
    used[static_cast<size_t>(i)] = 1;
  }
  for (int i = 0; i < n; i++)
    if (!used[static_cast<size_t>(i)])
      return ss_error_set(err, SS_EINPUT,
                          "point %d is not a vertex of the hull (inside it or on its "
                          "boundary)",
                          i);

  // A simplicial polytope: triangles only, and no two neighbouring triangles
  // on one plane (four points on one facet).
  for (Mesh::Face_index f : mesh.faces())
    if (mesh.degree(f) != 3)
      return ss_error_set(err, SS_EINTERNAL, "hull: a facet with %u sides",
                          static_cast<unsigned>(mesh.degree(f)));
  if (mesh.number_of_faces() != 2 * static_cast<size_t>(n) - 4)
    return ss_error_set(err, SS_EINTERNAL, "hull: %zu facets on %d vertices, not %d",
                        static_cast<size_t>(mesh.number_of_faces()), n, 2 * n - 4);
  for (Mesh::Edge_index e : mesh.edges()) {
    Mesh::Halfedge_index h = mesh.halfedge(e), g = mesh.opposite(h);
    const Point &a = mesh.point(mesh.source(h)), &b = mesh.point(mesh.target(h));
    const Point &c = mesh.point(mesh.target(mesh.next(h)));
    const Point &d = mesh.point(mesh.target(mesh.next(g)));
    if (CGAL::orientation(a, b, c, d) == CGAL::COPLANAR)
      return ss_error_set(
          err, SS_EINPUT, "points %d, %d, %d and %d lie on one hull facet",
          vidx[mesh.source(h).idx()], vidx[mesh.target(h).idx()],
          vidx[mesh.target(mesh.next(h)).idx()], vidx[mesh.target(mesh.next(g)).idx()]);
  }

  // Faces of a Surface_mesh hull run counterclockwise seen from outside.
  out.clear();
  out.reserve(mesh.number_of_faces());
  for (Mesh::Face_index f : mesh.faces()) {
    Mesh::Halfedge_index h = mesh.halfedge(f);
    Tri t = {vidx[mesh.source(h).idx()], vidx[mesh.target(h).idx()],
             vidx[mesh.target(mesh.next(h)).idx()]};
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    out.push_back(t);
  }
  std::sort(out.begin(), out.end());
  return SS_OK;
}

} // namespace

extern "C" ss_status ss_hull_sphere_triangles(int n, const double *xyz, int **tri,
                                              int *ntri, ss_error *err) {
  *tri = nullptr;
  *ntri = 0;
  ss_status st = SS_OK;
  try {
    std::vector<Tri> t;
    st = hull(n, xyz, t, err);
    if (st == SS_OK) {
      int *a = static_cast<int *>(std::malloc(t.size() * 3 * sizeof(int)));
      if (!a) return ss_error_nomem(err, "hull triangles");
      for (size_t i = 0; i < t.size(); i++)
        for (size_t j = 0; j < 3; j++)
          a[3 * i + j] = t[i][j];
      *tri = a;
      *ntri = static_cast<int>(t.size());
    }
  } catch (const std::bad_alloc &) {
    st = ss_error_nomem(err, "convex hull");
  } catch (const std::exception &e) {
    st = ss_error_set(err, SS_EINTERNAL, "convex hull: %s", e.what());
  } catch (...) {
    st = ss_error_set(err, SS_EINTERNAL, "convex hull: unknown exception");
  }
  return st;
}
