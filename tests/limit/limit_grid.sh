# limit_grid.sh — sourced by the limit shell tests (not run):
#   limit_grid N   the Medit mesh of the N x N x N block of unit cubes on
#                  stdout: vertices (i, j, k), i fastest; hexahedra in the
#                  same order, corners as ss_cx.h orders them
limit_grid() {
  awk -v n="$1" 'BEGIN {
    printf "MeshVersionFormatted 2\nDimension 3\nVertices\n%d\n", (n + 1) ^ 3
    for (k = 0; k <= n; k++) for (j = 0; j <= n; j++) for (i = 0; i <= n; i++) print i, j, k, 0
    printf "Hexahedra\n%d\n", n ^ 3
    for (k = 0; k < n; k++) for (j = 0; j < n; j++) for (i = 0; i < n; i++) {
      v = i + (n + 1) * (j + (n + 1) * k) + 1; r = n + 1; l = r * r
      print v, v + 1, v + 1 + r, v + r, v + l, v + 1 + l, v + 1 + r + l, v + r + l, 0 }
    print "End" }'
}
