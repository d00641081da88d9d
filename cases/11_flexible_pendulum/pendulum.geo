// The flexible pendulum of cases/11_flexible_pendulum: a steel strip L = 1 m along x, h = 5 mm
// along y (the plane of the swing), b = 20 mm along z, centred on the x axis. Unit: m.
// Structured hex20 (element_order 2) 40 x 1 x 1 cells: the faces at x = 0 (the pin) and x = L
// (the tip) are the node sets.
SetFactory("OpenCASCADE");
L = 1;
h = 0.005;
b = 0.02;
Box(1) = {0, -h / 2, -b / 2, L, h, b};
e = 1e-6;
Transfinite Curve{:} = 41;
Transfinite Curve{Curve In BoundingBox{-e, -h, -b, e, h, b}} = 2;
Transfinite Curve{Curve In BoundingBox{L - e, -h, -b, L + e, h, b}} = 2;
Transfinite Surface{:};
Recombine Surface{:};
Transfinite Volume{1};
Physical Volume("beam") = {1};
Physical Surface("pin") = Surface In BoundingBox{-e, -h, -b, e, h, b};
Physical Surface("tip") = Surface In BoundingBox{L - e, -h, -b, L + e, h, b};
