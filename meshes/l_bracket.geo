// A steel L-bracket (cases/07_bracket_modes): a base arm 100 mm x 60 mm x 10 mm on z = 0 and a
// leg 10 mm thick rising to z = 80 mm at x = 0. Unit: m. Structured hexahedra (hex20 with
// element_order 2) of about s = 5 mm (a file that sets s before `Include`-ing this one meshes
// coarser), from four blocks: the corner, the arm in two (its far 30 mm are bolted down) and
// the leg.
SetFactory("OpenCASCADE");
a = 0.1;
w = 0.06;
t = 0.01;
H = 0.08;
If (!Exists(s))
  s = 0.005;
EndIf
Box(1) = {0, 0, 0, t, w, t};
b = 0.03;
Box(2) = {t, 0, 0, a - t - b, w, t};
Box(3) = {a - b, 0, 0, b, w, t};
Box(4) = {0, 0, t, t, w, H - t};
BooleanFragments{ Volume{1:4}; Delete; }{}
curves[] = Curve{:};
For c In {0:#curves[] - 1}
  box[] = BoundingBox Curve{curves[c]};
  length = Sqrt((box[3] - box[0])^2 + (box[4] - box[1])^2 + (box[5] - box[2])^2);
  Transfinite Curve{curves[c]} = Floor(length / s + 0.5) + 1;
EndFor
Transfinite Surface{:};
Recombine Surface{:};
Transfinite Volume{:};
e = 1e-6;
Physical Volume("bracket") = Volume{:};
// Bolted down: the arm's bottom face z = 0 over its far 30 mm, x >= a - b.
Physical Surface("base") = Surface In BoundingBox{a - b - e, -e, -e, a + e, w + e, e};
// Where a part attaches: the leg's top face z = H.
Physical Surface("top") = Surface In BoundingBox{-e, -e, H - e, t + e, w + e, H + e};
