# FreeCAD FemMesh conversion for VoroHex: node orders between VTK and SMESH (FreeCAD's
# FemMesh), node groups per CAD entity, and the FemMesh of a core mesh. Used by VoroHex.py
# (MeshResult.to_femmesh, from_femmesh) and VoroHexObjects.py (the document object's mesh).
import contextlib
import ctypes
import os
import sys
from array import array

# VTK hex order -> SMESH (FreeCAD FemMesh) order; the permutation is its own inverse.
SMESH_FROM_VTK = (0, 3, 2, 1, 4, 7, 6, 5)
# The same for 20-node hexahedra (VTK_QUADRATIC_HEXAHEDRON -> SMESH's quadratic hexa): the
# corners as above, then SMESH's mid-edge nodes of its edges 1-2 2-3 3-4 4-1, 5-6 6-7 7-8
# 8-5, 1-5 2-6 3-7 4-8, which are VTK's edges 3-0 2-3 1-2 0-1, 7-4 6-7 5-6 4-5, 0-4 3-7 2-6
# 1-5. FreeCAD's CalculiX writer turns it into a positive C3D20 (tests/python checks it).
SMESH_FROM_VTK20 = SMESH_FROM_VTK + (11, 10, 9, 8, 15, 14, 13, 12, 16, 19, 18, 17)


def vtk_cells(hexes, mid):
    """Per hexahedron its 8 (or, with mid-edge nodes, 20) 0-based node indices, VTK order;
    hexes and mid are flat int32 sequences (8 and 12 per hex; mid empty for first order)."""
    n = len(hexes) // 8
    if not mid:
        return [hexes[8 * e:8 * e + 8] for e in range(n)]
    return [list(hexes[8 * e:8 * e + 8]) + list(mid[12 * e:12 * e + 12]) for e in range(n)]


def smesh_nodes(cell):
    """1-based FemMesh node ids of a VTK-order cell (8 or 20 nodes), in SMESH order."""
    order = SMESH_FROM_VTK20 if len(cell) == 20 else SMESH_FROM_VTK
    return [cell[k] + 1 for k in order]


@contextlib.contextmanager
def quiet_stdout():
    """Standard output (the process's, file descriptor 1) sent to the null device for the
    block: FreeCAD's FemMesh.addGroup and addGroupElements print two lines per group to the C++
    standard output, about 200 lines for a part of 90 faces, edges and vertices. Where the
    descriptor cannot be duplicated, nothing is changed."""
    fd = 1  # where C++'s std::cout writes, whatever Python's sys.stdout is
    try:
        if sys.stdout is not None:
            sys.stdout.flush()
        saved = os.dup(fd)
    except (AttributeError, OSError, ValueError):
        yield
        return
    try:
        libc = ctypes.CDLL(None)
    except OSError:
        libc = None
    null = os.open(os.devnull, os.O_WRONLY)
    try:
        os.dup2(null, fd)
        yield
    finally:
        if libc is not None:
            libc.fflush(None)  # what C stdio buffered goes to the null device, not after it
        os.dup2(saved, fd)
        os.close(saved)
        os.close(null)


def add_groups(fm, groups):
    """Adds one node group per CAD entity (name "Face7", ...) to a Fem.FemMesh; groups:
    [(name, 0-based node indices)]."""
    with quiet_stdout():
        for name, nodes in groups:
            gid = fm.addGroup(name, "Node")
            fm.addGroupElements(gid, [int(n) + 1 for n in nodes])


def femmesh_of(core_mesh, groups=()):
    """A Fem.FemMesh of a _VoroHexCore.HexMesh (SMESH node order, 1-based ids), with `groups`."""
    import Fem

    fm = Fem.FemMesh()
    nodes = array("d", core_mesh.node_bytes())
    for i in range(len(nodes) // 3):
        fm.addNode(nodes[3 * i], nodes[3 * i + 1], nodes[3 * i + 2], i + 1)
    cells = vtk_cells(array("i", core_mesh.hex_bytes()), array("i", core_mesh.mid_edge_bytes()))
    for e, cell in enumerate(cells):
        fm.addVolume(smesh_nodes(cell), e + 1)
    add_groups(fm, groups)
    return fm
