"""The length Problem 2 meshes the flattened plane at (Section 4, steps 3-4), and how refusals name it.

It is the caller's l (the paper's), or under sound joints ``(1 + D) l`` when
the mesh remapped at l lacks area
(:func:`~equimesh.surface.optimize.joints.joint_spacing`; docs/decisions.md,
"Sound joints").  A refusal of steps 3-4 compares a length on the flattened
surface with that spacing; it names it as ``l = 5``, or as ``the spacing
1.012 l = 5.06 meshed for sound joints (l = 5)``, and suggests a bound on the
caller's l, not on the spacing.
"""

from dataclasses import dataclass

import numpy as np

from ..errors import number


@dataclass(frozen=True)
class PlaneLength:
    """Problem 2's spacing ``value = l * factor`` of the caller's ``l``: ``factor`` 1, or ``1 + D`` for sound joints.

    Attributes
    ----------
    l : float
        The caller's target length.
    factor : float
        The spacing over ``l``, at least 1.
    """

    l: float
    factor: float = 1.0

    @classmethod
    def of(cls, l):
        """``l`` itself if a :class:`PlaneLength`, else the caller's float ``l`` meshed at itself."""
        return l if isinstance(l, cls) else cls(float(l))

    @property
    def value(self):
        """The spacing, ``l * factor`` (``l`` exactly at factor 1)."""
        return self.l * self.factor

    @property
    def symbol(self):
        """``l``, or ``1.012 l``: the spacing in a sentence comparing with it ("parts of at least 1.012 l")."""
        return "l" if self.factor == 1.0 else f"{number(self.factor, 4)} l"

    def __str__(self):
        """``l = 5``, or ``the spacing 1.012 l = 5.06 meshed for sound joints (l = 5)``."""
        text = f"{self.symbol} = {number(self.value)}"
        return text if self.factor == 1.0 else f"the spacing {text} meshed for sound joints (l = {number(self.l)})"

    def suggest(self, bound):
        """The caller's l to suggest for a spacing of at most ``bound`` (rounded down already): ``bound`` at factor 1,
        else ``bound / factor`` rounded down (a hint: the factor is the one at this l)."""
        return bound if self.factor == 1.0 else round_down(bound / self.factor)


def round_down(x, digits=4):
    """``x`` rounded down to ``digits`` significant digits, so that a suggested bound ``l <= x`` is safe."""
    if x <= 0:
        return 0.0
    scale = 10.0 ** (np.floor(np.log10(x)) - digits + 1)
    return float(np.floor(x / scale) * scale)
