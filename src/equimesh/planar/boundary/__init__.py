"""Step 2 of Algorithm INCREMENT: points on the boundary of P, every part in [l, 2l] (Sections 2 and 3).

* :mod:`.resample`    the resampled boundary of a polygon (:func:`~.resample.resample_boundary`);
* :mod:`.sides`       where the points of each side lie: the paper's equal split
                      (:func:`~.sides.split_counts`), staggered next to corners sharper than
                      :data:`~.sides.SHARP_CORNER`, short sides and sharp corners placed jointly;
* :mod:`.corner`      one sharp corner decided on a grid (a search and a proof);
* :mod:`.chain`       sharp corners in a row decided jointly on a grid;
* :mod:`.phase`       beyond the paper: straight sides along or across the lattice at its period, in phase with
                      its first row (:func:`~.phase.in_phase`), so the strip repeats;
* :mod:`.separation`  Lemma 3 (1) checked on the resampled boundary, and what a refusal proves.
"""
