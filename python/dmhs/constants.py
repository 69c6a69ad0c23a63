"""The constants of LAMMPS' Python module (``lammps.constants``), same names and values."""

# data types (extract_global/extract_atom dtype)
LAMMPS_AUTODETECT = None
LAMMPS_NONE = -1
LAMMPS_INT = 0
LAMMPS_INT_2D = 1
LAMMPS_DOUBLE = 2
LAMMPS_DOUBLE_2D = 3
LAMMPS_INT64 = 4
LAMMPS_INT64_2D = 5
LAMMPS_STRING = 6

# extract_compute / extract_fix styles and types
LMP_STYLE_GLOBAL = 0
LMP_STYLE_ATOM = 1
LMP_STYLE_LOCAL = 2
LMP_TYPE_SCALAR = 0
LMP_TYPE_VECTOR = 1
LMP_TYPE_ARRAY = 2
LMP_SIZE_VECTOR = 3
LMP_SIZE_ROWS = 4
LMP_SIZE_COLS = 5

# error levels (lammps.error)
LMP_ERROR_WARNING = 0
LMP_ERROR_ONE = 1
LMP_ERROR_ALL = 2
LMP_ERROR_WORLD = 4
LMP_ERROR_UNIVERSE = 8

# extract_variable types
LMP_VAR_EQUAL = 0
LMP_VAR_ATOM = 1
LMP_VAR_VECTOR = 2
LMP_VAR_STRING = 3

LMP_BUFSIZE = 1024
LMP_MAX_GROUP = 32
