"""Exact and independent reference solutions, as plain functions (SI units).

Each module states its problem, its conventions and its source:

1. elastic contact: Hertz (:mod:`.hertz`), Westergaard's periodic sinusoid (:mod:`.westergaard`),
   and a dense direct solve of the periodic problem with the exact full-contact Fourier solution
   (:mod:`.periodic_exact`);
2. viscoelastic: Hunter's rolling cylinder on a standard linear solid (:mod:`.hunter`), checked
   by a brute-force collocation (:mod:`.bruteforce_line`), and Lee & Radok's creep indentation
   (:mod:`.lee_radok`);
3. the validation cases (:mod:`validation.cases`) compare every solver with these.
"""
