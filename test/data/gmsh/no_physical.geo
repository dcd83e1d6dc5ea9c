// 2 x 2 quadrilaterals and no physical group at all.
Include "square.geo";
Recombine Surface{1};
