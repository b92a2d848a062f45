"""Developer tools that are not results: mutation testing of the algorithm modules (:mod:`tools.mutation`)."""
