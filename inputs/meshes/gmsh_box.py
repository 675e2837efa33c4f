"""Writes gmsh_box_v41.msh and gmsh_box_v22.msh with Gmsh itself (pip package `gmsh`).

Two boxes [0,2]x[0,1]x[0,1] and [2,3]x[0,1]x[0,1] (m), glued at x = 2, meshed with
transfinite hexahedra (4x2x2 and 2x2x2). Physical groups: volumes `fill` and `toe`, surfaces
`base` (z = 0), `upstream` (x = 0), `joint` (x = 2, internal), curve `crest_line`
(x = 0, z = 1), point `origin`. Run: python3 gmsh_box.py
"""
import gmsh

gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
gmsh.model.add("box")
occ = gmsh.model.occ
a = occ.addBox(0, 0, 0, 2, 1, 1)
b = occ.addBox(2, 0, 0, 1, 1, 1)
occ.fragment([(3, a)], [(3, b)])
occ.synchronize()

def surfaces_at(x0, y0, z0, x1, y1, z1, dim=2):
    eps = 1e-6
    return [t for (_, t) in gmsh.model.getEntitiesInBoundingBox(
        x0 - eps, y0 - eps, z0 - eps, x1 + eps, y1 + eps, z1 + eps, dim)]

for (dim, tag) in gmsh.model.getEntities(1):
    xmin, ymin, zmin, xmax, ymax, zmax = gmsh.model.getBoundingBox(dim, tag)
    length = max(xmax - xmin, ymax - ymin, zmax - zmin)
    n = int(round(length / 0.5)) + 1
    gmsh.model.mesh.setTransfiniteCurve(tag, n)
for (dim, tag) in gmsh.model.getEntities(2):
    gmsh.model.mesh.setTransfiniteSurface(tag)
    gmsh.model.mesh.setRecombine(dim, tag)
for (dim, tag) in gmsh.model.getEntities(3):
    gmsh.model.mesh.setTransfiniteVolume(tag)

vols = sorted(t for (_, t) in gmsh.model.getEntities(3))
gmsh.model.addPhysicalGroup(3, [vols[0]], name="fill")
gmsh.model.addPhysicalGroup(3, [vols[1]], name="toe")
gmsh.model.addPhysicalGroup(2, surfaces_at(0, 0, 0, 3, 1, 0), name="base")
gmsh.model.addPhysicalGroup(2, surfaces_at(0, 0, 0, 0, 1, 1), name="upstream")
gmsh.model.addPhysicalGroup(2, surfaces_at(2, 0, 0, 2, 1, 1), name="joint")
gmsh.model.addPhysicalGroup(1, surfaces_at(0, 0, 1, 0, 1, 1, 1), name="crest_line")
gmsh.model.addPhysicalGroup(0, surfaces_at(0, 0, 0, 0, 0, 0, 0), name="origin")
gmsh.model.mesh.generate(3)

gmsh.option.setNumber("Mesh.Binary", 0)
gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
gmsh.write("gmsh_box_v41.msh")
gmsh.option.setNumber("Mesh.MshFileVersion", 2.2)
gmsh.write("gmsh_box_v22.msh")
gmsh.finalize()
