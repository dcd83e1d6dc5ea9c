// A disk falling on a block, meshed in 4-node quadrilaterals for exic (disk_on_block.inp).
//
//   Physical Surface(1): the disk (disk.geo)          -> region 1, material set 1
//   Physical Surface(2): the block [-2, 2] x [-1, 0]  -> region 2, material set 2
//   Physical Curve(11):  the disk's rim               -> edge set 11
//   Physical Curve(21):  the block's top, y = 0       -> edge set 21
//   Physical Curve(22):  the block's bottom, y = -1   -> edge set 22 (PBOUndary fixes it)
//
// The block is made by extrusion with Layers and Recombine: a structured mesh of nx x ny
// quadrilaterals whose nodes sit exactly at x = -2 + 4 i/nx, y = -1 + j/ny, the nodes of the
// BLOCk CARTesian,nx,ny of disk_on_block_blocks.inp (a transfinite surface would do too, but
// Gmsh places transfinite nodes by numerical integration, off by about 1e-12 of the length).
// Mesh: gmsh -2 disk_on_block.geo -format msh41 -o disk_on_block.msh
Include "disk.geo";

nx = 16;      // block elements along x
ny = 4;       // block elements along y
Point(101) = {-2, -1, 0};
bottom[] = Extrude {4, 0, 0} { Point{101}; Layers{nx}; };
block[] = Extrude {0, 1, 0} { Curve{bottom[1]}; Layers{ny}; Recombine; };
// block[0]: the top curve, block[1]: the surface, block[2], block[3]: the sides

Physical Surface(2) = {block[1]};
Physical Curve("top", 21) = {block[0]};
Physical Curve("bottom", 22) = {bottom[1]};
