"""How strong the property tests are: mutation testing of the algorithm modules with mutmut.

For each module of :data:`~tools.mutation.modules.MODULES` mutmut makes small changes to the code (an
operator, a constant, a comparison), one at a time, and runs the tests selected for that module.  A mutant is
*killed* when a test fails, *survived* when every test passes.  A survivor is either a gap in the tests
(then a test is added that kills it) or an *equivalent* mutant that no test can kill, argued in
``equivalent.toml``; the report lists every survivor with its argument or flags it as a missing test.

``modules``     what is mutated, against which test files (and the kernels' environment)
``mutants``     the mutants of a module as mutmut makes them, in process, each keyed by its statement before
                and after the mutation, normalised so that formatting does not count
``equivalent``  the arguments of ``equivalent.toml`` and the matching of survivors to them; the orphan check
``run``         running mutmut on a module, or on some of its functions, in a scratch copy (``.mutation/``)
``report``      ``results/mutation.md`` and ``results/mutation.json`` with provenance
``carry``       a row measured before a module moved or was reformatted, carried if the code is the same

Run ``python -m tools.mutation --help`` (or ``make mutation``) from the repository's root; mutmut comes
from the ``[mutation]`` extra.
"""
