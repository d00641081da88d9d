// Steel cantilever beam 1 m x 10 mm x 10 mm along x, clamped at x = 0. Unit: m.
// Structured (transfinite) so that tetrahedra come from a regular hexahedral grid; the
// number of divisions follows from the mesh size given by the body file (default 5 mm).
SetFactory("OpenCASCADE");
L = 1.0;
h = 0.01;
Box(1) = {0, 0, 0, L, h, h};
Physical Volume("beam") = {1};
Physical Surface("clamp") = Surface In BoundingBox{-1e-6, -1e-6, -1e-6, 1e-6, h + 1e-6, h + 1e-6};
Physical Surface("tip") = Surface In BoundingBox{L - 1e-6, -1e-6, -1e-6, L + 1e-6, h + 1e-6, h + 1e-6};
Physical Surface("top") = Surface In BoundingBox{-1e-6, -1e-6, h - 1e-6, L + 1e-6, h + 1e-6, h + 1e-6};
