"""Two touching surfaces' friction and bounce combined as ODE combines them, on pybullet.

Gazebo's ODE gives a contact the smaller ``mu`` (and the smaller bounce) of its two
surfaces; Bullet multiplies the two bodies' ``lateralFriction`` (and ``restitution``) and
lets no one choose per pair. So before each step the links that touch (pybullet's contacts
of the step before) get values whose products are the pairs' minimums: with x = log f,
``x_a + x_b = log min(mu_a, mu_b)`` for every touching pair, solved by least squares. That
is exact for any contact graph without cycles (a box on a table between two fingers) and for
a cycle of odd length; an even cycle of unequal surfaces is the best fit. A link touching
nothing keeps sqrt(mu): a new contact of equal surfaces is right from its first step, one of
unequal surfaces from its second. Bullet caps a pair's friction at 10.
"""

from __future__ import annotations

import math
from typing import Dict, FrozenSet, List, Tuple

import numpy as np
import pybullet as p

Part = Tuple[int, int]  # (body, link index; -1 the base)
# Fields of pybullet's lateralFriction and restitution, and their getDynamicsInfo indices.
FIELDS = (('lateralFriction', 1), ('restitution', 5))
# Weight of each link's own sqrt(mu) against the pairs' equations: a hint, never a compromise.
PRIOR = 1e-6


class SurfaceCombiner:
    """Each link's (friction, restitution) as its surface says, and per step the values that
    make pybullet's products ODE's minimums for the pairs in contact."""

    def __init__(self, client: int) -> None:
        self.client = client
        self.values: Dict[Part, Tuple[float, float]] = {}  # the surfaces' (mu, bounce)
        self.applied: Dict[Part, Tuple[float, float]] = {}  # what pybullet has now
        self.pairs: FrozenSet[Tuple[Part, Part]] = frozenset()

    def add(self, body: int, link: int, mu: float, restitution: float) -> None:
        part = (body, link)
        self.values[part] = (mu, restitution)
        self._apply(part, (math.sqrt(mu), math.sqrt(restitution)))

    def forget(self, body: int) -> None:
        """A removed body's links."""
        for part in [k for k in self.values if k[0] == body]:
            del self.values[part]
            self.applied.pop(part, None)
        self.pairs = frozenset(pair for pair in self.pairs if body not in (pair[0][0], pair[1][0]))

    def update(self) -> None:
        """Values for the pairs touching now; nothing to do while they stay the same."""
        contacts = p.getContactPoints(physicsClientId=self.client)
        if not contacts and not self.pairs:
            return  # nothing touches, as before (most steps of an arm in the air)
        pairs = set()
        for c in contacts:
            a, b = (c[1], c[3]), (c[2], c[4])
            if a in self.values and b in self.values:
                pairs.add((a, b) if a <= b else (b, a))
        current = frozenset(pairs)
        if current == self.pairs:
            return
        self.pairs = current
        touching = {part for pair in current for part in pair}
        wanted = {part: (math.sqrt(mu), math.sqrt(r)) for part, (mu, r) in self.values.items()}
        if current:
            solved = [solve(current, {k: self.values[k][i] for k in touching}) for i in (0, 1)]
            for part in touching:
                wanted[part] = (solved[0][part], solved[1][part])
        for part, value in wanted.items():
            if self.applied.get(part) != value:
                self._apply(part, value)

    def _apply(self, part: Part, value: Tuple[float, float]) -> None:
        # Its own call: with linearDamping in the same changeDynamics, pybullet drops a link's
        # lateralFriction without a word.
        for (name, _), v in zip(FIELDS, value):
            p.changeDynamics(part[0], part[1], physicsClientId=self.client, **{name: v})
        self.applied[part] = value


def solve(pairs: FrozenSet[Tuple[Part, Part]], mu: Dict[Part, float]) -> Dict[Part, float]:
    """Per-part factors whose product over each pair is the pair's smaller ``mu``
    (least squares in log space, each part held weakly to sqrt of its own)."""
    out: Dict[Part, float] = {}
    zero = {k for k, v in mu.items() if v <= 0.0}  # a zero factor makes any product its min, 0
    for k in zero:
        out[k] = 0.0
    parts = sorted(k for k in mu if k not in zero)
    index = {k: i for i, k in enumerate(parts)}
    rows: List[List[float]] = []
    rhs: List[float] = []
    for a, b in sorted(pairs):
        if a in zero or b in zero:
            continue
        row = [0.0] * len(parts)
        row[index[a]] += 1.0  # a link touching itself (never here) would count twice
        row[index[b]] += 1.0
        rows.append(row)
        rhs.append(math.log(min(mu[a], mu[b])))
    for k in parts:
        row = [0.0] * len(parts)
        row[index[k]] = PRIOR
        rows.append(row)
        rhs.append(PRIOR * 0.5 * math.log(mu[k]))
    if parts:
        x = np.linalg.lstsq(np.array(rows), np.array(rhs), rcond=None)[0]
        for k, v in zip(parts, x):
            out[k] = math.exp(float(v))
    return out
