"""What a result is worth: its estimated discretisation errors and the warnings a user should read.

Workflow (every :func:`bem.solve` runs it; docs/theory.md §13):

1. indicators of the solution's own resolution, from its pressure, heights, material and
   speed (:mod:`.indicators`: contact perimeter, near-Nyquist dissipation, peak sharpness,
   sub-cell leading-edge layers, points per wavelength, the friction forms' gap);
2. the estimated relative error of ``friction``, ``contact_fraction`` and ``peak_pressure``
   against the same surface content on a grid twice as fine (:mod:`.estimate`), or that error
   measured by solving it (:mod:`.refined`, ``error_estimate="refined"``);
3. the findings, plain sentences saying what to change (:mod:`.findings`), gathered over the
   points of a sweep by :func:`.findings.gather`;
4. :func:`.assess.assess` puts the estimate and the findings on the result.
"""

from .estimate import QUANTITIES, ErrorEstimate
from .findings import Finding, gather

__all__ = ["QUANTITIES", "ErrorEstimate", "Finding", "gather"]
