// The beam of meshes/beam_stop.geo posed for a planar scene (run.sh's planar runs): its
// cross-section centred on z = 0, so that the mesh is mirror-symmetric about B's xy plane, with
// three cells across z, so that each bending pair splits (616.0 / 619.3 Hz) into one mode in the
// plane and one out of it: on the square 2 x 2 section the pairs are equal and the eigensolver
// returns mixtures, which the planar check refuses.
z0 = -0.02;
z_cells = 3;
Include "../../meshes/beam_stop.geo";
