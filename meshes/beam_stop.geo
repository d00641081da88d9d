// Steel beam 0.6 m x 40 mm x 40 mm along x that strikes a stop with the face y = 0 of its last
// cell (cases/06_beam_on_stop). Unit: m. Structured hexahedra 30 x 2 x 2 (the beam of
// tests/mbs/beam_stop_test.cc), from two blocks so that the last cell's face is a surface.
SetFactory("OpenCASCADE");
L = 0.6;
h = 0.04;
Box(1) = {0, 0, 0, L - L / 30, h, h};
Box(2) = {L - L / 30, 0, 0, L / 30, h, h};
BooleanFragments{ Volume{1, 2}; Delete; }{}
e = 1e-6;
curves[] = Curve{:};
For c In {0:#curves[] - 1}
  box[] = BoundingBox Curve{curves[c]};
  If (box[3] - box[0] > L / 30 + e)
    Transfinite Curve{curves[c]} = 30;
  ElseIf (box[3] - box[0] > e)
    Transfinite Curve{curves[c]} = 2;
  Else
    Transfinite Curve{curves[c]} = 3;
  EndIf
EndFor
Transfinite Surface{:};
Recombine Surface{:};
Transfinite Volume{:};
Physical Volume("beam") = Volume{:};
Physical Surface("pad") = Surface In BoundingBox{L - L / 30 - e, -e, -e, L + e, e, h + e};
