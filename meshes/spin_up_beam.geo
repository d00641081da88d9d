// The spin-up beam of Kane, Ryan & Banerjee (1987) (cases/08_spin_up_beam): L = 10 m along x,
// a section h x 2 h centred on the x axis, h = sqrt(12 EI / EA) = 0.0775 m along y (the plane of
// rotation) so that EA and EI are the published ones. Unit: m. Structured hex20 (element_order 2)
// 20 x 1 x 1 cells, as tests/validation/spin_up_test.cc builds it.
SetFactory("OpenCASCADE");
L = 10;
h = Sqrt(12 * 1.4e4 / 2.8e7);
Box(1) = {0, -h / 2, -h, L, h, 2 * h};
Transfinite Curve{:} = 2;
e = 1e-6;
Transfinite Curve{Curve In BoundingBox{-e, -h / 2 - e, -h - e, L + e, -h / 2 + e, -h + e}} = 21;
Transfinite Curve{Curve In BoundingBox{-e, h / 2 - e, -h - e, L + e, h / 2 + e, -h + e}} = 21;
Transfinite Curve{Curve In BoundingBox{-e, -h / 2 - e, h - e, L + e, -h / 2 + e, h + e}} = 21;
Transfinite Curve{Curve In BoundingBox{-e, h / 2 - e, h - e, L + e, h / 2 + e, h + e}} = 21;
Transfinite Surface{:};
Recombine Surface{:};
Transfinite Volume{1};
Physical Volume("beam") = {1};
Physical Surface("hub") = Surface In BoundingBox{-e, -h, -2 * h, e, h, 2 * h};
Physical Surface("tip") = Surface In BoundingBox{L - e, -h, -2 * h, L + e, h, 2 * h};
