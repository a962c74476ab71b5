// Two-material square membrane (used by tests and as a gmsh example): the
// left half "soft", the right half "stiff"; boundary curve "edge".
L = 0.1;
lc = L / 10;
Point(1) = {0, 0, 0, lc};
Point(2) = {L/2, 0, 0, lc};
Point(3) = {L, 0, 0, lc};
Point(4) = {L, L, 0, lc};
Point(5) = {L/2, L, 0, lc};
Point(6) = {0, L, 0, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 6};
Line(6) = {6, 1};
Line(7) = {2, 5};
Curve Loop(1) = {1, 7, 5, 6};
Plane Surface(1) = {1};
Curve Loop(2) = {2, 3, 4, -7};
Plane Surface(2) = {2};
Physical Surface("soft") = {1};
Physical Surface("stiff") = {2};
Physical Curve("edge") = {1, 2, 3, 4, 5, 6};
