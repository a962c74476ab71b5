// Square membrane, side L (m), clamped edge. Used by the demo impact runs.
// Physical groups: surface "membrane" (the material region), curve "edge"
// (the boundary), point-free: the strike node is chosen by coordinates.
// Both can be set from the command line: gmsh -2 -setnumber lc 1e-3 square.geo
DefineConstant[ L = 0.1 ];         // side (m)
DefineConstant[ lc = L / 40 ];     // target element size (m)
Point(1) = {-L/2, -L/2, 0, lc};
Point(2) = { L/2, -L/2, 0, lc};
Point(3) = { L/2,  L/2, 0, lc};
Point(4) = {-L/2,  L/2, 0, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Surface("membrane") = {1};
Physical Curve("edge") = {1, 2, 3, 4};
