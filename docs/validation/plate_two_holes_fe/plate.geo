// The two-hole plate of scenes/plate_two_holes.yaml between its grips, for a finite-element
// reference (README.md here). Units mm. The plate is 50 x 100 mm; pdk clamps the bottom 3 mm and
// pulls the top 3 mm, so the deforming part is y = 3 ... 97. Holes: radius 5 at (17.5, 42.5) and
// (32.5, 57.5) (other centres: -setnumber x1 ... y2). Element size hf in y = 30 ... 70 (both
// holes and all ligaments), h elsewhere.
// gmsh -2 plate.geo -setnumber hf 0.5 -setnumber h 1.5 -format inp -o mesh.inp
DefineConstant[ hf = 0.5, h = 1.5, x1 = 17.5, y1 = 42.5, x2 = 32.5, y2 = 57.5 ];
Point(1) = {0, 3, 0, h}; Point(2) = {50, 3, 0, h}; Point(3) = {50, 97, 0, h}; Point(4) = {0, 97, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Point(10) = {x1, y1, 0, hf}; Point(11) = {x1 + 5, y1, 0, hf}; Point(12) = {x1, y1 + 5, 0, hf};
Point(13) = {x1 - 5, y1, 0, hf}; Point(14) = {x1, y1 - 5, 0, hf};
Circle(11) = {11, 10, 12}; Circle(12) = {12, 10, 13}; Circle(13) = {13, 10, 14}; Circle(14) = {14, 10, 11};
Curve Loop(2) = {11, 12, 13, 14};
Point(20) = {x2, y2, 0, hf}; Point(21) = {x2 + 5, y2, 0, hf}; Point(22) = {x2, y2 + 5, 0, hf};
Point(23) = {x2 - 5, y2, 0, hf}; Point(24) = {x2, y2 - 5, 0, hf};
Circle(21) = {21, 20, 22}; Circle(22) = {22, 20, 23}; Circle(23) = {23, 20, 24}; Circle(24) = {24, 20, 21};
Curve Loop(3) = {21, 22, 23, 24};
Plane Surface(1) = {1, 2, 3};
Field[1] = Box; Field[1].VIn = hf; Field[1].VOut = h;
Field[1].XMin = -1; Field[1].XMax = 51; Field[1].YMin = 30; Field[1].YMax = 70; Field[1].Thickness = 5;
Background Field = 1;
Recombine Surface{1};
Mesh.RecombinationAlgorithm = 1;
Mesh.ElementOrder = 2;
Mesh.SecondOrderIncomplete = 1;
Physical Surface("plate") = {1};
