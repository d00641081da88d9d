// Steel beam 0.6 m x 40 mm x 40 mm along x that strikes a stop with the face y = 0 of its last
// cell (cases/06_beam_on_stop). Unit: m. Structured hexahedra 30 x 2 x 2 (the beam of
// tests/mbs/beam_stop_test.cc), from two blocks so that the last cell's face is a surface.
// A file that sets z0 and z_cells and includes this one gets the cross-section at z0 <= z <=
// z0 + h with z_cells cells across z (cases/06_beam_on_stop/beam_planar.geo).
SetFactory("OpenCASCADE");
L = 0.6;
h = 0.04;
DefineConstant[ z0 = 0, z_cells = 2 ];
Box(1) = {0, 0, z0, L - L / 30, h, h};
Box(2) = {L - L / 30, 0, z0, L / 30, h, h};
BooleanFragments{ Volume{1, 2}; Delete; }{}
e = 1e-6;
curves[] = Curve{:};
For c In {0:#curves[] - 1}
  box[] = BoundingBox Curve{curves[c]};
  If (box[3] - box[0] > L / 30 + e)
    Transfinite Curve{curves[c]} = 30;
  ElseIf (box[3] - box[0] > e)
    Transfinite Curve{curves[c]} = 2;
  ElseIf (box[5] - box[2] > e)
    Transfinite Curve{curves[c]} = z_cells + 1;
  Else
    Transfinite Curve{curves[c]} = 3;
  EndIf
EndFor
Transfinite Surface{:};
Recombine Surface{:};
Transfinite Volume{:};
Physical Volume("beam") = Volume{:};
Physical Surface("pad") = Surface In BoundingBox{L - L / 30 - e, -e, z0 - e, L + e, e, z0 + h + e};
