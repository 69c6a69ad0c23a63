"""Read dmhs' .vtu files with meshio and with VTK's own XML reader (run by tests/output_formats.rs):
points and fields, and both readers give the same values."""
import sys

import meshio
import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader

m = meshio.read(sys.argv[1])
n = int(sys.argv[2])
assert m.points.shape == (n, 3), m.points.shape
for arg in sys.argv[3:]:
    # NAME or NAME:COMPONENTS
    name, _, comps = arg.partition(":")
    assert name in m.point_data, (name, list(m.point_data))
    a = np.asarray(m.point_data[name])
    assert len(a) == n, (name, a.shape)
    if comps:
        assert a.shape == (n, int(comps)), (name, a.shape)
if "id" in m.point_data:
    assert np.issubdtype(np.asarray(m.point_data["id"]).dtype, np.integer), m.point_data["id"].dtype
assert len(m.cells) == 1 and m.cells[0].type == "vertex" and len(m.cells[0].data) == n
print("meshio reads", n, "points with", sorted(m.point_data))

# VTK's reader (what ParaView uses): same points, same arrays, integer ids
r = vtkXMLUnstructuredGridReader()
r.SetFileName(sys.argv[1])
r.Update()
assert r.GetErrorCode() == 0, r.GetErrorCode()
g = r.GetOutput()
assert g.GetNumberOfPoints() == n and g.GetNumberOfCells() == n, (g.GetNumberOfPoints(), g.GetNumberOfCells())
assert np.array_equal(vtk_to_numpy(g.GetPoints().GetData()), m.points)
pd = g.GetPointData()
names = sorted(pd.GetArrayName(k) for k in range(pd.GetNumberOfArrays()))
assert names == sorted(m.point_data), (names, sorted(m.point_data))
for name in names:
    a = vtk_to_numpy(pd.GetArray(name))
    b = np.asarray(m.point_data[name])
    assert np.array_equal(a, b.reshape(a.shape)), name
if "id" in names:
    assert pd.GetArray("id").GetDataTypeAsString() in ("long", "long long", "vtkIdType"), pd.GetArray("id").GetDataTypeAsString()
print("VTK reads", n, "points with", names)
print("VTU OK")
