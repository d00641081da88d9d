// Steel plate 0.2 m x 0.2 m x 3 mm for cases/09_sphere_on_plate. Unit: m. Structured hexahedra
// 40 x 40 x 2 (5 mm cells) from a 3 x 3 grid of boxes, so that the central 30 mm x 30 mm of the
// top face is a surface of its own (the contact patch); side faces x = 0, 0.2 and y = 0, 0.2.
SetFactory("OpenCASCADE");
a = 0.2;
t = 0.003;
c = 0.03;
cell = 0.005;
o = 0.5 * (a - c);
xs[] = {0, o, o + c, a};
k = 1;
For i In {0:2}
  For j In {0:2}
    Box(k) = {xs[i], xs[j], 0, xs[i + 1] - xs[i], xs[j + 1] - xs[j], t};
    k += 1;
  EndFor
EndFor
BooleanFragments{ Volume{1:9}; Delete; }{}
e = 1e-6;
curves[] = Curve{:};
For n In {0:#curves[] - 1}
  box[] = BoundingBox Curve{curves[n]};
  length = box[3] - box[0] + box[4] - box[1];
  If (length > e)
    Transfinite Curve{curves[n]} = Round(length / cell) + 1;
  Else
    Transfinite Curve{curves[n]} = 3;
  EndIf
EndFor
Transfinite Surface{:};
Recombine Surface{:};
Transfinite Volume{:};
Physical Volume("plate") = Volume{:};
Physical Surface("patch") = Surface In BoundingBox{o - e, o - e, t - e, o + c + e, o + c + e, t + e};
Physical Surface("sides") = Surface In BoundingBox{-e, -e, -e, e, a + e, t + e};
Physical Surface("sides") += Surface In BoundingBox{a - e, -e, -e, a + e, a + e, t + e};
Physical Surface("sides") += Surface In BoundingBox{-e, -e, -e, a + e, e, t + e};
Physical Surface("sides") += Surface In BoundingBox{-e, a - e, -e, a + e, a + e, t + e};
