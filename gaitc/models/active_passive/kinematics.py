"""Forward kinematics of an active/passive robot: wireframe vertices and masses in space.

Thesis 4.1.2: f_c places the contact points (wireframe vertices) and f_m the centre of mass
of every component as a function of its state; the mounting connections chain the
component frames, T_to = T_from · F_f(p_f) · Trans(d) · R · Hinge(q) · Trans(−p_t).
The passive variables x = (z, roll, pitch, twists..., hinges...) place the root component
above the ground of a heading frame (the root's ground projection, aligned with its yaw).
Everything is evaluated for a batch of x at once; :meth:`Kinematics.heights` adds the
derivatives of the heights (exact for rotations, central differences for twists).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from gaitc.models.active_passive.frenet import segment
from gaitc.models.active_passive.robot import (
    ActivePassiveRobot,
    Component,
    Connection,
    PassiveRange,
)

Array = NDArray[np.float64]

GRAVITY = 9810.0  # mm/s²
ROOT_VARIABLES = ("height", "roll", "pitch")
_SHAPES = 4096  # actuator shapes kept between postures
_X, _Y = np.array([1.0, 0.0, 0.0]), np.array([0.0, 1.0, 0.0])
_TWIST_STEP = 1e-5  # rad of total twist, for central differences


@dataclass(frozen=True)
class Posture:
    """A batch of robot postures: vertices (B, V, 3), component centres of mass (B, C, 3)."""

    vertices: Array
    centres: Array


def _axis_rotation(axis: Array, angle: Array) -> Array:
    """Rotations about a unit axis, one per angle: (B, 3, 3) (Rodrigues)."""
    key = axis.tobytes()
    if key not in _SKEWS:
        k = np.array([[0.0, -axis[2], axis[1]], [axis[2], 0.0, -axis[0]], [-axis[1], axis[0], 0.0]])
        _SKEWS[key] = (k, k @ k)
    k, k2 = _SKEWS[key]
    out: Array = _EYE + np.sin(angle)[:, None, None] * k + (1.0 - np.cos(angle))[:, None, None] * k2
    return out


_SKEWS: dict[bytes, tuple[Array, Array]] = {}
_EYE = np.eye(3)


@dataclass(frozen=True)
class Prepared:
    """What one set of active states fixes: each rigid group's vertices and centres of mass
    in its head's frame, and the frames (R, p) at which children hang off static members."""

    active: Array
    vertices: dict[str, Array]  # head -> (V, 3)
    centres: dict[str, Array]  # head -> (C, 3)
    anchors: dict[str, tuple[Array, Array]]  # link target -> anchor frame in its head frame


