// The L-bracket of l_bracket.geo, coarse (cells of about 10 mm) for case 07's short mode.
s = 0.01;
Include "l_bracket.geo";
