"""Inputs by construction, shared by the tests, the experiments and the benchmarks.

* :mod:`.generators`  convex polygons with inner angles >= 90 degrees (valid inputs of Problem 1);
* :mod:`.shapes`      non-convex polygons for Problem 2 (orthogonal, letters, stars, flattened squares).
"""
