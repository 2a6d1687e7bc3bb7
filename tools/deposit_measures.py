"""Measures of how far a deposit spread that rest on its mass, not on its
outermost points: the mass centroid and the mass quantiles along x.

A deposit's extent (its farthest point, or the last bin holding a point)
depends on the resolution: finer points make thinner tongues and single
points thrown ahead. The centroid of the reference volumes V0 (the mass
over the density) and the x below which a fraction f of them lies do not
count a thin front more because it is resolved.
"""


def mass_centroid_x(xs, v0s):
    """Centroid along x of the points weighted by their reference volume."""
    total = sum(v0s)
    return sum(x * v for x, v in zip(xs, v0s)) / total


def mass_quantile_x(xs, v0s, fraction):
    """The smallest point x such that the points at or left of it hold at
    least @p fraction of the total reference volume."""
    total = sum(v0s)
    held = 0.0
    for x, v in sorted(zip(xs, v0s)):
        held += v
        if held >= fraction * total * (1 - 1e-12):
            return x
    return max(xs)
