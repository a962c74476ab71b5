// Clamped circular membrane of radius R = 0.5 m for Hencky's problem
// (cases/membrane/hencky-circle.toml), with a node at the centre for the probe.
// Physical groups: surface "membrane", curve "rim".
R = 0.5;        // radius (m)
lc = R / 8;     // target element size (m): coarse, the explicit run stays fast
Point(1) = {0, 0, 0, lc};
Point(2) = {R, 0, 0, lc};
Point(3) = {0, R, 0, lc};
Point(4) = {-R, 0, 0, lc};
Point(5) = {0, -R, 0, lc};
Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Circle(3) = {4, 1, 5};
Circle(4) = {5, 1, 2};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Point{1} In Surface{1};
Physical Surface("membrane") = {1};
Physical Curve("rim") = {1, 2, 3, 4};
