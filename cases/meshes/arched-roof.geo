// Arched fabric roof canopy of the drag paper, section 5.1 (Fig. 11):
// 11.10 m long (x), 10.20 m wide (y), arched across the 10.20 m span on a
// 12.00 m radius; the fabric is continuously supported along the two gable
// ends and discretely by 12 springs, 6 per long edge, at the ends of the
// curved supporting beams.
//
// Coordinates: the charge of section 5.2 sits at the origin, at the centre
// of the enclosed area on the ground (hemispherical surface burst), 4.40 m
// below the highest point of the roof. Hence the crown line is at z = 4.40 m,
// the arc centre at z = 4.40 - 12.00 = -7.60 m, the rise of the arch
// 12 - sqrt(12^2 - 5.1^2) = 1.138 m and the long edges (eaves) at
// z = 3.262 m.
//
// Assumption (the text does not give Fig. 11's spacing): six curved beams,
// equally spaced 11.10 / 5 = 2.22 m apart, two of them at the gable ends; the
// springs are at their 12 ends. The beams appear as interior curves of the
// mesh ("beams") so the fabric has nodes on them; the case puts a rigid arc
// under each inner beam line (blast-roof.toml's [[rigid_surface]] tables,
// x = -3.33, -1.11, 1.11, 3.33 m), on which the fabric rests.
//
// Physical groups: surface "fabric"; curves "gables" (x = -5.55 and 5.55),
// "eaves" (the two long edges), "beams" (the four interior beam lines);
// points "springs" (the 12 beam ends). The roof centre (x = y = 0, z = 4.40)
// lies mid-bay; probes find its nearest node by coordinates.
L = 11.10;        // length along x (m)
B = 10.20;        // span along y (m)
R = 12.00;        // arch radius (m)
ztop = 4.40;      // crown height above the charge (m)
nbay = 5;         // bays between the 6 beams
lc = 0.5;         // target element size (m); override with -setnumber lc VALUE

zc = ztop - R;                   // arc centre height
zeave = zc + Sqrt(R^2 - (B/2)^2);
x0 = -L/2;

Point(1) = {x0, -B/2, zeave, lc};
Point(2) = {x0, 0, ztop, lc};
Point(3) = {x0,  B/2, zeave, lc};
Point(4) = {x0, 0, zc, lc};      // arc centre (not meshed)
Circle(1) = {1, 4, 2};
Circle(2) = {2, 4, 3};

// Extrude the gable arc bay by bay: each step adds one beam line.
first[] = {1, 2};
surfs[] = {};
beamcurves[] = {};
eaves[] = {};
springs[] = {1, 3};
crowns[] = {};
For i In {1:nbay}
  e1[] = Extrude {L/nbay, 0, 0} { Curve{first[0]}; };
  e2[] = Extrude {L/nbay, 0, 0} { Curve{first[1]}; };
  // e1[0] = far arc piece, e1[1] = surface, e1[2..3] = side lines
  surfs[] += {e1[1], e2[1]};
  eaves[] += {e1[2], e2[3]};
  first[] = {e1[0], e2[0]};
  If (i < nbay)
    beamcurves[] += {e1[0], e2[0]};
  EndIf
EndFor

Coherence;
Physical Surface("fabric") = {surfs[]};
Physical Curve("gables") = {1, 2, first[0], first[1]};
Physical Curve("beams") = {beamcurves[]};
Physical Curve("eaves") = {eaves[]};
// Beam ends: the points of the mesh on y = +-B/2 at the beam positions.
springpts[] = Point In BoundingBox {x0 - 1e-3, -B/2 - 1e-3, zeave - 1e-3,
                                     -x0 + 1e-3, -B/2 + 1e-3, zeave + 1e-3};
springpts[] += Point In BoundingBox {x0 - 1e-3, B/2 - 1e-3, zeave - 1e-3,
                                      -x0 + 1e-3, B/2 + 1e-3, zeave + 1e-3};
Physical Point("springs") = {springpts[]};
Mesh.Algorithm = 6;  // Frontal-Delaunay on the curved surface
