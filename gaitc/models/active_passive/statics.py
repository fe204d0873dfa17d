"""The two static problems of the active/passive model (thesis 4.2.2).

Passive states: "a minimum-energy optimization problem ... that minimizes the height of the
center of gravity of the robot but constrains the boundaries of the actuators to remain above
the ground", with the passive hinges held within their bounds.  Here the energy is the CG
height plus the (optional) elastic energy of the passive variables, scaled by the weight;
solved with SLSQP inside a trust region, with the derivatives of
:meth:`Kinematics.heights` (exact but for the twists).
Normal loads ("Robot Angular Momentum"): the minimum average vertex load satisfying the static
force and moment balance over the vertices within ε of the ground; read as the least-squares
(most even) loads N ≥ 0 with ΣN = Mg and zero moment about the centre of gravity.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import minimize, nnls

from gaitc.models.active_passive.kinematics import GRAVITY, Kinematics, Posture, Prepared

Array = NDArray[np.float64]

_BALANCE = 1e4  # weight of the balance rows against the evenness rows in the NNLS
_LEVER = 100.0  # mm; scales the moment rows
_TRUST = 0.15  # rad: the largest change of a passive angle in one SLSQP run
_MOVES = 8  # SLSQP runs per solve, each recentred on the last
_FTOL = 1e-5  # mm of CG height; 1e-7 took 70 % more evaluations for the same motion


@dataclass(frozen=True)
class Rest:
    """A solved posture: passive variables x, its wireframe and centres, and solver facts."""

    x: Array
    posture: Posture
    energy: float  # CG height plus elastic energy over the weight, mm
    iterations: int
    converged: bool


class RestSolver:
    """Finds the passive state of minimum energy for given active states."""

    def __init__(self, kinematics: Kinematics) -> None:
        self.kin = kinematics
        self.weight = float(kinematics.masses.sum()) * GRAVITY
        self._bounds = kinematics.bounds()
        self._stiffness = np.array([p.stiffness for p in kinematics.passive])
        self.evaluations = 0

    def _batch(self, active: Prepared, x: Array) -> tuple[Array, Array]:
        """Energy/weight and its gradient (n + 1,), vertex heights and their Jacobian
        (n + 1, V), from :meth:`Kinematics.heights`."""
        self.evaluations += 1
        vz, cz, jv, jc = self.kin.heights(active, x)
        masses = self.kin.masses
        total = float(masses.sum())
        energy = float(masses @ cz) / total + float(self.kin.elastic(x[None])[0]) / self.weight
        grad = masses @ jc / total
        grad[3:] += self._stiffness * x[3:] / self.weight
        return np.concatenate([[energy], grad]), np.vstack([vz, jv.T])

    def solve(self, active: Array, start: Array) -> Rest:
        """The rest posture, warm-started from ``start`` (its height is made feasible first)."""
        prepared = self.kin.prepare(active)
        low_b = np.array([b[0] if b[0] is not None else -np.inf for b in self._bounds])
        high_b = np.array([b[1] if b[1] is not None else np.inf for b in self._bounds])
        x0 = np.clip(np.array(start, dtype=float), low_b, high_b)
        low = self.kin.posture(prepared, x0[None])
        x0[0] -= float(low.vertices[0, :, 2].min())
        cache: dict[bytes, tuple[Array, Array]] = {}

        def values(x: Array) -> tuple[Array, Array]:
            key = x.tobytes()
            if key not in cache:
                cache.clear()
                energy, heights = self._batch(prepared, x)
                cache[key] = (energy, heights)
            return cache[key]

        def fun(x: Array) -> float:
            return float(values(x)[0][0])

        def grad(x: Array) -> Array:
            out: Array = values(x)[0][1:]
            return out

        def cons(x: Array) -> Array:
            out: Array = values(x)[1][0]
            return out

        def cons_jac(x: Array) -> Array:
            out: Array = values(x)[1][1:].T
            return out

        x, iterations, ok = x0, 0, True
        for _ in range(_MOVES):  # a trust region: the posture deforms continuously
            low, high = np.maximum(low_b, x - _TRUST), np.minimum(high_b, x + _TRUST)
            low[0], high[0] = -np.inf, np.inf
            result = minimize(
                fun,
                x,
                jac=grad,
                method="SLSQP",
                bounds=list(zip(low, high, strict=True)),
                constraints=[{"type": "ineq", "fun": cons, "jac": cons_jac}],
                options={"maxiter": 200, "ftol": _FTOL},
            )
            iterations += int(result.nit)
            # status 8: the line search cannot improve x at the solver's precision
            ok = bool(result.success or result.status == 8)
            edge = ((np.abs(result.x - low) < 1e-9) & (low > low_b)) | (
                (np.abs(result.x - high) < 1e-9) & (high < high_b)
            )
            x = np.clip(result.x, low_b, high_b)
            if not edge.any():
                break
        posture = self.kin.posture(prepared, x[None])
        lowest = float(posture.vertices[0, :, 2].min())
        if lowest != 0.0:  # SLSQP ends within its tolerance: set the robot onto the ground
            x[0] -= lowest
            lift = np.array([0.0, 0.0, -lowest])
            posture = Posture(posture.vertices + lift, posture.centres + lift)
        cg = float(posture.centres[0, :, 2] @ self.kin.masses) / float(self.kin.masses.sum())
        energy = cg + float(self.kin.elastic(x[None])[0]) / self.weight
        return Rest(x, posture, energy, iterations, ok)

    def lowest(self, active: Array, spread: float = 0.2) -> Rest:
        """The lowest-energy rest found from the flat posture and from each passive variable
        (twists, hinges) started ``spread`` rad to either side: the contact problem has
        several local minima (a leg pair may rest on either side of its hinge)."""
        n = self.kin.size
        starts = [np.zeros(n)]
        for i in range(3, n):
            for sign in (-1.0, 1.0):
                start = np.zeros(n)
                start[i] = sign * spread
                starts.append(start)
        rests = [self.solve(active, start) for start in starts]
        return min(rests, key=lambda rest: rest.energy)  # the first of equals: deterministic


def normal_loads(points: Array, centre: Array, weight: float, tolerance: float) -> Array:
    """Loads on every vertex (zero off the ground) for vertices ``points`` (V, 3).

    Minimises Σ N² subject to ΣN = weight, Σ N (x − c_x) = Σ N (y − c_y) = 0 and N ≥ 0,
    over the vertices with z ≤ lowest + tolerance; when the centre lies outside their hull
    the balance is met in the least-squares sense.
    """
    heights = points[:, 2]
    touching = np.flatnonzero(heights <= heights.min() + tolerance)
    d = (points[touching, :2] - centre[None, :2]) / _LEVER
    a = np.vstack([np.ones(touching.size), d[:, 0], d[:, 1]])
    b = np.array([1.0, 0.0, 0.0])
    system = np.vstack([_BALANCE * a, np.eye(touching.size)])
    target = np.concatenate([_BALANCE * b, np.zeros(touching.size)])
    share, _ = nnls(system, target)
    total = share.sum()
    loads = np.zeros(points.shape[0])
    loads[touching] = weight * share / (total if total > 0 else 1.0)
    return loads
