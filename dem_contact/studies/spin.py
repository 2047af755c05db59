"""Impacts with out-of-plane spin: how f/mu and the rebound depend on a spin about the incident tangential
direction (which gives the contact point a velocity across the impact plane), for a scene of Wu, Thornton
& Li (2009), compared with the planar impact along the incident slip and with the BEM reference.

Frame of ``impacts.impact3d`` (z into the wall, x along the incident tangential velocity): a spin wx gives
the slip velocity a component s_y = -R wx across the impact plane, measured by
Theta_across = 2 s_y / ((1 + e_n) mu V_n) as Theta measures the in-plane one.
"""
from __future__ import annotations

import math
import time
import warnings
from dataclasses import asdict, dataclass

import numpy as np

from ..impacts.impact import impact
from ..impacts.impact3d import impact3d
from ..laws.model import Scene, reference_speed


@dataclass
class SpinRow:
    law: str
    angle_deg: float
    spin_x: float                 # wx [rad/s]
    Theta: float                  # in-plane Theta of the incident slip
    Theta_across: float
    f_over_mu: float              # in-plane
    f_across_over_mu: float
    e_t: float
    Omega_r: float
    rebound_angle_deg: float
    out_of_plane_angle_deg: float
    slip_angle_i_deg: float
    slip_angle_r_deg: float
    planar_f_over_mu: float       # planar impact at the incident slip speed |s_i|
    planar_deviation: float       # |f_vec/mu - planar f/mu along the slip|


def spin_for_Theta_across(scene: Scene, vn: float, Theta_across: float) -> float:
    """wx [rad/s] giving Theta_across (with e_n = 1: elastic normal restitution assumed for the target)."""
    return -Theta_across * scene.mu * vn / scene.sphere.radius


def spin_sweep(scene: Scene, vn: float = 5.0, angles=(10.0, 30.0, 50.0), Theta_across=np.linspace(-6, 6, 25),
               *, steps_per_contact: float | None = None, label: str | None = None) -> list:
    """3D impacts at each impact angle [deg] (tangential velocity along x) with a spin wx about x chosen
    for each target Theta_across; each compared with the planar impact along its incident slip."""
    rows = []
    R = scene.sphere.radius
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for ang in angles:
            vt = vn * math.tan(math.radians(ang))
            for Tx in Theta_across:
                wx = spin_for_Theta_across(scene, vn, float(Tx))
                q = impact3d(scene, vn, (vt, 0.0), (wx, 0.0, 0.0), steps_per_contact=steps_per_contact)
                s = np.array([vt, -R * wx])
                speed = float(np.hypot(*s))
                p = impact(scene, vn, speed, 0.0, steps_per_contact=steps_per_contact)
                f_vec = np.array([q.f_over_mu, q.f_across_over_mu])
                dev = float(np.hypot(*(f_vec - p.f_over_mu * s / speed))) if speed > 0 else float(np.hypot(*f_vec))
                rows.append(SpinRow(label or scene.tangential, ang, wx, q.Theta, q.Theta_across, q.f_over_mu,
                                    q.f_across_over_mu, q.e_t, q.Omega_r, q.rebound_angle_deg,
                                    q.out_of_plane_angle_deg, q.slip_angle_i_deg, q.slip_angle_r_deg,
                                    p.f_over_mu, dev))
    return rows


@dataclass
class BEMSpinCase:
    """A BEM impact with a spin about the incident direction (frame of ``impacts.impact3d``)."""
    angle_deg: float
    Theta_across: float           # the target
    vt: float                     # tangential velocity of the centre, along x [m/s]
    spin_x: float                 # wx [rad/s]
    f_over_mu: float              # impulse ratio / mu in the impact plane
    f_across_over_mu: float
    out_of_plane_angle_deg: float
    n_across: int
    steps: int
    seconds: float


@dataclass
class BEMSpinRow:
    law: str
    angle_deg: float
    spin_x: float
    Theta: float
    Theta_across: float
    f_over_mu: float              # the law (impact3d)
    f_across_over_mu: float
    bem_f_over_mu: float          # the BEM (reference.impact.bem_impact)
    bem_f_across_over_mu: float
    error: float                  # |f_vec(law) - f_vec(BEM)| / mu
    out_of_plane_angle_deg: float
    bem_out_of_plane_angle_deg: float
    bem_seconds: float


