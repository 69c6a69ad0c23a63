"""Read dmhs' .vtu files with meshio (run by tests/output_formats.rs): points and fields."""
import sys

import meshio
import numpy as np

m = meshio.read(sys.argv[1])
n = int(sys.argv[2])
assert m.points.shape == (n, 3), m.points.shape
for name in sys.argv[3:]:
    assert name in m.point_data, (name, list(m.point_data))
    assert len(m.point_data[name]) == n
assert len(m.cells) == 1 and m.cells[0].type == "vertex" and len(m.cells[0].data) == n
print("meshio reads", n, "points with", sorted(m.point_data))
print("VTU OK")
