// Axisymmetric elastic half-space in (r, z): the quarter disk r >= 0, z <= 0 of radius R,
// for a rigid punch of rim radius a on the surface z = 0 (x = r, y = z in gmsh).
//
// Physical groups (numeric tags are what the Rust reader uses; names are for people):
//   1 contact   candidate contact line: [b, a] for the flat annulus, [0, a] otherwise
//   5 hole      the free surface under the annulus' hole, [0, b] (only when b > 0)
//   2 free      free surface [a, R]
//   3 far       far boundary, the arc of radius R (u = 0)
//   4 axis      symmetry axis r = 0 (u_r = 0)
//  10 solid     the domain
//
// Mesh size: min(hmin + grading * distance to the edges, hline + grading * distance to the contact
// line): graded toward the rim r = a (and r = b), hline along the contact line, growing linearly
// away from it, so that a domain of R = 1e5 a costs only a few dozen element layers. With
// bref >= 0, also hb + grading * distance to the point (bref, 0): refinement around the free inner
// edge of a concave punch located on a coarser solve; with cref >= 0, likewise hc + grading *
// distance to (cref, 0): the second free edge of a contact with two (the torus). With band > 0,
// also hband + grading * distance to the surface segment [a - band, a] (a Box field one element
// thick, its transition layer growing at the same slope): the rim band the pull-off simulation
// resolves its cohesive zone in. Sizes are capped at hmax (0: no cap).
//
// Parameters (override with gmsh -setnumber NAME VALUE):
DefineConstant[
  a = 1, b = 0, R = 1e5,
  hmin = 2e-3, hline = 2e-2, grading = 0.25,
  bref = -1, hb = 1e-3,
  cref = -1, hc = 1e-3,
  band = 0, hband = 1e-3,
  split = 0,
  order = 1
];
// split > 0: the free surface is cut at r = split * a into two curves (both in group 2). gmsh
// integrates the size along each curve's parameter; a single curve from a to R with elements of
// 1e-7 at one end and R/10 at the other stalls it, two curves do not.

Point(1) = {0, 0, 0};
Point(3) = {a, 0, 0};
Point(4) = {R, 0, 0};
Point(5) = {0, -R, 0};
If (b > 0)
  Point(2) = {b, 0, 0};
  Line(1) = {1, 2};
  Line(2) = {2, 3};
Else
  Line(2) = {1, 3};
EndIf
If (split > 0)
  Point(6) = {split * a, 0, 0};
  Line(3) = {3, 6};
  Line(6) = {6, 4};
Else
  Line(3) = {3, 4};
EndIf
Circle(4) = {4, 1, 5};
Line(5) = {5, 1};
// Counter-clockwise in (r, z), so that triangles are positively oriented.
If (b > 0 && split > 0)
  Curve Loop(1) = {-5, -4, -6, -3, -2, -1};
ElseIf (b > 0)
  Curve Loop(1) = {-5, -4, -3, -2, -1};
ElseIf (split > 0)
  Curve Loop(1) = {-5, -4, -6, -3, -2};
Else
  Curve Loop(1) = {-5, -4, -3, -2};
EndIf
Plane Surface(1) = {1};

Physical Curve("contact", 1) = {2};
If (b > 0)
  Physical Curve("hole", 5) = {1};
EndIf
If (split > 0)
  Physical Curve("free", 2) = {3, 6};
Else
  Physical Curve("free", 2) = {3};
EndIf
Physical Curve("far", 3) = {4};
Physical Curve("axis", 4) = {5};
Physical Surface("solid", 10) = {1};

Field[1] = Distance;
If (b > 0)
  Field[1].PointsList = {2, 3};
Else
  Field[1].PointsList = {3};
EndIf
Field[2] = Distance;
Field[2].CurvesList = {2};
Field[2].Sampling = 400;
Field[3] = MathEval;
Field[3].F = Sprintf("%g + %g * F1", hmin, grading);
Field[4] = MathEval;
Field[4].F = Sprintf("%g + %g * F2", hline, grading);
If (bref >= 0)
  Field[6] = MathEval;
  Field[6].F = Sprintf("%g + %g * sqrt((x - %g)^2 + y^2)", hb, grading, bref);
EndIf
If (band > 0)
  Field[7] = Box;
  Field[7].VIn = hband;
  Field[7].VOut = R;
  Field[7].XMin = a - band;
  Field[7].XMax = a;
  Field[7].YMin = -hband;
  Field[7].YMax = hband;
  Field[7].Thickness = R / grading;
EndIf
Field[5] = Min;
If (bref >= 0 && band > 0)
  Field[5].FieldsList = {3, 4, 6, 7};
ElseIf (bref >= 0)
  Field[5].FieldsList = {3, 4, 6};
ElseIf (band > 0)
  Field[5].FieldsList = {3, 4, 7};
Else
  Field[5].FieldsList = {3, 4};
EndIf
If (cref >= 0)
  Field[8] = MathEval;
  Field[8].F = Sprintf("%g + %g * sqrt((x - %g)^2 + y^2)", hc, grading, cref);
  Field[9] = Min;
  Field[9].FieldsList = {5, 8};
  Background Field = 9;
Else
  Background Field = 5;
EndIf

Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.Algorithm = 6;
Mesh.ElementOrder = order;
Mesh.SecondOrderLinear = 1;   // straight-sided quadratic elements (affine geometry)
Mesh.MshFileVersion = 4.1;
Mesh.Binary = 0;
