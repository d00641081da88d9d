// The pinion's steel shaft for cases/10_gear_pair: a cylinder of radius 15 mm along z from
// z = -0.1 m (the driven end, "drive") to z = 0 (the pinion's end face, "gear"). Unit: m.
SetFactory("OpenCASCADE");
L = 0.1;
R = 0.015;
Cylinder(1) = {0, 0, -L, 0, 0, L, R};
Physical Volume("shaft") = {1};
Physical Surface("drive") = Surface In BoundingBox{-R - 1e-6, -R - 1e-6, -L - 1e-6, R + 1e-6, R + 1e-6, -L + 1e-6};
Physical Surface("gear") = Surface In BoundingBox{-R - 1e-6, -R - 1e-6, -1e-6, R + 1e-6, R + 1e-6, 1e-6};
