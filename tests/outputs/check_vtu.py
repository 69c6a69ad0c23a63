"""Read dmhs' .vtu files with meshio (run by tests/output_formats.rs): points and fields."""
import sys

import meshio
import numpy as np

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
print("VTU OK")
