// A unit square surface and nothing else: a purely 2-D geometry, which flexmbs rejects.
SetFactory("OpenCASCADE");
Rectangle(1) = {0, 0, 0, 1, 1};
Physical Surface("square") = {1};
