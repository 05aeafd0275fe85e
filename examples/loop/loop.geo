// Loop-like tensile part: a 140 x 100 x 10 mm plate with a central rounded-rectangle opening and
// two pin holes on the long axis; pulled apart through the pins.
// Regenerate the committed mesh (first-order tets, 29 409 with Gmsh 4.8.4) with:
//   gmsh loop.geo -3 -format msh41 -o loop.msh
// Units: mm. x along 140, y along 100, z through the 10 mm thickness; min corner at the origin.
SetFactory("OpenCASCADE");

length = 140;
width = 100;
thickness = 10;
opening_length = 70;   // central opening, centred on the plate
opening_width = 40;
opening_radius = 10;   // corner radius of the opening
pin_diameter = 12;
pin_x_left = 15;
pin_x_right = 125;
eps = 1e-3;            // bounding-box slack when picking faces

Box(1) = {0, 0, 0, length, width, thickness};
Rectangle(10) = {(length - opening_length) / 2, (width - opening_width) / 2, 0,
                 opening_length, opening_width, opening_radius};
Extrude {0, 0, thickness} { Surface{10}; }
Cylinder(3) = {pin_x_left, width / 2, 0, 0, 0, thickness, pin_diameter / 2};
Cylinder(4) = {pin_x_right, width / 2, 0, 0, 0, thickness, pin_diameter / 2};
BooleanDifference(100) = { Volume{1}; Delete; }{ Volume{2, 3, 4}; Delete; };

// Faces by position: cylinder walls of the pins, walls of the opening, the four outer sides.
r = pin_diameter / 2;
pin_left() = Surface In BoundingBox{pin_x_left - r - eps, width / 2 - r - eps, -eps,
                                    pin_x_left + r + eps, width / 2 + r + eps, thickness + eps};
pin_right() = Surface In BoundingBox{pin_x_right - r - eps, width / 2 - r - eps, -eps,
                                     pin_x_right + r + eps, width / 2 + r + eps, thickness + eps};
opening() = Surface In BoundingBox{(length - opening_length) / 2 - eps,
                                   (width - opening_width) / 2 - eps, -eps,
                                   (length + opening_length) / 2 + eps,
                                   (width + opening_width) / 2 + eps, thickness + eps};
outer() = Surface In BoundingBox{-eps, -eps, -eps, eps, width + eps, thickness + eps};
outer() += Surface In BoundingBox{length - eps, -eps, -eps,
                                  length + eps, width + eps, thickness + eps};
outer() += Surface In BoundingBox{-eps, -eps, -eps, length + eps, eps, thickness + eps};
outer() += Surface In BoundingBox{-eps, width - eps, -eps,
                                  length + eps, width + eps, thickness + eps};

Physical Volume("part") = {100};
Physical Surface("pin_left") = {pin_left()};
Physical Surface("pin_right") = {pin_right()};
Physical Surface("opening") = {opening()};
Physical Surface("outer") = {outer()};

// Finer around the pins and the opening's corners (curvature), ~4 mm elsewhere.
Mesh.MeshSizeMax = 3.0;
Mesh.MeshSizeFromCurvature = 24;  // elements per full circle
Mesh.ElementOrder = 1;
Mesh.Algorithm3D = 1;             // Delaunay
Mesh.Optimize = 1;
