// 2 x 2 transfinite square without Recombine: 8 three-node triangles.
Include "square.geo";
Physical Surface(1) = {1};
