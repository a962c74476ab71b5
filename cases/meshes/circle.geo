// Circular membrane of radius R (m), clamped rim. Used by the demo impact runs.
// Physical groups: surface "membrane", curve "edge".
R = 0.05;       // radius (m)
lc = R / 20;    // target element size (m)
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
Physical Surface("membrane") = {1};
Physical Curve("edge") = {1, 2, 3, 4};
