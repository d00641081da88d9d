// Line 3 lacks a comma: gmsh reports a syntax error on line 3.
Point(1) = {0, 0, 0, 1};
Point(2) = {1, 0, 0 1};
