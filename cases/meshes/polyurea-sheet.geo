// Clamped circular polyurea sheet of the sheet-impact case
// (cases/membrane/polyurea-sheet-impact.toml): radius R = 125 mm (the polyurea
// chapter's plate radius), graded from lc_c at the centre, where the
// projectile strikes, to lc_r at the clamped rim.
// Physical groups: surface "membrane", curve "edge".
// Finer or coarser: gmsh -2 -setnumber lc_c 1.5e-3 -setnumber lc_r 6e-3 polyurea-sheet.geo
R = 0.125;                        // radius (m)
DefineConstant[ lc_c = 3.0e-3 ];  // element size at the centre (m)
DefineConstant[ lc_r = 10.0e-3 ]; // element size at the rim (m)
Point(1) = {0, 0, 0, lc_c};
Point(2) = {R, 0, 0, lc_r};
Point(3) = {0, R, 0, lc_r};
Point(4) = {-R, 0, 0, lc_r};
Point(5) = {0, -R, 0, lc_r};
Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Circle(3) = {4, 1, 5};
Circle(4) = {5, 1, 2};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Point{1} In Surface{1};           // the centre node: the size lc_c holds there
Physical Surface("membrane") = {1};
Physical Curve("edge") = {1, 2, 3, 4};
