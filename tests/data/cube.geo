// A 0.1 m steel cube, for fast tests of `flexmbs mesh`. Unit: m.
SetFactory("OpenCASCADE");
a = 0.1;
Box(1) = {0, 0, 0, a, a, a};
Physical Volume("block") = {1};
Physical Surface("bottom") = Surface In BoundingBox{-1e-6, -1e-6, -1e-6, a + 1e-6, a + 1e-6, 1e-6};
Physical Surface("top") = Surface In BoundingBox{-1e-6, -1e-6, a - 1e-6, a + 1e-6, a + 1e-6, a + 1e-6};
