// Steel connecting rod of the Simo & Vu-Quoc slider-crank: a round bar 0.3 m long of 6 mm
// diameter along x, from x = 0 (end_a, at the crank pin) to x = 0.3 m (end_b, at the slider),
// with a mesh node on its axis at mid-length (mid). Unit: m. The mesh size comes from the body
// file.
SetFactory("OpenCASCADE");
L = 0.3;
r = 0.003;
Cylinder(1) = {0, 0, 0, L, 0, 0, r};
Point(100) = {L / 2, 0, 0};
Point{100} In Volume{1};
Physical Volume("rod") = {1};
Physical Surface("end_a") = Surface In BoundingBox{-1e-6, -r - 1e-6, -r - 1e-6, 1e-6, r + 1e-6, r + 1e-6};
Physical Surface("end_b") = Surface In BoundingBox{L - 1e-6, -r - 1e-6, -r - 1e-6, L + 1e-6, r + 1e-6, r + 1e-6};
Physical Point("mid") = {100};
