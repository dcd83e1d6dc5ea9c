// 2 x 2 nine-node quadrilaterals (Mesh.ElementOrder = 2).
Include "square.geo";
Recombine Surface{1};
Mesh.ElementOrder = 2;
Physical Surface(1) = {1};
Physical Curve(5) = {1};
