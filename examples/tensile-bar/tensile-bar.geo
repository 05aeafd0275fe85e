// Dog-bone tensile bar after ISO 527-2 type 1A: 170 mm long, 80 mm parallel gauge section
// 10 mm wide, 20 mm wide grips, 4 mm thick, 24 mm transition radius (meeting the grips at an
// angle, as in the standard). Pulled through the end faces.
// Regenerate the committed mesh (first-order tets, 4 036 with Gmsh 4.8.4) with:
//   gmsh tensile-bar.geo -3 -format msh41 -o tensile-bar.msh
// Units: mm. x along the bar, y across, z through the thickness; min corner at the origin.
SetFactory("OpenCASCADE");

length = 170;
grip_width = 20;
gauge_width = 10;
gauge_length = 80;   // parallel narrow section, centred
radius = 24;
thickness = 4;
eps = 1e-3;

mid = length / 2;
step = (grip_width - gauge_width) / 2;              // 5 mm per side
run = Sqrt(radius^2 - (radius - step)^2);           // x extent of one transition
xg0 = mid - gauge_length / 2;                       // gauge section ends
xg1 = mid + gauge_length / 2;
yl = step;                                          // narrow edges
yh = step + gauge_width;

// Outline, counter-clockwise from the origin.
Point(1) = {0, 0, 0};
Point(2) = {xg0 - run, 0, 0};
Point(3) = {xg0, yl, 0};
Point(4) = {xg1, yl, 0};
Point(5) = {xg1 + run, 0, 0};
Point(6) = {length, 0, 0};
Point(7) = {length, grip_width, 0};
Point(8) = {xg1 + run, grip_width, 0};
Point(9) = {xg1, yh, 0};
Point(10) = {xg0, yh, 0};
Point(11) = {xg0 - run, grip_width, 0};
Point(12) = {0, grip_width, 0};
// Arc centres, tangent to the narrow edges.
Point(13) = {xg0, yl - radius, 0};
Point(14) = {xg1, yl - radius, 0};
Point(15) = {xg1, yh + radius, 0};
Point(16) = {xg0, yh + radius, 0};

Line(1) = {1, 2};
Circle(2) = {2, 13, 3};
Line(3) = {3, 4};
Circle(4) = {4, 14, 5};
Line(5) = {5, 6};
Line(6) = {6, 7};
Line(7) = {7, 8};
Circle(8) = {8, 15, 9};
Line(9) = {9, 10};
Circle(10) = {10, 16, 11};
Line(11) = {11, 12};
Line(12) = {12, 1};
Curve Loop(1) = {1 : 12};
Plane Surface(1) = {1};
Extrude {0, 0, thickness} { Surface{1}; }

grip_left() = Surface In BoundingBox{-eps, -eps, -eps, eps, grip_width + eps, thickness + eps};
grip_right() = Surface In BoundingBox{length - eps, -eps, -eps, length + eps, grip_width + eps,
                                      thickness + eps};
Physical Volume("part") = {1};
Physical Surface("grip_left") = {grip_left()};
Physical Surface("grip_right") = {grip_right()};

Mesh.MeshSizeMax = 2.5;
Mesh.ElementOrder = 1;
Mesh.Algorithm3D = 1;  // Delaunay
Mesh.Optimize = 1;
