// Steel rod 0.5 m x 20 mm x 20 mm along x, struck on its end face x = 0 (cases/04_sphere_on_rod).
// Unit: m. Structured hexahedra: 100 cells along x, one across (the cross-section moves as a
// whole under an axial load on the face centre, as the 1-D rod of the reference assumes).
SetFactory("OpenCASCADE");
L = 0.5;
h = 0.02;
Box(1) = {0, 0, 0, L, h, h};
Transfinite Curve{:} = 2;
Transfinite Curve{Curve In BoundingBox{-1e-6, -1e-6, -1e-6, L + 1e-6, 1e-6, 1e-6}} = 101;
Transfinite Curve{Curve In BoundingBox{-1e-6, h - 1e-6, -1e-6, L + 1e-6, h + 1e-6, 1e-6}} = 101;
Transfinite Curve{Curve In BoundingBox{-1e-6, -1e-6, h - 1e-6, L + 1e-6, 1e-6, h + 1e-6}} = 101;
Transfinite Curve{Curve In BoundingBox{-1e-6, h - 1e-6, h - 1e-6, L + 1e-6, h + 1e-6, h + 1e-6}} = 101;
Transfinite Surface{:};
Recombine Surface{:};
Transfinite Volume{1};
Physical Volume("rod") = {1};
Physical Surface("end") = Surface In BoundingBox{-1e-6, -1e-6, -1e-6, 1e-6, h + 1e-6, h + 1e-6};
