// A torus surface (R = 1, r = 0.4) meshed by gmsh: about 5 800 triangles,
// for the quasi 4-8 claims of section 3.3 on a mesh the project did not make
// (tests/scheme/test_quasi48.c).  Only the physical surface is saved, so the
// file holds triangles alone (no seam lines or points).
SetFactory("OpenCASCADE");
Torus(1) = {0, 0, 0, 1, 0.4};
Physical Surface(1) = {1};
Mesh.MeshSizeMin = 0.08;
Mesh.MeshSizeMax = 0.08;
Mesh.Algorithm = 6;
