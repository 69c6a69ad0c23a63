# Chunk-averaged data for fix 4 and group all
# Timestep Number-of-chunks Total-count
# Chunk Coord1 Ncount vx
200 8 288
  1 0.0625 36.6 0.388939
  2 0.1875 38.6 1.719
  3 0.3125 31.3 2.45979
  4 0.4375 34.2 3.44194
  5 0.5625 37.1 4.44245
  6 0.6875 36.7 5.55311
  7 0.8125 35.2 6.7348
  8 0.9375 38.3 7.58783
