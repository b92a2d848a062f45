"""Inputs by construction, shared by the tests and the experiments (the benchmarks freeze their own).

* :mod:`.generators`  convex polygons with inner angles >= 90 degrees (valid inputs of Problem 1);
* :mod:`.shapes`      non-convex polygons for Problem 2 (orthogonal, letters, stars, flattened squares);
* :mod:`.surfaces`    Bezier patches for Section 4 (the mildly curved dome of the "bounded" sweep);
* :mod:`.meshes`      triangle meshes of roofs (the triangle-mesh input of Section 4);
* :mod:`.benchmark`   the benchmark set: five surfaces with their l, on which any mesher is compared
  (``BENCHMARK``, ``triangle_mesh``; docs/benchmark.md).
"""
