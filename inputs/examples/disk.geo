// A disk of radius R centred at (0, yc), meshed in 4-node quadrilaterals for exic (GMSH command).
// An O-grid: a centre square of n x n quadrilaterals and four ring sectors of n x m, all
// transfinite. Transfinite surfaces give triangles unless they are recombined: the Recombine
// line below is what makes them quadrilaterals (exic refuses triangles).
//
//   Physical Surface(1): the disk          -> exic region 1, material set 1
//   Physical Curve(11):  the disk's rim    -> exic edge set 11 (contact SURFace PHYSical,11)
//
// disk_on_block.geo includes this file. Mesh: gmsh -2 disk.geo -format msh41 -o disk.msh
R = 1.0;      // radius
yc = 1.05;    // centre (0, yc): 0.05 above the block's top y = 0 of disk_on_block.geo
a = 0.45;     // half side of the centre square
n = 8;        // elements along a side of the square and along each quarter of the rim
m = 4;        // elements across the ring

Point(1) = {0, yc, 0};
Point(2) = { a, yc - a, 0}; Point(3) = { a, yc + a, 0};
Point(4) = {-a, yc + a, 0}; Point(5) = {-a, yc - a, 0};
c = R/Sqrt(2);
Point(6) = { c, yc - c, 0}; Point(7) = { c, yc + c, 0};
Point(8) = {-c, yc + c, 0}; Point(9) = {-c, yc - c, 0};
Line(1) = {2, 3}; Line(2) = {3, 4}; Line(3) = {4, 5}; Line(4) = {5, 2};
Circle(5) = {6, 1, 7}; Circle(6) = {7, 1, 8}; Circle(7) = {8, 1, 9}; Circle(8) = {9, 1, 6};
Line(9) = {2, 6}; Line(10) = {3, 7}; Line(11) = {4, 8}; Line(12) = {5, 9};
Curve Loop(1) = {1, 2, 3, 4};      Plane Surface(1) = {1};
Curve Loop(2) = {9, 5, -10, -1};   Plane Surface(2) = {2};
Curve Loop(3) = {10, 6, -11, -2};  Plane Surface(3) = {3};
Curve Loop(4) = {11, 7, -12, -3};  Plane Surface(4) = {4};
Curve Loop(5) = {12, 8, -9, -4};   Plane Surface(5) = {5};
Transfinite Curve{1:8} = n + 1;
Transfinite Curve{9:12} = m + 1;
Transfinite Surface{1:5};
Recombine Surface{1:5};

Physical Surface(1) = {1:5};
Physical Curve("rim", 11) = {5:8};