class Kinematics:
    """Forward kinematics of one robot; ``active`` is (A, 3): each actuator's curvature
    vector (κ cos φ, κ sin φ) and its active torsion, in the order of :attr:`actuators`.

    Components that no passive variable moves relative to each other form a rigid group
    under a head (the root, a hinge's child, a twisting actuator and its children), so that
    :meth:`posture` only chains the heads.  Vertices, centres and :attr:`masses` are listed
    group by group (:attr:`order` gives the component of each centre).
    """

    def __init__(self, robot: ActivePassiveRobot) -> None:
        self.robot = robot
        self.actuators = tuple(c.name for c in robot.components if c.is_actuator)
        comps = {c.name: c for c in robot.components}
        twisting = [c for c in robot.components if c.torsion is not None]
        self.passive: tuple[PassiveRange, ...] = tuple(
            c.torsion for c in twisting if c.torsion is not None
        ) + tuple(j.joint for j in robot.connections if j.joint is not None)
        self.size = len(ROOT_VARIABLES) + len(self.passive)
        self._twist_index = {c.name: len(ROOT_VARIABLES) + i for i, c in enumerate(twisting)}
        joints = [j for j in robot.connections if j.joint is not None]
        first_joint = len(ROOT_VARIABLES) + len(twisting)
        self._joint_index = {j.target: first_joint + i for i, j in enumerate(joints)}
        self._incoming = {j.target: j for j in robot.connections}
        self.head: dict[str, str] = {}
        for c in robot.components:
            link = self._incoming.get(c.name)
            # a new rigid group starts at the root, at a hinge, at a twisting actuator and
            # at whatever hangs off one
            moved = c.name in self._twist_index
            if link is None or link.joint is not None or moved or link.source in self._twist_index:
                self.head[c.name] = c.name
            else:
                self.head[c.name] = self.head[link.source]
        self.heads = tuple(dict.fromkeys(self.head.values()))
        self.order = tuple(c for h in self.heads for c in comps if self.head[c] == h)
        self.masses = np.array([comps[n].mass for n in self.order])
        self.friction = np.concatenate(
            [
                np.tile(np.array(comps[n].friction), comps[n].stations)
                if comps[n].is_actuator
                else np.array(comps[n].friction)
                for n in self.order
            ]
        )
        # backbone samples: the wireframe stations plus the arc lengths that anchor children
        self._samples: dict[str, Array] = {}
        self._vertex_rows: dict[str, NDArray[np.intp]] = {}
        self._anchor_rows: dict[str, int] = {}
        self._sections: dict[str, Array] = {}
        for c in robot.components:
            if not c.is_actuator:
                continue
            stations = np.linspace(0.0, c.length, c.stations)
            arcs = [j.arc for j in robot.connections if j.source == c.name and j.arc is not None]
            samples = np.unique(np.concatenate([stations, np.array(arcs, dtype=float)]))
            self._samples[c.name] = samples
            self._vertex_rows[c.name] = np.searchsorted(samples, stations)
            self._sections[c.name] = np.array([[0.0, u, v] for u, v in c.section])
            for j in robot.connections:
                if j.source == c.name and j.arc is not None:
                    self._anchor_rows[j.target] = int(np.searchsorted(samples, j.arc))
        self._slots()
        self._links = {
            j.target: (np.array(j.offset), np.array(j.rotation), np.array(j.target_point))
            for j in robot.connections
        }
        self._axes = {j.target: np.array(j.axis) for j in robot.connections}
        self._shapes: dict[tuple[str, float, float, float], tuple[Array, Array, Array]] = {}

    def _slots(self) -> None:
        """Where each head's vertices and centres sit in the stacked points of a posture."""
        comps = {c.name: c for c in self.robot.components}
        group: list[int] = []
        vertex_slots: list[int] = []
        centre_slots: list[int] = []
        for i, head in enumerate(self.heads):
            members = [comps[n] for n in self.order if self.head[n] == head]
            nv = sum(
                len(c.section) * c.stations if c.is_actuator else len(c.wireframe) for c in members
            )
            start = len(group)
            vertex_slots += range(start, start + nv)
            centre_slots += range(start + nv, start + nv + len(members))
            group += [i] * (nv + len(members))
        self._group_of = np.array(group)
        self._subtree: dict[str, NDArray[np.intp]] = {}  # the points a hinge here turns
        for head in self.heads:
            below = []
            for i, other in enumerate(self.heads):
                walk: str | None = other
                while walk is not None and walk != head:
                    link = self._incoming.get(walk)
                    walk = link.source if link is not None else None
                if walk == head:
                    below.append(i)
            self._subtree[head] = np.flatnonzero(np.isin(self._group_of, below))
        self._vertex_slots = np.array(vertex_slots)
        self._centre_slots = np.array(centre_slots)

    def bounds(self) -> list[tuple[float | None, float | None]]:
        """Bounds of x: the height is free, roll and pitch within ±0.8 rad (46°)."""
        return [(None, None), (-0.8, 0.8), (-0.8, 0.8)] + [(p.lower, p.upper) for p in self.passive]

    def elastic(self, x: Array) -> Array:
        """The elastic energy ½ Σ k q² of the passive variables, (B,)."""
        k = np.array([p.stiffness for p in self.passive])
        q = x[:, len(ROOT_VARIABLES) :]
        energy: Array = 0.5 * (q * q) @ k
        return energy

    def _shape(self, comp: Component, active: Array, tau: Array) -> tuple[Array, Array, Array]:
        """Local vertices (B, V, 3), centre (B, 3) and sample frames of an actuator."""
        ky, kz, _ = active
        batch = tau.shape[0]
        points, sections, centre = segment(
            float(np.hypot(ky, kz)),
            float(np.arctan2(kz, ky)),
            tau,
            self._samples[comp.name],
            comp.length,
        )
        rows = self._vertex_rows[comp.name]
        across = np.swapaxes(sections[:, rows] @ self._sections[comp.name].T, -1, -2)
        local = points[:, rows, None, :] + across
        frames = np.concatenate([sections, points[..., None]], axis=-1)  # (B, S, 3, 4)
        return local.reshape(batch, -1, 3), centre, frames

    def _still(self, comp: Component, active: Array) -> tuple[Array, Array, Array]:
        """The shape of an actuator without passive twist (kept: legs often hold theirs)."""
        key = (comp.name, float(active[0]), float(active[1]), float(active[2]))
        if key not in self._shapes:
            if len(self._shapes) > _SHAPES:
                self._shapes.clear()
            local, centre, frames = self._shape(comp, active, np.array([active[2]]))
            self._shapes[key] = (local[0], centre[0], frames[0])
        return self._shapes[key]

    def prepare(self, active: Array) -> Prepared:
        """Everything the active states fix, for :meth:`posture`."""
        act = {name: active[i] for i, name in enumerate(self.actuators)}
        rel: dict[str, tuple[Array, Array]] = {}
        verts: dict[str, list[Array]] = {h: [] for h in self.heads}
        cents: dict[str, list[Array]] = {h: [] for h in self.heads}
        frames: dict[str, Array] = {}
        anchors: dict[str, tuple[Array, Array]] = {}
        for comp in self.robot.components:
            head = self.head[comp.name]
            if head == comp.name:
                rot, pos = np.eye(3), np.zeros(3)
            else:
                link = self._incoming[comp.name]
                prot, ppos = rel[link.source]
                arot, apos = self._anchor(link, frames)
                rot, pos = _link(prot @ arot, ppos + prot @ apos, link)
            rel[comp.name] = (rot, pos)
            if comp.name in self._twist_index:
                continue  # shaped per posture
            if comp.is_actuator:
                local, centre, frames[comp.name] = self._still(comp, act[comp.name])
            else:
                local, centre = np.array(comp.wireframe), np.array(comp.cg)
            verts[head].append(local @ rot.T + pos)
            cents[head].append(rot @ centre + pos)
        for j in self.robot.connections:
            if self.head[j.target] == j.target and j.source not in self._twist_index:
                prot, ppos = rel[j.source]
                arot, apos = self._anchor(j, frames)
                anchors[j.target] = (prot @ arot, ppos + prot @ apos)
        return Prepared(
            active,
            {h: np.concatenate(v) if v else np.zeros((0, 3)) for h, v in verts.items()},
            {h: np.array(c).reshape(-1, 3) for h, c in cents.items()},
            anchors,
        )

    def _anchor(self, link: Connection, frames: dict[str, Array]) -> tuple[Array, Array]:
        if link.arc is None:
            return np.eye(3), np.array(link.point)
        f = frames[link.source][self._anchor_rows[link.target]]
        return f[:, :3], f[:, 3]

    def posture(self, prep: Prepared | Array, x: Array) -> Posture:
        """Vertices and centres of mass in the heading frame for a batch ``x`` of shape (B, n)."""
        if not isinstance(prep, Prepared):
            prep = self.prepare(prep)
        placed, _, _ = self._place(prep, x)
        return Posture(placed[:, self._vertex_slots], placed[:, self._centre_slots])

    def heights(self, prep: Prepared, x: Array) -> tuple[Array, Array, Array, Array]:
        """Heights of the vertices (V,) and centres (C,) at one x, and their derivatives
        (V, n), (C, n): exact for the height and every rotation (∂p/∂q = a × (p − o)),
        central differences for the twists."""
        twists = sorted(self._twist_index.values())
        rows = [x]
        for j in twists:
            for sign in (1.0, -1.0):
                row = x.copy()
                row[j] += sign * _TWIST_STEP
                rows.append(row)
        placed, pitch, hinges = self._place(prep, np.array(rows))
        p0 = placed[0]
        jac = np.zeros((p0.shape[0], x.size))
        jac[:, 0] = 1.0
        rel = p0 - np.array([0.0, 0.0, x[0]])
        roll_axis = pitch[0] @ _X
        jac[:, 1] = roll_axis[0] * rel[:, 1] - roll_axis[1] * rel[:, 0]
        jac[:, 2] = -rel[:, 0]  # about +y
        for head, col in self._joint_index.items():
            axis, origin = hinges[head]
            below = self._subtree[head]
            d = p0[below] - origin[0]
            jac[below, col] = axis[0, 0] * d[:, 1] - axis[0, 1] * d[:, 0]
        for i, j in enumerate(twists):
            jac[:, j] = (placed[1 + 2 * i, :, 2] - placed[2 + 2 * i, :, 2]) / (2 * _TWIST_STEP)
        z = p0[:, 2]
        return (
            z[self._vertex_slots],
            z[self._centre_slots],
            jac[self._vertex_slots],
            jac[self._centre_slots],
        )

    def _place(
        self, prep: Prepared, x: Array
    ) -> tuple[Array, Array, dict[str, tuple[Array, Array]]]:
        """Every point of every head, placed; the pitch rotations; each hinge's axis and
        origin in the heading frame."""
        batch = x.shape[0]
        roll = _axis_rotation(_X, x[:, 1])
        pitch = _axis_rotation(_Y, x[:, 2])
        world: dict[str, tuple[Array, Array]] = {}
        hinges: dict[str, tuple[Array, Array]] = {}
        twisted: dict[str, Array] = {}
        points: list[Array] = []  # every head's vertices, then centres, in its own frame
        act = {name: prep.active[i] for i, name in enumerate(self.actuators)}
        for head in self.heads:
            link = self._incoming.get(head)
            if link is None:
                rot = pitch @ roll
                pos = np.zeros((batch, 3))
                pos[:, 2] = x[:, 0]
            else:
                if link.source in self._twist_index:
                    prot, ppos = world[link.source]
                    f = twisted[link.source][:, self._anchor_rows[head]]
                    arot, apos = f[:, :, :3], f[:, :, 3]
                    prot, ppos = prot @ arot, ppos + (prot @ apos[..., None])[..., 0]
                else:
                    hrot, hpos = world[self.head[link.source]]
                    arot, apos = prep.anchors[head]
                    prot, ppos = hrot @ arot, hpos + hrot @ apos
                offset, turn, target = self._links[head]
                pos = ppos + prot @ offset
                rot = prot @ turn
                if head in self._joint_index:
                    hinges[head] = (rot @ self._axes[head], pos)
                    rot = rot @ _axis_rotation(self._axes[head], x[:, self._joint_index[head]])
                pos = pos - rot @ target
            world[head] = (rot, pos)
            if head in self._twist_index:
                comp = self.robot.component(head)
                tau = x[:, self._twist_index[head]] / comp.length
                local, centre, fr = self._shape(comp, act[head], tau)
                twisted[head] = fr
                points.append(np.concatenate([local, centre[:, None]], axis=1))
            else:
                group = np.concatenate([prep.vertices[head], prep.centres[head]])
                points.append(np.broadcast_to(group, (batch, *group.shape)))
        placed = np.concatenate(
            [
                pts @ np.swapaxes(world[h][0], 1, 2) + world[h][1][:, None]
                for h, pts in zip(self.heads, points, strict=True)
            ],
            axis=1,
        )
        return placed, pitch, hinges


def _link(rot: Array, pos: Array, link: Connection) -> tuple[Array, Array]:
    """Offset d (in the anchor frame), rotation R and −p_t of a static connection."""
    pos = pos + rot @ np.array(link.offset)
    rot = rot @ np.array(link.rotation)
    return rot, pos - rot @ np.array(link.target_point)
