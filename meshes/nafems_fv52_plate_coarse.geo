// The FV52 plate of nafems_fv52_plate.geo, coarse (8 x 8 x 2 cells) for the case's short mode.
N = 8;
NZ = 2;
Include "nafems_fv52_plate.geo";