def bem_spin_reference(scene: Scene, cases, vn: float = 5.0, *, n_across: int = 32, steps: int = 200) -> list:
    """The BEM impact (``reference.impact.bem_impact``; its z axis points out of the wall, so vectors are
    mapped by y -> -y, z -> -z) for each (angle [deg], Theta_across), the spin about the incident
    direction from ``spin_for_Theta_across``."""
    from ..reference.impact import bem_impact

    out = []
    for ang, Tacross in cases:
        vt = vn * math.tan(math.radians(ang))
        wx = spin_for_Theta_across(scene, vn, Tacross)
        t0 = time.perf_counter()
        b = bem_impact(scene, vn, (vt, 0.0), (wx, 0.0, 0.0), n_across=n_across, steps=steps)
        tb = time.perf_counter() - t0
        fb = -np.array([b.tangential_impulse[0], -b.tangential_impulse[1]]) / (b.normal_impulse * scene.mu)
        vb = np.array([b.v_r[0], -b.v_r[1]])
        out.append(BEMSpinCase(ang, Tacross, vt, wx, float(fb[0]), float(fb[1]),
                               math.degrees(math.atan2(vb[1], math.hypot(vb[0], b.e_n * vn))), n_across, steps, tb))
    return out


def law_scenes(scene: Scene, laws, vn: float) -> dict:
    """law -> the scene with that tangential law and every other setting of ``scene``
    (``Scene.with_tangential``), its reference speed (the placement of the mdr springs, the calibrations) at
    the study's ``vn``."""
    return {law: scene.with_tangential(law, v_ref=reference_speed(vn)) for law in laws}


def compare_spin_cases(scenes: dict, reference, vn: float = 5.0, *, steps_per_contact: float | None = None) -> list:
    """Each scene's ``impact3d`` (``scenes``: label -> Scene) against the BEM cases ``reference``
    (``bem_spin_reference``), through the impulse-ratio vector f/mu; steps per contact default to the
    BEM's steps."""
    rows = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for b in reference:
            for label, sc in scenes.items():
                q = impact3d(sc, vn, (b.vt, 0.0), (b.spin_x, 0.0, 0.0),
                             steps_per_contact=steps_per_contact or b.steps)
                err = math.hypot(q.f_over_mu - b.f_over_mu, q.f_across_over_mu - b.f_across_over_mu)
                rows.append(BEMSpinRow(label, b.angle_deg, b.spin_x, q.Theta, q.Theta_across, q.f_over_mu,
                                       q.f_across_over_mu, b.f_over_mu, b.f_across_over_mu, err,
                                       q.out_of_plane_angle_deg, b.out_of_plane_angle_deg, b.seconds))
    return rows


def bem_spin_cases(scene: Scene, cases, vn: float = 5.0, *, n_across: int = 32, steps: int = 200,
                   laws=("mdr_adaptive", "mdr", "md")) -> list:
    """``compare_spin_cases`` on a freshly computed ``bem_spin_reference``, each law at ``steps`` steps
    per contact."""
    return compare_spin_cases(law_scenes(scene, laws, vn),
                              bem_spin_reference(scene, cases, vn, n_across=n_across, steps=steps), vn)


def write_rows(rows, path):
    """CSV of dataclass rows, one per line."""
    import csv

    with open(path, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(asdict(rows[0])))
        w.writeheader()
        for r in rows:
            w.writerow({k: (float(v) if isinstance(v, np.floating) else v) for k, v in asdict(r).items()})


def read_bem_spin_reference(path) -> list:
    """``bem_spin_reference`` cases from ``write_rows``'s CSV."""
    import csv

    with open(path, newline="", encoding="utf-8-sig") as fh:   # BOM accepted
        return [BEMSpinCase(*(int(d[k]) if k in ("n_across", "steps") else float(d[k])
                              for k in BEMSpinCase.__dataclass_fields__)) for d in csv.DictReader(fh)]


def time_per_impact(scene: Scene, vn: float, vt, spin, steps_per_contact: float, repeats: int = 20) -> float:
    """Best time [s] of one 3D impact in the bare kernel ``integrate_impact3d`` (warm JIT)."""
    from ..impacts.impact import MAX_CONTACT_TIMES, body_inertia, time_step
    from ..impacts.impact3d import N_OUT3, N_SERIES3, integrate_impact3d, new_contact_state

    dt, spc = time_step(scene, vn, steps_per_contact)
    inv_m, R1, R2, iI1, iI2 = body_inertia(scene)
    out, ser = np.zeros(N_OUT3), np.zeros((0, N_SERIES3))
    params, H = new_contact_state(scene)
    w1, w2 = np.asarray(spin, dtype=float), np.zeros(3)
    best = math.inf
    for _ in range(repeats + 1):
        H[:] = 0.0
        t0 = time.perf_counter()
        integrate_impact3d(scene.normal_id, scene.tangential_id, params, H, vn, vt[0], vt[1], w1, w2, inv_m, R1,
                           R2, iI1, iI2, dt, int(MAX_CONTACT_TIMES * spc) + 10, True, True, out, ser)
        best = min(best, time.perf_counter() - t0)
    return best
