"""The planar algorithms of the paper: Problem 1 (Section 2) and Problem 2 (Section 3).

Subpackages and modules, in the order of the data flow:

* :mod:`.polygon`    validation of the input polygon against the problem's assumptions;
* :mod:`.boundary`   Step 2, the boundary points (staggered at sharp corners) and Lemma 3 (1);
* :mod:`.insertion`  farthest-point (Voronoi) insertion under visibility distance with a
                     constrained Delaunay triangulation; the engines (``ENGINES``);
* :mod:`.increment`  Problem 1, Algorithm INCREMENT (Theorems 1 and 2);
* :mod:`.bounds`     bounds on the optimal node count (checks Theorem 2);
* :mod:`.lattice`    Problem 2, the triangular lattice part H' kept clear of the boundary
                     (:mod:`.clearance` decides the clearance row by row);
* :mod:`.strip`      Problem 2 end to end: lattice part plus boundary strip (Theorem 3);
* :mod:`.placement`  beyond the paper: the lattice angle and offset with the most G1 edges;
* :mod:`.limits`     the size guard shared by the planar verbs and the surface pipeline;
* :mod:`.guarantees` Theorems 1 and 3 checked on every returned mesh.

The public verbs are re-exported by :mod:`equimesh`.
"""
