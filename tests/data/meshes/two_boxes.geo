// Two unit boxes sharing a face, each its own physical volume (7 and 9), with a physical
// surface so that the files also hold triangles the readers must skip. The .msh files of this
// folder are this geometry meshed once and saved in each format (README.md).
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Box(2) = {1, 0, 0, 1, 1, 1};
BooleanFragments{ Volume{1}; Delete; }{ Volume{2}; Delete; }
Physical Volume(7) = {1};
Physical Volume(9) = {2};
Physical Surface(3) = {1};
MeshSize{ PointsOf{ Volume{:}; } } = 0.6;
