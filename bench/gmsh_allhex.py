#!/usr/bin/python3
"""Gmsh's automatic all-hex mesh of a CAD file: tetrahedra split into hexahedra
(Mesh.SubdivisionAlgorithm=2, Mesh.RecombineAll=1). The baseline VoroHex is compared with.

usage: gmsh_allhex.py IN.step OUT.msh SIZE
"""
import sys

import gmsh

src, out, size = sys.argv[1], sys.argv[2], float(sys.argv[3])
gmsh.initialize(["-noenv"])
gmsh.option.setNumber("General.Terminal", 0)
gmsh.option.setNumber("General.NumThreads", 1)
gmsh.model.occ.importShapes(src)
gmsh.model.occ.synchronize()
# The subdivision halves every edge, so mesh at twice the size to get edges near SIZE.
gmsh.option.setNumber("Mesh.MeshSizeMin", 2 * size)
gmsh.option.setNumber("Mesh.MeshSizeMax", 2 * size)
gmsh.option.setNumber("Mesh.SubdivisionAlgorithm", 2)
gmsh.option.setNumber("Mesh.RecombineAll", 1)
gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
gmsh.model.mesh.generate(3)
gmsh.write(out)
gmsh.finalize()
