// NAFEMS FV52 (cases/05_nafems_fv52): the thick square plate 10 m x 10 m x 1 m, [0, 10]^2 x [0, 1].
// Unit: m. Structured hexahedra (hex20 with element_order 2): N x N cells in plane, NZ through the
// thickness (N, NZ even; a file that sets them before `Include`-ing this one meshes coarser).
// Built from 2 x 2 x 2 blocks so that the mid-plane's centre lines x = 5 and y = 5 (z = 0.5) are
// geometric curves: the case's in-plane restraints.
SetFactory("OpenCASCADE");
If (!Exists(N))
  N = 20;
EndIf
If (!Exists(NZ))
  NZ = 4;
EndIf
a = 10;
t = 1;
k = 0;
For i In {0:1}
  For j In {0:1}
    For l In {0:1}
      k += 1;
      Box(k) = {i * a / 2, j * a / 2, l * t / 2, a / 2, a / 2, t / 2};
    EndFor
  EndFor
EndFor
BooleanFragments{ Volume{1:8}; Delete; }{}
e = 1e-6;
// Vertical curves (through the thickness) get NZ / 2 cells, in-plane ones N / 2.
curves[] = Curve{:};
For c In {0:#curves[] - 1}
  box[] = BoundingBox Curve{curves[c]};
  If (box[5] - box[2] > e)
    Transfinite Curve{curves[c]} = NZ / 2 + 1;
  Else
    Transfinite Curve{curves[c]} = N / 2 + 1;
  EndIf
EndFor
Transfinite Surface{:};
Recombine Surface{:};
Transfinite Volume{:};
Physical Volume("plate") = Volume{:};
// The four bottom edges (z = 0 on the plate's outline): held in z.
Physical Curve("bottom_edges") = Curve In BoundingBox{-e, -e, -e, a + e, e, e};
Physical Curve("bottom_edges") += Curve In BoundingBox{-e, a - e, -e, a + e, a + e, e};
Physical Curve("bottom_edges") += Curve In BoundingBox{-e, -e, -e, e, a + e, e};
Physical Curve("bottom_edges") += Curve In BoundingBox{a - e, -e, -e, a + e, a + e, e};
// In-plane restraints: the mid-plane's centre line x = 5 (along y), held in x, and y = 5 (along
// x), held in y; they meet at the centre.
Physical Curve("mid_x") = Curve In BoundingBox{a / 2 - e, -e, t / 2 - e, a / 2 + e, a + e, t / 2 + e};
Physical Curve("mid_y") = Curve In BoundingBox{-e, a / 2 - e, t / 2 - e, a + e, a / 2 + e, t / 2 + e};
// The side faces, for the variant held as the 3-D simply supported plate (w and the tangential
// displacement zero on the faces): x = 0 and x = a, then y = 0 and y = a.
Physical Surface("sides_x") = Surface In BoundingBox{-e, -e, -e, e, a + e, t + e};
Physical Surface("sides_x") += Surface In BoundingBox{a - e, -e, -e, a + e, a + e, t + e};
Physical Surface("sides_y") = Surface In BoundingBox{-e, -e, -e, a + e, e, t + e};
Physical Surface("sides_y") += Surface In BoundingBox{-e, a - e, -e, a + e, a + e, t + e};
